// sdfc's playground: the scene's text compiled in this page by the WebAssembly compiler
// (sdfc.mjs) on every edit, drawn with WebGPU by the host page's code (host.js: the library
// entry and its manifest) — or, where WebGPU is missing, with WebGL2 by the WebGL2 host's
// code (host_webgl2.js: the GLSL ES fragment entry) — orbited with the mouse; the compiler's diagnostics listed under the
// text; parameters as sliders; the scene shareable in the address. docs/playground.md.
import { load } from "./sdfc.js";
import { createHostFrom, hostPixels, orbit } from "./host.js";
import * as gl2 from "./host_webgl2.js";

const EXAMPLES = ["baked", "blobs", "composition", "dodecahedron", "domain_ops", "gem", "implicit",
  "jewel", "lamp", "mandelbulb", "primitives", "shapes", "squircle", "temple", "textures",
  "tori_terrain", "village"];
const FIRST = `// Edit me: the picture follows.
camera { eye (3, 2.5, -5)  target (0, 0.6, 0) }
material red { color #d04038 }
smooth_union(0.3) {
  sphere(0.8) at (0, 0.8, 0) : red
  box((1.6, 0.4, 1.6))
}
plane(y, -0.2)
`;

const $ = (id) => document.getElementById(id);
const source = $("source");
const canvas = $("picture");
const status = $("status");

// What the page is doing, for its test (examples/hosts/test/playground.mjs).
const state = (window.sdfcPlayground = { glErrors: [], compiles: 0, ok: false, diagnostics: [], frames: 0, host: null, response: null, compiledText: null });

/** The scene's text from the address (`#s=…`, deflated and base64url), if it carries one. */
async function fromAddress() {
  const m = location.hash.match(/^#s=([A-Za-z0-9_-]+)$/);
  if (!m) return null;
  const b64 = m[1].replace(/-/g, "+").replace(/_/g, "/");
  const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate-raw"));
  return new Response(stream).text();
}

/** The address that carries `text`. */
async function toAddress(text) {
  const stream = new Blob([text]).stream().pipeThrough(new CompressionStream("deflate-raw"));
  const bytes = new Uint8Array(await new Response(stream).arrayBuffer());
  let s = "";
  for (const b of bytes) s += String.fromCharCode(b);
  const b64 = btoa(s).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
  return `${location.origin}${location.pathname}#s=${b64}`;
}

/** A diagnostic as the CLI's one-line form: `file:line:column: severity: message`. */
function line(d) {
  const label = d.label ? ` (${d.label})` : "";
  return `${d.file}:${d.span.line}:${d.span.column}: ${d.severity}: ${d.message}${label}`;
}

/**
 * How the page draws: WebGPU with the library entry in WGSL, or, where WebGPU is missing (or
 * `?webgl2` asks), WebGL2 with the fragment entry in GLSL ES 3.00; `make` a host for a compile's
 * response, `draw` a frame on the canvas, `pixels` the scene's camera offscreen for the tests.
 */
async function makeRenderer() {
  const forced = new URLSearchParams(location.search).has("webgl2");
  const adapter = !forced && navigator.gpu && (await navigator.gpu.requestAdapter());
  if (adapter) {
    const device = await adapter.requestDevice();
    const format = navigator.gpu.getPreferredCanvasFormat();
    const context = canvas.getContext("webgpu");
    context.configure({ device, format, alphaMode: "opaque" });
    const here = new URL("scene.json", location.href);
    return {
      kind: "webgpu", target: "wgsl", entry: "library", format,
      make: (r, f) => createHostFrom(device, r.code, r.manifest, f, here),
      draw(host, eye, values) {
        const encoder = host.draw(context.getCurrentTexture().createView(), canvas.width, canvas.height, eye, values);
        device.queue.submit([encoder.finish()]);
      },
      pixels: async (r, w, h, values) => hostPixels(await createHostFrom(device, r.code, r.manifest, "rgba8unorm", here), w, h, values),
    };
  }
  const gl = canvas.getContext("webgl2");
  if (!gl) {
    status.textContent = "this browser has neither WebGPU nor WebGL2: the scene compiles, but cannot be drawn";
    return { kind: "none", target: "wgsl", entry: "library", make: null, draw() {}, pixels: async () => [] };
  }
  status.textContent = "no WebGPU here: drawing with WebGL2";
  return {
    kind: "webgl2", target: "glsl", entry: "fragment",
    make: async (r) => gl2.createHost(gl, r.code, r.manifest),
    // The canvas: GL's origin, and not sRGB, so the entry encodes.
    draw(host, eye, values) {
      host.draw(canvas.width, canvas.height, eye, values, { yUp: true, srgb: true });
      // GL's errors on the live canvas, counted for the test (and the page's status).
      const error = gl.getError();
      if (error) state.glErrors.push([state.frames, error]);
    },
    pixels: async (r, w, h, values) => gl2.hostPixels(gl, gl2.createHost(gl, r.code, r.manifest), w, h, values),
  };
}

async function main() {
  const sdfc = await load(await (await fetch("sdfc.wasm")).arrayBuffer());
  const renderer = await makeRenderer();
  state.renderer = renderer.kind;
  const values = {};
  let offset = null;
  let target = [0, 0, 0];

  async function compile() {
    const text = source.value;
    const t0 = performance.now();
    const r = sdfc.compile({ source: text, name: "scene.sdf", target: renderer.target, entry: renderer.entry });
    const ms = performance.now() - t0;
    state.compiles += 1;
    state.diagnostics = r.diagnostics ?? [];
    $("diagnostics").textContent = [r.error, ...state.diagnostics.map(line)].filter(Boolean).join("\n");
    state.ok = Boolean(r.ok);
    if (!r.ok || !renderer.make) {
      state.compiledText = text;
      return;
    }
    const host = await renderer.make(r, renderer.format);
    const keepCamera = state.host && JSON.stringify(state.host.manifest.camera) === JSON.stringify(r.manifest.camera);
    state.host = host;
    state.response = r;
    if (!keepCamera) {
      target = r.manifest.camera.target;
      offset = r.manifest.camera.eye.map((x, i) => x - target[i]);
    }
    sliders(r.manifest);
    $("download").href = URL.createObjectURL(new Blob([r.code], { type: "text/plain" }));
    status.textContent = `${renderer.kind}: compiled in ${ms.toFixed(1)} ms`;
    state.compiledText = text;
    state.framesAtCompile = state.frames;
  }

  function sliders(manifest) {
    const box = $("sliders");
    box.textContent = "";
    for (const f of manifest.params.fields) {
      if (f.name === "time" && f.builtin) continue;
      values[f.name] = values[f.name]?.length === f.default.length ? values[f.name] : [...f.default];
      f.default.forEach((d, i) => {
        const lo = f.min ? f.min[i] : d - 1;
        const hi = f.max ? f.max[i] : d + 1;
        const label = document.createElement("label");
        label.textContent = f.default.length > 1 ? `${f.name}.${"xyz"[i]}` : f.name;
        const input = Object.assign(document.createElement("input"), {
          type: "range", min: lo, max: hi, step: (hi - lo) / 1000, value: values[f.name][i],
        });
        // A parameter is the uniform's: moving it draws again, no compile.
        input.oninput = () => (values[f.name][i] = Number(input.value));
        label.append(input);
        box.append(label);
      });
    }
  }

  // Compile on every edit, after a pause (and never two at once).
  let timer = null;
  let running = Promise.resolve();
  source.oninput = () => {
    clearTimeout(timer);
    timer = setTimeout(() => (running = running.then(compile).catch((e) => (status.textContent = String(e.message ?? e)))), 120);
  };
  $("examples").append(...EXAMPLES.map((n) => Object.assign(document.createElement("option"), { value: n, textContent: n })));
  $("examples").onchange = async (e) => {
    if (!e.target.value) return;
    source.value = await (await fetch(`examples/${e.target.value}.sdf`)).text();
    source.oninput();
  };
  $("share").onclick = async () => {
    history.replaceState(null, "", await toAddress(source.value));
  };
  // The orbit camera of `sdfc view`: drag to turn, wheel to zoom, double-click to reset.
  let dragging = null;
  canvas.onpointerdown = (e) => (dragging = [e.clientX, e.clientY]);
  window.onpointerup = () => (dragging = null);
  window.onpointermove = (e) => {
    if (!dragging || !offset) return;
    offset = orbit(offset, e.clientX - dragging[0], e.clientY - dragging[1]);
    dragging = [e.clientX, e.clientY];
  };
  canvas.onwheel = (e) => {
    e.preventDefault();
    if (offset) offset = offset.map((x) => x * Math.exp(e.deltaY * 0.001));
  };
  canvas.ondblclick = () => {
    const c = state.host?.manifest.camera;
    if (c) offset = c.eye.map((x, i) => x - c.target[i]);
  };
  // For the test: the last compiled scene's picture from its own camera at time 0, as
  // `sdfc render` draws it, with the sliders' values.
  state.pixels = async (w, h) => Array.from(await renderer.pixels(state.response, w, h, { ...values, time: [0] }));

  source.value = (await fromAddress()) ?? FIRST;
  await compile();
  const started = performance.now();
  let last = performance.now();
  const frame = () => {
    const host = state.host;
    if (host && offset) {
      const time = host.manifest.params.fields.find((f) => f.name === "time");
      if (time) values.time = [(performance.now() - started) / 1000];
      const eye = offset.map((x, i) => x + target[i]);
      renderer.draw(host, eye, values);
      state.frames += 1;
      state.eye = eye;
      const now = performance.now();
      if (state.frames % 30 === 0) status.textContent = `${status.textContent.split(" · ")[0]} · ${(now - last).toFixed(0)} ms a frame`;
      last = now;
    }
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);
}

main().catch((e) => (status.textContent = String(e.message ?? e)));
