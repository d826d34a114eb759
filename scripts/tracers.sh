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
      --size "$size" --output steps --tracer "$tracer" --steps 200
  done
  ./target/release/sdfc render "examples/$scene.sdf" -o "docs/tracers/$scene-discontinuity.png" \
    --size "$size" --output steps --discontinuity 2 --steps 200
  echo "rendered $scene"
done
