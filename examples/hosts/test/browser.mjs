// What every host test here shares: headless Chromium (WebGPU on SwiftShader, WebGL2 through
// ANGLE on SwiftShader) and a local server for a host page and a scene's files.
import puppeteer from "puppeteer-core";
import http from "node:http";
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";

/** The folder of a host page (`webgpu`, `webgl2`) beside this one. */
export const hostDir = (name) => path.join(path.dirname(path.dirname(fileURLToPath(import.meta.url))), name);

const types = {
  ".html": "text/html",
  ".js": "text/javascript",
  ".json": "application/json",
  ".glb": "model/gltf-binary",
  ".r32f": "application/octet-stream",
};

/**
 * Serves `pageDir`'s files at `/NAME` and `sceneDir`'s at `/scene/NAME`, and for each `PREFIX`
 * of `trees` the folder it names with its subfolders (`/three/build/three.module.js`); resolves
 * to the port. Anything else is a blank page.
 */
export async function serve(pageDir, sceneDir, trees = {}) {
  const server = http.createServer((req, res) => {
    const url = decodeURIComponent(new URL(req.url, "http://x").pathname);
    const tree = Object.keys(trees).find((prefix) => url.startsWith(prefix));
    const file = tree
      ? path.join(trees[tree], path.normalize("/" + url.slice(tree.length)))
      : url.startsWith("/scene/")
      ? sceneDir && path.join(sceneDir, path.basename(url))
      : pageDir && path.join(pageDir, path.basename(url === "/" ? "index.html" : url));
    if (!file) {
      res.writeHead(200, { "content-type": "text/html" });
      res.end("<!doctype html><title>sdfc</title>");
      return;
    }
    fs.readFile(file, (err, data) => {
      if (err) {
        res.writeHead(404);
        res.end();
        return;
      }
      res.writeHead(200, { "content-type": types[path.extname(file)] ?? "text/plain" });
      res.end(data);
    });
  });
  await new Promise((ok) => server.listen(0, "127.0.0.1", ok));
  return { server, port: server.address().port };
}

/** Headless Chromium with WebGPU and WebGL2 on SwiftShader; CHROME names the browser. */
export function launch() {
  return puppeteer.launch({
    executablePath: process.env.CHROME ?? "/usr/bin/chromium-headless-shell",
    headless: "shell",
    args: [
      "--no-sandbox",
      "--enable-unsafe-webgpu",
      "--enable-features=Vulkan",
      "--use-angle=swiftshader",
      "--use-webgpu-adapter=swiftshader",
      "--enable-unsafe-swiftshader",
    ],
  });
}
