// A WebGPU host for sdfc's library output (docs/interface.md), with no framework: it loads the
// library's WGSL and its manifest, draws a full-screen pass that asks the library for each
// pixel's colour, orbits the scene's camera with the mouse, and makes a slider for each
// parameter from the manifest (its range, its default). `time` runs with the clock.
//
// Files it loads, written by:  sdfc emit SCENE.sdf --entry library -o scene.wgsl --manifest scene.json
// (the page's `?scene=NAME` loads NAME.wgsl and NAME.json instead), and the distance maps of a
// scene that bakes parts (`bake`), written beside them and named by the manifest's `volumes`,
// or the buffers of a scene emitted as data (`--form data`), named by the manifest's `data`.

// The host's own shader: a full-screen triangle, and the pixel's ray given to the library's
// `color` (its name from the manifest, so a `--prefix`ed library works too).
const HOST_WGSL = (color) => /* wgsl */ `
struct HostCamera {
  eye: vec4<f32>,
  right: vec4<f32>,
  up: vec4<f32>,
  forward: vec4<f32>,
  size: vec4<f32>,
}
@group(1) @binding(0) var<uniform> camera: HostCamera;

@vertex
fn host_vertex(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
  let xy = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
  return vec4<f32>(xy * 2.0 - 1.0, 0.0, 1.0);
}

fn host_srgb(c: vec3<f32>) -> vec3<f32> {
  let l = clamp(c, vec3<f32>(0.0), vec3<f32>(1.0));
  return select(1.055 * pow(l, vec3<f32>(1.0 / 2.4)) - 0.055, l * 12.92, l <= vec3<f32>(0.0031308));
}

@fragment
fn host_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
  let u = 2.0 * position.x / camera.size.x - 1.0;
  let v = 1.0 - 2.0 * position.y / camera.size.y;
  let rd = normalize(camera.forward.xyz + camera.right.xyz * u + camera.up.xyz * v);
  let c = ${color}(camera.eye.xyz, rd, camera.size.z);
  // The canvas is not sRGB: encode here (the library's colours are linear).
  return vec4<f32>(host_srgb(c.rgb), 1.0);
}
`;

const sub = (a, b) => a.map((x, i) => x - b[i]);
const add = (a, b) => a.map((x, i) => x + b[i]);
const scale = (a, k) => a.map((x) => x * k);
const dot = (a, b) => a.reduce((s, x, i) => s + x * b[i], 0);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a) => scale(a, 1 / Math.sqrt(dot(a, a)));

/** The host's camera uniform: the pinhole camera of `sdfc render` (docs/interface.md). */
function cameraBytes(eye, target, up, fovDegrees, width, height) {
  const forward = normalize(sub(target, eye));
  const right = normalize(cross(forward, up));
  const realUp = cross(right, forward);
  const t = Math.tan((fovDegrees * Math.PI) / 360);
  const aspect = width / height;
  return new Float32Array([
    ...eye, 0,
    ...scale(right, t * aspect), 0,
    ...scale(realUp, t), 0,
    ...forward, 0,
    width, height, t / height, 0,
  ]);
}

/** The `Params` uniform from the manifest: each field's value (default unless given) at its offset. */
function paramsBytes(manifest, values) {
  const size = manifest.params.size;
  const data = new Float32Array(Math.max(size, 16) / 4);
  for (const f of manifest.params.fields) {
    const v = values[f.name] ?? f.default;
    v.forEach((x, i) => (data[f.offset / 4 + i] = x));
  }
  return data;
}

/**
 * The scene's baked distance maps (the manifest's `volumes`, docs/bake.md), each an r32float 3D
 * texture filled from its raw bytes (`given[i]`, else the file beside the manifest): the bind
 * group entries for them.
 */
async function volumeEntries(device, manifest, manifestUrl, given = null) {
  return Promise.all(
    (manifest.volumes ?? []).map(async (v, i) => {
      if (v.format !== "r32float") throw new Error(`volume ${v.global}: unknown format ${v.format}`);
      let bytes = given?.[i];
      if (!bytes) {
        const r = await fetch(new URL(v.file, manifestUrl));
        if (!r.ok) throw new Error(`${v.file}: ${r.status}`);
        bytes = await r.arrayBuffer();
      }
      const [w, h, d] = v.size;
      if (bytes.byteLength !== 4 * w * h * d) {
        throw new Error(`${v.file}: ${bytes.byteLength} bytes, but ${w}×${h}×${d} r32float texels take ${4 * w * h * d}`);
      }
      const texture = device.createTexture({
        size: [w, h, d],
        dimension: "3d",
        format: "r32float",
        usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST,
      });
      // x fastest, then y, then z: the file's layout is the texture's.
      device.queue.writeTexture({ texture }, bytes, { bytesPerRow: 4 * w, rowsPerImage: h }, [w, h, d]);
      return { binding: v.binding.binding, resource: texture.createView({ dimension: "3d" }) };
    }),
  );
}

/**
 * The data form's buffers (the manifest's `data`, docs/data-form.md: `sdfc emit --form data`
 * writes them beside the shader; the playground's compiler makes them in the page): each
 * uploaded whole as a read-only storage buffer at its binding — the three `given` byte arrays,
 * else the files the manifest names. The bind group entries for them (none for the inline form).
 */
async function dataEntries(device, manifest, manifestUrl, given = null) {
  const buffers = manifest.data?.buffers ?? [];
  const bytes = given ?? (await Promise.all(
    buffers.map(async (b) => {
      if (!b.file) throw new Error(`the data buffer ${b.name} has no file: emit with -o FILE`);
      const r = await fetch(new URL(b.file, manifestUrl));
      if (!r.ok) throw new Error(`${b.file}: ${r.status}`);
      const bytes = await r.arrayBuffer();
      if (bytes.byteLength !== b.bytes) throw new Error(`${b.file}: ${bytes.byteLength} bytes, the manifest says ${b.bytes}`);
      return bytes;
    }),
  ));
  return uploaded(device, manifest, bytes);
}

/** The data form's buffers from their `bytes` (one per manifest buffer), as bind group entries. */
function uploaded(device, manifest, bytes) {
  const limit = Math.min(device.limits.maxStorageBufferBindingSize, device.limits.maxBufferSize);
  return (manifest.data?.buffers ?? []).map((b, i) => {
    if (bytes[i].byteLength > limit) {
      throw new Error(`${b.name}: ${bytes[i].byteLength} bytes, and this device binds at most ${limit} per buffer: emit with --form inline, or fewer parts`);
    }
    const buffer = device.createBuffer({ size: bytes[i].byteLength, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
    device.queue.writeBuffer(buffer, 0, bytes[i]);
    return { binding: b.binding.binding, resource: { buffer } };
  });
}

/**
 * The data form's pre-pass on `device` (docs/data-form.md): `shader` is a compile's `prune`
 * (the playground's compiler gives it: `{code, workgroup, bindings, level_words, room_words,
 * scratch_missed, chunk, room_per_cell, scratch_per_cell}`). `run(seed)` prunes every cell of
 * a seed's grid (`sdfc.seed(values)`: the table, what the pre-pass knows of its parts, the
 * whole and outside programs, the ranges' first contents, and each level's cells and
 * uniform), grid by grid in one submission, and returns the three buffers the library reads
 * (nodes, code, ranges) with a promise of whether every cell found room (else the host makes
 * the buffers in WebAssembly).
 */
function devicePruner(device, shader) {
  const module = device.createShaderModule({ code: shader.code });
  const pipeline = device.createComputePipeline({ layout: "auto", compute: { module, entryPoint: "main" } });
  const limit = Math.min(device.limits.maxStorageBufferBindingSize, device.limits.maxBufferSize);
  // Cells a dispatch prunes (they share the scratch, emptied between dispatches), and words of
  // room a cell is given in the programs' buffer and the scratch — the compiler's, as `sdfc
  // render` gives them.
  const { chunk, room_per_cell: codePerCell, scratch_per_cell: scratchPerCell } = shader;
  const { STORAGE, COPY_DST, COPY_SRC, UNIFORM, MAP_READ } = GPUBufferUsage;
  const buffer = (size, usage, bytes = null) => {
    const b = device.createBuffer({ size: Math.max(16, Math.ceil(size / 4) * 4), usage });
    if (bytes) device.queue.writeBuffer(b, 0, bytes);
    return b;
  };
  return {
    run(seed) {
      const cells = seed.levels.reduce((n, l) => n + l.cells, 0);
      const codeWords = Math.min(limit / 4, seed.code.byteLength / 4 + codePerCell * cells);
      const scratchWords = Math.min(limit / 4, chunk * scratchPerCell);
      const nodes = buffer(seed.nodes.byteLength, STORAGE | COPY_DST, seed.nodes);
      const meta = buffer(seed.meta.byteLength, STORAGE | COPY_DST, seed.meta);
      const ranges = buffer(seed.ranges.byteLength, STORAGE | COPY_DST, seed.ranges);
      const code = buffer(codeWords * 4, STORAGE | COPY_DST, seed.code);
      const scratch = buffer(scratchWords * 4, STORAGE);
      const counter = buffer(16, STORAGE | COPY_DST | COPY_SRC, new Uint32Array([seed.code.byteLength / 4, 0, 0, 0]));
      const encoder = device.createCommandEncoder();
      for (const level of seed.levels) {
        for (let first = 0; first < level.cells; first += chunk) {
          const words = level.words.slice();
          [codeWords, scratchWords, first].forEach((x, i) => (words[shader.room_words[i]] = x));
          const uniform = buffer(words.byteLength, UNIFORM | COPY_DST, words);
          const entries = [nodes, meta, code, ranges, uniform, counter, scratch].map((b, i) => ({ binding: shader.bindings[i], resource: { buffer: b } }));
          const pass = encoder.beginComputePass();
          pass.setPipeline(pipeline);
          pass.setBindGroup(0, device.createBindGroup({ layout: pipeline.getBindGroupLayout(0), entries }));
          pass.dispatchWorkgroups(Math.ceil(Math.min(chunk, level.cells - first) / shader.workgroup));
          pass.end();
          // The scratch is empty again for the next dispatch.
          encoder.clearBuffer(counter, 12, 4);
        }
      }
      const readback = buffer(16, MAP_READ | COPY_DST);
      encoder.copyBufferToBuffer(counter, 0, readback, 0, 16);
      device.queue.submit([encoder.finish()]);
      const fits = readback.mapAsync(GPUMapMode.READ).then(() => {
        const missed = new Uint32Array(readback.getMappedRange())[1];
        readback.unmap();
        return missed === 0;
      });
      return { buffers: [nodes, code, ranges], fits };
    },
  };
}

/** The values of the parameters the data form's buffers follow, as a key (defaults where unset). */
function followed(manifest, values) {
  return JSON.stringify(
    (manifest.data?.follows ?? []).map((name) => values[name] ?? manifest.params.fields.find((f) => f.name === name).default),
  );
}

/** Everything the page draws with: the device, pipeline and buffers for one scene. */
export async function createHost(base, format) {
  if (!navigator.gpu) throw new Error("this browser has no WebGPU");
  const [library, manifest] = await Promise.all([
    fetch(`${base}.wgsl`).then((r) => (r.ok ? r.text() : Promise.reject(new Error(`${base}.wgsl: ${r.status}`)))),
    fetch(`${base}.json`).then((r) => (r.ok ? r.json() : Promise.reject(new Error(`${base}.json: ${r.status}`)))),
  ]);
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) throw new Error("no WebGPU adapter");
  const device = await adapter.requestDevice();
  return createHostFrom(device, library, manifest, format, new URL(`${base}.json`, location.href));
}

/**
 * [createHost] from a library's WGSL and manifest already in hand (the playground compiles them
 * in the page) on `device`; baked maps' bytes are `volumes` (one per manifest volume) or fetched
 * beside `manifestUrl`. A data form's buffers come from `makeData(values)` (three byte arrays
 * at those parameter values: the playground's compiler) where given, made again whenever a
 * parameter they follow changes; else from the files, and those parameters stay at their
 * defaults.
 */
export async function createHostFrom(device, library, manifest, format, manifestUrl, volumes = null, makeData = null, prune = null) {
  if (manifest.format !== "sdfc-manifest 1") throw new Error(`unknown manifest format ${manifest.format}`);
  const color = manifest.functions.find((f) => f.name === (manifest.prefix ? `${manifest.prefix}_color` : "color"));
  if (!color) throw new Error("the manifest lists no `color`: emit with --entry library");
  const module = device.createShaderModule({ code: library + "\n" + HOST_WGSL(color.name) });
  const info = await module.getCompilationInfo();
  const errors = info.messages.filter((m) => m.type === "error");
  if (errors.length) throw new Error(errors.map((m) => `${m.lineNum}:${m.linePos} ${m.message}`).join("\n"));
  const pipeline = device.createRenderPipeline({
    layout: "auto",
    vertex: { module, entryPoint: "host_vertex" },
    fragment: { module, entryPoint: "host_fragment", targets: [{ format }] },
    primitive: { topology: "triangle-list" },
  });
  const cameraBuffer = device.createBuffer({ size: 80, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
  const cameraGroup = device.createBindGroup({
    layout: pipeline.getBindGroupLayout(1),
    entries: [{ binding: 0, resource: { buffer: cameraBuffer } }],
  });
  // The scene's parameters, where the manifest gives their binding (docs/interface.md), and
  // its baked maps: the library's group 0.
  const entries = await volumeEntries(device, manifest, manifestUrl, volumes);
  let paramsBuffer = null;
  if (manifest.params.binding) {
    paramsBuffer = device.createBuffer({
      size: Math.max(manifest.params.size, 16),
      usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST,
    });
    entries.push({ binding: manifest.params.binding.binding, resource: { buffer: paramsBuffer } });
  }
  // The data form's buffers, at the values of the parameters they follow (`madeAt`): pruned
  // on the device where the compiler gave its pre-pass (`prune`: its shader and the seed's
  // maker), else made in WebAssembly (`makeData`), else loaded from the files.
  const pruner = prune && manifest.data ? devicePruner(device, prune.shader) : null;
  const stats = { prunes: 0, fellBack: 0, ms: 0 };
  let checked = Promise.resolve();
  const made = (values) => {
    const seed = pruner && prune.seed(values);
    if (!seed) {
      const given = makeData(values);
      return given && uploaded(device, manifest, given);
    }
    const t0 = performance.now();
    const run = pruner.run(seed);
    stats.prunes += 1;
    checked = run.fits.then((ok) => {
      stats.ms = performance.now() - t0;
      if (ok) return;
      // A cell found no room: the buffers made in WebAssembly instead (the next draw).
      stats.fellBack += 1;
      data = uploaded(device, manifest, makeData(values));
      paramsGroup = group();
    });
    return (manifest.data?.buffers ?? []).map((b, i) => ({ binding: b.binding.binding, resource: { buffer: run.buffers[i] } }));
  };
  let madeAt = followed(manifest, {});
  let data = makeData && manifest.data ? made({}) : await dataEntries(device, manifest, manifestUrl, null);
  const group = () => device.createBindGroup({ layout: pipeline.getBindGroupLayout(0), entries: [...entries, ...data] });
  let paramsGroup = entries.length + data.length ? group() : null;
  /**
   * The data form's buffers made for `values` where the parameters they follow changed (see
   * `draw`); a promise that settles once the device's pre-pass is known to have found room
   * (or its buffers were made again in WebAssembly).
   */
  function update(values) {
    const now = followed(manifest, values);
    if (now !== madeAt) {
      const name = manifest.data.follows.find((n, i) => JSON.stringify(JSON.parse(now)[i]) !== JSON.stringify(JSON.parse(madeAt)[i]));
      if (!makeData) {
        throw new Error(`${name} moves parts of the data form, whose buffers hold them at its default: give it that default in the scene and emit again`);
      }
      const next = made(values);
      if (!next) throw new Error(`at this value of ${name} the scene's parts need another shader: compile it again`);
      data = next;
      madeAt = now;
      paramsGroup = group();
    }
    return checked;
  }
  /** Draws into `view` (a texture view of `width`×`height`) from `eye` with `values`. */
  function draw(view, width, height, eye, values) {
    const c = manifest.camera;
    // The data form's parts were placed at `madeAt`: at other values of the parameters they
    // follow the buffers are made again, or — without a maker — the drawing is refused (it
    // would put the parts where they are not).
    update(values);
    device.queue.writeBuffer(cameraBuffer, 0, cameraBytes(eye, c.target, c.up, c.fov_degrees, width, height));
    if (paramsBuffer) device.queue.writeBuffer(paramsBuffer, 0, paramsBytes(manifest, values));
    const encoder = device.createCommandEncoder();
    const pass = encoder.beginRenderPass({
      colorAttachments: [{ view, loadOp: "clear", storeOp: "store", clearValue: [0, 0, 0, 1] }],
    });
    pass.setPipeline(pipeline);
    if (paramsGroup) pass.setBindGroup(0, paramsGroup);
    pass.setBindGroup(1, cameraGroup);
    pass.draw(3);
    pass.end();
    return encoder;
  }
  return { device, manifest, draw, update, stats };
}

/**
 * Renders `width`×`height` from the scene's own camera with `values` into a texture and
 * returns its RGBA8 pixels (sRGB, row-major, y down): what the tests compare with `sdfc render`.
 */
export async function renderPixels(base, width, height, values = {}) {
  return hostPixels(await createHost(base, "rgba8unorm"), width, height, values);
}

/** [renderPixels] with a host already made (its format rgba8unorm), from the scene's camera. */
export async function hostPixels(host, width, height, values = {}, eye = host.manifest.camera.eye) {
  const format = "rgba8unorm";
  const texture = host.device.createTexture({
    size: [width, height],
    format,
    usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC,
  });
  const row = Math.ceil((4 * width) / 256) * 256;
  const readback = host.device.createBuffer({ size: row * height, usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ });
  // (A data form pruned on the device: drawn at once — the queue runs the pre-pass first — and
  // drawn again if it turns out a cell found no room and the buffers were made in WebAssembly.)
  const fellBack = host.stats?.fellBack;
  const encoder = host.draw(texture.createView(), width, height, eye, values);
  encoder.copyTextureToBuffer({ texture }, { buffer: readback, bytesPerRow: row }, [width, height]);
  host.device.queue.submit([encoder.finish()]);
  await readback.mapAsync(GPUMapMode.READ);
  const data = new Uint8Array(readback.getMappedRange());
  const out = new Uint8Array(4 * width * height);
  for (let y = 0; y < height; y++) out.set(data.subarray(y * row, y * row + 4 * width), 4 * width * y);
  readback.unmap();
  await host.update?.(values);
  if (host.stats && host.stats.fellBack !== fellBack) return hostPixels(host, width, height, values, eye);
  return out;
}

/** The orbit camera's turn: `offset` (eye − target) after a drag of `dx`, `dy` pixels. */
export function orbit(offset, dx, dy) {
  const r = Math.hypot(...offset);
  const azimuth = Math.atan2(offset[0], offset[2]) - dx * 0.01;
  const elevation = Math.min(1.5, Math.max(-1.5, Math.asin(offset[1] / r) + dy * 0.01));
  return [r * Math.cos(elevation) * Math.sin(azimuth), r * Math.sin(elevation), r * Math.cos(elevation) * Math.cos(azimuth)];
}

/** The interactive page: orbit camera, sliders from the manifest's parameters, `time` running. */
async function main() {
  const status = document.getElementById("status");
  const canvas = document.getElementById("view");
  if (!canvas || new URLSearchParams(location.search).has("test")) return;
  const base = new URLSearchParams(location.search).get("scene") ?? "scene";
  try {
    const format = navigator.gpu.getPreferredCanvasFormat();
    const host = await createHost(base, format);
    const context = canvas.getContext("webgpu");
    context.configure({ device: host.device, format, alphaMode: "opaque" });
    const m = host.manifest;
    const values = {};
    const sliders = document.getElementById("sliders");
    for (const f of m.params.fields) {
      if (f.name === "time" && f.builtin) continue;
      for (let i = 0; i < f.default.length; i++) {
        const lo = f.min ? f.min[i] : f.default[i] - 1;
        const hi = f.max ? f.max[i] : f.default[i] + 1;
        const label = document.createElement("label");
        const name = f.default.length > 1 ? `${f.name}.${"xyz"[i]}` : f.name;
        label.textContent = `${name} (${f.kind})`;
        const input = Object.assign(document.createElement("input"), {
          type: "range", min: lo, max: hi, step: (hi - lo) / 1000, value: f.default[i],
        });
        // A parameter that moves the data form's parts: its buffers hold them at the
        // default, so the slider stays there (another default in the scene, emitted again, moves them).
        if (m.data?.follows.includes(f.name)) {
          input.disabled = true;
          label.title = "moves parts held in the data buffers, made at the default";
        }
        values[f.name] = [...f.default];
        input.oninput = () => (values[f.name][i] = Number(input.value));
        sliders.append(label, input);
      }
    }
    const target = m.camera.target;
    let offset = sub(m.camera.eye, target);
    let dragging = null;
    canvas.onpointerdown = (e) => (dragging = [e.clientX, e.clientY]);
    window.onpointerup = () => (dragging = null);
    window.onpointermove = (e) => {
      if (!dragging) return;
      offset = orbit(offset, e.clientX - dragging[0], e.clientY - dragging[1]);
      dragging = [e.clientX, e.clientY];
    };
    canvas.onwheel = (e) => {
      e.preventDefault();
      offset = scale(offset, Math.exp(e.deltaY * 0.001));
    };
    const started = performance.now();
    // What the page is doing, for its test (examples/hosts/test/render.mjs).
    window.sdfcLive = { frames: 0, eye: null };
    const frame = () => {
      const time = m.params.fields.find((f) => f.name === "time");
      // (Parts of the data form that move with `time` are held where its buffers hold them.)
      if (time && !m.data?.follows.includes("time")) {
        // Seconds since the page started, wrapped into `time`'s declared range if it has one.
        let t = (performance.now() - started) / 1000;
        if (time.min && time.max[0] > time.min[0]) t = time.min[0] + (t % (time.max[0] - time.min[0]));
        values.time = [t];
      }
      const eye = add(target, offset);
      const encoder = host.draw(context.getCurrentTexture().createView(), canvas.width, canvas.height, eye, values);
      host.device.queue.submit([encoder.finish()]);
      window.sdfcLive.frames += 1;
      window.sdfcLive.eye = eye;
      requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
  } catch (e) {
    status.textContent = String(e.message ?? e);
  }
}

main();
