#!/usr/bin/env bash
# How far the quality tables' FLIP column (the final image against `reference --final` at level 1,
# Fresnel off) depends on the reference's level, on the scenes and cells where FLIP and the
# relative RMSE rank techniques differently (results/quality/README.md, "FLIP against the
# relative RMSE"), and of the other tables with a FLIP column: level 1 against level 2 of each
# scene, and each of those cells' render against both.
# Writes results/quality/flip_levels.csv (one row per pair: scene, a, photons, the reference's
# level, the FLIP mean) and leaves the images, and FLIP error images beside each compared render, in WORK.
#   bash scripts/flip_levels.sh          # WORK defaults to out/flip_levels
# Needs a release build. On lavapipe each level-2 reference (2^26 photons) takes minutes. Images
# already in WORK are reused (each reuse is printed): delete WORK after a change that alters them.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${CAUSTICLAB:-target/release/causticlab}
work=${WORK:-out/flip_levels}
csv=results/quality/flip_levels.csv
mkdir -p "$work"
rows=()
# The FLIP mean of $1 against $2; compare's own error (a missing or mismatched image) stops the
# script, and so does a comparison without a FLIP (compare's warning says why).
flip() {
  local json
  json=$("$bin" compare "$1" "$2" --json --error-image "$3")
  python3 -c 'import json, sys
f = json.loads(sys.argv[1]).get("flip")
if f is None:
    sys.exit(f"flip_levels.sh: compare {sys.argv[2]} {sys.argv[3]} gave no FLIP")
print("%.6f" % f["mean"])' "$json" "$1" "$2"
}
# The scenes of the quality tables' paragraph, then those of W&D 2006 Fig. 10 (both octahedra),
# and the bunny of Wyman 2008 Fig. 7 and the front: each level 1 against level 2.
for s in sphere_on_plane ring_cardioid underwater octahedron octahedron_metal bunny_in_room; do
  for level in 1 2; do
    [ -f "$work/$s/L$level/final.exr" ] && echo "flip_levels.sh: reusing $work/$s/L$level/final.exr" >&2
    [ -f "$work/$s/L$level/final.exr" ] || \
      "$bin" reference --final --scene "scenes/$s.toml" --level "$level" --fresnel false --out "$work/$s/L$level" > /dev/null
  done
  rows+=("$s,L1,-,L2,$(flip "$work/$s/L1/final.exr" "$work/$s/L2/final.exr" "$work/$s/L1.vsL2.png")")
done
# scene|name|photons|render flags: the cells of Q1, Q2 and Q4 the page's paragraph compares.
cells="sphere_on_plane|wd-points|256|--technique wd-points
sphere_on_plane|gather eye Eq. 11|256|--technique wd-gather --space eye --gather-lighting eq11
sphere_on_plane|wd-points|512|--technique wd-points
sphere_on_plane|wd-points thin-lens|512|--technique wd-points --splat thin-lens
sphere_on_plane|shah|2048|--technique shah
sphere_on_plane|wd-points|2048|--technique wd-points
ring_cardioid|wd-points|256|--technique wd-points
ring_cardioid|wd-points|1024|--technique wd-points
ring_cardioid|quads eye Eq. 3 polygons|256|--technique wd-quads --space eye --quad-draw polygons
ring_cardioid|quads eye Eq. 4|256|--technique wd-quads --space eye --quad-lighting eq4
ring_cardioid|gather eye Eq. 10|256|--technique wd-gather --space eye
underwater|shah-vertex|256|--technique shah-vertex
underwater|wd-points|256|--technique wd-points
underwater|wd-points|1024|--technique wd-points
underwater|quads eye Eq. 3|256|--technique wd-quads --space eye"
while IFS='|' read -r s name n flags; do
  out=$work/$s/$(tr -cs 'A-Za-z0-9' '-' <<< "$name")$n
  # shellcheck disable=SC2086 # the flags are words
  [ -f "$out/final.exr" ] && echo "flip_levels.sh: reusing $out/final.exr" >&2
  [ -f "$out/final.exr" ] || "$bin" render --scene "scenes/$s.toml" $flags --photons "$n" --fresnel false --out "$out" > /dev/null
  for level in 1 2; do
    rows+=("$s,$name,$n^2,L$level,$(flip "$out/final.exr" "$work/$s/L$level/final.exr" "$out.vsL$level.png")")
  done
done <<< "$cells"
{
  echo "scene,a,photons,reference_level,flip"
  printf '%s\n' "${rows[@]}"
} > "$csv"
cat "$csv"
echo "wrote $csv"
