// Compiles WGSL modules with Chrome's own WebGPU (Tint, then SwiftShader's pipeline compiler)
// in headless Chromium: what runtime/tests/browser.rs checks for every emitted module.
//
//   node webgpu-compile.mjs DIR
//
// Every DIR/*.wgsl is given to `createShaderModule` and its `getCompilationInfo` read; a file
// named *.compute.wgsl or *.trace.wgsl is also made a compute pipeline of its `main`, and a
// *.fragment.wgsl a render pipeline of a full-screen triangle and its `main` (rgba8unorm).
// Prints one line per file (`ok NAME` or `error NAME: message`) and a summary; exits 1 if any
// file was refused. CHROME names the browser (default /usr/bin/chromium-headless-shell).
import fs from "node:fs";
import path from "node:path";
import { launch, serve } from "./browser.mjs";

const [dir] = process.argv.slice(2);
const files = fs.readdirSync(dir).filter((f) => f.endsWith(".wgsl")).sort();
const { server, port } = await serve(null, null);
const browser = await launch();
let refused = 0;
try {
  const page = await browser.newPage();
  await page.goto(`http://127.0.0.1:${port}/`);
  await page.evaluate(async () => {
    const adapter = await navigator.gpu.requestAdapter();
    window.device = await adapter.requestDevice({
      requiredLimits: { maxStorageBuffersPerShaderStage: adapter.limits.maxStorageBuffersPerShaderStage },
    });
  });
  for (const name of files) {
    const code = fs.readFileSync(path.join(dir, name), "utf8");
    const kind = name.endsWith(".fragment.wgsl") ? "fragment" : /\.(compute|trace)\.wgsl$/.test(name) ? "compute" : "library";
    const said = await page.evaluate(
      async (code, kind) => {
        const device = window.device;
        device.pushErrorScope("validation");
        const module = device.createShaderModule({ code });
        const info = await module.getCompilationInfo();
        const errors = info.messages.filter((m) => m.type === "error").map((m) => `${m.lineNum}:${m.linePos} ${m.message}`);
        try {
          if (kind === "compute") {
            await device.createComputePipelineAsync({ layout: "auto", compute: { module, entryPoint: "main" } });
          } else if (kind === "fragment") {
            const vs = device.createShaderModule({
              code: "@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> { let p = vec2<f32>(f32(i & 1u) * 4.0 - 1.0, f32(i >> 1u) * 4.0 - 1.0); return vec4<f32>(p, 0.0, 1.0); }",
            });
            await device.createRenderPipelineAsync({
              layout: "auto",
              vertex: { module: vs, entryPoint: "vs" },
              fragment: { module, entryPoint: "main", targets: [{ format: "rgba8unorm" }] },
            });
          }
        } catch (e) {
          errors.push(String(e.message ?? e));
        }
        const scope = await device.popErrorScope();
        if (scope) errors.push(scope.message);
        return errors;
      },
      code,
      kind,
    );
    if (said.length) {
      refused += 1;
      console.log(`error ${name}: ${said.join(" | ").slice(0, 400)}`);
    } else {
      console.log(`ok ${name}`);
    }
  }
  const adapter = await page.evaluate(async () => {
    const a = await navigator.gpu.requestAdapter();
    return a?.info ? `${a.info.vendor} ${a.info.architecture}`.trim() : "unknown";
  });
  console.log(`compiled ${files.length} modules with Chrome's WebGPU (${adapter}): ${refused} refused`);
} catch (e) {
  console.error(String(e.message ?? e));
  refused = -1;
} finally {
  await browser.close();
  server.close();
}
process.exit(refused === 0 ? 0 : 1);
