#!/usr/bin/env bash
# The viewer's frame time against the bench's throughput frame for the same scene and settings
# (`shah` on the glass sphere at 256²): runs bench_configs/viewer_frame_time.toml, then
# `causticlab view` under xvfb-run on the same scene without its receiver map (the bench leaves
# that validation instrument out of timed frames), with the panel shown and hidden (F1), and
# with every pass timed (`--pass-timing pass`, what `auto` picks on a GPU). The four runs are
# repeated ROUNDS times, interleaved, so that each round's ratios compare runs a minute apart
# (the host's speed drifts by about 10% over longer spans); results/viewer_frame_time.csv gets
# every round's measurements, and results/viewer_frame_time.md, written from that file's rows,
# every round and the median of each ratio. Run it on a quiet machine, from a release build:
#   cargo build --release && bash scripts/viewer_frame_time.sh [BINARY] [FRAMES] [ROUNDS]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-target/release/causticlab}
frames=${2:-200}
rounds=${3:-3}
[[ "$frames" =~ ^[0-9]+$ && "$frames" -gt 10 ]] || { echo "viewer_frame_time.sh: FRAMES must be over 10 (the first 10 are warm-up)" >&2; exit 2; }
[[ "$rounds" =~ ^[0-9]+$ && "$rounds" -ge 1 ]] || { echo "viewer_frame_time.sh: ROUNDS must be at least 1" >&2; exit 2; }
out=results/viewer_frame_time.md
csv=results/viewer_frame_time.csv
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

sed '/^\[receiver_map\]/,$d' scenes/sphere_on_plane.toml > "$tmp/sphere_on_plane.toml"
printf '1 key f1\n' > "$tmp/hide_panel.txt"
for round in $(seq 1 "$rounds"); do
    "$bin" bench bench_configs/viewer_frame_time.toml --results "$tmp/results-$round" > "$tmp/bench-$round.txt"
    # The viewer runs' order turns with the round, so drift within a round favours none of them.
    order=(shown hidden passes)
    shift_by=$(( (round - 1) % 3 ))
    order=("${order[@]:$shift_by}" "${order[@]:0:$shift_by}")
    echo "${order[*]}" > "$tmp/order-$round.txt"
    for panel in "${order[@]}"; do
        extra=(--pass-timing frame)
        [ "$panel" = hidden ] && extra+=(--script "$tmp/hide_panel.txt")
        [ "$panel" = passes ] && extra=(--pass-timing pass)
        xvfb-run -a -s "-screen 0 640x480x24" "$bin" view --scene "$tmp/sphere_on_plane.toml" --technique shah \
            --size 256 --exit-after "$frames" --no-hot-reload "${extra[@]}" > "$tmp/view-$panel-$round.txt"
    done
    echo "round $round of $rounds done" >&2
done

# Every round's measurements, full precision, into $csv (one row per round); then the page from
# that file's rows: every number on it is a cell of the CSV or computed from its rows.
python3 - "$tmp" "$rounds" "$csv" <<'MEASURED'
import csv, glob, gzip, json, re, sys
tmp, rounds, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
def view(path):
    text = open(path).read()
    m = re.search(r"wall ([0-9.]+) ms a frame .*GPU ([0-9.]+) ms a frame", text)
    n = re.search(r"([0-9]+) passes timed", text)
    return {"wall": m.group(1), "gpu": m.group(2), "passes": n.group(1) if n else ""}
def num(v):
    return "" if v is None or v != v else repr(v)
cols = ["round", "bench_ms", "bench_spread_pct", "bench_fps"]
for k in ("shown", "hidden", "passes"):
    cols += [f"{k}_wall_ms", f"{k}_gpu_ms", f"{k}_ratio"]
cols += ["passes_timed", "run_order"]
rows, meta = [], None
for r in range(1, rounds + 1):
    j = json.load(gzip.open(glob.glob(f"{tmp}/results-{r}/**/viewer_frame_time.json.gz", recursive=True)[0], "rt"))
    meta = meta or j["meta"]
    cell = j["cells"][0]
    frame = cell["metrics"]["frame"]
    bench = frame["value"]
    spread = 100 * (frame["q3"] - frame["q1"]) / bench if frame.get("q1") is not None else None
    row = {"round": r, "bench_ms": num(bench), "bench_spread_pct": num(spread), "bench_fps": num(cell["metrics"]["fps"]["value"])}
    for k in ("shown", "hidden", "passes"):
        # The viewer's summary line prints its times to three decimals: the CSV keeps them as printed.
        v = view(f"{tmp}/view-{k}-{r}.txt")
        row |= {f"{k}_wall_ms": v["wall"], f"{k}_gpu_ms": v["gpu"], f"{k}_ratio": num(float(v["wall"]) / bench)}
        if k == "passes":
            row["passes_timed"] = v["passes"]
    row["run_order"] = open(f"{tmp}/order-{r}.txt").read().strip()
    rows.append(row)
with open(out, "w", newline="") as f:
    w = csv.DictWriter(f, cols, lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
json.dump({k: meta[k] for k in ("device", "driver_info", "cpu", "commit", "date")}, open(f"{tmp}/meta.json", "w"))
MEASURED

python3 - "$csv" "$tmp/meta.json" "$out" "$frames" <<'PAGE'
import csv, json, os, statistics, sys
data, meta, out, frames = sys.argv[1], json.load(open(sys.argv[2])), sys.argv[3], sys.argv[4]
runs = list(csv.DictReader(open(data, newline="")))
K = ("shown", "hidden", "passes")
f = lambda x, col: float(x[col])
med = {k: statistics.median(f(x, f"{k}_ratio") for x in runs) for k in K}
n_passes = int(runs[-1]["passes_timed"]) if runs[-1]["passes_timed"] else None
# The cost of a timestamp: the wall time every pass timed adds to whole frames timed, over the
# 2 n - 2 timestamps it adds (n pairs instead of one), the median over the rounds.
per_stamp = (statistics.median((f(x, "passes_wall_ms") - f(x, "shown_wall_ms")) / (2 * n_passes - 2) for x in runs)
             if n_passes and n_passes > 1 else float("nan"))
orders = {x["run_order"] for x in runs}
order = ("one after the other" if len(orders) == 1
         else "one after the other in an order that turns with the round (`run_order` in the CSV)")
name = os.path.basename(data)
lines = [
    "# The viewer's frame time against the bench's throughput frame",
    "",
    f"`bash scripts/viewer_frame_time.sh` on {meta['device']} ({meta['driver_info']}), {meta['cpu']}, "
    f"commit {meta['commit']}, {meta['date']}: `shah` on the glass sphere (`sphere_on_plane`, "
    f"its receiver map left out as the bench leaves it out), photon buffer 512², eye render 256². "
    f"{len(runs)} rounds, each the bench (`bench_configs/viewer_frame_time.toml`, throughput: median of timed "
    f"blocks) then three viewer runs of {frames} frames (mean wall time per frame after the first 10), "
    f"{order}; a ratio divides a viewer run by its own round's bench.",
    "",
    "| round | bench ms | view, whole frames timed, panel shown | panel hidden (F1) | every pass timed (`--pass-timing pass`) |",
    "|---|---|---|---|---|",
]
for x in runs:
    cells = " | ".join(f"{f(x, k + '_wall_ms'):.1f} ms ({f(x, k + '_ratio'):.2f}x)" for k in K)
    spread = f" ±{f(x, 'bench_spread_pct'):.0f}%" if x["bench_spread_pct"] else ""
    lines.append(f"| {x['round']} | {f(x, 'bench_ms'):.1f}{spread} ({f(x, 'bench_fps'):.2f} fps) | {cells} |")
lines += [
    f"| **median ratio** | | **{med['shown']:.2f}x** | **{med['hidden']:.2f}x** | **{med['passes']:.2f}x** |",
    "",
    "±: the bench cell's interquartile range over its timed blocks, as a share of the median (the",
    "bench measures a cell again, up to twice, while that is over 10%, and keeps the narrowest",
    "attempt). A viewer run within that range of its round's bench is as fast as the bench to this",
    "precision; a ratio below 1 is such a run, not a viewer faster than the bench.",
    "",
    "Whole frames timed is what `--pass-timing auto` (the default) picks on a software device such as",
    "this one. The viewer's frame adds the display pass (the tone map into the window's image), the",
    "copy into the swapchain image, the egui panel (laid out, tessellated, drawn) and the present",
    "through Xvfb, whose server shares the two cores with llvmpipe's threads. Its GPU time per",
    "frame (median over the run's frames, round by round): "
    + "; ".join(" / ".join(f"{f(x, k + '_gpu_ms'):.1f}" for k in K) + " ms" for x in runs)
    + f" (panel shown / hidden / every pass timed, {n_passes} passes summed).",
    "",
    f"Timing every pass costs the frame about {per_stamp:.1f} ms for each added timestamp (median over the",
    f"rounds; {n_passes} timestamp pairs instead of one). That fits lavapipe's source, which flushes the",
    "gallium context at every timestamp not written at the top of the pipe (`handle_write_timestamp`",
    "in Mesa's `lvp_execute.c`), so that llvmpipe finishes the work queued before each one; the flush",
    "was not isolated in a measurement of its own. On a GPU a timestamp is a write into a query pool,",
    "so `--pass-timing auto` times every pass there and whole frames on a software device; T switches",
    "while running.",
    "",
    f"Every round's numbers, unrounded, are in [{name}]({name}) (the viewer's wall and GPU times as its",
    "summary line prints them, to three decimals; the bench's time, spread and rate and the ratios in",
    "full); a page that quotes them cites that file.",
    "",
]
open(out, "w").write("\n".join(lines))
print("\n".join(lines))
PAGE
