#!/usr/bin/env bash
# The viewer's frame time against the bench's throughput frame for the same scene and settings
# (`shah` on the glass sphere at 256²): runs bench_configs/viewer_frame_time.toml, then
# `causticlab view` under xvfb-run on the same scene without its receiver map (the bench leaves
# that validation instrument out of timed frames), with the panel shown and hidden (F1), and
# writes both into results/viewer_frame_time.md; then the same with every pass timed
# (`--pass-timing pass`, what `auto` picks on a GPU). Run it on a quiet machine, from a release build:
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
for panel in shown hidden passes; do
    extra=(--pass-timing frame)
    [ "$panel" = hidden ] && extra+=(--script "$tmp/hide_panel.txt")
    [ "$panel" = passes ] && extra=(--pass-timing pass)
    xvfb-run -a -s "-screen 0 640x480x24" "$bin" view --scene "$tmp/sphere_on_plane.toml" --technique shah \
        --size 256 --exit-after "$frames" --no-hot-reload "${extra[@]}" > "$tmp/view-$panel.txt"
done

python3 - "$json" "$tmp/view-shown.txt" "$tmp/view-hidden.txt" "$out" "$frames" "$tmp/view-passes.txt" <<'PY'
import json, re, sys
j = json.load(open(sys.argv[1]))
cell = j["cells"][0]
bench_ms = cell["metrics"]["frame"]["value"]
bench_fps = cell["metrics"]["fps"]["value"]
meta = j["meta"]
def view(path):
    text = open(path).read()
    m = re.search(r"wall ([0-9.]+) ms a frame .*GPU ([0-9.]+) ms a frame", text)
    n = re.search(r"([0-9]+) passes timed", text)
    return float(m.group(1)), float(m.group(2)), text.strip(), int(n.group(1)) if n else None
shown, hidden, passes = view(sys.argv[2]), view(sys.argv[3]), view(sys.argv[6])
per_timestamp = (passes[0] - shown[0]) / (2 * passes[3] - 2) if passes[3] else float("nan")
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
    f"| `causticlab view` (whole frames timed, as the bench's: the default on a software device), panel shown (mean wall time of {sys.argv[5]} frames after the first 10) | {shown[0]:.1f} | {shown[0] / bench_ms:.2f} |",
    f"| `causticlab view`, panel hidden (F1) | {hidden[0]:.1f} | {hidden[0] / bench_ms:.2f} |",
    f"| `causticlab view --pass-timing pass` (every pass timed: the default on a GPU), panel shown | {passes[0]:.1f} | {passes[0] / bench_ms:.2f} |",
    "",
    "The viewer's frame adds the display pass (the tone map into the window's image), the copy",
    "into the swapchain image, the egui panel (laid out, tessellated, drawn) and the present",
    "through Xvfb. Its GPU time per frame (median): "
    f"{shown[1]:.1f} ms with the panel, {hidden[1]:.1f} ms without, {passes[1]:.1f} ms with every pass timed "
    f"({passes[3]} passes, summed).",
    "",
    "Timing every pass costs the frame "
    f"{passes[0] - shown[0]:.1f} ms here: {passes[3]} timestamp pairs instead of one, about {per_timestamp:.1f} ms",
    "for each added timestamp. That fits lavapipe's source, which flushes the gallium context at",
    "every timestamp not written at the top of the pipe (`handle_write_timestamp` in Mesa's",
    "`lvp_execute.c`), so that llvmpipe finishes the work queued before each one; the flush was not",
    "isolated in a measurement of its own. On a GPU a timestamp is a write into a query pool, so",
    "`--pass-timing auto` (the default) times every pass there and whole frames on a software",
    "device; T switches while running.",
    "",
    "The viewer's own summary lines:",
    "",
    "```text",
    shown[2].splitlines()[-1],
    hidden[2].splitlines()[-1],
    passes[2].splitlines()[-1],
    "```",
    "",
]
open(sys.argv[4], "w").write("\n".join(lines))
print("\n".join(lines))
PY
