#!/usr/bin/env bash
# The viewer's frame time against the bench's throughput frame for the same scene and settings
# (`shah` on the glass sphere at 256²): runs bench_configs/viewer_frame_time.toml, then
# `causticlab view` under xvfb-run on the same scene without its receiver map (the bench leaves
# that validation instrument out of timed frames), with the panel shown and hidden (F1), and
# writes both into results/viewer_frame_time.md. Run it on a quiet machine, from a release build:
#   cargo build --release && bash scripts/viewer_frame_time.sh [BINARY] [FRAMES]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-target/release/causticlab}
frames=${2:-600}
out=results/viewer_frame_time.md
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$bin" bench bench_configs/viewer_frame_time.toml --results "$tmp/results" > "$tmp/bench.txt"
json=$(find "$tmp/results" -name viewer_frame_time.json | head -1)
sed '/^\[receiver_map\]/,$d' scenes/sphere_on_plane.toml > "$tmp/sphere_on_plane.toml"
printf '1 key f1\n' > "$tmp/hide_panel.txt"
for panel in shown hidden frames; do
    extra=()
    [ "$panel" = hidden ] && extra=(--script "$tmp/hide_panel.txt")
    [ "$panel" = frames ] && extra=(--no-pass-timestamps)
    xvfb-run -a -s "-screen 0 640x480x24" "$bin" view --scene "$tmp/sphere_on_plane.toml" --technique shah \
        --size 256 --exit-after "$frames" --no-hot-reload "${extra[@]}" > "$tmp/view-$panel.txt"
done

python3 - "$json" "$tmp/view-shown.txt" "$tmp/view-hidden.txt" "$out" "$frames" "$tmp/view-frames.txt" <<'PY'
import json, re, sys
j = json.load(open(sys.argv[1]))
cell = j["cells"][0]
bench_ms = cell["metrics"]["frame"]["value"]
bench_fps = cell["metrics"]["fps"]["value"]
meta = j["meta"]
def view(path):
    text = open(path).read()
    m = re.search(r"wall ([0-9.]+) ms a frame .*GPU ([0-9.]+) ms a frame", text)
    return float(m.group(1)), float(m.group(2)), text.strip()
shown, hidden, frames = view(sys.argv[2]), view(sys.argv[3]), view(sys.argv[6])
lines = [
    "# The viewer's frame time against the bench's throughput frame",
    "",
    f"`bash scripts/viewer_frame_time.sh` on {meta['device']} ({meta['driver_info']}), {meta['cpu']}, "
    f"commit {meta['commit']}, {meta['date']}: `shah` on the glass sphere (`sphere_on_plane`, "
    f"its receiver map left out as the bench leaves it out), photon buffer 512², eye render 256².",
    "",
    "| frame | ms per frame | ÷ bench |",
    "|---|---|---|",
    f"| bench, throughput (`bench_configs/viewer_frame_time.toml`: median of timed blocks; {bench_fps:.2f} fps) | {bench_ms:.1f} | 1.00 |",
    f"| `causticlab view`, panel shown, every pass timed (mean wall time of {sys.argv[5]} frames after the first 10) | {shown[0]:.1f} | {shown[0] / bench_ms:.2f} |",
    f"| `causticlab view`, panel hidden (F1), every pass timed | {hidden[0]:.1f} | {hidden[0] / bench_ms:.2f} |",
    f"| `causticlab view --no-pass-timestamps`, panel shown (whole frames timed, as the bench's) | {frames[0]:.1f} | {frames[0] / bench_ms:.2f} |",
    "",
    "The viewer's frame adds the display pass (the tone map into the window's image), the copy",
    "into the swapchain image, the egui panel (laid out, tessellated, drawn) and the present",
    "through Xvfb. Its GPU time per frame (median; passes summed where every pass is timed):",
    f"{shown[1]:.1f} ms with the panel, {hidden[1]:.1f} ms without, {frames[1]:.1f} ms timing whole frames.",
    "`--no-pass-timestamps` times whole frames, as the bench's throughput frames are timed, instead",
    "of every pass (no per-pass graph).",
    "",
    "The viewer's own summary lines:",
    "",
    "```text",
    shown[2].splitlines()[-1],
    hidden[2].splitlines()[-1],
    frames[2].splitlines()[-1],
    "```",
    "",
]
open(sys.argv[4], "w").write("\n".join(lines))
print("\n".join(lines))
PY
