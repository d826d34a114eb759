// Compiles scene files with the WebAssembly compiler in Node (V8, the engine of Chromium's
// pages): `node web/test/compile.mjs SDFC.wasm TARGET ENTRY FILE…` prints one JSON line per
// file: its name, the response, and the milliseconds the compile took: the first time (a
// `bake` is sampled then) and the best of 3.
import { readFileSync } from 'node:fs';
import { performance } from 'node:perf_hooks';
import { load } from '../sdfc.mjs';

const [wasmPath, target, entry, ...files] = process.argv.slice(2);
const sdfc = await load(readFileSync(wasmPath));
for (const file of files) {
  const source = readFileSync(file, 'utf8');
  let best = Infinity;
  let first;
  let response;
  for (let k = 0; k < 3; k++) {
    const t0 = performance.now();
    response = sdfc.compileText({ source, name: file, target, entry });
    const ms = performance.now() - t0;
    first ??= ms;
    best = Math.min(best, ms);
  }
  // The response's text as the compiler wrote it (re-serialised, `1.0` would become `1`).
  const head = JSON.stringify({ file, first_ms: first, ms: best });
  console.log(`${head.slice(0, -1)},"response":${response}}`);
}
