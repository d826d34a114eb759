#!/usr/bin/env bash
# Regenerates the distance-map table of docs/bake.md (Liktor's Table 1, with the error beside
# the time): the 200-ball fluid of examples/bench/ baked at 32…256 points and analytic, every
# form against the analytic scene's one f64 ground truth, in one `sdfc bench` run.
# Usage: bash scripts/bake_bench.sh [WIDTHxHEIGHT] [REPEAT]    (about 15 minutes on 2 cores)
set -euo pipefail
# Every bake measured, none read from the cache folder.
export SDFC_CACHE_DIR=off
cd "$(dirname "$0")/.."
size="${1:-320x180}"
repeat="${2:-3}"
cargo build --release -q -p sdfc
python3 scripts/fluid.py
mkdir -p docs/bake
./target/release/sdfc bench examples/bench/fluid_baked.sdf --truth examples/bench/fluid.sdf \
  --bake-sweep 32,64,128,256 --tracers basic --steps 16,32,64,128,256,1024 \
  --size "$size" --repeat "$repeat" --json > docs/bake/fluid.json
python3 scripts/bake_report.py docs/bake/fluid.json docs/bake.md
