#!/usr/bin/env bash
# Error images of Wyman & Davis 2006's techniques (and the light-space splat) against the exact
# CPU reference: results/quality/images/<scene>/<technique>-<photons>.png, red where a technique
# is too bright, blue where too dark (`causticlab compare --error-image X.png`), all saturating
# at the same |E/E0 error| (ERROR_SCALE, default 2) so the images compare across techniques.
# Sparse photons (256^2) show the noise of points and quads, dense ones (2048^2) the blur of the
# gathers (the paper's Fig. 11 remarks).
#   bash scripts/error_images.sh [scene ...]   (default: sphere_on_plane ring_cardioid)
# BIN (default target/release/causticlab), REF_PHOTONS (16M), WORK (out/quality), RESULTS.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${BIN:-target/release/causticlab}
ref_photons=${REF_PHOTONS:-16000000}
scale=${ERROR_SCALE:-2}
work=${WORK:-out/quality}
results=${RESULTS:-results/quality/images}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(sphere_on_plane ring_cardioid)
# name|render flags (every one --fresnel false, as the reference)
variants=(
  "wd-points|--technique wd-points"
  "eye-points|--technique wd-eye-points --gather-lighting eq11"
  "quads-eye|--technique wd-quads --space eye --quad-lighting eq4"
  "quads-light|--technique wd-quads --space light --quad-lighting eq4"
  "gather-eye|--technique wd-gather --space eye --gather-lighting eq11"
  "gather-light|--technique wd-gather --space light --gather-lighting eq11"
)
for s in "${scenes[@]}"; do
  ref=$work/$s/ref1
  [ -f "$ref/receiver.exr" ] || $bin reference --scene "scenes/$s.toml" --photons "$ref_photons" --seed 1 --fresnel false --out "$ref"
  mkdir -p "$results/$s" "$work/$s/images"
  for v in "${variants[@]}"; do
    IFS='|' read -r name flags <<< "$v"
    for n in 256 2048; do
      out=$work/$s/images/$name-$n
      # shellcheck disable=SC2086 # the flags are words
      $bin render --scene "scenes/$s.toml" $flags --photons "$n" --fresnel false --dump receiver --out "$out" > "$out.log"
      printf '%s %s %s: ' "$s" "$name" "$n"
      $bin compare "$out/receiver.exr" "$ref/receiver.exr" --error-image "$results/$s/$name-$n.png" \
        --error-scale "$scale" --json | python3 -c 'import json,sys; c=json.load(sys.stdin); print("rel. RMSE %.3f, flux %.3f" % (c["rel_rmse"], c["caustic_flux_ratio"]))'
    done
  done
done
