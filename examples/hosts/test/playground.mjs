// The playground (target/web, built by scripts/build_web.sh) in headless Chromium: types a
// scene into it character by character, then a typo, moves a slider, shares the scene and
// reopens it; prints one JSON object of what happened and writes the pictures (RGBA8, y down):
//
//   node playground.mjs WEB_DIR SCENE_FILE TYPO_FILE OUT_DIR WIDTH HEIGHT [no-webgpu]
//
// With `no-webgpu` the pages have no `navigator.gpu` (a browser without WebGPU): the playground
// falls back to WebGL2.
// OUT_DIR/typed.rgba: the typed scene from its own camera; OUT_DIR/slid.rgba: after its first
// slider moved to its maximum. CHROME names the browser.
import fs from "node:fs";
import path from "node:path";
import { launch, serve } from "./browser.mjs";

const [webDir, sceneFile, typoFile, outDir, width, height, mode] = process.argv.slice(2);
const [w, h] = [Number(width), Number(height)];
const { server, port } = await serve(webDir, null, { "/examples/": path.join(webDir, "examples") });
const browser = await launch();
let code = 0;
const logs = [];
/** Waits until the page compiled `text` (and drew, when it compiles). */
const compiled = (page, text) =>
  page.waitForFunction(
    (t) => window.sdfcPlayground?.compiledText === t && (!window.sdfcPlayground.ok || window.sdfcPlayground.frames > 0),
    { timeout: 60000 },
    text,
  );
/** Replaces the editor's text by typing `text` key by key. */
async function type(page, text) {
  await page.$eval("#source", (el) => (el.value = ""));
  await page.focus("#source");
  await page.keyboard.type(text);
  await compiled(page, text);
}
/** A page, without WebGPU when asked. */
async function newPage() {
  const page = await browser.newPage();
  if (mode === "no-webgpu") {
    await page.evaluateOnNewDocument(() => Object.defineProperty(Navigator.prototype, "gpu", { get: () => undefined }));
  }
  return page;
}
try {
  const page = await newPage();
  page.on("console", (m) => logs.push(m.text()));
  page.on("pageerror", (e) => logs.push(String(e)));
  await page.goto(`http://127.0.0.1:${port}/index.html`);
  await page.waitForFunction(() => window.sdfcPlayground?.compiles > 0, { timeout: 60000 });
  const first = await page.evaluate(() => ({ ok: window.sdfcPlayground.ok, frames: window.sdfcPlayground.frames, renderer: window.sdfcPlayground.renderer }));

  const scene = fs.readFileSync(sceneFile, "utf8");
  const t0 = Date.now();
  await type(page, scene);
  const typedMs = Date.now() - t0;
  const typed = await page.evaluate(() => ({ ok: window.sdfcPlayground.ok, compiles: window.sdfcPlayground.compiles, diagnostics: window.sdfcPlayground.diagnostics }));
  fs.writeFileSync(`${outDir}/typed.rgba`, Buffer.from(await page.evaluate((w, h) => window.sdfcPlayground.pixels(w, h), w, h)));

  // Measured, not asserted: from a keystroke (a space at the end) to the first frame of the
  // scene it makes (the 120 ms pause, the compile, the first draw), and the frame rate while
  // orbiting (the canvas at 640×360, two seconds of dragging).
  const latencies = [];
  for (let k = 0; k < 3; k++) {
    const text = await page.$eval("#source", (el) => el.value);
    const t = Date.now();
    await page.keyboard.type(" ");
    await page.waitForFunction(
      (t) => window.sdfcPlayground.compiledText === t && window.sdfcPlayground.framesAtCompile !== undefined && window.sdfcPlayground.frames > window.sdfcPlayground.framesAtCompile,
      { timeout: 20000 },
      text + " ",
    );
    latencies.push(Date.now() - t);
  }
  await page.$eval("#source", (el) => (el.value = el.value.trimEnd() + "\n"));
  await page.$eval("#source", (el) => el.dispatchEvent(new Event("input")));
  await compiled(page, scene);
  const box = await (await page.$("#picture")).boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  const [f0, start] = [await page.evaluate(() => window.sdfcPlayground.frames), Date.now()];
  for (let k = 0; k < 40; k++) {
    await page.mouse.move(box.x + box.width / 2 + 4 * k, box.y + box.height / 2 + (k % 7));
    await new Promise((ok) => setTimeout(ok, 50));
  }
  const [f1, t1] = [await page.evaluate(() => window.sdfcPlayground.frames), Date.now()];
  await page.mouse.up();
  const orbitFps = (1000 * (f1 - f0)) / (t1 - start);
  // Back to the scene's own camera for the pictures.
  await page.click("#picture", { clickCount: 2 });

  // A slider: moved to its maximum, the picture changes and nothing is compiled.
  const compilesBefore = await page.evaluate(() => window.sdfcPlayground.compiles);
  const sliders = await page.$$eval("#sliders input", (all) => {
    if (all.length === 0) return 0;
    all[0].value = all[0].max;
    all[0].dispatchEvent(new Event("input"));
    return all.length;
  });
  fs.writeFileSync(`${outDir}/slid.rgba`, Buffer.from(await page.evaluate((w, h) => window.sdfcPlayground.pixels(w, h), w, h)));
  const compilesAfter = await page.evaluate(() => window.sdfcPlayground.compiles);

  // Share: the address carries the scene; a new page opened on it has the same text.
  await page.click("#share");
  await page.waitForFunction(() => location.hash.startsWith("#s="), { timeout: 10000 });
  const address = await page.evaluate(() => location.href);
  const other = await newPage();
  other.on("pageerror", (e) => logs.push(String(e)));
  await other.goto(address);
  await other.waitForFunction(() => window.sdfcPlayground?.compiles > 0, { timeout: 60000 });
  const reopened = await other.$eval("#source", (el) => el.value);

  // A typo: the diagnostics the page lists.
  const typo = fs.readFileSync(typoFile, "utf8");
  await type(page, typo);
  const broken = await page.evaluate(() => ({
    ok: window.sdfcPlayground.ok,
    diagnostics: window.sdfcPlayground.diagnostics,
    shown: document.getElementById("diagnostics").textContent,
    frames: window.sdfcPlayground.frames,
  }));
  console.log(JSON.stringify({
    first, typed, typedMs, latencies, orbitFps, sliders, compilesBefore, compilesAfter,
    shared: reopened === scene, addressLength: address.length, broken,
    errors: logs.filter((l) => /error/i.test(l)),
    glErrors: await page.evaluate(() => window.sdfcPlayground.glErrors.slice(0, 5)),
  }));
} catch (e) {
  console.error(String(e.message ?? e));
  code = 1;
} finally {
  await browser.close();
  server.close();
}
process.exit(code);
