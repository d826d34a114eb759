#!/usr/bin/env bash
# Renders every example into docs/gallery/ (colour, and the step-count heat map), the images the
# README shows. Usage: bash scripts/gallery.sh [WIDTHxHEIGHT]
set -euo pipefail
cd "$(dirname "$0")/.."
size="${1:-480x270}"
cargo build --release -q -p sdfc
mkdir -p docs/gallery
for scene in examples/*.sdf; do
  name=$(basename "$scene" .sdf)
  ./target/release/sdfc render "$scene" -o "docs/gallery/$name.png" --size "$size" --samples 4
  ./target/release/sdfc render "$scene" -o "docs/gallery/$name-steps.png" --size "$size" --channel steps
  echo "rendered $name"
done
