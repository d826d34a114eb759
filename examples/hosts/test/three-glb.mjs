// Loads a glTF file with three.js's GLTFLoader in headless Chromium (WebGL2 through ANGLE on
// SwiftShader) on the page examples/hosts/three/index.html, drawn lit from above with its
// materials, and saves a screenshot: a mesh from `sdfc mesh` read and drawn by a tool that is
// not sdfc's.
//
//   node three-glb.mjs MODEL.glb OUT.png [WIDTH HEIGHT]
//
// Prints one JSON line: the triangles and materials three.js loaded, the model's box, and how
// many pixels differ from the background. Exit 1 if the page failed.
import path from "node:path";
import { fileURLToPath } from "node:url";
import { hostDir, launch, serve } from "./browser.mjs";

const [model, out, width = "800", height = "500"] = process.argv.slice(2);
const here = path.dirname(fileURLToPath(import.meta.url));

const { server, port } = await serve(hostDir("three"), path.dirname(path.resolve(model)), {
  "/three/": path.join(here, "node_modules/three"),
});
const browser = await launch();
let status = 0;
try {
  const tab = await browser.newPage();
  const errors = [];
  tab.on("pageerror", (e) => errors.push(String(e)));
  await tab.setViewport({ width: Number(width), height: Number(height) });
  const query = new URLSearchParams({ model: path.basename(model), w: width, h: height });
  await tab.goto(`http://127.0.0.1:${port}/index.html?${query}`);
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
