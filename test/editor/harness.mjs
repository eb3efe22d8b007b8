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
