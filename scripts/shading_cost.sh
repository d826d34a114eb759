#!/usr/bin/env bash
# Measures what each shading feature costs on one scene and writes docs/shading.md: the
# composition (examples/composition.sdf) with every feature removed, then with each one added
# alone, then all of them; `sdfc bench` with the scene's own tracer and budget, full-frame time
# (GPU timestamps) and the evaluations shading adds per pixel, as the module counts them. Then
# the jewel with Keinert's dynamic offset for secondary rays and with a fixed one.
# Usage: bash scripts/shading_cost.sh [WIDTHxHEIGHT] [REPEAT]
set -euo pipefail
cd "$(dirname "$0")/.."
size="${1:-480x270}"
repeat="${2:-7}"
cargo build --release -q -p sdfc
sdfc=./target/release/sdfc
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The composition without shadows or occlusion: the plain scene.
sed -e 's/  shadow soft  softness 16//' -e '/^occlusion /d' examples/composition.sdf > "$tmp/none.sdf"
variant() { # name, then sed expressions applied to the plain scene
  local name=$1; shift
  sed "$@" "$tmp/none.sdf" > "$tmp/$name.sdf"
}
variant shadow -e 's/^\(light { direction (-0.5, 1, -0.45).*intensity 1\)/\1  shadow soft  softness 16/'
variant occlusion -e 's/^background #202030/&\nocclusion { samples 5  distance 0.4  strength 1.2 }/'
variant fog -e 's/^background #202030/&\nfog { density 0.04 }/'
variant mirror -e 's/^material red    { color #c8372d  specular 0.6 }/material red    { color #c8372d  specular 0.6  reflect 0.4 }/'
variant glass -e 's/^material white  { color #e6e2da  specular 0.3 }/material white  { color #e6e2da  specular 0.3  transparent 0.85  ior 1.5 }/'
variant all -e 's/^\(light { direction (-0.5, 1, -0.45).*intensity 1\)/\1  shadow soft  softness 16/' \
  -e 's/^background #202030/&\nocclusion { samples 5  distance 0.4  strength 1.2 }\nfog { density 0.04 }/' \
  -e 's/^material red    { color #c8372d  specular 0.6 }/material red    { color #c8372d  specular 0.6  reflect 0.4 }/' \
  -e 's/^material white  { color #e6e2da  specular 0.3 }/material white  { color #e6e2da  specular 0.3  transparent 0.85  ior 1.5 }/'
for name in none shadow occlusion fog mirror glass all; do
  if [ "$name" != none ] && cmp -s "$tmp/none.sdf" "$tmp/$name.sdf"; then
    echo "error: the variant '$name' did not change the scene" >&2
    exit 1
  fi
  $sdfc bench "$tmp/$name.sdf" --tracers enhanced --steps 160 --size "$size" --repeat "$repeat" \
    --json > "$tmp/$name.json"
  echo "measured $name" >&2
done
for offset in dynamic fixed; do
  flag=""
  [ "$offset" = fixed ] && flag="--fixed-offset"
  $sdfc bench examples/jewel.sdf --tracers relaxed --steps 160 --size "$size" --repeat "$repeat" \
    --json $flag > "$tmp/jewel-$offset.json"
  $sdfc render examples/jewel.sdf --size "$size" --samples 1 $flag -o "$tmp/jewel-$offset.png"
  echo "measured the jewel, $offset offset" >&2
done
python3 scripts/shading_report.py "$tmp" "$size" "$repeat" > docs/shading.md
mkdir -p docs/shading
cp "$tmp/jewel-dynamic.png" docs/shading/jewel-dynamic.png
cp "$tmp/jewel-fixed.png" docs/shading/jewel-fixed.png
echo "wrote docs/shading.md" >&2
