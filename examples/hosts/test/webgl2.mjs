// Compiles and draws sdfc's GLSL ES 3.00 in headless Chromium's WebGL2 (ANGLE on SwiftShader):
// what runtime/tests/browser.rs checks against `sdfc render`.
//
//   node webgl2.mjs compile DIR
//     Every DIR/*.frag (a fragment entry, or a library with its placeholder main) is compiled
//     and linked with a full-screen triangle; every DIR/*.shadertoy.glsl inside Shadertoy's
//     prelude and main. One line per file (`ok NAME` or `error NAME: log`), then a summary;
//     exit 1 if any was refused.
//   node webgl2.mjs render SCENE_DIR JOBS_JSON OUT_DIR
//     JOBS_JSON is a list of {name, width, height, values, target, yUp, kind}: kind "fragment"
//     draws NAME.frag, "library" NAME.glsl (both with NAME.json, by ../webgl2/host.js),
//     "shadertoy" NAME.shadertoy.glsl at iTime = `time` and iMouse = 0. Writes OUT_DIR/I.rgba,
//     RGBA8 rows with y down.
// CHROME names the browser (default /usr/bin/chromium-headless-shell).
import fs from "node:fs";
import path from "node:path";
import { hostDir, launch, serve } from "./browser.mjs";

const SHADERTOY_PRELUDE = `#version 300 es
precision highp float;
precision highp int;
uniform vec3 iResolution;
uniform float iTime;
uniform vec4 iMouse;
out vec4 shadertoy_color;
`;
const SHADERTOY_MAIN = "\nvoid main() { mainImage(shadertoy_color, gl_FragCoord.xy); }\n";

const [mode, ...rest] = process.argv.slice(2);
const sceneDir = rest[0];
const { server, port } = await serve(hostDir("webgl2"), sceneDir);
const browser = await launch();
let failed = 0;
try {
  const page = await browser.newPage();
  const logs = [];
  page.on("pageerror", (e) => logs.push(String(e)));
  await page.goto(`http://127.0.0.1:${port}/index.html?test`);
  const renderer = await page.evaluate(() => {
    const gl = document.createElement("canvas").getContext("webgl2");
    if (!gl) return null;
    const info = gl.getExtension("WEBGL_debug_renderer_info");
    return info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
  });
  if (!renderer) throw new Error("no WebGL2 in this browser");
  if (mode === "compile") {
    const files = fs.readdirSync(sceneDir).filter((f) => f.endsWith(".frag") || f.endsWith(".shadertoy.glsl")).sort();
    for (const name of files) {
      let code = fs.readFileSync(path.join(sceneDir, name), "utf8");
      if (name.endsWith(".shadertoy.glsl")) code = SHADERTOY_PRELUDE + code + SHADERTOY_MAIN;
      const said = await page.evaluate(async (code) => {
        const { link } = await import("./host.js");
        const gl = document.createElement("canvas").getContext("webgl2");
        try {
          link(gl, code);
          return null;
        } catch (e) {
          return String(e.message ?? e);
        }
      }, code);
      if (said) {
        failed += 1;
        console.log(`error ${name}: ${said.replace(/\s+/g, " ").slice(0, 400)}`);
      } else {
        console.log(`ok ${name}`);
      }
    }
    console.log(`compiled and linked ${files.length} shaders with Chrome's WebGL2 (${renderer}): ${failed} refused`);
  } else if (mode === "render") {
    const [, jobsJson, outDir] = rest;
    const jobs = JSON.parse(jobsJson);
    for (const [i, job] of jobs.entries()) {
      let pixels;
      if (job.kind === "shadertoy") {
        const code = SHADERTOY_PRELUDE + fs.readFileSync(path.join(sceneDir, `${job.name}.shadertoy.glsl`), "utf8") + SHADERTOY_MAIN;
        pixels = await page.evaluate(async (code, w, h, time) => {
          const { link } = await import("./host.js");
          const canvas = document.createElement("canvas");
          const gl = canvas.getContext("webgl2");
          const p = link(gl, code);
          const fbo = gl.createFramebuffer();
          gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
          const rb = gl.createRenderbuffer();
          gl.bindRenderbuffer(gl.RENDERBUFFER, rb);
          gl.renderbufferStorage(gl.RENDERBUFFER, gl.RGBA8, w, h);
          gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.RENDERBUFFER, rb);
          gl.useProgram(p);
          gl.uniform3f(gl.getUniformLocation(p, "iResolution"), w, h, 1);
          gl.uniform1f(gl.getUniformLocation(p, "iTime"), time);
          gl.uniform4f(gl.getUniformLocation(p, "iMouse"), 0, 0, 0, 0);
          gl.viewport(0, 0, w, h);
          gl.drawArrays(gl.TRIANGLES, 0, 3);
          const raw = new Uint8Array(4 * w * h);
          gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, raw);
          const out = new Uint8Array(raw.length);
          for (let y = 0; y < h; y++) out.set(raw.subarray(4 * w * (h - 1 - y), 4 * w * (h - y)), 4 * w * y);
          return Array.from(out);
        }, code, job.width, job.height, job.time ?? 0);
      } else {
        pixels = await page.evaluate(
          async (job) => {
            const { renderPixels } = await import("./host.js");
            const px = await renderPixels(`scene/${job.name}`, job.width, job.height, job.values ?? {}, {
              target: job.target ?? "rgba8",
              yUp: job.yUp ?? true,
              library: job.kind === "library",
            });
            return Array.from(px);
          },
          job,
        );
      }
      fs.writeFileSync(path.join(outDir, `${i}.rgba`), Buffer.from(pixels));
    }
    console.log(`rendered ${jobs.length} pictures with Chrome's WebGL2 (${renderer})`);
    if (logs.length) throw new Error(logs.join("\n"));
  } else {
    throw new Error(`unknown mode ${mode}`);
  }
} catch (e) {
  console.error(String(e.message ?? e));
  failed = -1;
} finally {
  await browser.close();
  server.close();
}
process.exit(failed === 0 ? 0 : 1);
