#!/usr/bin/env bash
# Regenerates docs/benchmarks.md and its plots: `sdfc bench` on the seeds' three scenes (the
# Mandelbulb, the composition of tori/spheres/boxes/cylinders, the planar village), every
# tracer at 8…256 steps against the f64 ground truth.
# Usage: bash scripts/bench.sh [WIDTHxHEIGHT] [REPEAT]
set -euo pipefail
cd "$(dirname "$0")/.."
size="${1:-320x180}"
repeat="${2:-5}"
eps=0.0001
cargo build --release -q -p sdfc
mkdir -p docs/benchmarks
for scene in mandelbulb composition village; do
  ./target/release/sdfc bench "examples/$scene.sdf" --size "$size" --repeat "$repeat" \
    --epsilon "$eps" --json --plot "docs/benchmarks/$scene.png" > "docs/benchmarks/$scene.json"
  echo "measured $scene" >&2
done
# Compile time (criterion): parse → check → lower → validate → WGSL for generated scenes.
cargo bench -q -p sdfc-compiler > /dev/null
python3 scripts/bench_report.py "$size" "$repeat" "$eps" > docs/benchmarks.md
echo "wrote docs/benchmarks.md" >&2
