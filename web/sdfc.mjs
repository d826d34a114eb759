// sdfc's compiler as WebAssembly, for pages and for Node: `const sdfc = await load(bytes)`,
// then `sdfc.compile({ source, name, target, entry })` returns `{ ok, code, manifest,
// diagnostics, summary }` (see web/src/lib.rs), `sdfc.volume(i)` the bytes of its baked
// volume i, `sdfc.data(values)` its data form's buffers at parameter values, `sdfc.seed(values)`
// what the device's pre-pass starts from. The module's five exports are used directly:
// a request is written into memory from `sdfc_alloc`, `sdfc_compile` returns the response's
// length and text, both are given back with `sdfc_free`.

// Words of the pre-pass's level uniform (`tape::seed::LEVEL_WORDS`).
const LEVEL_WORDS = 20;

export async function load(bytes) {
  const { instance } = await WebAssembly.instantiate(bytes, {});
  const wasm = instance.exports;
  const encoder = new TextEncoder();
  const decoder = new TextDecoder();
  const api = {
    // The response as the compiler wrote it (JSON text: its numbers as written, `1.0` not `1`).
    compileText(request) {
      const input = encoder.encode(JSON.stringify(request));
      const at = wasm.sdfc_alloc(input.length);
      new Uint8Array(wasm.memory.buffer, at, input.length).set(input);
      const out = wasm.sdfc_compile(at, input.length);
      wasm.sdfc_free(at, input.length);
      const len = new DataView(wasm.memory.buffer).getUint32(out, true);
      const text = decoder.decode(new Uint8Array(wasm.memory.buffer, out + 4, len));
      wasm.sdfc_free(out, 4 + len);
      return text;
    },
    compile(request) {
      return JSON.parse(api.compileText(request));
    },
    // Baked volume `index` of the last scene that compiled (the manifest's `volumes[index]`):
    // its r32float texels as the file `sdfc emit` writes, or null.
    volume(index) {
      const out = wasm.sdfc_volume(index);
      if (!out) return null;
      const len = new DataView(wasm.memory.buffer).getUint32(out, true);
      const bytes = new Uint8Array(wasm.memory.buffer, out + 4, len).slice();
      wasm.sdfc_free(out, 4 + len);
      return bytes;
    },
    // The data form's buffers (nodes, code, ranges) of the last scene that compiled as data
    // (its manifest has `data`), at parameter `values` ({name: [numbers]}): three Uint8Arrays,
    // or null where these values need another shader.
    data(values) {
      const all = handed(wasm.sdfc_data, values);
      return all && split(all, 3);
    },
    // What the device's pre-pass (the compile's `prune`) starts from for the last scene that
    // compiled as data, at parameter `values`: `{nodes, meta, code, ranges, levels: [{cells,
    // words}]}` (byte arrays; each level's uniform as a Uint32Array whose rooms the page fills
    // in), or null where these values need another shader or the scene has no grid.
    seed(values) {
      const all = handed(wasm.sdfc_seed, values);
      if (!all) return null;
      const [nodes, meta, code, ranges, levels] = split(all, 5);
      const words = new Uint32Array(levels.buffer, levels.byteOffset, levels.byteLength / 4);
      const out = [];
      for (let i = 0; i < words.length; i += 1 + LEVEL_WORDS) {
        out.push({ cells: words[i], words: words.slice(i + 1, i + 1 + LEVEL_WORDS) });
      }
      return { nodes, meta, code, ranges, levels: out };
    },
  };
  // A request's JSON handed to `f`; its answer's bytes (after their length), or null.
  function handed(f, request) {
    const input = encoder.encode(JSON.stringify(request ?? {}));
    const at = wasm.sdfc_alloc(input.length);
    new Uint8Array(wasm.memory.buffer, at, input.length).set(input);
    const out = f(at, input.length);
    wasm.sdfc_free(at, input.length);
    if (!out) return null;
    const len = new DataView(wasm.memory.buffer).getUint32(out, true);
    const all = new Uint8Array(wasm.memory.buffer, out + 4, len).slice();
    wasm.sdfc_free(out, 4 + len);
    return all;
  }
  // `count` byte arrays, each after its length (4 bytes, little-endian).
  function split(all, count) {
    const parts = [];
    for (let k = 0, i = 0; k < count; k++) {
      const n = new DataView(all.buffer).getUint32(i, true);
      parts.push(all.slice(i + 4, i + 4 + n));
      i += 4 + n;
    }
    return parts;
  }
  return api;
}
