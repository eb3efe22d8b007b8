// The mesh and its field, drawn so that the field reads at every zoom and an edit costs the glyphs, not the faces.
//
// Two layers. The WebGL canvas holds what moves with the camera only: the shaded mesh and the lines of the 3D
// scene the caller passes (boundary loops, streamlines); it is drawn again only when the camera moves, the size
// changes or those lines change (a "view" frame, `stale`). In the same frame the mesh is drawn a second time into a
// render target with each pixel's face number (+1; 0 is the background), read back once.
//
// Over it a 2D canvas (`overlay`, no pointer events) holds what an edit changes, in screen space:
// - the field: the screen is cut into cells of CELL CSS pixels (each centre moved by up to a quarter of a cell, the
//   same for every frame, so that the glyphs make no grid); each cell whose centre is on the mesh gets a glyph of
//   the face under that centre, the n directions as rays of the face's frame mapped to the screen (the derivative
//   of the projection at the face's incentre: a direction seen edge-on is short, as on a disc lying on the
//   surface), the longest RAY pixels long. So the field is drawn as densely at the whole-mesh view of a 100k-face
//   mesh as on one face filling the screen, and an edit redraws a few thousand lines: the field's angle per face
//   (4 bytes, as the server sends it) turned by the cell's 2 x 2 matrix kept from the view frame;
// - the pinned directions: arrows of a fixed length in pixels (PIN; the sharp features' pins shorter, FEATURE_PIN)
//   from the face's incentre, where the face is seen (its incentre near the surface under that pixel); of the
//   sharp features' pins, one a cell of FEATURE_PIN pixels;
// - the singularities' markers: squares of MARKER pixels on top of everything (never cut by the surface).
import * as THREE from "three";

const CELL = 16, RAY = 7, PIN = 26, FEATURE_PIN = 12, MARKER = 12, ID_SCALE = 2;
const INK = "#1f3a93";

const shadedVertex = /* glsl */ `
out vec3 vNormal;
void main() {
  vNormal = normalMatrix * normal;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}`;

const shadedFragment = /* glsl */ `
precision highp float;
uniform vec3 surface;
in vec3 vNormal;
layout(location = 0) out highp vec4 color;
void main() { color = vec4(surface * (0.38 + 0.62 * abs(normalize(vNormal).z)), 1.0); } // a headlight`;

// the face number + 1 in the red, green and blue bytes (16.7 million faces)
const idVertex = /* glsl */ `
in float faceId;
flat out float vId;
void main() {
  vId = faceId + 1.0;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}`;

const idFragment = /* glsl */ `
precision highp float;
flat in float vId;
layout(location = 0) out highp vec4 color;
void main() {
  float id = vId;
  color = vec4(mod(id, 256.0), mod(floor(id / 256.0), 256.0), floor(id / 65536.0), 255.0) / 255.0;
}`;

// a hash of the cell (x, y) in [0, 1)
function hash(x, y, salt) {
  let h = Math.imul(x, 374761393) ^ Math.imul(y, 668265263) ^ Math.imul(salt, 1274126177);
  h = Math.imul(h ^ (h >>> 13), 1103515245);
  return ((h ^ (h >>> 16)) >>> 0) / 4294967296;
}

export class FieldView {
  // V: (nv, 3) and F: (m, 3) flat arrays, as the server sent them
  constructor(renderer, V, F) {
    this.renderer = renderer;
    const m = this.faces = F.length / 3;
    const indexed = new THREE.BufferGeometry();
    indexed.setAttribute("position", new THREE.BufferAttribute(V, 3));
    indexed.setIndex(new THREE.BufferAttribute(F, 1));
    indexed.computeVertexNormals();
    indexed.computeBoundingSphere();
    indexed.computeBoundingBox();
    this.boundingSphere = indexed.boundingSphere;

    // per face its frame: the unit normal, e1 along its first edge, e2 = normal x e1; its incentre and inradius;
    // and three corners per face with the face's number (an indexed mesh cannot carry per-face attributes)
    const position = new Float32Array(9 * m), faceId = new Float32Array(3 * m);
    this.normals = new Float32Array(3 * m);
    this.e1 = new Float32Array(3 * m);
    this.e2 = new Float32Array(3 * m);
    this.incircles = new Float32Array(4 * m);
    let edgeSum = 0;
    for (let f = 0; f < m; ++f) {
      const a = F[3 * f], b = F[3 * f + 1], c = F[3 * f + 2];
      const ax = V[3 * a], ay = V[3 * a + 1], az = V[3 * a + 2];
      const bx = V[3 * b], by = V[3 * b + 1], bz = V[3 * b + 2];
      const cx = V[3 * c], cy = V[3 * c + 1], cz = V[3 * c + 2];
      const la = Math.hypot(bx - cx, by - cy, bz - cz), lb = Math.hypot(cx - ax, cy - ay, cz - az);
      const lc = Math.hypot(ax - bx, ay - by, az - bz), perimeter = la + lb + lc;
      const ux = bx - ax, uy = by - ay, uz = bz - az, wx = cx - ax, wy = cy - ay, wz = cz - az;
      let nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
      const twiceArea = Math.hypot(nx, ny, nz);
      nx /= twiceArea; ny /= twiceArea; nz /= twiceArea;
      const e1x = ux / lc, e1y = uy / lc, e1z = uz / lc;
      this.normals[3 * f] = nx; this.normals[3 * f + 1] = ny; this.normals[3 * f + 2] = nz;
      this.e1[3 * f] = e1x; this.e1[3 * f + 1] = e1y; this.e1[3 * f + 2] = e1z;
      this.e2[3 * f] = ny * e1z - nz * e1y; this.e2[3 * f + 1] = nz * e1x - nx * e1z;
      this.e2[3 * f + 2] = nx * e1y - ny * e1x;
      this.incircles[4 * f] = (la * ax + lb * bx + lc * cx) / perimeter;
      this.incircles[4 * f + 1] = (la * ay + lb * by + lc * cy) / perimeter;
      this.incircles[4 * f + 2] = (la * az + lb * bz + lc * cz) / perimeter;
      this.incircles[4 * f + 3] = twiceArea / perimeter;
      edgeSum += lc;
      for (let k = 0; k < 3; ++k) {
        const v = F[3 * f + k], o = 9 * f + 3 * k;
        position[o] = V[3 * v]; position[o + 1] = V[3 * v + 1]; position[o + 2] = V[3 * v + 2];
        faceId[3 * f + k] = f;
      }
    }
    this.meanEdge = edgeSum / m;

    const offset = { side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 };
    this.viewScene = new THREE.Scene();
    this.viewScene.add(new THREE.Mesh(indexed, new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3, vertexShader: shadedVertex, fragmentShader: shadedFragment,
      uniforms: { surface: { value: new THREE.Color(0xc3ccd9) } }, ...offset })));
    const corners = new THREE.BufferGeometry();
    corners.setAttribute("position", new THREE.BufferAttribute(position, 3));
    corners.setAttribute("faceId", new THREE.BufferAttribute(faceId, 1));
    corners.boundingSphere = this.boundingSphere;
    this.idScene = new THREE.Scene();
    this.idScene.add(new THREE.Mesh(corners, new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3, vertexShader: idVertex, fragmentShader: idFragment, side: THREE.DoubleSide })));
    this.idTarget = null;
    // per pixel of the face buffer (ID_SCALE times coarser than the drawing buffer, rows from the bottom): the face
    // number + 1, 0: the background
    this.ids = null;

    this.overlay = document.createElement("canvas");
    this.overlay.style.cssText = "position: absolute; left: 0; top: 0; pointer-events: none";
    this.context = this.overlay.getContext("2d");

    this.field = null;
    this.n = 1;
    this.showGlyphs = true;
    this.stale = true; // the view frame no longer matches the camera, the size or the 3D lines
    // the glyphs' cells of the view frame: per cell its centre (overlay pixels, from the top left), its face and the
    // 2 x 2 matrix from the face's frame to the overlay's pixels (scaled: the longest direction RAY pixels)
    this.cells = { count: 0, centre: new Float32Array(0), face: new Int32Array(0), matrix: new Float32Array(0) };
    this.pins = [];     // [{face, direction: [x, y, z], feature: bool}]
    this.markers = [];  // [{position: [x, y, z], color: "css"}]
    this.camera = null;
  }

  // "glyphs", or "none" (the surface alone, e.g. under streamlines)
  set style(name) { this.showGlyphs = name === "glyphs"; }

  // the field of a solve: per face the angle of one of its n directions, counter-clockwise from its first edge
  // (float32, as the server sends it)
  setField(angles, n) {
    this.field = angles;
    this.n = n;
  }

  setPins(pins) { this.pins = pins; }
  setMarkers(markers) { this.markers = markers; }

  // draws the view frame if it is stale (then `lines`, a scene of 3D lines, over the mesh with the same camera),
  // then the overlay
  render(camera, background, lines) {
    const renderer = this.renderer, size = renderer.getDrawingBufferSize(new THREE.Vector2());
    this.camera = camera;
    if (this.overlay.width !== size.x || this.overlay.height !== size.y) {
      this.overlay.width = size.x;
      this.overlay.height = size.y;
      const css = renderer.getSize(new THREE.Vector2());
      this.overlay.style.width = css.x + "px";
      this.overlay.style.height = css.y + "px";
      this.stale = true;
    }
    if (this.stale) {
      const autoClear = renderer.autoClear;
      renderer.autoClear = false;
      renderer.setClearColor(background, 1);
      renderer.clear(true, true, true);
      renderer.render(this.viewScene, camera);
      if (lines) renderer.render(lines, camera);
      this.readIds(camera, size);
      renderer.autoClear = autoClear;
      this.selectCells(camera, size);
      this.stale = false;
    }
    this.drawOverlay();
  }

  // the face number of every pixel, into this.ids
  readIds(camera, size) {
    const renderer = this.renderer, w = Math.ceil(size.x / ID_SCALE), h = Math.ceil(size.y / ID_SCALE);
    if (!this.idTarget || this.idTarget.width !== w || this.idTarget.height !== h) {
      this.idTarget?.dispose();
      this.idTarget = new THREE.WebGLRenderTarget(w, h, { minFilter: THREE.NearestFilter,
        magFilter: THREE.NearestFilter, depthBuffer: true, generateMipmaps: false });
      this.ids = new Uint8Array(4 * w * h);
    }
    renderer.setRenderTarget(this.idTarget);
    renderer.setClearColor(0x000000, 0);
    renderer.clear(true, true, true);
    renderer.render(this.idScene, camera);
    renderer.setRenderTarget(null);
    renderer.readRenderTargetPixels(this.idTarget, 0, 0, w, h, this.ids);
  }

  // the face seen at overlay pixel (x, y) (from the top left), or -1
  faceAt(x, y) {
    if (!this.ids) return -1;
    const w = this.idTarget.width, h = this.idTarget.height;
    x = Math.floor(x / ID_SCALE); y = Math.floor(y / ID_SCALE);
    if (x < 0 || y < 0 || x >= w || y >= h) return -1;
    const o = 4 * ((h - 1 - y) * w + x), ids = this.ids;
    return ids[o] + 256 * ids[o + 1] + 65536 * ids[o + 2] - 1;
  }

  // the projection of face f's frame at its incentre: [x, y] of the incentre in overlay pixels and the overlay
  // pixels per unit of e1 and of e2 (the derivative of the projection), or null behind the camera
  frameOnScreen(f, P) {
    const c = this.incircles, w = this.overlay.width, h = this.overlay.height, e = P.elements;
    const x = c[4 * f], y = c[4 * f + 1], z = c[4 * f + 2];
    const cw = e[3] * x + e[7] * y + e[11] * z + e[15];
    if (cw <= 0) return null;
    const cx = (e[0] * x + e[4] * y + e[8] * z + e[12]) / cw, cy = (e[1] * x + e[5] * y + e[9] * z + e[13]) / cw;
    const along = t => {
      const tx = t[3 * f], ty = t[3 * f + 1], tz = t[3 * f + 2];
      const dw = e[3] * tx + e[7] * ty + e[11] * tz;
      const dx = (e[0] * tx + e[4] * ty + e[8] * tz - cx * dw) / cw;
      const dy = (e[1] * tx + e[5] * ty + e[9] * tz - cy * dw) / cw;
      return [dx * w / 2, -dy * h / 2];
    };
    return { x: (cx + 1) / 2 * w, y: (1 - cy) / 2 * h, u: along(this.e1), v: along(this.e2) };
  }

  // the cells whose centre is on the mesh, their faces and matrices (see the top of this file)
  selectCells(camera, size) {
    camera.updateMatrixWorld();
    const P = new THREE.Matrix4().multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
    const cell = CELL * this.renderer.getPixelRatio(), ray = RAY * this.renderer.getPixelRatio();
    const nx = Math.ceil(size.x / cell), ny = Math.ceil(size.y / cell), capacity = nx * ny;
    if (this.cells.centre.length < 2 * capacity)
      this.cells = { count: 0, centre: new Float32Array(2 * capacity), face: new Int32Array(capacity),
                     matrix: new Float32Array(4 * capacity) };
    const { centre, face, matrix } = this.cells;
    let count = 0;
    for (let j = 0; j < ny; ++j)
      for (let i = 0; i < nx; ++i) {
        const x = (i + 0.25 + 0.5 * hash(i, j, 1)) * cell, y = (j + 0.25 + 0.5 * hash(i, j, 2)) * cell;
        const f = this.faceAt(x, y);
        if (f < 0) continue;
        const s = this.frameOnScreen(f, P);
        if (!s) continue;
        // the largest singular value of [u v]: the longest direction drawn RAY pixels long
        const [a, b] = s.u, [c, d] = s.v, q = a * a + b * b + c * c + d * d, det = a * d - b * c;
        const sigma = Math.sqrt((q + Math.sqrt(Math.max(0, q * q - 4 * det * det))) / 2);
        if (!(sigma > 0)) continue;
        centre[2 * count] = x; centre[2 * count + 1] = y;
        face[count] = f;
        const k = ray / sigma;
        matrix[4 * count] = a * k; matrix[4 * count + 1] = b * k; matrix[4 * count + 2] = c * k;
        matrix[4 * count + 3] = d * k;
        ++count;
      }
    this.cells.count = count;
  }

  // the overlay: glyphs, pins, markers
  drawOverlay() {
    const g = this.context, ratio = this.renderer.getPixelRatio();
    g.clearRect(0, 0, this.overlay.width, this.overlay.height);
    g.lineCap = "round";
    if (this.showGlyphs && this.field) this.drawGlyphs(g, ratio);
    if (this.pins.length && this.camera) this.drawPins(g, ratio);
    // the squares on whole pixels (no blended edges), every outline before every square: markers side by side
    // overlap, none cuts another with its outline
    const s = Math.round(MARKER * ratio), p = new THREE.Vector3(), w = this.overlay.width, h = this.overlay.height;
    const corners = this.markers.map(({ position }) => {
      p.fromArray(position).project(this.camera);
      return [Math.round((p.x + 1) / 2 * w - s / 2), Math.round((1 - p.y) / 2 * h - s / 2)];
    });
    g.fillStyle = "#202020";
    for (const [x, y] of corners) g.fillRect(x - ratio, y - ratio, s + 2 * ratio, s + 2 * ratio);
    this.markers.forEach(({ color }, i) => {
      g.fillStyle = color;
      g.fillRect(corners[i][0], corners[i][1], s, s);
    });
  }

  // the n directions of each cell's face: n rays from its centre (for an even n, n / 2 lines through it); n = 1 an
  // arrow
  drawGlyphs(g, ratio) {
    const { count, centre, face, matrix } = this.cells, field = this.field, n = this.n;
    const lines = n % 2 === 0 ? n / 2 : n, through = n % 2 === 0;
    const turnC = Math.cos(2 * Math.PI / n), turnS = Math.sin(2 * Math.PI / n);
    g.beginPath();
    for (let i = 0; i < count; ++i) {
      const t = field[face[i]], x = centre[2 * i], y = centre[2 * i + 1];
      const a = matrix[4 * i], b = matrix[4 * i + 1], c = matrix[4 * i + 2], d = matrix[4 * i + 3];
      let cos = Math.cos(t), sin = Math.sin(t);
      for (let k = 0; k < lines; ++k) {
        const dx = a * cos + c * sin, dy = b * cos + d * sin;
        if (through) { g.moveTo(x - dx, y - dy); g.lineTo(x + dx, y + dy); }
        else {
          g.moveTo(x, y); g.lineTo(x + dx, y + dy);
          if (n === 1) { // the head
            g.moveTo(x + 0.5 * dx - 0.3 * dy, y + 0.5 * dy + 0.3 * dx); g.lineTo(x + dx, y + dy);
            g.lineTo(x + 0.5 * dx + 0.3 * dy, y + 0.5 * dy - 0.3 * dx);
          }
        }
        const next = cos * turnC - sin * turnS;
        sin = cos * turnS + sin * turnC;
        cos = next;
      }
    }
    g.strokeStyle = INK;
    g.lineWidth = ratio; // one pixel: Chromium strokes thousands of lines of 1 pixel in 2-4 ms, of 1.3 pixels in 30-55
    g.stroke();
  }

  // each pin whose face is seen: an arrow from its incentre along the direction on the face, PIN pixels long
  // (FEATURE_PIN for the sharp features'); seen: the face under the incentre's pixel is the pin's, or its incentre
  // is within two mean edges or two pixels' width of the pin's
  drawPins(g, ratio) {
    const camera = this.camera, P = new THREE.Matrix4().multiplyMatrices(camera.projectionMatrix,
                                                                          camera.matrixWorldInverse);
    const c = this.incircles, h = this.overlay.height;
    const perPixel = 2 * Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2) / h;
    const arrows = { false: [], true: [] }, taken = new Set();
    for (const { face: f, direction, feature } of this.pins) {
      const s = this.frameOnScreen(f, P);
      if (!s) continue;
      const seenFace = this.faceAt(s.x, s.y);
      if (seenFace < 0) continue;
      if (seenFace !== f) {
        const dx = c[4 * seenFace] - c[4 * f], dy = c[4 * seenFace + 1] - c[4 * f + 1];
        const dz = c[4 * seenFace + 2] - c[4 * f + 2];
        const depth = camera.position.distanceTo(new THREE.Vector3(c[4 * f], c[4 * f + 1], c[4 * f + 2]));
        if (Math.hypot(dx, dy, dz) > Math.max(2 * this.meanEdge, 2 * perPixel * depth)) continue;
      }
      // the direction in the face's frame, then on the screen
      const e1 = this.e1, e2 = this.e2, [px, py, pz] = direction;
      const u = px * e1[3 * f] + py * e1[3 * f + 1] + pz * e1[3 * f + 2];
      const v = px * e2[3 * f] + py * e2[3 * f + 1] + pz * e2[3 * f + 2];
      const dx = s.u[0] * u + s.v[0] * v, dy = s.u[1] * u + s.v[1] * v, length = Math.hypot(dx, dy);
      if (!(length > 0)) continue;
      if (feature) { // one arrow a cell of FEATURE_PIN pixels: thousands of them along the edges would be a band
        const key = Math.floor(s.x / (FEATURE_PIN * ratio)) + "," + Math.floor(s.y / (FEATURE_PIN * ratio));
        if (taken.has(key)) continue;
        taken.add(key);
      }
      arrows[!!feature].push([s.x, s.y, dx / length, dy / length]);
    }
    for (const feature of [true, false]) {
      const list = arrows[feature];
      if (!list.length) continue;
      const L = (feature ? FEATURE_PIN : PIN) * ratio, head = (feature ? 4 : 7) * ratio;
      g.beginPath();
      for (const [x, y, dx, dy] of list) {
        const tx = x + L * dx, ty = y + L * dy;
        g.moveTo(x, y); g.lineTo(tx, ty);
        g.moveTo(tx - head * (dx - 0.6 * dy), ty - head * (dy + 0.6 * dx)); g.lineTo(tx, ty);
        g.lineTo(tx - head * (dx + 0.6 * dy), ty - head * (dy - 0.6 * dx));
      }
      g.lineJoin = "round";
      g.strokeStyle = "rgba(255, 255, 255, 0.85)"; // a halo over the glyphs
      g.lineWidth = (feature ? 3 : 5) * ratio;
      g.stroke();
      g.strokeStyle = "#e0700b";
      g.lineWidth = (feature ? 1.5 : 2.5) * ratio;
      g.stroke();
    }
  }

  // the WebGL canvas with the overlay over it, in a canvas of the drawing buffer's size (the PNG of the view, and the
  // tests' pixels)
  composite() {
    const out = document.createElement("canvas");
    out.width = this.overlay.width;
    out.height = this.overlay.height;
    const g = out.getContext("2d", { willReadFrequently: true });
    g.drawImage(this.renderer.domElement, 0, 0);
    g.drawImage(this.overlay, 0, 0);
    return out;
  }

  // the n directions of every face as the glyphs draw them (n per face, 3 numbers each): at the angle of the field
  // plus 2 pi k / n in the face's frame; for the tests, which check them against the library
  directions() {
    const { field, n, e1, e2 } = this, m = this.faces;
    const out = new Float32Array(m * n * 3);
    for (let f = 0; f < m; ++f)
      for (let k = 0; k < n; ++k) {
        const t = field[f] + 2 * Math.PI * k / n, cos = Math.cos(t), sin = Math.sin(t), o = 3 * (f * n + k);
        for (let i = 0; i < 3; ++i) out[o + i] = cos * e1[3 * f + i] + sin * e2[3 * f + i];
      }
    return out;
  }
}
