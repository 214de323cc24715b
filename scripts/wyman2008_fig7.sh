#!/usr/bin/env bash
# Wyman 2008 Fig. 7 as images of one frame: constant splats, the thin lens, interpolated
# multiple-resolution splats and Sec. 3.3's varying splats (bench_configs/wyman2008_fig7.toml
# measures them). Per scene and method: results/quality/images/wyman2008_fig7/<scene>/
# <method>-<photons>.png, the final frame, and <method>-<photons>-error.png against the exact CPU
# reference (`causticlab compare --error-image`: red too bright, blue too dark, saturating at
# ERROR_SCALE, default 2), with the relative RMSE and flux printed.
#   bash scripts/wyman2008_fig7.sh [scene ...]   (default: sphere_on_plane bunny_in_room)
# BIN (default target/release/causticlab), PHOTONS (128), REF_PHOTONS (4194304), WORK
# (out/fig7), RESULTS.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${BIN:-target/release/causticlab}
photons=${PHOTONS:-128}
ref_photons=${REF_PHOTONS:-4194304}
scale=${ERROR_SCALE:-2}
work=${WORK:-out/fig7}
results=${RESULTS:-results/quality/images/wyman2008_fig7}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(sphere_on_plane bunny_in_room)
# name|render flags (every one --fresnel false and the fitted photon view, as the bench config)
methods=(
  "constant|--technique hcm"
  "thin-lens|--technique wd-points --splat thin-lens"
  "interpolated|--technique hcm --splat interpolated"
  "sec3.3|--technique hcm --splat varying-multires"
)
for s in "${scenes[@]}"; do
  ref=$work/$s/ref
  [ -f "$ref/receiver.exr" ] || $bin reference --scene "scenes/$s.toml" --photons "$ref_photons" --seed 1 --fresnel false --out "$ref" > /dev/null
  mkdir -p "$results/$s"
  for m in "${methods[@]}"; do
    IFS='|' read -r name flags <<< "$m"
    out=$work/$s/$name-$photons
    # shellcheck disable=SC2086 # the flags are words
    $bin render --scene "scenes/$s.toml" $flags --photon-view fitted --photons "$photons" --fresnel false \
      --dump receiver --out "$out" > "$out.log"
    cp "$out/final.png" "$results/$s/$name-$photons.png"
    printf '%s %s %s²: ' "$s" "$name" "$photons"
    $bin compare "$out/receiver.exr" "$ref/receiver.exr" --error-image "$results/$s/$name-$photons-error.png" \
      --error-scale "$scale" --json 2> /dev/null | python3 -c 'import json,sys; c=json.load(sys.stdin); print("rel. RMSE %.3f, flux %.3f" % (c["rel_rmse"], c["caustic_flux_ratio"]))'
  done
done
