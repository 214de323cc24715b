#!/usr/bin/env bash
# The viewer's frame time against the bench's throughput frame for the same scene and settings
# (`shah` on the glass sphere at 256²): runs bench_configs/viewer_frame_time.toml, then
# `causticlab view` under xvfb-run on the same scene without its receiver map (the bench leaves
# that validation instrument out of timed frames), with the panel shown and hidden (F1), and
# with every pass timed (`--pass-timing pass`, what `auto` picks on a GPU). The four runs are
# repeated ROUNDS times, interleaved, so that each round's ratios compare runs a minute apart
# (the host's speed drifts by about 10% over longer spans); results/viewer_frame_time.md gets
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
    for panel in "${order[@]}"; do
        extra=(--pass-timing frame)
        [ "$panel" = hidden ] && extra+=(--script "$tmp/hide_panel.txt")
        [ "$panel" = passes ] && extra=(--pass-timing pass)
        xvfb-run -a -s "-screen 0 640x480x24" "$bin" view --scene "$tmp/sphere_on_plane.toml" --technique shah \
            --size 256 --exit-after "$frames" --no-hot-reload "${extra[@]}" > "$tmp/view-$panel-$round.txt"
    done
    echo "round $round of $rounds done" >&2
done

python3 - "$tmp" "$rounds" "$out" "$frames" <<'PY'
import glob, json, re, statistics, sys
tmp, rounds, out, frames = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
def view(path):
    text = open(path).read()
    m = re.search(r"wall ([0-9.]+) ms a frame .*GPU ([0-9.]+) ms a frame", text)
    n = re.search(r"([0-9]+) passes timed", text)
    return {"wall": float(m.group(1)), "gpu": float(m.group(2)), "line": text.strip().splitlines()[-1],
            "passes": int(n.group(1)) if n else None}
runs = []
for r in range(1, rounds + 1):
    j = json.load(open(glob.glob(f"{tmp}/results-{r}/**/viewer_frame_time.json", recursive=True)[0]))
    cell = j["cells"][0]
    frame = cell["metrics"]["frame"]
    spread = (frame["q3"] - frame["q1"]) / frame["value"] if frame.get("q1") is not None else float("nan")
    runs.append({"meta": j["meta"], "bench": frame["value"], "fps": cell["metrics"]["fps"]["value"], "spread": spread,
                 **{k: view(f"{tmp}/view-{k}-{r}.txt") for k in ("shown", "hidden", "passes")}})
meta = runs[0]["meta"]
ratio = {k: [x[k]["wall"] / x["bench"] for x in runs] for k in ("shown", "hidden", "passes")}
med = {k: statistics.median(v) for k, v in ratio.items()}
n_passes = runs[-1]["passes"]["passes"]
per_stamp = (statistics.median([(x["passes"]["wall"] - x["shown"]["wall"]) / (2 * n_passes - 2) for x in runs])
             if n_passes and n_passes > 1 else float("nan"))
lines = [
    "# The viewer's frame time against the bench's throughput frame",
    "",
    f"`bash scripts/viewer_frame_time.sh` on {meta['device']} ({meta['driver_info']}), {meta['cpu']}, "
    f"commit {meta['commit']}, {meta['date']}: `shah` on the glass sphere (`sphere_on_plane`, "
    f"its receiver map left out as the bench leaves it out), photon buffer 512², eye render 256². "
    f"{rounds} rounds, each the bench (`bench_configs/viewer_frame_time.toml`, throughput: median of timed "
    f"blocks) then three viewer runs of {frames} frames (mean wall time per frame after the first 10), "
    "one after the other in an order that turns with the round; a ratio divides a viewer run by its own round's bench.",
    "",
    "| round | bench ms | view, whole frames timed, panel shown | panel hidden (F1) | every pass timed (`--pass-timing pass`) |",
    "|---|---|---|---|---|",
]
for i, x in enumerate(runs, 1):
    cells = " | ".join(f"{x[k]['wall']:.1f} ms ({x[k]['wall'] / x['bench']:.2f}x)" for k in ("shown", "hidden", "passes"))
    lines.append(f"| {i} | {x['bench']:.1f} ±{100 * x['spread']:.0f}% ({x['fps']:.2f} fps) | {cells} |")
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
    + "; ".join(f"{x['shown']['gpu']:.1f} / {x['hidden']['gpu']:.1f} / {x['passes']['gpu']:.1f} ms" for x in runs)
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
    "The viewer's own summary lines, round by round:",
    "",
    "```text",
] + [x[k]["line"] for x in runs for k in ("shown", "hidden", "passes")] + ["```", ""]
open(out, "w").write("\n".join(lines))
print("\n".join(lines))
PY
