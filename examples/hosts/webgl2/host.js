// A WebGL2 host for sdfc's GLSL ES 3.00 output (docs/interface.md, "Host checklist"), with no
// framework and no name written by hand: block names, bindings, offsets and the fragment
// entry's flags all come from the manifest.
//
//   the fragment entry:  sdfc emit SCENE.sdf --target glsl --glsl-version 300es --entry fragment -o scene.frag --manifest scene.json
//   the library:         sdfc emit SCENE.sdf --target glsl --glsl-version 300es --entry library -o scene.glsl --manifest scene.library.json
//
// The page (`index.html?scene=NAME`) draws NAME.frag with NAME.json, orbiting with the mouse,
// a slider per parameter, `time` running with the clock.

const VERTEX = `#version 300 es
void main() {
  vec2 xy = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(xy * 2.0 - 1.0, 0.0, 1.0);
}
`;

const sub = (a, b) => a.map((x, i) => x - b[i]);
const add = (a, b) => a.map((x, i) => x + b[i]);
const scale = (a, k) => a.map((x) => x * k);
const dot = (a, b) => a.reduce((s, x, i) => s + x * b[i], 0);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a) => scale(a, 1 / Math.sqrt(dot(a, a)));

/** The pinhole camera of `sdfc render` (docs/interface.md): eye, right, up, forward, footprint. */
function camera(manifest, eye, width, height) {
  const c = manifest.camera;
  const forward = normalize(sub(c.target, eye));
  const right = normalize(cross(forward, c.up));
  const up = cross(right, forward);
  const t = Math.tan((c.fov_degrees * Math.PI) / 360);
  return { eye, right: scale(right, t * width / height), up: scale(up, t), forward, pixel: t / height };
}

/**
 * The `View` uniform's bytes, at the offsets the manifest gives its members: the camera, the
 * image size, and the fragment entry's flags where the manifest puts them (`fragment.y_up`,
 * `fragment.srgb`).
 */
function viewBytes(manifest, view, width, height, flags) {
  const struct = manifest.structs.find((s) => s.name === manifest.view.struct);
  const bytes = new ArrayBuffer(struct.size);
  const f = new Float32Array(bytes);
  const u = new Uint32Array(bytes);
  const at = (member) => struct.members.find((m) => m.name === member).offset / 4;
  const put = (member, values) => values.forEach((x, i) => (f[at(member) + i] = x));
  put("eye", view.eye);
  put("right", [...view.right, 0.5]);
  put("up", [...view.up, 0.5]);
  put("forward", view.forward);
  put("size", [width, height, view.pixel]);
  [0, 0, width, height].forEach((x, i) => (u[at("offset") + i] = x));
  const fragment = manifest.fragment;
  if (fragment) {
    f[at(fragment.y_up.field) + fragment.y_up.component] = flags.yUp ? 1 : 0;
    f[at(fragment.srgb.field) + fragment.srgb.component] = flags.srgb ? 1 : 0;
  }
  return bytes;
}

/** The `Params` uniform from the manifest: each field's value (default unless given) at its offset. */
function paramsBytes(manifest, values) {
  const data = new Float32Array(Math.max(manifest.params.size, 16) / 4);
  for (const f of manifest.params.fields) {
    (values[f.name] ?? f.default).forEach((x, i) => (data[f.offset / 4 + i] = x));
  }
  return data;
}

/**
 * The library as a whole fragment shader: its placeholder `main` (GLSL needs one; docs/interface.md)
 * replaced by one that traces the pixel's ray with the library's `color` (its name as the
 * manifest declares it) and encodes sRGB.
 */
function libraryShader(code, manifest) {
  const color = manifest.functions.find((f) => f.name === (manifest.prefix ? `${manifest.prefix}_color` : "color"));
  if (!color?.declaration) throw new Error("the manifest declares no `color`: emit with --entry library");
  const name = color.declaration.match(/(\w+)\(/)[1];
  const body = code.replace(/\nvoid main\(\) \{[\s\S]*\n\}\s*$/, "\n");
  if (body === code) throw new Error("the library has no placeholder main");
  return `${body}
uniform HostCamera { vec4 eye; vec4 right; vec4 up; vec4 forward; vec4 size; } host_camera;
out vec4 host_color;
vec3 host_srgb(vec3 c) {
  vec3 l = clamp(c, 0.0, 1.0);
  return mix(1.055 * pow(l, vec3(1.0 / 2.4)) - 0.055, l * 12.92, lessThanEqual(l, vec3(0.0031308)));
}
void main() {
  vec2 p = vec2(gl_FragCoord.x, host_camera.size.y - gl_FragCoord.y);
  float u = 2.0 * p.x / host_camera.size.x - 1.0;
  float v = 1.0 - 2.0 * p.y / host_camera.size.y;
  vec3 rd = normalize(host_camera.forward.xyz + host_camera.right.xyz * u + host_camera.up.xyz * v);
  vec4 c = ${name}(host_camera.eye.xyz, rd, host_camera.size.z);
  host_color = vec4(host_srgb(c.rgb), c.w);
}
`;
}

function compile(gl, type, source) {
  const s = gl.createShader(type);
  gl.shaderSource(s, source);
  gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(`compile: ${gl.getShaderInfoLog(s)}`);
  return s;
}

/** A linked program of the host's full-screen triangle and `fragment`; throws with the log. */
export function link(gl, fragment) {
  const p = gl.createProgram();
  gl.attachShader(p, compile(gl, gl.VERTEX_SHADER, VERTEX));
  gl.attachShader(p, compile(gl, gl.FRAGMENT_SHADER, fragment));
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(`link: ${gl.getProgramInfoLog(p)}`);
  return p;
}

/**
 * Everything drawing needs, for `code` (the fragment entry, or the library with `library`
 * set) and its manifest: the program and a buffer per uniform block, each block bound by the
 * name and binding the manifest gives.
 */
export function createHost(gl, code, manifest, library = false, volumes = null) {
  if (manifest.format !== "sdfc-manifest 1") throw new Error(`unknown manifest format ${manifest.format}`);
  const program = link(gl, library ? libraryShader(code, manifest) : code);
  const textures = volumeTextures(gl, program, manifest, volumes);
  const blocks = [];
  const uniforms = manifest.bindings.filter((b) => b.space === "uniform");
  if (library) uniforms.push({ glsl_block: "HostCamera", binding: 0, size: 80, host: true });
  for (const b of uniforms) {
    const index = gl.getUniformBlockIndex(program, b.glsl_block);
    if (index === gl.INVALID_INDEX) continue; // declared, but read by nothing the entry calls
    gl.uniformBlockBinding(program, index, b.binding);
    const buffer = gl.createBuffer();
    gl.bindBuffer(gl.UNIFORM_BUFFER, buffer);
    gl.bufferData(gl.UNIFORM_BUFFER, Math.max(b.size, 16), gl.DYNAMIC_DRAW);
    blocks.push({ ...b, buffer });
  }
  /** Draws `width`×`height` into the bound framebuffer from `eye` with `values` and `flags`. */
  function draw(width, height, eye, values, flags) {
    const view = camera(manifest, eye, width, height);
    gl.useProgram(program);
    textures.forEach((t, unit) => {
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(gl.TEXTURE_3D, t.texture);
      gl.uniform1i(t.location, unit);
    });
    for (const b of blocks) {
      let bytes;
      if (b.host) bytes = hostCameraBytes(view, width, height);
      else if (b.binding === manifest.view?.binding?.binding) bytes = viewBytes(manifest, view, width, height, flags);
      else bytes = paramsBytes(manifest, values);
      gl.bindBuffer(gl.UNIFORM_BUFFER, b.buffer);
      gl.bufferSubData(gl.UNIFORM_BUFFER, 0, bytes);
      gl.bindBufferBase(gl.UNIFORM_BUFFER, b.binding, b.buffer);
    }
    gl.viewport(0, 0, width, height);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }
  return { manifest, draw };
}

/**
 * The scene's baked distance maps (the manifest's `volumes`, docs/bake.md) as R32F 3D textures
 * from their bytes (`volumes[i]`: r32float texels, x fastest, as `sdfc emit` writes the files),
 * each with the sampler uniform the manifest's binding names (the shader reads texels with
 * `texelFetch`: no filtering). A scene with volumes and no bytes is an error, not a picture
 * without its maps.
 */
function volumeTextures(gl, program, manifest, volumes) {
  const list = manifest.volumes ?? [];
  if (list.length > 0 && volumes?.length !== list.length) {
    throw new Error(`the scene samples ${list.length} baked volume(s): the host needs their bytes`);
  }
  return list.map((v, i) => {
    if (v.format !== "r32float") throw new Error(`volume ${v.global}: unknown format ${v.format}`);
    const [w, h, d] = v.size;
    const bytes = volumes[i] instanceof ArrayBuffer ? volumes[i] : volumes[i].slice().buffer;
    if (bytes.byteLength !== 4 * w * h * d) {
      throw new Error(`${v.file}: ${bytes.byteLength} bytes, but ${w}×${h}×${d} r32float texels take ${4 * w * h * d}`);
    }
    const texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_3D, texture);
    for (const p of [gl.TEXTURE_MIN_FILTER, gl.TEXTURE_MAG_FILTER]) gl.texParameteri(gl.TEXTURE_3D, p, gl.NEAREST);
    for (const p of [gl.TEXTURE_WRAP_S, gl.TEXTURE_WRAP_T, gl.TEXTURE_WRAP_R]) gl.texParameteri(gl.TEXTURE_3D, p, gl.CLAMP_TO_EDGE);
    gl.texImage3D(gl.TEXTURE_3D, 0, gl.R32F, w, h, d, 0, gl.RED, gl.FLOAT, new Float32Array(bytes));
    const binding = manifest.bindings.find((b) => b.name === v.global);
    return { texture, location: gl.getUniformLocation(program, binding?.glsl_block ?? "") };
  });
}

/** The bytes of the manifest's baked volumes, from their files beside `${base}.json`. */
export function fetchVolumes(manifest, base) {
  const at = new URL(`${base}.json`, location.href);
  return Promise.all(
    (manifest.volumes ?? []).map((v) =>
      fetch(new URL(v.file, at)).then((r) => (r.ok ? r.arrayBuffer() : Promise.reject(new Error(`${v.file}: ${r.status}`)))),
    ),
  );
}

/** The library host's own camera block (`HostCamera`: eye, right, up, forward, size). */
function hostCameraBytes(view, width, height) {
  return new Float32Array([...view.eye, 0, ...view.right, 0, ...view.up, 0, ...view.forward, 0, width, height, view.pixel, 0]);
}

/**
 * Renders `width`×`height` from the scene's camera into an offscreen framebuffer and returns
 * its RGBA8 pixels, row-major with y down (as `sdfc render` writes them): `target` "rgba8" (the
 * entry encodes sRGB) or "srgb8" (an SRGB8_ALPHA8 renderbuffer: the entry writes linear light
 * and GL encodes), `yUp` the origin flag (true is GL's; false draws the picture upside down),
 * `eye` where the camera is (by default the scene's).
 */
export async function renderPixels(base, width, height, values = {}, options = {}) {
  const { target = "rgba8", yUp = true, library = false } = options;
  const ext = library ? "glsl" : "frag";
  const [code, manifest] = await Promise.all([
    fetch(`${base}.${ext}`).then((r) => (r.ok ? r.text() : Promise.reject(new Error(`${base}.${ext}: ${r.status}`)))),
    fetch(`${base}.json`).then((r) => (r.ok ? r.json() : Promise.reject(new Error(`${base}.json: ${r.status}`)))),
  ]);
  const canvas = document.createElement("canvas");
  const gl = canvas.getContext("webgl2");
  if (!gl) throw new Error("this browser has no WebGL2");
  const volumes = await fetchVolumes(manifest, base);
  return hostPixels(gl, createHost(gl, code, manifest, library, volumes), width, height, values, { target, yUp });
}

/** [renderPixels] with a host already made on `gl`, from the scene's camera. */
export function hostPixels(gl, host, width, height, values = {}, options = {}) {
  const { target = "rgba8", yUp = true, eye = host.manifest.camera.eye } = options;
  // Errors from earlier work on this context are not this picture's (the caller may look
  // at them first).
  while (gl.getError() !== gl.NO_ERROR);
  const fbo = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
  const rb = gl.createRenderbuffer();
  gl.bindRenderbuffer(gl.RENDERBUFFER, rb);
  gl.renderbufferStorage(gl.RENDERBUFFER, target === "srgb8" ? gl.SRGB8_ALPHA8 : gl.RGBA8, width, height);
  gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.RENDERBUFFER, rb);
  if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) throw new Error("incomplete framebuffer");
  host.draw(width, height, eye, values, { yUp, srgb: target === "rgba8" });
  const raw = new Uint8Array(4 * width * height);
  gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, raw);
  const error = gl.getError();
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  gl.deleteRenderbuffer(rb);
  gl.deleteFramebuffer(fbo);
  if (error) throw new Error(`GL error ${error}`);
  // readPixels' rows start at the bottom: turn them to y down.
  const out = new Uint8Array(raw.length);
  for (let y = 0; y < height; y++) out.set(raw.subarray(4 * width * (height - 1 - y), 4 * width * (height - y)), 4 * width * y);
  return out;
}

/** The interactive page: the fragment entry on the canvas, orbit, sliders, `time` running. */
async function main() {
  const status = document.getElementById("status");
  const canvas = document.getElementById("view");
  if (!canvas || new URLSearchParams(location.search).has("test")) return;
  const base = new URLSearchParams(location.search).get("scene") ?? "scene";
  try {
    const [code, manifest] = await Promise.all([fetch(`${base}.frag`).then((r) => r.text()), fetch(`${base}.json`).then((r) => r.json())]);
    const gl = canvas.getContext("webgl2");
    const host = createHost(gl, code, manifest, false, await fetchVolumes(manifest, base));
    const values = {};
    for (const f of manifest.params.fields) {
      if (f.name === "time" && f.builtin) continue;
      values[f.name] = [...f.default];
      f.default.forEach((d, i) => {
        const [lo, hi] = [f.min ? f.min[i] : d - 1, f.max ? f.max[i] : d + 1];
        const label = Object.assign(document.createElement("label"), { textContent: `${f.name}${f.default.length > 1 ? "." + "xyz"[i] : ""} (${f.kind}${f.unit ? ", " + f.unit : ""})` });
        const input = Object.assign(document.createElement("input"), { type: "range", min: lo, max: hi, step: (hi - lo) / 1000, value: d });
        input.oninput = () => (values[f.name][i] = Number(input.value));
        document.getElementById("sliders").append(label, input);
      });
    }
    const target = manifest.camera.target;
    let offset = sub(manifest.camera.eye, target);
    let dragging = null;
    canvas.onpointerdown = (e) => (dragging = [e.clientX, e.clientY]);
    window.onpointerup = () => (dragging = null);
    window.onpointermove = (e) => {
      if (!dragging) return;
      const [dx, dy] = [e.clientX - dragging[0], e.clientY - dragging[1]];
      dragging = [e.clientX, e.clientY];
      const r = Math.hypot(...offset);
      const azimuth = Math.atan2(offset[0], offset[2]) - dx * 0.01;
      const elevation = Math.min(1.5, Math.max(-1.5, Math.asin(offset[1] / r) + dy * 0.01));
      offset = [r * Math.cos(elevation) * Math.sin(azimuth), r * Math.sin(elevation), r * Math.cos(elevation) * Math.cos(azimuth)];
    };
    const started = performance.now();
    window.sdfcLive = { frames: 0 };
    const frame = () => {
      const time = manifest.params.fields.find((f) => f.name === "time");
      if (time) {
        let t = (performance.now() - started) / 1000;
        if (time.min && time.max[0] > time.min[0]) t = time.min[0] + (t % (time.max[0] - time.min[0]));
        values.time = [t];
      }
      // The canvas: GL's origin, and not sRGB, so the entry encodes.
      host.draw(canvas.width, canvas.height, add(target, offset), values, { yUp: true, srgb: true });
      window.sdfcLive.frames += 1;
      requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
  } catch (e) {
    status.textContent = String(e.message ?? e);
  }
}

main();
