#!/usr/bin/env bash
# Builds sdfc's compiler for the browser (web/: WebAssembly, no wasm-bindgen) into
# target/web/sdfc.wasm and says its size, raw and gzipped, and bundles the page's editor
# (CodeMirror 6, with npm and esbuild); target/web/ is then the whole playground (the page, the
# editor, the WebGPU and WebGL2 hosts' code, the examples):
#   python3 -m http.server -d target/web 8000     # and open http://localhost:8000 Needs the wasm32-unknown-unknown
# target (`rustup target add wasm32-unknown-unknown`). Its own target folder, so that it does
# not wait on (or invalidate) the native build's.
set -euo pipefail
cd "$(dirname "$0")/.."
# Nested scenes recurse: a 32 MiB stack in the module's memory (the CLI's thread has 256 MiB);
# runtime/tests/web.rs compiles scenes nested to every limit of the compiler with it.
export RUSTFLAGS="-C link-arg=-zstack-size=33554432"
cargo build --quiet --release -p sdfc-web --target wasm32-unknown-unknown --target-dir target/wasm
mkdir -p target/web
# The editor (CodeMirror 6), bundled by esbuild; both pinned by web/package-lock.json.
if [ ! -x web/node_modules/.bin/esbuild ] || [ web/package-lock.json -nt web/node_modules/.package-lock.json ]; then
  (cd web && npm ci --no-audit --no-fund --loglevel=error)
fi
web/node_modules/.bin/esbuild web/editor.js --bundle --format=esm --minify --log-level=warning \
  --outfile=target/web/editor.js
cp target/wasm/wasm32-unknown-unknown/release/sdfc_web.wasm target/web/sdfc.wasm
cp web/index.html web/playground.js web/verify.js examples/hosts/webgpu/host.js target/web/
cp web/sdfc.mjs target/web/sdfc.js
cp examples/hosts/webgl2/host.js target/web/host_webgl2.js
mkdir -p target/web/examples
cp examples/*.sdf target/web/examples/
raw=$(stat -c %s target/web/sdfc.wasm)
gz=$(gzip -9 -c target/web/sdfc.wasm | wc -c)
echo "target/web/sdfc.wasm: $raw bytes, $gz gzipped"
