// Loads a glTF file with three.js's GLTFLoader in headless Chromium (WebGL2 through ANGLE on
// SwiftShader), draws it lit from above with its materials, and saves a screenshot: a mesh
// from `sdfc mesh` read and drawn by a tool that is not sdfc's.
//
//   node three-glb.mjs MODEL.glb OUT.png [WIDTH HEIGHT]
//
// Prints one JSON line: the triangles and materials three.js loaded, the model's box, and how
// many pixels differ from the background. Exit 1 if the page failed.
import http from "node:http";
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";
import { launch } from "./browser.mjs";

const [model, out, width = "800", height = "500"] = process.argv.slice(2);
const here = path.dirname(fileURLToPath(import.meta.url));
const three = path.join(here, "node_modules/three");

const page = `<!doctype html>
<meta charset="utf-8"><title>sdfc mesh in three.js</title>
<style>html, body { margin: 0; background: #1e2230; }</style>
<script type="importmap">
{ "imports": { "three": "/three/build/three.module.js", "three/addons/": "/three/examples/jsm/" } }
</script>
<script type="module">
import * as THREE from "three";
import { GLTFLoader } from "three/addons/loaders/GLTFLoader.js";
const [w, h] = [${Number(width)}, ${Number(height)}];
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setSize(w, h);
renderer.setClearColor(0x1e2230);
document.body.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 1.2));
const sun = new THREE.DirectionalLight(0xffffff, 2.0);
sun.position.set(-0.5, 1, 0.6);
scene.add(sun);
new GLTFLoader().load("/model.glb", (gltf) => {
  scene.add(gltf.scene);
  const box = new THREE.Box3().setFromObject(gltf.scene);
  const size = box.getSize(new THREE.Vector3());
  const centre = box.getCenter(new THREE.Vector3());
  const camera = new THREE.PerspectiveCamera(35, w / h, 0.001 * size.length(), 100 * size.length());
  const d = 1.1 * size.length();
  // From the side sdfc's scenes are usually seen from: negative z, looking along +z.
  camera.position.copy(centre).add(new THREE.Vector3(0.55 * d, 0.45 * d, -0.9 * d));
  camera.lookAt(centre);
  renderer.render(scene, camera);
  let triangles = 0;
  const materials = new Set();
  gltf.scene.traverse((o) => {
    if (o.isMesh) {
      triangles += o.geometry.index ? o.geometry.index.count / 3 : o.geometry.attributes.position.count / 3;
      materials.add(o.material.name);
    }
  });
  window.result = { triangles, materials: [...materials], box: [box.min.toArray(), box.max.toArray()] };
}, undefined, (e) => { window.result = { error: String(e) }; });
</script>`;

const server = http.createServer((req, res) => {
  const url = decodeURIComponent(new URL(req.url, "http://x").pathname);
  let file = null;
  let type = "application/octet-stream";
  if (url === "/") {
    res.writeHead(200, { "content-type": "text/html" });
    res.end(page);
    return;
  } else if (url === "/model.glb") {
    file = model;
    type = "model/gltf-binary";
  } else if (url.startsWith("/three/")) {
    file = path.join(three, path.normalize(url.slice("/three/".length)));
    type = "text/javascript";
  }
  fs.readFile(file ?? "", (err, data) => {
    if (err) {
      res.writeHead(404);
      res.end();
      return;
    }
    res.writeHead(200, { "content-type": type });
    res.end(data);
  });
});
await new Promise((ok) => server.listen(0, "127.0.0.1", ok));
const browser = await launch();
let status = 0;
try {
  const tab = await browser.newPage();
  const errors = [];
  tab.on("pageerror", (e) => errors.push(String(e)));
  await tab.setViewport({ width: Number(width), height: Number(height) });
  await tab.goto(`http://127.0.0.1:${server.address().port}/`);
  await tab.waitForFunction(() => window.result !== undefined, { timeout: 120000 });
  const result = await tab.evaluate(() => window.result);
  const canvas = await tab.$("canvas");
  await canvas.screenshot({ path: out });
  // Pixels that are not the background, read back from the canvas.
  const drawn = await tab.evaluate(() => {
    const c = document.querySelector("canvas");
    const gl = c.getContext("webgl2");
    const px = new Uint8Array(c.width * c.height * 4);
    gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
    let n = 0;
    for (let i = 0; i < px.length; i += 4) {
      if (Math.abs(px[i] - 0x1e) + Math.abs(px[i + 1] - 0x22) + Math.abs(px[i + 2] - 0x30) > 6) n++;
    }
    return n;
  });
  console.log(JSON.stringify({ ...result, drawn, pixels: Number(width) * Number(height), errors }));
  if (result.error || errors.length) status = 1;
} finally {
  await browser.close();
  server.close();
}
process.exit(status);
