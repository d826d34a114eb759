// The playground's second compiler, in a worker: it samples the `@lipschitz` claims of the
// scene the page last compiled (which the page's own compile skips: up to hundreds of
// milliseconds for an `implicit`, and the check only ever warns) off the page's thread, and
// posts back the whole list of diagnostics, as `sdfc check` gives it. The newest request wins.
import { load } from "./sdfc.js";

const ready = fetch("sdfc.wasm")
  .then((r) => r.arrayBuffer())
  .then(load);
let latest = null;
let busy = false;

onmessage = (e) => {
  latest = e.data;
  if (!busy) run();
};

async function run() {
  busy = true;
  const sdfc = await ready;
  while (latest) {
    const { id, request } = latest;
    latest = null;
    const t0 = performance.now();
    const r = sdfc.compile({ ...request, annotations: "now" });
    postMessage({ id, diagnostics: r.diagnostics ?? [], ms: performance.now() - t0 });
    // Let a newer request in before the next round.
    await new Promise((ok) => setTimeout(ok, 0));
  }
  busy = false;
}
