#!/usr/bin/env bash
# Regenerates docs/benchmarks.md and its plots and JSON (docs/benchmarks/):
# - `sdfc bench` on the seeds' three scenes (the Mandelbulb, the composition of
#   tori/spheres/boxes/cylinders, the planar village), every tracer at 8…256 steps against the
#   f64 ground truth, trace-only and full-frame times;
# - sdfc's trace-only shader next to hand-written references (runtime/benches/reference/),
#   alternating frames in one process;
# - bounding boxes in map(): a flat 39-part village with and without its box tree, copies
#   grouped into repeats, and every example with a tree against its plain trace; the CPU;
# - the cost of a trivial frame against a bare dispatch and a hand-written one-step tracer;
# - compile time: criterion in the library, and `sdfc emit` as a whole process.
# Usage: bash scripts/bench.sh [WIDTHxHEIGHT] [REPEAT]
set -euo pipefail
cd "$(dirname "$0")/.."
size="${1:-320x180}"
repeat="${2:-5}"
eps=0.0001
cargo build --release -q -p sdfc
sdfc=./target/release/sdfc
out=docs/benchmarks
mkdir -p "$out"
# `sdfc emit` of the 10 001-node scene of compiler/benches/compile.rs as a whole process, first:
# right after criterion's and the GPU's work the same command measured 105 ms against 75 ms
# on its own (the kernel's huge pages are then fragmented; stop 18).
python3 scripts/emit_time.py "$sdfc" > "$out/emit-process.json"
for scene in mandelbulb composition village; do
  $sdfc bench "examples/$scene.sdf" --size "$size" --repeat "$repeat" \
    --epsilon "$eps" --json --plot "$out/$scene.png" > "$out/$scene.json"
  echo "measured $scene" >&2
done
# Hand-written references: basic tracing with each example's own budget, ε and distance.
for spec in composition:160:composition mandelbulb:256:mandelbulb village:200:village \
  village:200:village_cells village:200:village_instanced; do
  IFS=: read -r scene steps ref <<< "$spec"
  $sdfc bench "examples/$scene.sdf" --tracers basic --steps "$steps" --size "$size" --no-bvh \
    --repeat 21 --reference "runtime/benches/reference/$ref.wgsl" --json > "$out/reference-$ref.json"
  echo "measured $scene against $ref.wgsl" >&2
done
# Large unions: the flat village written apart (every part its own), without and with its box
# tree, as written (copies grouped into repeats), and the village's own repeats; then each
# beside the apart village's plain trace, alternating frames.
for v in village_flat_apart village_flat; do
  for bvh in --no-bvh ""; do
    $sdfc bench "examples/bench/$v.sdf" --tracers basic,enhanced --steps 200 --size "$size" \
      --repeat 9 $bvh --json > "$out/bvh-$v${bvh:+-off}.json"
  done
done
$sdfc bench examples/village.sdf --tracers basic,enhanced --steps 200 --size "$size" \
  --repeat 9 --json > "$out/bvh-village.json"
tmp=$(mktemp -d)
$sdfc emit examples/bench/village_flat_apart.sdf --entry trace --tracer basic --no-bvh -q \
  -o "$tmp/apart.wgsl"
for v in village_flat_apart village_flat; do
  $sdfc bench "examples/bench/$v.sdf" --tracers basic --steps 200 --size "$size" --repeat 21 \
    --reference "$tmp/apart.wgsl" --json > "$out/bvh-side-$v.json"
done
# Where trees pay: each example's trace with its default trees (only unions of 5 or more
# parts) and with every tree (--bvh), each beside its plain trace (--no-bvh).
for scene in blobs composition dodecahedron domain_ops jewel lamp primitives shapes temple \
  textures tori_terrain village; do
  f="examples/$scene.sdf"
  $sdfc emit "$f" --entry trace --tracer basic --steps 200 --no-bvh -q -o "$tmp/plain.wgsl"
  for bvh in "" --bvh; do
    $sdfc emit "$f" --entry trace --tracer basic --steps 200 $bvh -q -o "$tmp/trees.wgsl"
    if cmp -s "$tmp/plain.wgsl" "$tmp/trees.wgsl"; then
      echo '{"plain": true}' > "$out/trees-$scene${bvh:+-all}.json"
    else
      $sdfc bench "$f" --tracers basic --steps 200 --size "$size" --repeat 11 $bvh \
        --reference "$tmp/plain.wgsl" --json > "$out/trees-$scene${bvh:+-all}.json"
    fi
  done
done
rm -r "$tmp"
echo "measured large unions" >&2
# A trivial frame: against a dispatch that traces nothing at four sizes (the fixed cost per
# frame is where time against pixels meets zero pixels), and a one-step tracer at 512².
for n in 128 256 512 1024; do
  $sdfc bench examples/bench/trivial.sdf --tracers basic --steps 1 --size "${n}x${n}" --repeat 21 \
    --reference runtime/benches/reference/bare.wgsl --json > "$out/trivial-bare-$n.json"
done
$sdfc bench examples/bench/trivial.sdf --tracers basic --steps 1 --size 512x512 --repeat 21 \
  --reference runtime/benches/reference/trivial.wgsl --json > "$out/trivial-trivial.json"
# Frames of 8² and 16² pixels, which are all fixed cost: the fixed cost measured directly.
for n in 8 16; do
  $sdfc bench examples/bench/trivial.sdf --tracers basic --steps 1 --size "${n}x${n}" --repeat 41 \
    --reference runtime/benches/reference/bare.wgsl --json > "$out/trivial-tiny-$n.json"
done
echo "measured the trivial frame" >&2
# Compile time (criterion): parse → check → lower → validate → WGSL for generated scenes; and
# the CPU field with and without bounding-volume trees.
rm -rf "target/criterion/CPU field"  # (a renamed scene's old estimates would be read too)
cargo bench -q -p sdfc-compiler > /dev/null
python3 scripts/bench_report.py "$size" "$repeat" "$eps" > docs/benchmarks.md
echo "wrote docs/benchmarks.md" >&2
