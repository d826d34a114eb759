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
    first, typed, typedMs, sliders, compilesBefore, compilesAfter,
    shared: reopened === scene, addressLength: address.length, broken,
    errors: logs.filter((l) => /error/i.test(l)),
  }));
} catch (e) {
  console.error(String(e.message ?? e));
  code = 1;
} finally {
  await browser.close();
  server.close();
}
process.exit(code);
