#!/usr/bin/env bash
# Runs the extremes suite (runtime/tests/extremes.rs) on the GPU and writes its tables into
# docs/stability.md between the `<!-- suite -->` markers. Usage: bash scripts/stability.sh
set -euo pipefail
cd "$(dirname "$0")/.."
SDFC_STABILITY_DOC="$PWD/docs/stability.md" \
  cargo test --release -q -p sdfc --test integration extremes:: -- --nocapture > /dev/null
echo "wrote docs/stability.md"
