// Renders scenes with the WebGPU host page in headless Chromium (WebGPU on SwiftShader) and
// writes their RGBA8 pixels: what runtime/tests/browser.rs compares with `sdfc render`.
//
//   node webgpu-render.mjs SCENE_DIR JOBS_JSON OUT_DIR LIVE_NAME
//
// JOBS_JSON is a list of {name, width, height, values, refused}: each draws NAME.wgsl with
// NAME.json (`sdfc emit --entry library --manifest`, in SCENE_DIR) into OUT_DIR/I.rgba (rows
// with y down), or, where `refused` is set, must fail to draw (it prints "refused NAME: why"). Then the live page is opened on LIVE_NAME: sliders, frames, a drag. The page and
// host.js are served from ../webgpu. CHROME names the browser (default
// /usr/bin/chromium-headless-shell).
import fs from "node:fs";
import { hostDir, launch, serve } from "./browser.mjs";

const [sceneDir, jobsJson, outDir, name] = process.argv.slice(2);
const { server, port } = await serve(hostDir("webgpu"), sceneDir);
const browser = await launch();
let code = 0;
try {
  const page = await browser.newPage();
  const logs = [];
  page.on("console", (m) => logs.push(m.text()));
  page.on("pageerror", (e) => logs.push(String(e)));
  await page.goto(`http://127.0.0.1:${port}/index.html?test`);
  const jobs = JSON.parse(jobsJson);
  for (const [i, job] of jobs.entries()) {
    const drawn = await page.evaluate(
      async (job) => {
        const host = await import("./host.js");
        try {
          const px = await host.renderPixels(`scene/${job.name}`, job.width, job.height, job.values ?? {});
          return { pixels: Array.from(px) };
        } catch (e) {
          return { refused: String(e.message ?? e) };
        }
      },
      job,
    );
    // A job marked `refused` must be refused by the page (no picture drawn), and only it.
    if (drawn.refused && job.refused) console.log(`refused ${job.name}: ${drawn.refused}`);
    else if (drawn.refused) throw new Error(`${job.name}: ${drawn.refused}`);
    else if (job.refused) throw new Error(`${job.name}: drawn, but should have been refused`);
    else fs.writeFileSync(`${outDir}/${i}.rgba`, Buffer.from(drawn.pixels));
  }
  const adapter = await page.evaluate(async () => {
    const a = await navigator.gpu.requestAdapter();
    return a?.info ? `${a.info.vendor} ${a.info.architecture} ${a.info.description}`.trim() : "unknown";
  });
  console.log(`rendered ${jobs.length} pictures with WebGPU (${adapter})`);
  // The interactive page on the same scene: a slider per parameter component, frames drawn,
  // no error shown, and dragging turns the camera (the picture changes).
  const live = await browser.newPage();
  live.on("pageerror", (e) => logs.push(String(e)));
  await live.setViewport({ width: 1280, height: 700 });
  await live.goto(`http://127.0.0.1:${port}/index.html?scene=scene/${name}`);
  await live.waitForFunction(() => document.querySelectorAll("input[type=range]").length > 0 || document.getElementById("status").textContent, { timeout: 20000 });
  await live.waitForFunction(() => window.sdfcLive && window.sdfcLive.frames > 2, { timeout: 20000 });
  const before = await live.evaluate(() => window.sdfcLive.eye);
  await live.mouse.move(400, 300);
  await live.mouse.down();
  await live.mouse.move(600, 320, { steps: 5 });
  await live.mouse.up();
  const drawn = await live.evaluate(() => window.sdfcLive.frames);
  await live.waitForFunction((n) => window.sdfcLive.frames > n + 2, { timeout: 20000 }, drawn);
  const after = await live.evaluate(() => window.sdfcLive.eye);
  const sliders = await live.evaluate(() => document.querySelectorAll("input[type=range]").length);
  const status = await live.evaluate(() => document.getElementById("status").textContent);
  console.log(`page: sliders=${sliders} status=${JSON.stringify(status)} dragged=${JSON.stringify(before) !== JSON.stringify(after)} errors=${JSON.stringify(logs.filter((l) => /error/i.test(l)))}`);
} catch (e) {
  console.error(String(e.message ?? e));
  code = 1;
} finally {
  await browser.close();
  server.close();
}
process.exit(code);
