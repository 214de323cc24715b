#!/usr/bin/env bash
# The ring's cusp under each reconstruction of T5 (results/photon_trace_reconstructions_findings.md):
# the final image of ring_cardioid at 256² photons (the count where they differ most), Fresnel
# off as in the table, for the exact reference (`causticlab reference --final`) and each row
# that the eye reads (the binned photons reach only the receiver map), the same rectangle around
# the cardioid's cusp cropped out of each and set side by side (scripts/side_by_side.py):
# docs/images/ring_cusp_reconstructions.png.
#   bash scripts/reconstruction_images.sh
# BIN (default target/release/causticlab), WORK (default out/reconstructions), PHOTONS (256),
# EXPOSURE (0.3: the scene's 1.0 saturates the caustic; a copy of the scene in WORK sets it).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${BIN:-target/release/causticlab}
work=${WORK:-out/reconstructions}
photons=${PHOTONS:-256}
exposure=${EXPOSURE:-0.3}
mkdir -p "$work"
scene=$work/ring_cardioid.toml
sed "s/^\[render\]\$/[render]\nexposure = $exposure/" scenes/ring_cardioid.toml > "$scene"
grep -q "^exposure = $exposure" "$scene" || { echo "reconstruction_images: no [render] table to set the exposure in" >&2; exit 1; }
# name|render flags, left to right after the reference
variants=(
  "wd-points|--technique wd-points"
  "wd-quads-light-eq4|--technique wd-quads --space light --quad-lighting eq4"
  "hcm-varying-multires|--technique hcm --splat varying-multires"
  "photon-trace|--technique photon-trace"
  "differentials|--technique photon-trace --differentials true"
  "screen-space|--technique photon-trace --deposit screen-space"
)
$bin reference --final --scene "$scene" --fresnel false --out "$work/reference"
inputs=("$work/reference/final.png")
for v in "${variants[@]}"; do
  name=${v%%|*}
  # shellcheck disable=SC2086
  $bin render --scene "$scene" --photons "$photons" --fresnel false ${v#*|} --out "$work/$name" >/dev/null
  inputs+=("$work/$name/final.png")
done
# The cusp of the 512² eye's view: x 248..407, y 160..319.
python3 scripts/side_by_side.py docs/images/ring_cusp_reconstructions.png 248 160 160 160 "${inputs[@]}"
echo "wrote docs/images/ring_cusp_reconstructions.png (${#inputs[@]} images: reference, then ${variants[*]%%|*})"
