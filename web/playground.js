// sdfc's playground: the scene's text compiled in this page by the WebAssembly compiler
// (sdfc.mjs) on every edit in a CodeMirror editor (editor.js), drawn with WebGPU by the host
// page's code (host.js: the library entry and its manifest) — or, where WebGPU is missing, with
// WebGL2 by the WebGL2 host's code (host_webgl2.js: the GLSL ES fragment entry) — orbited with
// the mouse at a coarser resolution while it moves; the compiler's diagnostics underlined and
// listed; parameters as sliders and colour pickers; the tracer and its settings in a panel; the
// scene shareable in the address; its shaders, manifest and picture as downloads.
// docs/playground.md.
import { load } from "./sdfc.js";
import { createEditor } from "./editor.js";
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
const canvas = $("picture");
const status = $("status");
/** The canvas's full size; while the camera moves it draws at a fraction of it (not with `?full`). */
const FULL = [canvas.width, canvas.height];
const REFINE = !new URLSearchParams(location.search).has("full");

// What the page is doing, for its test (examples/hosts/test/playground.mjs).
const state = (window.sdfcPlayground = {
  glErrors: [], compiles: 0, ok: false, diagnostics: [], frames: 0, host: null, response: null,
  compiledText: null, scale: 1, coarseFrames: 0,
});

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
      make: (r, f) => createHostFrom(device, r.code, r.manifest, f, here, r.volumes, r.data, r.prune),
      draw(host, eye, values) {
        const encoder = host.draw(context.getCurrentTexture().createView(), canvas.width, canvas.height, eye, values);
        device.queue.submit([encoder.finish()]);
      },
      pixels: async (r, w, h, values, eye) =>
        hostPixels(await createHostFrom(device, r.code, r.manifest, "rgba8unorm", here, r.volumes, r.data, r.prune), w, h, values, eye ?? r.manifest.camera.eye),
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
    make: async (r) => gl2.createHost(gl, r.code, r.manifest, false, r.volumes),
    // The canvas: GL's origin, and not sRGB, so the entry encodes.
    draw(host, eye, values) {
      host.draw(canvas.width, canvas.height, eye, values, { yUp: true, srgb: true });
      // GL's errors on the live canvas, counted for the test (and the page's status).
      const error = gl.getError();
      if (error) state.glErrors.push([state.frames, error]);
    },
    pixels: async (r, w, h, values, eye) => gl2.hostPixels(gl, gl2.createHost(gl, r.code, r.manifest, false, r.volumes), w, h, values, { eye: eye ?? r.manifest.camera.eye }),
  };
}

async function main() {
  const sdfc = await load(await (await fetch("sdfc.wasm")).arrayBuffer());
  const renderer = await makeRenderer();
  state.renderer = renderer.kind;
  state.sdfc = sdfc;
  const values = {};
  let offset = null;
  let target = [0, 0, 0];
  /** The tracer the panel asks for (`{name, settings}`), or null for the scene's own. */
  let tracer = null;
  /** Whether the next animation frame must draw, and when the camera last moved. */
  let dirty = true;
  let moved = -Infinity;
  let fullFrameMs = 0;

  /** The compiler's request for the editor's text: `target`/`entry` as asked, the panel's tracer. */
  const request = (text, target, entry) => ({ source: text, name: "scene.sdf", target, entry, ...(tracer ? { tracer } : {}) });
  const ask = (text, target, entry) => sdfc.compile(request(text, target, entry));
  // The `@lipschitz` claims are sampled by a second compiler in a worker (verify.js), after
  // the picture: their check only warns, and can take hundreds of milliseconds.
  const verifier = new Worker("verify.js", { type: "module" });
  let asked = 0;
  let askedText = null;
  verifier.onmessage = (e) => {
    if (e.data.id !== asked) return;
    state.diagnostics = e.data.diagnostics;
    state.verifyMs = e.data.ms;
    editor.diagnose(state.diagnostics, "scene.sdf");
    $("diagnostics").textContent = state.diagnostics.map(line).join("\n");
    state.verified = askedText;
  };

  async function compile() {
    const text = editor.text();
    const t0 = performance.now();
    const r = sdfc.compile({ ...request(text, renderer.target, renderer.entry), annotations: "later" });
    const ms = performance.now() - t0;
    state.diagnostics = r.diagnostics ?? [];
    editor.diagnose(state.diagnostics, "scene.sdf");
    $("diagnostics").textContent = [r.error, ...state.diagnostics.map(line)].filter(Boolean).join("\n");
    state.ok = Boolean(r.ok);
    state.compileMs = ms;
    if (r.tracer) panel(r);
    asked += 1;
    askedText = text;
    if (r.pending) verifier.postMessage({ id: asked, request: request(text, renderer.target, renderer.entry) });
    else state.verified = text;
    // (`compiles` and `compiledText` change last, once the answer is in use: the test waits on them.)
    // The baked volumes' bytes, made by the compile (the files `sdfc emit` would write).
    if (r.ok) r.volumes = (r.manifest.volumes ?? []).map((_, i) => sdfc.volume(i));
    // A scene of many parts compiles to the data form (WebGPU): its buffers are made by the
    // compiler in the page at the sliders' values, again when a slider moves its parts.
    if (r.ok && r.manifest.data) r.data = (v) => sdfc.data(v);
    // Pruned on the page's device where the compiler gave its pre-pass (WebGPU).
    if (r.ok && r.manifest.data && r.prune) r.prune = { shader: r.prune, seed: (v) => sdfc.seed(v) };
    else r.prune = null;
    if (!r.ok || !renderer.make) {
      state.compiles += 1;
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
    status.textContent = `${renderer.kind}: compiled in ${ms.toFixed(1)} ms`;
    state.framesAtCompile = state.frames;
    state.compiles += 1;
    state.compiledText = text;
    dirty = true;
  }

  /** A slider per number or vector component, a colour picker per colour (sRGB, as written). */
  function sliders(manifest) {
    const box = $("sliders");
    box.textContent = "";
    for (const f of manifest.params.fields) {
      if (f.name === "time" && f.builtin) continue;
      // A value set before stays where the new scene still has the parameter, of the same
      // size and within its range (as `sdfc view` keeps its keys' values); else the default.
      const kept = values[f.name];
      const fits = kept?.length === f.default.length && (!f.min || kept.every((x, i) => x >= f.min[i] && x <= f.max[i]));
      values[f.name] = fits ? kept : [...f.default];
      // A parameter is the uniform's: changing it draws again, no compile.
      if (f.kind === "color") {
        const label = Object.assign(document.createElement("label"), { textContent: f.name });
        const hex = values[f.name].map((c) => Math.round(Math.min(1, Math.max(0, c)) * 255).toString(16).padStart(2, "0"));
        const input = Object.assign(document.createElement("input"), { type: "color", value: `#${hex.join("")}` });
        input.oninput = () => {
          values[f.name] = [1, 3, 5].map((k) => parseInt(input.value.slice(k, k + 2), 16) / 255);
          dirty = true;
        };
        label.append(input);
        box.append(label);
        continue;
      }
      f.default.forEach((d, i) => {
        const lo = f.min ? f.min[i] : d - 1;
        const hi = f.max ? f.max[i] : d + 1;
        const label = document.createElement("label");
        label.textContent = f.default.length > 1 ? `${f.name}.${"xyz"[i]}` : f.name;
        const input = Object.assign(document.createElement("input"), {
          type: "range", min: lo, max: hi, step: (hi - lo) / 1000, value: values[f.name][i],
        });
        input.oninput = () => {
          values[f.name][i] = Number(input.value);
          dirty = true;
        };
        label.append(input);
        box.append(label);
      });
    }
  }

  /** The tracer panel: the tracer used and its settings; a change compiles again. */
  function panel(r) {
    const box = $("tracer");
    box.textContent = "";
    const pick = document.createElement("select");
    pick.id = "tracer-name";
    for (const t of r.tracers) pick.append(Object.assign(document.createElement("option"), { value: t.name, textContent: t.name }));
    pick.value = r.tracer.name;
    pick.onchange = () => {
      const params = r.tracers.find((t) => t.name === pick.value).params;
      const settings = Object.fromEntries(Object.entries(tracer?.settings ?? {}).filter(([k]) => params.includes(k)));
      tracer = { name: pick.value, settings };
      recompile(0);
    };
    box.append(Object.assign(document.createElement("label"), { textContent: "tracer " }), pick);
    for (const [name, value] of r.tracer.settings) {
      const label = Object.assign(document.createElement("label"), { textContent: name.replace("_", " ") + " " });
      const input = Object.assign(document.createElement("input"), { value, size: 6, name });
      input.onchange = () => {
        tracer = { name: pick.value, settings: { ...(tracer?.settings ?? {}), [name]: input.value.trim() } };
        recompile(0);
      };
      label.append(input);
      box.append(label);
    }
    const reset = Object.assign(document.createElement("button"), { textContent: "scene's", title: "the scene's own tracer settings" });
    reset.onclick = () => {
      tracer = null;
      recompile(0);
    };
    box.append(reset);
  }

  // Compile on every edit, after a pause (and never two at once).
  let timer = null;
  let running = Promise.resolve();
  const recompile = (pause) => {
    clearTimeout(timer);
    timer = setTimeout(() => (running = running.then(compile).catch((e) => (status.textContent = String(e.message ?? e)))), pause);
  };
  const editor = createEditor($("source"), (await fromAddress()) ?? FIRST, () => recompile(120));
  state.editor = editor;
  $("examples").append(...EXAMPLES.map((n) => Object.assign(document.createElement("option"), { value: n, textContent: n })));
  $("examples").onchange = async (e) => {
    if (!e.target.value) return;
    editor.setText(await (await fetch(`examples/${e.target.value}.sdf`)).text());
  };
  $("share").onclick = async () => {
    history.replaceState(null, "", await toAddress(editor.text()));
  };
  // Downloads: the shaders for other engines (fragment entries), the WGSL's manifest, the picture.
  const save = (blob, name) => {
    const a = Object.assign(document.createElement("a"), { href: URL.createObjectURL(blob), download: name });
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 10000);
  };
  for (const [id, target, name, part] of [
    ["get-wgsl", "wgsl", "scene.wgsl", "code"], ["get-glsl", "glsl", "scene.frag", "code"], ["get-manifest", "wgsl", "scene.json", "manifest"],
  ]) {
    $(id).onclick = () => {
      // (Inline, as `sdfc emit` writes it: a data form's buffers are not among the downloads.)
      const r = sdfc.compile({ ...request(editor.text(), target, "fragment"), form: "inline" });
      if (!r.ok) return (status.textContent = `${name}: the scene does not compile`);
      const text = part === "code" ? r.code : JSON.stringify(r.manifest, null, 2);
      save(new Blob([text], { type: "text/plain" }), name);
    };
  }
  $("get-png").onclick = async () => {
    if (!state.response || !offset) return;
    // Drawn offscreen at the canvas's full size from the camera as it is now (a WebGPU
    // canvas's own picture cannot be read back reliably once presented).
    const [w, h] = FULL;
    const eye = offset.map((x, i) => x + target[i]);
    const rgba = await renderer.pixels(state.response, w, h, values, eye);
    const picture = Object.assign(document.createElement("canvas"), { width: w, height: h });
    picture.getContext("2d").putImageData(new ImageData(new Uint8ClampedArray(rgba), w, h), 0, 0);
    picture.toBlob((blob) => save(blob, "scene.png"), "image/png");
  };
  // The orbit camera of `sdfc view`: drag to turn, wheel to zoom, double-click to reset.
  let dragging = null;
  const move = () => {
    moved = performance.now();
    dirty = true;
  };
  canvas.onpointerdown = (e) => (dragging = [e.clientX, e.clientY]);
  window.onpointerup = () => (dragging = null);
  window.onpointermove = (e) => {
    if (!dragging || !offset) return;
    offset = orbit(offset, e.clientX - dragging[0], e.clientY - dragging[1]);
    dragging = [e.clientX, e.clientY];
    move();
  };
  canvas.onwheel = (e) => {
    e.preventDefault();
    if (offset) offset = offset.map((x) => x * Math.exp(e.deltaY * 0.001));
    move();
  };
  canvas.ondblclick = () => {
    const c = state.host?.manifest.camera;
    if (c) offset = c.eye.map((x, i) => x - c.target[i]);
    dirty = true;
  };
  // For the test: the last compiled scene's picture from its own camera at time 0, as
  // `sdfc render` draws it, with the sliders' values.
  state.pixels = async (w, h) => Array.from(await renderer.pixels(state.response, w, h, { ...values, time: [0] }));

  /**
   * Draws a frame with the canvas at `scale` of its full size: progressive refinement, a
   * coarse picture while the camera moves (a half, a quarter where a full frame took over
   * 100 ms), the full one once it stops.
   */
  const started = performance.now();
  function draw(scale) {
    const [w, h] = FULL.map((n) => Math.max(1, Math.round(n * scale)));
    if (canvas.width !== w || canvas.height !== h) [canvas.width, canvas.height] = [w, h];
    const time = state.host.manifest.params.fields.find((f) => f.name === "time");
    if (time) values.time = [(performance.now() - started) / 1000];
    const eye = offset.map((x, i) => x + target[i]);
    renderer.draw(state.host, eye, values);
    state.frames += 1;
    state.eye = eye;
    state.scale = scale;
    if (scale < 1) state.coarseFrames += 1;
  }
  await compile();
  let last = performance.now();
  const frame = () => {
    const now = performance.now();
    const moving = now - moved < 250;
    const animated = state.host?.manifest.params.fields.some((f) => f.name === "time");
    const scale = moving && REFINE ? (fullFrameMs > 100 ? 0.25 : 0.5) : 1;
    if (state.host && offset && (dirty || animated || scale !== state.scale)) {
      dirty = false;
      draw(scale);
      if (scale === 1) fullFrameMs = now - last;
      if (state.frames % 30 === 0) status.textContent = `${status.textContent.split(" · ")[0]} · ${(now - last).toFixed(0)} ms a frame`;
    }
    last = now;
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);
}

main().catch((e) => (status.textContent = String(e.message ?? e)));
