#!/usr/bin/env bash
# Runs the criterion benchmarks of the CPU paths (crates/caustics/benches/cpu_paths.rs) and of
# the frame loop in both frame modes on the default Vulkan device (frame_loop.rs), and records
# their medians in results/criterion/<cpu-slug>.md (see results/criterion/README.md).
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

CPU="$cpu" CORES="$(nproc)" RUSTC="$(rustc --version)" \
COMMIT="$(git describe --always --dirty --abbrev=12 2>/dev/null || echo unknown)" \
DATE="$(date -u +%Y-%m-%dT%H:%M:%SZ)" START="$start" LOG="$log" \
CRITERION_DIR="$target_dir/criterion" OUT="$out" python3 - <<'EOF'
import glob, json, os, tempfile

env = os.environ
start = int(env["START"])
# Units of one element per group (criterion only knows "elements" or "bytes").
ELEMENT = {"scene_load": "tri", "bvh_build": "tri", "reference_trace": "photons", "frame_loop": "frames"}


def fmt_time(ns):
    for unit, scale in (("s", 1e9), ("ms", 1e6), ("µs", 1e3)):
        if ns >= scale:
            return f"{ns / scale:.3g} {unit}"
    return f"{ns:.3g} ns"


def fmt_rate(per_s, unit):
    for prefix, scale in (("G", 1e9), ("M", 1e6), ("k", 1e3)):
        if per_s >= scale:
            return f"{per_s / scale:.3g} {prefix}{unit}/s"
    return f"{per_s:.3g} {unit}/s"


rows = []
for est_path in glob.glob(os.path.join(env["CRITERION_DIR"], "**", "new", "estimates.json"), recursive=True):
    mtime = os.path.getmtime(est_path)
    if mtime < start - 1:
        continue  # left over from an earlier run (a renamed or skipped benchmark)
    new_dir = os.path.dirname(est_path)
    with open(est_path) as f:
        est = json.load(f)
    with open(os.path.join(new_dir, "benchmark.json")) as f:
        bench = json.load(f)
    median = est["median"]["point_estimate"]
    ci = est["median"]["confidence_interval"]
    throughput = ""
    tp = bench.get("throughput") or {}
    if "Elements" in tp:
        unit = ELEMENT.get(bench["group_id"], "elem")
        throughput = fmt_rate(tp["Elements"] / (median * 1e-9), unit)
    elif "Bytes" in tp:
        throughput = f"{tp['Bytes'] / (median * 1e-9) / 2**20:.3g} MiB/s"
    rows.append((mtime, bench["full_id"], fmt_time(median), f"{fmt_time(ci['lower_bound'])} – {fmt_time(ci['upper_bound'])}", throughput))
if not rows:
    raise SystemExit(f"criterion.sh: no estimates.json newer than the run under {env['CRITERION_DIR']}")
rows.sort()

with open(env["LOG"], errors="replace") as f:
    log = f.readlines()
skipped = [line.strip() for line in log if "cpu_paths: SKIPPING" in line]
gpu_lines = [line.strip() for line in log if line.startswith("frame_loop: ") and "mode, 20 frames" in line]

lines = [
    f"# CPU paths: criterion medians on {env['CPU']}",
    "",
    f"- CPU: {env['CPU']} ({env['CORES']} cores available; `trace_reference` uses all of them)",
    f"- rustc: {env['RUSTC']}",
    f"- commit: {env['COMMIT']}",
    f"- date: {env['DATE']}",
    "- command: `bash scripts/criterion.sh` (`cargo bench -p caustics --bench cpu_paths --bench frame_loop`, 10 samples per benchmark; `frame_loop` on the default Vulkan device)",
    "",
    "| benchmark | median | 95% CI of median | throughput |",
    "|---|---|---|---|",
]
lines += [f"| {name} | {med} | {ci} | {tp} |" for _, name, med, ci, tp in rows]
if gpu_lines:
    lines += ["", "The frame loop, 20 more frames per mode timed on the host and by the GPU (the same frames):", ""]
    lines += [f"- {g.removeprefix('frame_loop: ')}" for g in gpu_lines]
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
EOF
