// The playground (target/web, built by scripts/build_web.sh) in headless Chromium: types a
// scene into its editor character by character (the editor indents), then a typo, moves a
// slider, sets the tracer's steps, shares the scene and reopens it; prints one JSON object of
// what happened and writes the pictures (RGBA8, y down):
//
//   node playground.mjs WEB SCENE_FILE TYPO_FILE CLAIM_FILE TINT_FILE OUT_DIR WIDTH HEIGHT [no-webgpu]
//
// WEB: the page's address (`sdfc serve` serving target/web), or the folder to serve here.
// With `no-webgpu` the pages have no `navigator.gpu` (a browser without WebGPU): the playground
// falls back to WebGL2.
// OUT_DIR/typed.rgba: the typed scene from its own camera; OUT_DIR/slid.rgba: after its first
// slider moved to its maximum; OUT_DIR/tuned.rgba: then with the tracer panel's steps set to 12;
// OUT_DIR/tinted.rgba: TINT_FILE with its colour picker set to #20c040; OUT_DIR/baked.rgba: the
// `baked` example from the menu.
// CHROME names the browser.
import fs from "node:fs";
import path from "node:path";
import { launch, serve } from "./browser.mjs";

const [web, sceneFile, typoFile, claimFile, tintFile, outDir, width, height, mode] = process.argv.slice(2);
const [w, h] = [Number(width), Number(height)];
const { server, port } = web.startsWith("http")
  ? { server: null, port: null }
  : await serve(web, null, { "/examples/": path.join(web, "examples") });
const home = port ? `http://127.0.0.1:${port}/index.html` : web;
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
/** The editor's text. */
const text = (page) => page.evaluate(() => window.sdfcPlayground.editor.text());
/**
 * Replaces the editor's text by typing `scene` key by key, each line without its indentation
 * (the editor's own, as a user's Enter and `}` get it); waits until the page compiled what the
 * editor then holds, and returns that.
 */
async function type(page, scene) {
  await page.evaluate(() => window.sdfcPlayground.editor.setText(""));
  await page.focus(".cm-content");
  await page.keyboard.type(scene.replace(/^[ \t]+/gm, ""));
  const typed = await text(page);
  await compiled(page, typed);
  return typed;
}
/**
 * Frames a second while dragging the camera for about two seconds, and the canvas's scale and
 * coarse frames counted then.
 */
async function orbitRate(page) {
  const box = await (await page.$("#picture")).boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  const [f0, start] = [await page.evaluate(() => window.sdfcPlayground.frames), Date.now()];
  for (let k = 0; k < 100; k++) {
    await page.mouse.move(box.x + box.width / 2 + 2 * k, box.y + box.height / 2 + (k % 7));
    await new Promise((ok) => setTimeout(ok, 15));
  }
  const [f1, t1] = [await page.evaluate(() => window.sdfcPlayground.frames), Date.now()];
  const whileMoving = await page.evaluate(() => ({ scale: window.sdfcPlayground.scale, coarseFrames: window.sdfcPlayground.coarseFrames }));
  await page.mouse.up();
  return { fps: (1000 * (f1 - f0)) / (t1 - start), whileMoving };
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
  await page.goto(home);
  await page.waitForFunction(() => window.sdfcPlayground?.compiles > 0, { timeout: 60000 });
  const first = await page.evaluate(() => ({ ok: window.sdfcPlayground.ok, frames: window.sdfcPlayground.frames, renderer: window.sdfcPlayground.renderer }));

  const scene = fs.readFileSync(sceneFile, "utf8");
  const t0 = Date.now();
  const typedText = await type(page, scene);
  const typedMs = Date.now() - t0;
  const typed = await page.evaluate(() => ({ ok: window.sdfcPlayground.ok, compiles: window.sdfcPlayground.compiles, diagnostics: window.sdfcPlayground.diagnostics }));
  fs.writeFileSync(`${outDir}/typed.rgba`, Buffer.from(await page.evaluate((w, h) => window.sdfcPlayground.pixels(w, h), w, h)));

  // Measured, not asserted: from a keystroke (a space at the end) to the first frame of the
  // scene it makes (the 120 ms pause, the compile, the first draw), and the frame rate while
  // orbiting (the canvas at 640×360, two seconds of dragging).
  const latencies = [];
  for (let k = 0; k < 3; k++) {
    const before = await text(page);
    const t = Date.now();
    await page.keyboard.type(" ");
    await page.waitForFunction(
      (t) => window.sdfcPlayground.compiledText === t && window.sdfcPlayground.framesAtCompile !== undefined && window.sdfcPlayground.frames > window.sdfcPlayground.framesAtCompile,
      { timeout: 20000 },
      before + " ",
    );
    latencies.push(Date.now() - t);
  }
  await page.evaluate((t) => window.sdfcPlayground.editor.setText(t), scene);
  await compiled(page, scene);
  const { fps: orbitFps, whileMoving } = await orbitRate(page);
  // Progressive refinement: once the camera stops, the full picture.
  await page.waitForFunction(() => window.sdfcPlayground.scale === 1, { timeout: 20000 });
  const refined = await page.evaluate(() => [document.getElementById("picture").width, document.getElementById("picture").height]);
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

  // The tracer panel: 12 steps instead of the scene's, compiled again.
  await page.$eval("#tracer input[name=steps]", (el) => {
    el.value = "12";
    el.dispatchEvent(new Event("change"));
  });
  await page.waitForFunction((n) => window.sdfcPlayground.compiles > n && window.sdfcPlayground.frames > window.sdfcPlayground.framesAtCompile, { timeout: 60000 }, compilesAfter);
  fs.writeFileSync(`${outDir}/tuned.rgba`, Buffer.from(await page.evaluate((w, h) => window.sdfcPlayground.pixels(w, h), w, h)));
  const tracer = await page.evaluate(() => window.sdfcPlayground.response.tracer);
  // A value the tracer refuses: the compiler's message, and the picture kept.
  await page.$eval("#tracer input[name=steps]", (el) => {
    el.value = "0";
    el.dispatchEvent(new Event("change"));
  });
  await page.waitForFunction((n) => window.sdfcPlayground.compiles > n + 1, { timeout: 60000 }, compilesAfter);
  const refused = await page.$eval("#diagnostics", (el) => el.textContent);
  await page.click("#tracer button");
  await page.waitForFunction((n) => window.sdfcPlayground.compiles > n + 2 && window.sdfcPlayground.ok, { timeout: 60000 }, compilesAfter);

  // The downloads: the PNG is the canvas's picture.
  const client = await browser.target().createCDPSession();
  await client.send("Browser.setDownloadBehavior", { behavior: "allow", downloadPath: outDir, eventsEnabled: true });
  const downloaded = [];
  for (const [id, name] of [["get-png", "scene.png"], ["get-wgsl", "scene.wgsl"], ["get-glsl", "scene.frag"], ["get-manifest", "scene.json"]]) {
    await page.click(`#${id}`);
    const file = path.join(outDir, name);
    for (let k = 0; k < 100 && !(fs.existsSync(file) && fs.statSync(file).size > 0); k++) await new Promise((ok) => setTimeout(ok, 100));
    downloaded.push(fs.existsSync(file) ? name : `${name} (missing)`);
  }

  // The same orbit at full size throughout (`?full`: no coarse frames), in a page opened on
  // the same scene.
  const full = await newPage();
  await full.goto(home.replace(/\/(index\.html)?$/, "/index.html") + "?full");
  await full.waitForFunction(() => window.sdfcPlayground?.frames > 0, { timeout: 60000 });
  await full.evaluate((t) => window.sdfcPlayground.editor.setText(t), scene);
  await compiled(full, scene);
  const fullOrbit = await orbitRate(full);
  await full.close();

  // Share: the address carries the scene; a new page opened on it has the same text.
  await page.click("#share");
  await page.waitForFunction(() => location.hash.startsWith("#s="), { timeout: 10000 });
  const address = await page.evaluate(() => location.href);
  const other = await newPage();
  other.on("pageerror", (e) => logs.push(String(e)));
  await other.goto(address);
  await other.waitForFunction(() => window.sdfcPlayground?.compiles > 0, { timeout: 60000 });
  const reopened = await text(other);

  // A typo: the diagnostics the page lists.
  const typo = fs.readFileSync(typoFile, "utf8");
  await type(page, typo);
  // Its underline in the editor, and the message shown when the mouse is over it.
  const mark = await page.waitForSelector(".cm-lintRange-error", { timeout: 10000 });
  const underlined = await mark.evaluate((el) => el.textContent);
  const at = await mark.boundingBox();
  await page.mouse.move(at.x + at.width / 2, at.y + at.height / 2);
  const tooltip = await page
    .waitForSelector(".cm-tooltip-lint", { timeout: 10000 })
    .then((t) => t.evaluate((el) => el.textContent))
    .catch(() => null);
  const broken = await page.evaluate(() => ({
    ok: window.sdfcPlayground.ok,
    diagnostics: window.sdfcPlayground.diagnostics,
    shown: document.getElementById("diagnostics").textContent,
    frames: window.sdfcPlayground.frames,
  }));
  // An example from the menu whose scene bakes distance maps: the volumes' bytes come from
  // the compiler in the page.
  const before = await page.evaluate(() => window.sdfcPlayground.compiles);
  await page.select("#examples", "baked");
  await page.waitForFunction((n) => window.sdfcPlayground.compiles > n && window.sdfcPlayground.ok && window.sdfcPlayground.frames > window.sdfcPlayground.framesAtCompile, { timeout: 60000 }, before);
  const baked = await page.evaluate(() => ({ volumes: window.sdfcPlayground.response.volumes.map((v) => v.length), ms: window.sdfcPlayground.compileMs }));
  fs.writeFileSync(`${outDir}/baked.rgba`, Buffer.from(await page.evaluate((w, h) => window.sdfcPlayground.pixels(w, h), w, h)));

  // A claim too small for its shape: the picture comes from the page's compile, the warning
  // from the worker's check after it, as `sdfc check` gives it.
  const claim = fs.readFileSync(claimFile, "utf8");
  await page.evaluate((t) => window.sdfcPlayground.editor.setText(t), claim);
  await compiled(page, claim);
  await page.waitForFunction((t) => window.sdfcPlayground.verified === t, { timeout: 60000 }, claim);
  const claimed = await page.evaluate(() => ({ diagnostics: window.sdfcPlayground.diagnostics, ms: window.sdfcPlayground.verifyMs, marks: document.querySelectorAll(".cm-lintRange-warning").length }));

  // A colour parameter's picker: green instead of the default, no compile.
  const tinted = fs.readFileSync(tintFile, "utf8");
  await page.evaluate((t) => window.sdfcPlayground.editor.setText(t), tinted);
  await compiled(page, tinted);
  const tintCompiles = await page.evaluate(() => window.sdfcPlayground.compiles);
  const pickers = await page.$$eval("#sliders input[type=color]", (all) => {
    all[0].value = "#20c040";
    all[0].dispatchEvent(new Event("input"));
    return all.length;
  });
  fs.writeFileSync(`${outDir}/tinted.rgba`, Buffer.from(await page.evaluate((w, h) => window.sdfcPlayground.pixels(w, h), w, h)));
  const tint = { pickers, compiled: (await page.evaluate(() => window.sdfcPlayground.compiles)) - tintCompiles };

  // A scene of many parts (OUT_DIR/data.sdf, WebGPU only): compiled to the data form, its
  // buffers made by the compiler in the page, and made again when its slider moves a part.
  let data = null;
  if (mode === "webgpu" && fs.existsSync(`${outDir}/data.sdf`)) {
    const many = fs.readFileSync(`${outDir}/data.sdf`, "utf8");
    await page.evaluate((t) => window.sdfcPlayground.editor.setText(t), many);
    await compiled(page, many);
    const dataCompiles = await page.evaluate(() => window.sdfcPlayground.compiles);
    fs.writeFileSync(`${outDir}/data0.rgba`, Buffer.from(await page.evaluate((w, h) => window.sdfcPlayground.pixels(w, h), w, h)));
    // (A download's compile in between, inline GLSL, must leave the drawn scene's buffers.)
    await page.evaluate((t) => window.sdfcPlayground.sdfc.compile({ source: t, name: "scene.sdf", target: "glsl", entry: "fragment", form: "inline" }), many);
    const framesBefore = await page.evaluate(() => window.sdfcPlayground.frames);
    await page.$$eval("#sliders input[type=range]", (all) => {
      all[0].value = all[0].max;
      all[0].dispatchEvent(new Event("input"));
    });
    await page.waitForFunction((n) => window.sdfcPlayground.frames > n, { timeout: 60000 }, framesBefore);
    fs.writeFileSync(`${outDir}/data1.rgba`, Buffer.from(await page.evaluate((w, h) => window.sdfcPlayground.pixels(w, h), w, h)));
    data = {
      form: await page.evaluate(() => Boolean(window.sdfcPlayground.response.manifest.data)),
      follows: await page.evaluate(() => window.sdfcPlayground.response.manifest.data?.follows ?? []),
      compiled: (await page.evaluate(() => window.sdfcPlayground.compiles)) - dataCompiles,
      // The live canvas's host: how many times its device pruned the cells, how many of those
      // found no room (made in WebAssembly instead), and the last pre-pass's time.
      prune: await page.evaluate(() => window.sdfcPlayground.host?.stats ?? null),
      ok: await page.evaluate(() => window.sdfcPlayground.ok),
    };
  }

  // Compile time in the page for every example (the picture's compile, as each keystroke
  // makes it; the claims' check is the worker's): measured, not asserted.
  const examples = await page.evaluate(async () => {
    const out = {};
    for (const o of document.querySelectorAll("#examples option")) {
      if (!o.value) continue;
      const text = await (await fetch(`examples/${o.value}.sdf`)).text();
      const times = [];
      for (let k = 0; k < 3; k++) {
        const t0 = performance.now();
        window.sdfcPlayground.sdfc.compile({ source: text, name: "scene.sdf", target: "wgsl", entry: "library", annotations: "later" });
        times.push(performance.now() - t0);
      }
      out[o.value] = times.map((t) => Math.round(t * 10) / 10);
    }
    return out;
  });

  console.log(JSON.stringify({
    claimed, examples, tint,
    baked, data,
    first, typed, typedMs, indented: typedText === scene, latencies, orbitFps, whileMoving, refined,
    fullOrbitFps: fullOrbit.fps, fullOrbitScale: fullOrbit.whileMoving.scale,
    sliders, compilesBefore, compilesAfter, tracer, refused, downloaded,
    shared: reopened === scene, addressLength: address.length, broken, underlined, tooltip,
    errors: logs.filter((l) => /error/i.test(l)),
    glErrors: await page.evaluate(() => window.sdfcPlayground.glErrors.slice(0, 5)),
  }));
} catch (e) {
  console.error(String(e.message ?? e));
  code = 1;
} finally {
  await browser.close();
  server?.close();
}
process.exit(code);
