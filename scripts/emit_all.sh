#!/usr/bin/env bash
# Emits every scene the repository holds with the given sdfc binary, into OUT_DIR, so that two
# builds can be compared byte for byte (`diff -r`): each example (examples/**/*.sdf) for every
# target x entry (with its manifest), and every test scene (tests/, runtime/tests/, compiler/std/) as WGSL for
# each entry. A scene that fails keeps its exit status and diagnostics instead.
#
# usage: scripts/emit_all.sh SDFC OUT_DIR
set -uo pipefail
sdfc=$(realpath "$1")
out=$2
cd "$(dirname "$0")/.."
root=$(pwd)
mkdir -p "$out"
out=$(realpath "$out")
one() { # file target entry
  local name
  name=$(echo "$1" | tr '/' '_')
  local base="$out/$name.$3"
  local ext
  case $2 in spirv) ext=spv ;; msl) ext=metal ;; *) ext=$2 ;; esac
  (cd "$out" && "$sdfc" emit "$root/$1" --target "$2" --entry "$3" -o "$(basename "$base").$ext" \
    --manifest "$(basename "$base").$ext.json" --color never 2>"$(basename "$base").$ext.err"
  echo "exit $?" >>"$(basename "$base").$ext.err")
}
for f in $(find examples -name '*.sdf' | sort); do
  for t in wgsl spirv glsl msl hlsl; do
    for e in compute fragment library trace; do one "$f" "$t" "$e"; done
  done
done
for f in $(find examples -name '*.sdf' | sort); do one "$f" glsl shadertoy; done
for f in $(find tests runtime/tests compiler/std -name '*.sdf' | sort); do
  for e in compute fragment library; do one "$f" wgsl "$e"; done
done
echo "$(ls "$out" | wc -l) files in $out"
