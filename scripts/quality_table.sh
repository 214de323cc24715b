#!/usr/bin/env bash
# Regenerates results/quality/<scene>.md: the caustic techniques listed below (shah, wd-points, its
# thin-lens splats, shah-vertex and three hcm variants) against the exact CPU photon reference,
# at 256^2..2048^2 photons, with the reference's own noise (two seeds).
#   bash scripts/quality_table.sh [scene ...]      (default: sphere_on_plane sphere_oblique)
# Needs a release build (cargo build --release) and python3 for the table layout.
# REF_PHOTONS (default 16M), WORK (default out/quality) and RESULTS (default results/quality)
# override the reference size and where the renders and the tables go.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=target/release/causticlab
ref_photons=${REF_PHOTONS:-16000000}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(sphere_on_plane sphere_oblique)
work=${WORK:-out/quality}
results=${RESULTS:-results/quality}
mkdir -p "$work" "$results"
for s in "${scenes[@]}"; do
  scene=scenes/$s.toml
  rows=$work/$s.rows
  : > "$rows"
  for seed in 1 2; do
    [ -f "$work/$s/ref$seed/receiver.exr" ] || \
      $bin reference --scene "$scene" --photons "$ref_photons" --seed $seed --fresnel false --out "$work/$s/ref$seed"
  done
  echo "reference-noise|$ref_photons|$($bin compare "$work/$s/ref2/receiver.exr" "$work/$s/ref1/receiver.exr" --json | tr -d '\n')" >> "$rows"
  # label|folder|render flags
  variants=(
    "shah|shah|--technique shah"
    "wd-points|wd-points|--technique wd-points"
    "wd-points thin-lens (Wyman 2008 Fig. 7)|wd-points-thin-lens|--technique wd-points --splat thin-lens"
    "shah-vertex|shah-vertex|--technique shah-vertex"
    "hcm (compute, combine last)|hcm|--technique hcm --path compute --cluster last"
    "hcm varying multi-res (max distance)|hcm-varying|--technique hcm --path compute --cluster last --splat varying-multires"
    "hcm varying multi-res (beam area, Eq. 2)|hcm-beam-area|--technique hcm --path compute --cluster last --splat varying-multires --varying-radius beam-area"
  )
  for v in "${variants[@]}"; do
    IFS='|' read -r label folder flags <<< "$v"
    for n in 256 512 1024 2048; do
      [ "$folder" = shah-vertex ] && [ "$n" != 256 ] && continue   # photons follow the tessellation
      out=$work/$s/$folder-$n
      # shellcheck disable=SC2086 # the flags are words
      $bin render --scene "$scene" $flags --photons "$n" --fresnel false --out "$out" --dump receiver > "$out.log"
      echo "$label|$n|$($bin compare "$out/receiver.exr" "$work/$s/ref1/receiver.exr" --json | tr -d '\n')" >> "$rows"
    done
  done
  device=$($bin devices | sed -n 's/^\[\([0-9]*\)\] \(.*\) \[default\].*/\2/p' | head -1)
  python3 - "$s" "$rows" "$ref_photons" "$device" "$(git rev-parse --short HEAD)" > "$results/$s.md" <<'PY'
import json, sys, datetime
scene, rows, ref_photons, device, commit = sys.argv[1:6]
device = device.strip()
print(f"# Caustic quality: `{scene}` against the exact CPU photon reference\n")
print(f"Device: {device or 'default device'}; commit {commit}; {datetime.date.today()}. "
      f"Reference: `causticlab reference --photons {ref_photons} --fresnel false` (seed 1); all techniques "
      "`--fresnel false` (two refractions, all power transmitted), default splat (Gaussian, radius 1.5 texels; "
      "the `hcm varying` rows size each splat from its neighbours instead, the `thin-lens` row from a per-photon "
      "thin-lens model), "
      "caustic map 1024^2, 4 back-face iterations. Regenerate: `bash scripts/quality_table.sh " + scene + "`.\n")
print("Errors are over the texels where either receiver map differs from 1 by more than 0.05 "
      "(see `causticlab compare`). `shah-vertex` traces one photon per mesh vertex, so its photon count is "
      "the tessellation's, not N^2.\n")
print("| technique | photons | region texels | rel. RMSE | rel. RMSE after best scale | best scale | peak ratio | peak offset (texels) | caustic flux ratio |")
print("|---|---|---|---|---|---|---|---|---|")
for line in open(rows):
    t, n, js = line.rstrip("\n").split("|", 2)
    # A metric is null where a map has a texel that is not finite (non_finite_texels > 0).
    c = {k: (float("nan") if v is None else v) for k, v in json.loads(js).items()}
    label = "reference, seed 2 vs seed 1" if t == "reference-noise" else t
    count = f"{int(n):,} per light" if t == "reference-noise" else ("mesh vertices" if t == "shah-vertex" else f"{n}^2")
    print(f"| {label} | {count} | {c['region_texels']} | {c['rel_rmse']:.4f} | {c['rel_rmse_scaled']:.4f} | "
          f"{c['best_scale']:.4f} | {c['peak_ratio']:.4f} | {c['peak_offset_texels']:.2f} | {c['caustic_flux_ratio']:.4f} |")
PY
  echo "wrote $results/$s.md"
done
