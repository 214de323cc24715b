#!/usr/bin/env bash
# The reference final image's convergence (docs/flip.md, "The reference final image"): renders
# `reference --final` of a scene at levels 0 to LAST (each a caustic map twice as fine, the splat
# half as wide on the floor, 8 times the photons), compares each level with every finer one (HDR-FLIP
# of the final images, `causticlab compare --json`), and every technique's final image (the
# scene's settings) with the table's level (final_reference::TABLE_LEVEL) and the finer ones: refining
# is done when the next level changes the image by less than any technique's FLIP, and the
# techniques' FLIP hardly. Writes results/final_reference.csv (one row per
# pair) and leaves the images and FLIP error images in OUT.
#
#   bash scripts/final_reference.sh [SCENE] [LAST] [OUT]   # default: sphere_on_plane 2 out/final_reference
#   bash scripts/final_reference.sh sphere_on_plane 3        # as results/final_reference.csv was made
#
# On lavapipe the GPU tracer makes a few hundred thousand photons a second (results/photon_trace.md):
# level 2 (2^26 photons) takes minutes, level 3 (2^29) most of an hour.
set -euo pipefail
cd "$(dirname "$0")/.."

scene=${1:-sphere_on_plane}
last=${2:-2}
out=${3:-out/final_reference}
table_level=1
bin=${CAUSTICLAB:-target/debug/causticlab}
[ -x "$bin" ] || { echo "final_reference.sh: build first: cargo build" >&2; exit 1; }
csv=results/final_reference.csv
mkdir -p "$out"

for level in $(seq 0 "$last"); do
    [ -f "$out/L$level/final.exr" ] || "$bin" reference --final --scene "scenes/$scene.toml" --level "$level" --out "$out/L$level"
done
techniques="shah shah-vertex wd-points wd-eye-points wd-quads wd-gather hcm adaptive photon-trace"
for t in $techniques; do
    [ -f "$out/$t/final.exr" ] || "$bin" render --scene "scenes/$scene.toml" --technique "$t" --out "$out/$t" > /dev/null
done

# One row: A, its reference B (a level) and what A is, then compare's JSON of A against B (its
# error image and FLIP error image beside, $out/<A>_vs_<B>.png and .flip.png).
rows=()
row() {
    local a=$1 b=$2 kind=$3 a_exr=$4
    "$bin" compare --json "$a_exr" "$out/$b/final.exr" --error-image "$out/${a}_vs_$b.png" > "$out/${a}_vs_$b.json"
    rows+=("$a:$b:$kind")
}
for level in $(seq 0 $((last - 1))); do
    for finer in $(seq $((level + 1)) "$last"); do
        row "L$level" "L$finer" level "$out/L$level/final.exr"
    done
done
for t in $techniques; do
    for level in $(seq "$table_level" "$last"); do
        row "$t" "L$level" technique "$out/$t/final.exr"
    done
done

SCENE="$scene" OUT="$out" CSV="$csv" ROWS="${rows[*]}" python3 - <<'ROWS'
import csv, json, os
out, rows = os.environ["OUT"], os.environ["ROWS"].split()
with open(os.environ["CSV"], "w", newline="") as f:
    w = csv.writer(f)
    # The device that traced the references (their reference.json).
    device = json.load(open(f"{out}/L0/reference.json"))["device"]
    w.writerow(["a", "reference", "kind", "scene", "device", "flip_mean", "ppd", "width", "height", "rel_rmse"])
    for r in rows:
        a, b, kind = r.split(":")
        j = json.load(open(f"{out}/{a}_vs_{b}.json"))
        fl = j["flip"]
        w.writerow([a, b, kind, os.environ["SCENE"], device, f"{fl['mean']:.6f}", f"{fl['ppd']:.2f}", fl["width"],
                    fl["height"], f"{j['rel_rmse']:.6f}"])
        print(f"{a:14} vs {b}: HDR-FLIP {fl['mean']:.5f} at {fl['ppd']:.2f} ppd, {fl['width']}x{fl['height']}; "
              f"rel. RMSE {j['rel_rmse']:.5f}")
ROWS
echo "wrote $csv"
