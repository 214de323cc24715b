#!/usr/bin/env bash
# Runs the criterion benchmarks of the CPU paths (crates/caustics/benches/cpu_paths.rs) and of
# the frame loop in both frame modes on the default Vulkan device (frame_loop.rs), and records
# their medians in results/criterion/<cpu-slug>.csv, and results/criterion/<cpu-slug>.md from
# that file's rows (see results/criterion/README.md).
#
#   bash scripts/criterion.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

command -v cargo >/dev/null || { echo "criterion.sh: cargo not found" >&2; exit 1; }
command -v python3 >/dev/null || { echo "criterion.sh: python3 not found" >&2; exit 1; }

target_dir=$(cargo metadata --format-version 1 --no-deps | python3 -c 'import json,sys; print(json.load(sys.stdin)["target_directory"])')
log=$(mktemp)
trap 'rm -f "$log"' EXIT

start=$(date +%s)
cargo bench -p caustics --bench cpu_paths --bench frame_loop 2>&1 | tee "$log"

cpu=$(grep -m1 -E '^(model name|Model|cpu model)[[:space:]]*:' /proc/cpuinfo 2>/dev/null | cut -d: -f2- | sed 's/^[[:space:]]*//' || true)
[ -n "$cpu" ] || cpu="unknown $(uname -m) CPU"
slug=$(printf '%s' "$cpu" | tr '[:upper:]' '[:lower:]' | sed -E 's/[^a-z0-9]+/-/g; s/^-+//; s/-+$//')
mkdir -p results/criterion
out="results/criterion/$slug.md"
csv="results/criterion/$slug.csv"

# The medians (and the frame loop's host and GPU times) into $csv, one row per benchmark in the
# order they ran, full precision; then the page from that file's rows.
START="$start" LOG="$log" CRITERION_DIR="$target_dir/criterion" CSV="$csv" python3 - <<'MEASURED'
import csv, glob, json, os, re, tempfile

env = os.environ
start = int(env["START"])
# Units of one element per group (criterion only knows "elements" or "bytes").
ELEMENT = {"scene_load": "tri", "bvh_build": "tri", "reference_trace": "photons", "frame_loop": "frames"}


def num(v):
    return "" if v != v else repr(v)  # NaN: empty, as a claim cannot quote it


found = []
for est_path in glob.glob(os.path.join(env["CRITERION_DIR"], "**", "new", "estimates.json"), recursive=True):
    mtime = os.path.getmtime(est_path)
    if mtime < start - 1:
        continue  # left over from an earlier run (a renamed or skipped benchmark)
    new_dir = os.path.dirname(est_path)
    with open(est_path) as f:
        est = json.load(f)
    with open(os.path.join(new_dir, "benchmark.json")) as f:
        bench = json.load(f)
    median = est["median"]["point_estimate"]  # ns
    ci = est["median"]["confidence_interval"]
    per_s, unit = "", ""
    tp = bench.get("throughput") or {}
    if "Elements" in tp:
        per_s, unit = tp["Elements"] / (median * 1e-9), ELEMENT.get(bench["group_id"], "elem")
    elif "Bytes" in tp:
        per_s, unit = tp["Bytes"] / (median * 1e-9) / 2**20, "MiB"
    found.append((mtime, bench["full_id"], median / 1e6, ci["lower_bound"] / 1e6, ci["upper_bound"] / 1e6, per_s, unit))
if not found:
    raise SystemExit(f"criterion.sh: no estimates.json newer than the run under {env['CRITERION_DIR']}")
found.sort()

# frame_loop.rs's own lines: 20 more frames per mode, timed on the host and by the GPU.
loops = {}
with open(env["LOG"], errors="replace") as f:
    for line in f:
        m = re.match(r"frame_loop: (\S+) mode, (\d+) frames: host ms per frame median (\S+); GPU ms per frame \((.*)\) median (\S+)\s*$", line)
        if m:
            loops[m.group(1)] = (m.group(2), float(m.group(3)), m.group(4), float(m.group(5)))

rows = [["benchmark", "median_ms", "ci_low_ms", "ci_high_ms", "throughput_per_s", "throughput_unit",
         "loop_frames", "loop_host_ms_median", "loop_gpu_ms_median", "loop_gpu_timing"]]
for _, name, med, lo, hi, per_s, unit in found:
    loop = ["", "", "", ""]
    parts = name.split("/")
    if parts[0] == "frame_loop" and len(parts) > 1 and parts[1] in loops:
        frames, host, what, gpu = loops.pop(parts[1])
        loop = [frames, num(host), num(gpu), what]
    rows.append([name, num(med), num(lo), num(hi), "" if per_s == "" else num(per_s), unit] + loop)
for mode, (frames, host, what, gpu) in loops.items():  # a mode criterion did not time
    rows.append([f"frame_loop/{mode}", "", "", "", "", "", frames, num(host), num(gpu), what])

out = env["CSV"]
fd, tmp = tempfile.mkstemp(dir=os.path.dirname(out), prefix=".criterion-", suffix=".csv")
with os.fdopen(fd, "w", newline="") as f:
    csv.writer(f, lineterminator="\n").writerows(rows)
os.chmod(tmp, 0o644)
os.replace(tmp, out)
print(f"criterion.sh: wrote {out}")
MEASURED

CPU="$cpu" CORES="$(nproc)" RUSTC="$(rustc --version)" \
COMMIT="$(git describe --always --dirty --abbrev=12 2>/dev/null || echo unknown)" \
DATE="$(date -u +%Y-%m-%dT%H:%M:%SZ)" LOG="$log" CSV="$csv" OUT="$out" python3 - <<'PAGE'
import csv, os, tempfile

env = os.environ


def fmt_time(ms):
    for unit, scale in (("s", 1e3), ("ms", 1.0), ("µs", 1e-3)):
        if ms >= scale:
            return f"{ms / scale:.3g} {unit}"
    return f"{ms * 1e6:.3g} ns"


def fmt_rate(per_s, unit):
    if unit == "MiB":
        return f"{per_s:.3g} MiB/s"
    for prefix, scale in (("G", 1e9), ("M", 1e6), ("k", 1e3)):
        if per_s >= scale:
            return f"{per_s / scale:.3g} {prefix}{unit}/s"
    return f"{per_s:.3g} {unit}/s"


def ms_or_nan(cell):
    return f"{float(cell):.1f}" if cell else "NaN"


with open(env["CSV"], newline="") as f:
    rows = list(csv.DictReader(f))
with open(env["LOG"], errors="replace") as f:
    skipped = [line.strip() for line in f if "cpu_paths: SKIPPING" in line]

lines = [
    f"# CPU paths: criterion medians on {env['CPU']}",
    "",
    f"- CPU: {env['CPU']} ({env['CORES']} cores available; `trace_reference` uses all of them)",
    f"- rustc: {env['RUSTC']}",
    f"- commit: {env['COMMIT']}",
    f"- date: {env['DATE']}",
    "- command: `bash scripts/criterion.sh` (`cargo bench -p caustics --bench cpu_paths --bench frame_loop`, 10 samples per benchmark; `frame_loop` on the default Vulkan device)",
    f"- data: [{os.path.basename(env['CSV'])}]({os.path.basename(env['CSV'])}), this page's rows unrounded (times in ms, throughput per second)",
    "",
    "| benchmark | median | 95% CI of median | throughput |",
    "|---|---|---|---|",
]
for r in rows:
    if not r["median_ms"]:
        continue  # a frame_loop mode that only printed its host and GPU times
    tp = fmt_rate(float(r["throughput_per_s"]), r["throughput_unit"]) if r["throughput_per_s"] else ""
    ci = f"{fmt_time(float(r['ci_low_ms']))} – {fmt_time(float(r['ci_high_ms']))}"
    lines.append(f"| {r['benchmark']} | {fmt_time(float(r['median_ms']))} | {ci} | {tp} |")
loops = [r for r in rows if r["loop_frames"]]
if loops:
    lines += ["", f"The frame loop, {loops[0]['loop_frames']} more frames per mode timed on the host and by the GPU (the same frames):", ""]
    for r in loops:
        mode = r["benchmark"].split("/")[1]
        lines.append(
            f"- {mode} mode, {r['loop_frames']} frames: host ms per frame median {ms_or_nan(r['loop_host_ms_median'])}; "
            f"GPU ms per frame ({r['loop_gpu_timing']}) median {ms_or_nan(r['loop_gpu_ms_median'])}"
        )
if skipped:
    lines += ["", "Skipped:", ""] + [f"- {s}" for s in skipped]
lines.append("")

out = env["OUT"]
fd, tmp = tempfile.mkstemp(dir=os.path.dirname(out), prefix=".criterion-", suffix=".md")
with os.fdopen(fd, "w") as f:
    f.write("\n".join(lines))
os.chmod(tmp, 0o644)
os.replace(tmp, out)
print(f"criterion.sh: wrote {out}")
PAGE
