#!/usr/bin/env bash
# Trendall & Stewart 2000, Sec. 5.2: the relative RMS error of the pool's caustics, for each pool
# scene: the faithful 8-bit path against the float path (the paper: 26% on its worst-case
# frame), the float GPU path against the CPU f64 reference (the goal: at most 0.1%), and the
# convolution (f64) against Eq. 2 evaluated directly (what the convolution's approximations
# cost). Each as `causticlab compare` reports it, over every lit texel (--region lit: the paper's
# figure) and over the caustic region (where either map differs from 1 by more than 5%).
#   bash scripts/pool_rms.sh [scene ...]        (default: pool_overhead pool_oblique pool)
# Writes results/trendall_stewart2000/sec5_2.<device-slug>.csv (the measurements) and .md (the page,
# from that file's rows). Needs a release build
# (cargo build --release) and python3. BIN, WORK (default out/pool_rms) and RESULTS override.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${BIN:-target/release/causticlab}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(pool_overhead pool_oblique pool)
work=${WORK:-out/pool_rms}
results=${RESULTS:-results/trendall_stewart2000}
mkdir -p "$work" "$results"
device=$($bin devices | sed -n 's/^\[\([0-9]*\)\] \(.*\) \[default\].*/\2/p' | head -1 | sed 's/ *$//')
slug=$(echo "${device:-default}" | tr '[:upper:]' '[:lower:]' | sed 's/[^a-z0-9]\{1,\}/-/g; s/^-//; s/-$//' | cut -c1-48)
rows=$work/rows
: > "$rows"
cmp() {  # label scene a b
  for region in lit caustic; do
    echo "$1|$2|$region|$($bin compare "$3" "$4" --region $region --json | tr -d '\n')" >> "$rows"
  done
}
for s in "${scenes[@]}"; do
  for p in unorm8 float; do
    $bin --validate render --scene "scenes/$s.toml" --precision "$p" --dump receiver --out "$work/$s/$p" > "$work/$s.$p.log" 2>&1
  done
  $bin reference --scene "scenes/$s.toml" --out "$work/$s/f64" > /dev/null
  $bin reference --scene "scenes/$s.toml" --direct --out "$work/$s/direct" > /dev/null
  cmp "faithful 8-bit vs float (GPU)" "$s" "$work/$s/unorm8/receiver.exr" "$work/$s/float/receiver.exr"
  cmp "float (GPU) vs f64 (CPU)" "$s" "$work/$s/float/receiver.exr" "$work/$s/f64/receiver.exr"
  cmp "convolution (f64) vs Eq. 2 direct" "$s" "$work/$s/f64/receiver.exr" "$work/$s/direct/receiver.exr"
done
# The comparisons, one row per comparison and scene, into sec5_2.<slug>.csv (full precision, an
# empty cell where `compare` gives no number); then the page from that file's rows.
csv=$results/sec5_2.$slug.csv
out=$results/sec5_2.$slug.md
python3 - "$rows" "$csv" <<'MEASURED'
import csv, json, sys
rows, out = sys.argv[1:3]
table = {}
for line in open(rows):
    label, scene, region, js = line.rstrip("\n").split("|", 3)
    table.setdefault((label, scene), {})[region] = json.loads(js)
def num(v):
    # A metric is null where a map has a texel that is not finite (non_finite_texels > 0).
    return "" if v is None else repr(v)
with open(out, "w", newline="") as f:
    w = csv.writer(f, lineterminator="\n")
    w.writerow(["comparison", "scene", "rel_rmse_lit", "rel_rmse_caustic", "caustic_texels", "peak_ratio"])
    for (label, scene), r in table.items():
        lit, c = r["lit"], r["caustic"]
        w.writerow([label, scene, num(lit["rel_rmse"]), num(c["rel_rmse"]), num(c["region_texels"]), num(c["peak_ratio"])])
MEASURED
python3 - "$csv" "$device" "$(git rev-parse --short HEAD)" "$(date +%F)" > "$out" <<'PAGE'
import csv, sys
data, device, commit, date = sys.argv[1:5]
print("# Trendall & Stewart 2000, Sec. 5.2: relative RMS errors of the pool caustics\n")
print(f"Device: {device or 'default device'}; commit {commit}; {date}. "
      "Regenerate: `bash scripts/pool_rms.sh`. Each map is the receiver map E / E_flat on the pool bottom "
      "(256 x 256, 7 x 7 kernels); relative RMS = sqrt(sum (a - b)^2 / sum b^2), b the second map, as "
      "`causticlab compare --region lit|caustic` reports it: over every texel flat water lights (lit), or where "
      "either map differs from 1 by more than 5% (caustic).\n")
print("| comparison | scene | rel. RMS (lit) | rel. RMS (caustic region) | caustic texels | peak ratio |")
print("|---|---|---|---|---|---|")
def fmt(cell, spec):
    return format(float(cell), spec) if cell else "nan"  # empty: a map had a texel that is not finite
for r in csv.DictReader(open(data, newline="")):
    print(f"| {r['comparison']} | {r['scene']} | {fmt(r['rel_rmse_lit'], '.4g')} | {fmt(r['rel_rmse_caustic'], '.4g')} "
          f"| {r['caustic_texels']} | {fmt(r['peak_ratio'], '.3f')} |")
name = data.rsplit("/", 1)[-1]
print(f"\nThe rows unrounded: [{name}]({name}), written by the same run; a page that quotes them cites that file.")
PAGE
echo "wrote $csv and $out"
