#!/usr/bin/env bash
# The exact photon tracers' rates on this machine, side by side: the GPU tracer
# (`--technique photon-trace`, bench_configs/photon_trace_rate.toml, into results/<device>/) and
# the CPU reference (`causticlab reference`, three runs per cell, the median), both on the glass
# sphere and the glass bunny, Fresnel on and off. Writes results/photon_trace.csv (one row per
# scene and Fresnel setting) and results/photon_trace.md, the page, from that file's rows.
#
#   bash scripts/photon_rate.sh
#
# A timing run: build first, run it alone on a quiet machine from a clean commit (the bench
# refuses busy cells), then commit the results.
set -euo pipefail
cd "$(dirname "$0")/.."

bin=target/release/causticlab
[ -x "$bin" ] || { echo "photon_rate.sh: build first: cargo build --release" >&2; exit 1; }
photons=2048
runs=3
csv=results/photon_trace.csv
out=results/photon_trace.md
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The commit measured, before this run adds its tables to the tree; as the bench does
# (`bench::meta::commit`), results and Markdown being rewritten do not make the code dirty.
if [ -n "${CAUSTICLAB_COMMIT:-}" ]; then
    commit=$CAUSTICLAB_COMMIT
else
    source scripts/commit.sh
    commit=$(code_commit)
fi

"$bin" bench bench_configs/photon_trace_rate.toml | tee "$tmp/bench.log"
table=$(grep -o 'results/[^ ]*/photon_trace_rate\.json\.gz' "$tmp/bench.log" | tail -1)
[ -n "$table" ] || { echo "photon_rate.sh: the bench wrote no photon_trace_rate.json.gz" >&2; exit 1; }

for scene in sphere_on_plane bunny_in_room; do
    for fresnel in true false; do
        for run in $(seq "$runs"); do
            "$bin" reference --scene "scenes/$scene.toml" --photons $((photons * photons)) --fresnel "$fresnel" \
                --out "$tmp/$scene-$fresnel-$run" > /dev/null
        done
    done
done

# The measurements, one row per scene and Fresnel setting, into $csv (full precision); then the
# page from that file's rows: every number on the page is a cell of the CSV, rounded.
TMP="$tmp" TABLE="$table" PHOTONS="$photons" RUNS="$runs" CSV="$csv" python3 - <<'MEASURED'
import csv, gzip, json, os, statistics
tmp, n, runs = os.environ["TMP"], int(os.environ["PHOTONS"]), int(os.environ["RUNS"])
bench = json.load(gzip.open(os.environ["TABLE"], "rt"))
def find(scene, label):
    for c in bench["cells"]:
        cell = c["cell"]
        if cell["scene"].endswith(scene + ".toml") and cell["technique_label"] == label and cell["photons"] == n:
            return c
    raise SystemExit(f"no cell {scene} {label} {n}")
def gpu(scene, label, metric):
    return find(scene, label)["metrics"][metric]["value"]
def unmeasured(scene, label, metric):
    # As the table shows it: an entry plausibility rules c, e or f found beyond the device is
    # not a number (bench_configs/README.md#plausibility). The CSV leaves its value empty and
    # names the rule.
    index = find(scene, label)["cell"]["index"]
    for f in bench.get("plausibility", []):
        if f["cell"] == index and f["metric"] == metric and f["rule"] in ("c", "e", "f"):
            return f["rule"]
    return ""
rows = [["scene", "fresnel", "cpu_mphotons", "cpu_lo", "cpu_hi", "gpu_frame_mphotons", "frame_over_cpu",
         "gpu_host_mphotons", "host_over_cpu", "gpu_trace_mphotons", "gpu_trace_not_measured"]]
for scene in ["sphere_on_plane", "bunny_in_room"]:
    for fresnel, label in [("true", "Fresnel on"), ("false", "Fresnel off")]:
        rates = []
        for run in range(1, runs + 1):
            r = json.load(open(f"{tmp}/{scene}-{fresnel}-{run}/reference.json"))
            rates.append(r["photons_traced"] / r["seconds"] / 1e6)
        cpu = statistics.median(rates)
        frame = gpu(scene, label, "frame rate")
        host = gpu(scene, label, "host rate")
        rule = unmeasured(scene, label, "rate")
        trace = "" if rule else repr(gpu(scene, label, "rate"))
        rows.append([scene, "on" if fresnel == "true" else "off", repr(cpu), repr(min(rates)), repr(max(rates)),
                     repr(frame), repr(frame / cpu), repr(host), repr(host / cpu), trace, rule])
with open(os.environ["CSV"], "w", newline="") as f:
    csv.writer(f, lineterminator="\n").writerows(rows)
MEASURED

CSV="$csv" OUT="$out" PHOTONS="$photons" RUNS="$runs" COMMIT="$commit" DATE="$(date -u +%Y-%m-%dT%H:%M:%SZ)" \
TABLE_MD="$(python3 -c 'import os, sys; print(os.path.relpath(sys.argv[1].removesuffix(".json.gz") + ".md", "results"))' "$table")" \
DEVICE="$(python3 -c 'import gzip, json, sys; print(json.load(gzip.open(sys.argv[1], "rt"))["meta"]["device"])' "$table")" \
CPU="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')" CORES="$(nproc)" \
python3 - <<'PAGE'
import csv, os
env = os.environ
n, runs = int(env["PHOTONS"]), int(env["RUNS"])
def num(r, col, fmt):
    return fmt.format(float(r[col]))
table = []
for r in csv.DictReader(open(env["CSV"])):
    rule = r["gpu_trace_not_measured"]
    trace = f"not measured ({rule})" if rule else num(r, "gpu_trace_mphotons", "{:.3f}")
    table.append(
        f"| `{r['scene']}` | Fresnel {r['fresnel']} "
        f"| {num(r, 'cpu_mphotons', '{:.3f}')} ({num(r, 'cpu_lo', '{:.3f}')}-{num(r, 'cpu_hi', '{:.3f}')}) "
        f"| {num(r, 'gpu_frame_mphotons', '{:.3f}')} | {num(r, 'frame_over_cpu', '{:.2f}')} "
        f"| {num(r, 'gpu_host_mphotons', '{:.3f}')} | {num(r, 'host_over_cpu', '{:.2f}')} | {trace} |"
    )
data = os.path.basename(env["CSV"])
out = f"""# The exact photon tracers' rates, GPU and CPU, on one machine

Written by `bash scripts/photon_rate.sh` (commit {env['COMMIT']}, {env['DATE']}), on
{env['CPU']} ({env['CORES']} cores); the GPU tracer on {env['DEVICE']}.

- **CPU reference**: `causticlab reference --photons {n * n}` (every core), end to end (BVH
  build, tracing, binning into the receiver map), median of {runs} runs (the range in brackets).
- **GPU tracer, whole frame**: `photon_trace_rate.toml`'s `frame rate` at {n}² photons: the photons
  emitted per second of host wall time of a whole frame (the trace, the receiver positions, the
  splat into a 1024² caustic map, the eye's view at 256²), a lower bound on the tracer's rate.
- **GPU tracer, trace pass, host-timed**: its `host rate`: the trace pass submitted alone, from
  its submit to its fence (a submit and a wait included).
- **GPU tracer, trace pass, timestamps**: its `rate`, from the timestamps around the trace's
  dispatch. On lavapipe these miss the dispatch in most frames: where plausibility rules e or f
  find so, the entry reads `not measured`, as in the table.

| scene | Fresnel | CPU reference, M photons/s | GPU tracer, whole frame, M photons/s | GPU / CPU | GPU trace pass, host-timed, M photons/s | host-timed / CPU | GPU trace pass (timestamps), M photons/s |
|---|---|---|---|---|---|---|---|
""" + "\n".join(table) + f"""

The table behind the GPU columns: [{env['TABLE_MD']}]({env['TABLE_MD']}). This page's rows, unrounded
(the CPU runs' range in `cpu_lo` and `cpu_hi`, a rule's letter where the timestamps' rate is not
measured), are [{data}]({data}), written by the same run; a page that quotes them cites that file.
"""
open(env["OUT"], "w").write(out)
print(out)
PAGE
