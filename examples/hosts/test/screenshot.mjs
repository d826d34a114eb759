// A screenshot of the playground (target/web) for the README: an example chosen from its menu,
// drawn with WebGL2 (headless Chromium's screenshots show a WebGPU canvas blank):
//
//   node screenshot.mjs WEB_DIR EXAMPLE OUT.png
import path from "node:path";
import { launch, serve } from "./browser.mjs";

const [web, example, out] = process.argv.slice(2);
const { server, port } = await serve(web, null, { "/examples/": path.join(web, "examples") });
const browser = await launch();
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 640 });
  await page.goto(`http://127.0.0.1:${port}/index.html?webgl2`);
  await page.waitForFunction(() => window.sdfcPlayground?.compiles > 0, { timeout: 60000 });
  const before = await page.evaluate(() => window.sdfcPlayground.compiles);
  await page.select("#examples", example);
  await page.waitForFunction((n) => window.sdfcPlayground.compiles > n && window.sdfcPlayground.frames > window.sdfcPlayground.framesAtCompile, { timeout: 60000 }, before);
  await new Promise((ok) => setTimeout(ok, 1500));
  await page.screenshot({ path: out });
} finally {
  await browser.close();
  server.close();
}
