#!/usr/bin/env bash
# Regenerates results/quality/<scene>.csv and <scene>.md: the registry's variants marked
# `quality` (`causticlab variants --quality`: shah, wd-points, its thin-lens splats, shah-vertex
# and three hcm variants) against the exact
# CPU photon reference, at 256^2..2048^2 photons, with the reference's own noise (two seeds), and
# each final image's HDR-FLIP against the reference final image (`reference --final`, level 1,
# the scene's camera resolution, 67.02 pixels per degree: docs/flip.md). The CSV has a row per
# comparison (technique, photons, then compare's metrics, as formatted in the table); the .md
# prints the same rows, and the results pages quote the CSV.
#   bash scripts/quality_table.sh [scene ...]      (default: sphere_on_plane sphere_oblique)
# Needs a release build (cargo build --release) and python3 for the table layout.
# REF_PHOTONS (default 16M), FINAL_LEVEL (default 1), WORK (default out/quality) and RESULTS
# (default results/quality) override the references' sizes and where the renders and the tables
# go. The references are kept in WORK, in folders named by their photon count, and reused by the
# next run with that count (delete them after a change that alters them). The table's
# "Regenerate" line names the overrides its run was given.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=target/release/causticlab
ref_photons=${REF_PHOTONS:-16000000}
final_level=${FINAL_LEVEL:-1}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(sphere_on_plane sphere_oblique)
work=${WORK:-out/quality}
results=${RESULTS:-results/quality}
mkdir -p "$work" "$results"
# The command that regenerates these tables, with the overrides this run was given.
regen="bash scripts/quality_table.sh"
for v in REF_PHOTONS FINAL_LEVEL WORK RESULTS; do
  if [ -n "${!v:-}" ]; then regen="$v=${!v} $regen"; fi
done
for s in "${scenes[@]}"; do
  scene=scenes/$s.toml
  rows=$work/$s.rows
  : > "$rows"
  for seed in 1 2; do
    [ -f "$work/$s/ref${seed}_$ref_photons/receiver.exr" ] || \
      $bin reference --scene "$scene" --photons "$ref_photons" --seed $seed --fresnel false --out "$work/$s/ref${seed}_$ref_photons"
  done
  # The reference final images at the level, named by it: frames seeded from 1 (the one compared
  # with), and, for their own noise, from the first seed the first one did not use (level 1
  # traces two frames, seeds 1-2: the second starts at 3).
  finals=$work/$s/final$final_level
  [ -f "$finals/s1/final.exr" ] || \
    $bin reference --final --scene "$scene" --level "$final_level" --seed 1 --fresnel false --out "$finals/s1" > /dev/null
  seed2=$(python3 -c 'import json, sys; print(1 + json.load(open(sys.argv[1]))["refinement"]["frames"])' "$finals/s1/reference.json")
  [ -f "$finals/s$seed2/final.exr" ] || \
    $bin reference --final --scene "$scene" --level "$final_level" --seed "$seed2" --fresnel false --out "$finals/s$seed2" > /dev/null
  final_ref=$finals/s1/final.exr
  # One row: label|photons|compare of the receiver maps|compare of the final images. Each
  # compare in its own command, so that a failure (a missing image: compare names it) stops here.
  row() {
    local receiver final
    receiver=$($bin compare "$3" "$work/$s/ref1_$ref_photons/receiver.exr" --json | tr -d '\n')
    final=$($bin compare "$4" "$final_ref" --json | tr -d '\n')
    echo "$1|$2|$receiver|$final" >> "$rows"
  }
  row reference-noise "$ref_photons" "$work/$s/ref2_$ref_photons/receiver.exr" "$finals/s$seed2/final.exr"
  # The registry's rows marked `quality` (crates/caustics/src/techniques/variants.toml):
  # name|label|scenes|render flags|needs (quality rows need no feature beyond their technique).
  registry=$($bin variants --lines --quality)   # fails here with a binary that has no registry
  mapfile -t variants <<< "$registry"
  for v in "${variants[@]}"; do
    IFS='|' read -r folder label _ flags _ <<< "$v"
    for n in 256 512 1024 2048; do
      [ "$folder" = shah-vertex ] && [ "$n" != 256 ] && continue   # photons follow the tessellation
      out=$work/$s/$folder-$n
      # shellcheck disable=SC2086 # the flags are words
      $bin render --scene "$scene" $flags --photons "$n" --fresnel false --out "$out" --dump receiver > "$out.log"
      row "$label" "$n" "$out/receiver.exr" "$out/final.exr"
    done
  done
  device=$($bin devices | sed -n 's/^\[\([0-9]*\)\] \(.*\) \[default\].*/\2/p' | head -1)
  python3 - "$s" "$rows" "$ref_photons" "$device" "$(git rev-parse --short HEAD)" "$results/$s.csv" "$results/$s.md" \
    "$finals/s1/reference.json" "$seed2" "$regen" <<'PY'
import csv, json, sys, datetime
scene, rows, ref_photons, device, commit, csv_out, md_out, final_json, seed2, regen = sys.argv[1:11]
final = json.load(open(final_json))
level = final["refinement"]
device = device.strip()
REFERENCE = "reference, seed 2 vs seed 1"
COLUMNS = ["technique", "photons", "region_texels", "rel_rmse", "rel_rmse_scaled", "best_scale",
           "peak_ratio", "peak_offset_texels", "caustic_flux_ratio", "flip"]
# One row per comparison, every value formatted once: the CSV holds these strings and the
# Markdown table prints them. A metric is null where a map has a texel that is not finite
# (non_finite_texels > 0): an empty CSV cell (the column stays numeric), `nan` in the table.
# FLIP: the final images' HDR-FLIP mean, empty where compare left it out (its warning says why).
table = []
sizes = set()
for line in open(rows):
    t, n, js, fjs = line.rstrip("\n").split("|", 3)
    c = json.loads(js)
    fl = json.loads(fjs)["flip"]
    if fl is not None:
        sizes.add((fl["width"], fl["height"], round(fl["ppd"], 2)))
    fmt = lambda k, spec: "" if c[k] is None else format(c[k], spec)
    label = REFERENCE if t == "reference-noise" else t
    photons = n if t == "reference-noise" else ("mesh vertices" if t == "shah-vertex" else f"{n}^2")
    table.append([label, photons, fmt("region_texels", "d"), fmt("rel_rmse", ".4f"), fmt("rel_rmse_scaled", ".4f"),
                  fmt("best_scale", ".4f"), fmt("peak_ratio", ".4f"), fmt("peak_offset_texels", ".2f"),
                  fmt("caustic_flux_ratio", ".4f"), "" if fl is None else format(fl["mean"], ".5f")])
with open(csv_out, "w", newline="") as f:
    w = csv.writer(f, lineterminator="\n")
    w.writerow(COLUMNS)
    w.writerows(table)
with open(md_out, "w") as f:
    out = lambda s="": print(s, file=f)
    out(f"# Caustic quality: `{scene}` against the exact CPU photon reference\n")
    out(f"Device: {device or 'default device'}; commit {commit}; {datetime.date.today()}. "
        f"Reference: `causticlab reference --photons {ref_photons} --fresnel false` (seed 1); all techniques "
        "`--fresnel false` (two refractions, all power transmitted), default splat (Gaussian, radius 1.5 texels; "
        "the `hcm varying` rows size each splat from its neighbours instead, the `thin-lens` row from a per-photon "
        "thin-lens model), "
        "caustic map 1024^2, 4 back-face iterations. Regenerate: `" + regen + " " + scene + "`.\n")
    out("Errors are over the texels where either receiver map differs from 1 by more than 0.05 "
        "(see `causticlab compare`). `shah-vertex` traces one photon per mesh vertex, so its photon count is "
        "the tessellation's, not N^2.\n")
    size = "; ".join(f"{w}x{h} pixels at {p} pixels per degree" for w, h, p in sorted(sizes))
    out(f"FLIP: the mean HDR-FLIP of each render's final image against the reference final image "
        f"(`causticlab reference --final --level {level['level']} --fresnel false`: a {level['caustic_map_resolution']}^2 "
        f"caustic map of {level['frames']} x {level['photons']}^2 exact photons, seeds from 1), {size}, the exposures "
        "found from the reference (docs/flip.md); its first row compares the reference final image traced from "
        f"seed {seed2} with it.\n")
    out(f"The script writes the same rows to [`{scene}.csv`]({scene}.csv) (the values as printed here; "
        "a `nan` here is an empty cell there), which the results pages quote.\n")
    out("| technique | photons | region texels | rel. RMSE | rel. RMSE after best scale | best scale | peak ratio | peak offset (texels) | caustic flux ratio | FLIP (final image) |")
    out("|---|---|---|---|---|---|---|---|---|---|")
    for r in table:
        count = f"{int(r[1]):,} per light" if r[0] == REFERENCE else r[1]
        out("| " + " | ".join([r[0], count] + [v or "nan" for v in r[2:]]) + " |")
PY
  echo "wrote $results/$s.csv and $results/$s.md"
done
