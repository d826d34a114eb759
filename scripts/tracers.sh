#!/usr/bin/env bash
# Renders the step-count heat map of every tracer on the seeds' scenes into docs/tracers/, the
# images docs/tracers.md shows side by side. Usage: bash scripts/tracers.sh [WIDTHxHEIGHT]
set -euo pipefail
cd "$(dirname "$0")/.."
size="${1:-320x180}"
cargo build --release -q -p sdfc
mkdir -p docs/tracers
for scene in village composition mandelbulb jewel; do
  for tracer in basic relaxed enhanced hybrid auto; do
    ./target/release/sdfc render "examples/$scene.sdf" -o "docs/tracers/$scene-$tracer.png" \
      --size "$size" --channel steps --tracer "$tracer" --steps 200
  done
  ./target/release/sdfc render "examples/$scene.sdf" -o "docs/tracers/$scene-discontinuity.png" \
    --size "$size" --channel steps --discontinuity 2 --steps 200
  echo "rendered $scene"
done
# The options: a convex bound (the gem, with and without it), multi-resolution passes (the
# composition in 1, 2 and 4 passes) and cone anti-aliasing (the tori, colour, with and without).
./target/release/sdfc render examples/gem.sdf -o docs/tracers/gem-bound.png \
  --size "$size" --channel steps --steps 200
./target/release/sdfc render examples/gem.sdf -o docs/tracers/gem-no-bound.png \
  --size "$size" --channel steps --steps 200 --no-bound
for passes in 1 2 4; do
  ./target/release/sdfc render examples/composition.sdf -o "docs/tracers/composition-passes$passes.png" \
    --size "$size" --channel steps --steps 200 --passes "$passes"
done
./target/release/sdfc render examples/tori_terrain.sdf -o docs/tracers/tori-antialias.png --size "$size"
./target/release/sdfc render examples/tori_terrain.sdf -o docs/tracers/tori-no-antialias.png \
  --size "$size" --antialias none
echo "rendered the options"
