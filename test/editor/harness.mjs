// What the editor's browser test and its latency benchmark share: the server started on a mesh, and headless
// Chromium (Debian's, or TC_CHROMIUM) through playwright-core (NODE_PATH: the build's npm packages).
import { spawn } from "node:child_process";
import { createRequire } from "node:module";

const require = createRequire(import.meta.url);
const { chromium } = require("playwright-core");

// the launcher (trivial_connections-serve) on `mesh` with a free port, started in `cwd` (default: this process's;
// the server's folder unless `extra` names one); resolves once it listens (after factoring)
export async function startServer(serve, mesh, extra = [], cwd = undefined) {
  const server = spawn(serve, [mesh, "--port", "0", ...extra], { stdio: ["ignore", "pipe", "inherit"], cwd });
  const address = await new Promise((resolve, reject) => {
    let out = "";
    const timer = setTimeout(() => reject(new Error("the server did not start in 120 s")), 120000);
    server.stdout.on("data", d => {
      out += d;
      const m = out.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) {
        clearTimeout(timer);
        resolve(m[0]);
      }
    });
    server.on("exit", code => reject(new Error(`the server exited (${code}) before listening`)));
  });
  return { server, address };
}

// SwiftShader's GL unless TC_CHROMIUM_GL says otherwise (the machines this runs on may have no GPU)
export function launchBrowser() {
  return chromium.launch({
    executablePath: process.env.TC_CHROMIUM || "/usr/bin/chromium",
    args: ["--no-sandbox", `--use-gl=${process.env.TC_CHROMIUM_GL || "swiftshader"}`, "--enable-unsafe-swiftshader"],
  });
}

// what the page shows of the field at the current view (the browser test checks it, the latency benchmark reports
// it): the view drawn, then the WebGL canvas and its overlay composed; a pixel is the mesh's when the field view's
// face buffer has a face there, and ink when it is much bluer than red (the glyphs' #1f3a93, even half covered, and
// not the grey-blue shading, whose blue exceeds its red by 22 at most). Of the blocks of `block` x `block` pixels
// wholly on the mesh: the share holding ink (`coverage`); of the mesh's pixels: the share of ink (`ink`)
export function fieldCoverage(page, block = 24) {
  return page.evaluate(block => {
    const e = window.__editor, view = e.internals.fieldView;
    e.internals.draw();
    const canvas = view.composite(), w = canvas.width, h = canvas.height;
    const rgba = canvas.getContext("2d").getImageData(0, 0, w, h).data;
    let meshPixels = 0, inkPixels = 0, blocks = 0, inked = 0;
    for (let by = 0; by + block <= h; by += block)
      for (let bx = 0; bx + block <= w; bx += block) {
        let covered = 0, ink = 0;
        for (let y = by; y < by + block; ++y)
          for (let x = bx; x < bx + block; ++x) {
            if (view.faceAt(x, y) < 0) continue;
            ++covered;
            const o = 4 * (y * w + x);
            if (rgba[o + 2] - rgba[o] > 50) ++ink;
          }
        meshPixels += covered;
        inkPixels += ink;
        if (covered === block * block) {
          ++blocks;
          if (ink > 0) ++inked;
        }
      }
    return { coverage: blocks ? inked / blocks : 0, blocks, ink: meshPixels ? inkPixels / meshPixels : 0, meshPixels,
             glyphs: view.cells.count, faces: e.faces };
  }, block);
}
