// The mesh and its field, drawn so that an edit costs the pixels that change, not the faces.
//
// When the camera moves (a "view" frame): the shaded mesh is drawn into the canvas with its depth, its colour
// is kept in a texture, and the faces wide enough on the screen for a glyph (an inradius of 2.5 pixels or more,
// in the view) are listed. On every frame: the kept colour is copied back within the mesh's rectangle on the
// screen (this erases the previous glyphs and markers), then the listed faces are drawn again with their glyphs:
// the n directions of the face as rays from its incentre, inside its incircle (a glyph never leaves its face;
// for n = 1 the ray tapers towards its tip), the field's angle in the face's frame read from a float texture.
// A solve changes that texture only (4 bytes per face, as the server sends it). The canvas keeps the mesh's depth between frames (the
// drawing buffer is preserved), so markers, pins and lines drawn after it are hidden where they should be.
// Faces a few pixels wide get no glyph (it would be noise): zoom in, or show streamlines.
import * as THREE from "three";

// the same position in both mesh passes, so that the glyph pass meets the depth the view frame left
const shadedVertex = /* glsl */ `
out vec3 vNormal;
void main() {
  vNormal = normalMatrix * normal;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}`;

const shading = /* glsl */ `
uniform vec3 surface;
vec3 shade(vec3 normal) { return surface * (0.38 + 0.62 * abs(normalize(normal).z)); } // a headlight
`;

const shadedFragment = /* glsl */ `
precision highp float;
${shading}
in vec3 vNormal;
layout(location = 0) out highp vec4 color;
void main() { color = vec4(shade(vNormal), 1.0); }`;

const glyphVertex = /* glsl */ `
uniform highp sampler2D field;  // r: the angle of the face's direction in its frame
uniform int textureWidth;
in float faceId;
in vec3 local;            // this corner in its face's frame (about the incentre), and the face's inradius
flat out vec2 vRay;       // the face's direction in its frame (cos, sin): once per corner, not per pixel
flat out float vRadius;
out vec2 vLocal;
out vec3 vNormal;
void main() {
  int face = int(faceId);
  float angle = texelFetch(field, ivec2(face % textureWidth, face / textureWidth), 0).r;
  vRay = vec2(cos(angle), sin(angle));
  vRadius = local.z;
  vLocal = local.xy;
  vNormal = normalMatrix * normal;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}`;

const glyphFragment = /* glsl */ `
precision highp float;
precision highp int;
${shading}
uniform int n;
uniform vec2 turn;        // cos and sin of 2 pi / n
uniform vec3 ink;
flat in vec2 vRay;
flat in float vRadius;
in vec2 vLocal;
in vec3 vNormal;
layout(location = 0) out highp vec4 color;
void main() {
  float size = length(fwidth(vLocal)) * 0.7071; // the mesh's units per pixel here
  vec2 p = vLocal / size;                       // in pixels
  float r = 0.9 * vRadius / size;
  // the nearest of the n rays (the largest projection), p's distance along it and across it
  float along = -1.0, across = 0.0;
  vec2 d = vRay;
  for (int k = 0; k < 64; ++k) {
    if (k >= n) break;
    float a = dot(p, d);
    if (a > along) {
      along = a;
      across = abs(d.x * p.y - d.y * p.x);
    }
    d = vec2(d.x * turn.x - d.y * turn.y, d.x * turn.y + d.y * turn.x);
  }
  float w = n == 1 ? mix(1.6, 0.4, clamp(along / r, 0.0, 1.0)) : 0.75; // half-width
  float amount = along >= 0.0 && along <= r ? 1.0 - smoothstep(w - 0.5, w + 0.5, across) : 0.0;
  color = vec4(mix(shade(vNormal), ink, amount * smoothstep(2.5, 5.0, r)), 1.0);
}`;

const copyVertex = /* glsl */ `
void main() { gl_Position = vec4(position.xy, 0.0, 1.0); }`;

const copyFragment = /* glsl */ `
precision highp float;
uniform lowp sampler2D kept;
layout(location = 0) out highp vec4 color;
void main() { color = texelFetch(kept, ivec2(gl_FragCoord.xy), 0); }`;

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
    this.box = indexed.boundingBox;
    const vertexNormal = indexed.getAttribute("normal").array;

    // three corners per face, each with the face's data (an indexed mesh cannot carry per-face attributes); per
    // face its frame: the unit normal, e1 along its first edge, e2 = normal x e1; its incentre and inradius
    const position = new Float32Array(9 * m), normal = new Float32Array(9 * m), faceId = new Float32Array(3 * m);
    const local = new Float32Array(9 * m);
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
      const e2x = ny * e1z - nz * e1y, e2y = nz * e1x - nx * e1z, e2z = nx * e1y - ny * e1x;
      this.normals[3 * f] = nx; this.normals[3 * f + 1] = ny; this.normals[3 * f + 2] = nz;
      this.e1[3 * f] = e1x; this.e1[3 * f + 1] = e1y; this.e1[3 * f + 2] = e1z;
      this.e2[3 * f] = e2x; this.e2[3 * f + 1] = e2y; this.e2[3 * f + 2] = e2z;
      const ix = (la * ax + lb * bx + lc * cx) / perimeter, iy = (la * ay + lb * by + lc * cy) / perimeter;
      const iz = (la * az + lb * bz + lc * cz) / perimeter, r = twiceArea / perimeter;
      this.incircles[4 * f] = ix; this.incircles[4 * f + 1] = iy; this.incircles[4 * f + 2] = iz;
      this.incircles[4 * f + 3] = r;
      edgeSum += lc;
      for (let k = 0; k < 3; ++k) {
        const v = F[3 * f + k], o = 9 * f + 3 * k;
        const px = V[3 * v], py = V[3 * v + 1], pz = V[3 * v + 2];
        position[o] = px; position[o + 1] = py; position[o + 2] = pz;
        normal[o] = vertexNormal[3 * v]; normal[o + 1] = vertexNormal[3 * v + 1]; normal[o + 2] = vertexNormal[3 * v + 2];
        faceId[3 * f + k] = f;
        local[o] = (px - ix) * e1x + (py - iy) * e1y + (pz - iz) * e1z;
        local[o + 1] = (px - ix) * e2x + (py - iy) * e2y + (pz - iz) * e2z;
        local[o + 2] = r;
      }
    }
    this.meanEdge = edgeSum / m;

    // the field: one angle per face, rows of textureWidth
    this.textureWidth = 2048;
    const rows = Math.max(1, Math.ceil(m / this.textureWidth));
    this.angles = new Float32Array(this.textureWidth * rows);
    this.texture = new THREE.DataTexture(this.angles, this.textureWidth, rows, THREE.RedFormat, THREE.FloatType);
    this.texture.minFilter = this.texture.magFilter = THREE.NearestFilter;
    this.texture.generateMipmaps = false;
    this.texture.needsUpdate = true;

    const surface = { value: new THREE.Color(0xc3ccd9) };
    const offset = { side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 };
    this.viewScene = new THREE.Scene();
    this.viewScene.add(new THREE.Mesh(indexed, new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3, vertexShader: shadedVertex, fragmentShader: shadedFragment, uniforms: { surface },
      ...offset })));

    const corners = new THREE.BufferGeometry();
    corners.setAttribute("position", new THREE.BufferAttribute(position, 3));
    corners.setAttribute("normal", new THREE.BufferAttribute(normal, 3));
    corners.setAttribute("faceId", new THREE.BufferAttribute(faceId, 1));
    corners.setAttribute("local", new THREE.BufferAttribute(local, 3));
    corners.setIndex(new THREE.BufferAttribute(new Uint32Array(0), 1));
    corners.boundingSphere = this.boundingSphere;
    this.glyphUniforms = { surface, field: { value: this.texture }, textureWidth: { value: this.textureWidth },
                           n: { value: 1 }, turn: { value: new THREE.Vector2(1, 0) },
                           ink: { value: new THREE.Color(0x1f3a93) } };
    this.glyphMesh = new THREE.Mesh(corners, new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3, vertexShader: glyphVertex, fragmentShader: glyphFragment,
      uniforms: this.glyphUniforms, ...offset, depthFunc: THREE.LessEqualDepth, depthWrite: false }));
    this.glyphMesh.frustumCulled = false;
    this.glyphScene = new THREE.Scene();
    this.glyphScene.add(this.glyphMesh);

    this.kept = null; // the colour of the view frame
    this.copyUniforms = { kept: { value: null } };
    const quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3, vertexShader: copyVertex, fragmentShader: copyFragment, uniforms: this.copyUniforms,
      depthTest: false, depthWrite: false }));
    quad.frustumCulled = false;
    this.copyScene = new THREE.Scene();
    this.copyScene.add(quad);
    this.screenCamera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);

    this.field = null;
    this.n = 1;
    this.showGlyphs = true;
    this.stale = true; // the view frame no longer matches the camera or the size
    this.rectangle = null; // where the mesh is on the screen (CSS pixels, from the bottom left), null: anywhere
    this.glyphFaces = 0;
  }

  // "glyphs", or "none" (the surface alone, e.g. under streamlines)
  set style(name) { this.showGlyphs = name === "glyphs"; }

  // the field of a solve: per face the angle of one of its n directions, counter-clockwise from its first edge
  // (float32, as the server sends it)
  setField(angles, n) {
    this.angles.set(angles);
    this.texture.needsUpdate = true;
    this.field = angles;
    this.n = n;
    this.glyphUniforms.n.value = n;
    this.glyphUniforms.turn.value.set(Math.cos(2 * Math.PI / n), Math.sin(2 * Math.PI / n));
  }

  // draws the mesh and its field into the canvas (see the top of this file); the caller draws overlays after it
  // with the same camera, without writing depth
  render(camera, background) {
    const renderer = this.renderer, size = renderer.getDrawingBufferSize(new THREE.Vector2());
    if (!this.kept || this.kept.image.width !== size.x || this.kept.image.height !== size.y) {
      this.kept?.dispose();
      this.kept = new THREE.FramebufferTexture(size.x, size.y);
      this.kept.minFilter = this.kept.magFilter = THREE.NearestFilter;
      this.copyUniforms.kept.value = this.kept;
      this.stale = true;
    }
    const autoClear = renderer.autoClear;
    renderer.autoClear = false;
    if (this.stale) {
      renderer.setClearColor(background, 1);
      renderer.clear(true, true, true);
      renderer.render(this.viewScene, camera);
      renderer.copyFramebufferToTexture(this.kept);
      this.rectangle = this.screenRectangle(camera);
      this.selectGlyphFaces(camera);
      this.stale = false;
    } else {
      const r = this.rectangle;
      if (r) {
        renderer.setScissor(r.x, r.y, r.width, r.height);
        renderer.setScissorTest(true);
      }
      renderer.render(this.copyScene, this.screenCamera);
      renderer.setScissorTest(false);
    }
    if (this.showGlyphs && this.field && this.glyphFaces) renderer.render(this.glyphScene, camera);
    renderer.autoClear = autoClear;
  }

  // the faces in front of the camera, near the view, whose inradius at their incentre's depth is 2.5 pixels or more
  selectGlyphFaces(camera) {
    camera.updateMatrixWorld();
    const e = camera.matrixWorldInverse.elements, m = this.faces, c = this.incircles;
    const height = this.renderer.getDrawingBufferSize(new THREE.Vector2()).y;
    const pixelsPerUnit = height / 2 / Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2); // at depth 1
    const slopeX = camera.aspect * Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2) * 1.05;
    const slopeY = Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2) * 1.05;
    const selected = [];
    for (let f = 0; f < m; ++f) {
      const x = c[4 * f], y = c[4 * f + 1], z = c[4 * f + 2], r = c[4 * f + 3];
      const depth = -(e[2] * x + e[6] * y + e[10] * z + e[14]);
      if (depth <= camera.near || 0.9 * r * pixelsPerUnit < 2.5 * depth) continue;
      const vx = e[0] * x + e[4] * y + e[8] * z + e[12], vy = e[1] * x + e[5] * y + e[9] * z + e[13];
      if (Math.abs(vx) - r > slopeX * depth || Math.abs(vy) - r > slopeY * depth) continue;
      selected.push(3 * f, 3 * f + 1, 3 * f + 2);
    }
    this.glyphMesh.geometry.setIndex(new THREE.BufferAttribute(new Uint32Array(selected), 1));
    this.glyphFaces = selected.length / 3;
  }

  // the rectangle (CSS pixels, from the bottom left) holding the projection of the mesh's bounding box, or null
  // when the box reaches behind the camera
  screenRectangle(camera) {
    const box = this.box, view = this.renderer.getSize(new THREE.Vector2()), p = new THREE.Vector3();
    let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    for (let i = 0; i < 8; ++i) {
      p.set(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z);
      if (p.clone().applyMatrix4(camera.matrixWorldInverse).z >= -camera.near) return null;
      p.project(camera);
      x0 = Math.min(x0, p.x); x1 = Math.max(x1, p.x); y0 = Math.min(y0, p.y); y1 = Math.max(y1, p.y);
    }
    const left = Math.max(0, Math.floor((x0 + 1) / 2 * view.x) - 1);
    const bottom = Math.max(0, Math.floor((y0 + 1) / 2 * view.y) - 1);
    const right = Math.min(view.x, Math.ceil((x1 + 1) / 2 * view.x) + 1);
    const top = Math.min(view.y, Math.ceil((y1 + 1) / 2 * view.y) + 1);
    return { x: left, y: bottom, width: Math.max(0, right - left), height: Math.max(0, top - bottom) };
  }

  // the n directions of every face as the shader draws them (n per face, 3 numbers each): at the angle of the field
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
