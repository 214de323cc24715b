#!/usr/bin/env bash
# T2 beside the CPU reference: the GPU photon tracer's two traversals (its own BVH in a compute
# shader, `--trace compute`, and ray queries against Vulkan acceleration structures,
# `--trace ray-query`; bench_configs/photon_trace_paths.toml) on a device with ray queries, and
# the exact CPU reference (`causticlab reference`, three runs per cell, the median) on the same
# machine, on the glass sphere and the glass bunny, Fresnel on and off.
# Writes results/photon_trace_paths.csv (one row per scene and Fresnel setting) and
# results/photon_trace_paths.md, the page, from that file's rows.
#
#   bash scripts/photon_rate_paths.sh            # on Mesa 25's lavapipe (scripts/mesa25.sh)
#   bash scripts/photon_rate_paths.sh DEVICE     # on another device with ray queries
#
# The three are compared by their rates at the table's largest photon count, 512², the
# reference tracing at least as many photons and at least one of its tasks of 65,536 photons
# per core (so that every core traces: 512² is four tasks), by their tracing alone: the GPU tracer's
# trace pass submitted alone and timed on the host (`host rate`: its BVH and acceleration
# structures are built when the renderer is made), the reference's `trace_seconds` (its BVH
# built before, the direct light after). A timing run: build first, run it alone on a quiet
# machine from a clean commit (the bench refuses busy cells), then commit the results.
set -euo pipefail
cd "$(dirname "$0")/.."

bin=target/release/causticlab
[ -x "$bin" ] || { echo "photon_rate_paths.sh: build first: cargo build --release" >&2; exit 1; }
if [ $# -ge 1 ]; then
    device=$1
else
    env=$(bash scripts/mesa25.sh --env) || { echo "photon_rate_paths.sh: Mesa 25's lavapipe cannot be had" >&2; exit 1; }
    eval "$env"
    device=$(bash scripts/mesa25.sh --driver)
fi
photons=512
# The reference's photons: 512², or one task of 65,536 per core where that is more.
cores=$(nproc)
ref_photons=$((photons * photons > 65536 * cores ? photons * photons : 65536 * cores))
runs=3
csv=results/photon_trace_paths.csv
out=results/photon_trace_paths.md
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [ -n "${CAUSTICLAB_COMMIT:-}" ]; then
    commit=$CAUSTICLAB_COMMIT
else
    source scripts/commit.sh
    commit=$(code_commit)
fi

"$bin" --device "$device" bench bench_configs/photon_trace_paths.toml | tee "$tmp/bench.log"
table=$(grep -o 'results/[^ ]*/photon_trace_paths\.json\.gz' "$tmp/bench.log" | tail -1)
[ -n "$table" ] || { echo "photon_rate_paths.sh: the bench wrote no photon_trace_paths.json.gz" >&2; exit 1; }

for scene in sphere_on_plane bunny_in_room; do
    for fresnel in true false; do
        for run in $(seq "$runs"); do
            "$bin" reference --scene "scenes/$scene.toml" --photons "$ref_photons" --fresnel "$fresnel" \
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
def host_rate(scene, label):
    for c in bench["cells"]:
        cell = c["cell"]
        if cell["scene"].endswith(scene + ".toml") and cell["technique_label"] == label and cell["photons"] == n:
            return c["metrics"]["host rate"]["value"]
    raise SystemExit(f"no cell {scene} {label} {n}")
rows = [["scene", "fresnel", "cpu_trace_mphotons", "cpu_lo", "cpu_hi", "cpu_threads", "compute_mphotons",
         "compute_over_cpu", "ray_query_mphotons", "ray_query_over_cpu", "compute_over_ray_query"]]
for scene in ["sphere_on_plane", "bunny_in_room"]:
    for fresnel, on in [("true", "on"), ("false", "off")]:
        rates, threads = [], set()
        for run in range(1, runs + 1):
            r = json.load(open(f"{tmp}/{scene}-{fresnel}-{run}/reference.json"))
            rates.append(r["photons_traced"] / r["trace_seconds"] / 1e6)
            threads.add(r["threads"])
        if len(threads) != 1:
            raise SystemExit(f"{scene} Fresnel {on}: the reference's runs used {sorted(threads)} threads")
        if min(threads) < len(os.sched_getaffinity(0)):
            print(f"photon_rate_paths.sh: warning: {scene} Fresnel {on}: the reference traced with "
                  f"{min(threads)} threads on {len(os.sched_getaffinity(0))} cores (the system refused some)")
        cpu = statistics.median(rates)
        compute = host_rate(scene, f"compute, Fresnel {on}")
        rq = host_rate(scene, f"ray-query, Fresnel {on}")
        rows.append([scene, on, repr(cpu), repr(min(rates)), repr(max(rates)), str(threads.pop()), repr(compute),
                     repr(compute / cpu), repr(rq), repr(rq / cpu), repr(compute / rq)])
with open(os.environ["CSV"], "w", newline="") as f:
    csv.writer(f, lineterminator="\n").writerows(rows)
MEASURED

CSV="$csv" OUT="$out" PHOTONS="$photons" REF_PHOTONS="$ref_photons" RUNS="$runs" COMMIT="$commit" DATE="$(date -u +%Y-%m-%dT%H:%M:%SZ)" \
TABLE_MD="$(python3 -c 'import os, sys; print(os.path.relpath(sys.argv[1].removesuffix(".json.gz") + ".md", "results"))' "$table")" \
DEVICE="$(python3 -c 'import gzip, json, sys; m = json.load(gzip.open(sys.argv[1], "rt"))["meta"]; print(m["device"] + ", " + m["driver_name"] + " " + m["driver_info"])' "$table")" \
CPU="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')" CORES="$(nproc)" \
python3 - <<'PAGE'
import csv, os
env = os.environ
n, runs = int(env["PHOTONS"]), int(env["RUNS"])
def num(r, col, fmt):
    return fmt.format(float(r[col]))
table = []
for r in csv.DictReader(open(env["CSV"])):
    table.append(
        f"| `{r['scene']}` | Fresnel {r['fresnel']} "
        f"| {num(r, 'cpu_trace_mphotons', '{:.3f}')} ({num(r, 'cpu_lo', '{:.3f}')}-{num(r, 'cpu_hi', '{:.3f}')}), "
        f"{r['cpu_threads']} threads "
        f"| {num(r, 'compute_mphotons', '{:.3f}')} | {num(r, 'compute_over_cpu', '{:.2f}')} "
        f"| {num(r, 'ray_query_mphotons', '{:.4f}')} | {num(r, 'ray_query_over_cpu', '{:.3f}')} "
        f"| {num(r, 'compute_over_ray_query', '{:.1f}')} |"
    )
data = os.path.basename(env["CSV"])
out = f"""# T2 beside the CPU reference: compute BVH, ray queries and the CPU, tracing alone

Written by `bash scripts/photon_rate_paths.sh` (commit {env['COMMIT']}, {env['DATE']}), on
{env['CPU']} ({env['CORES']} cores); the GPU tracer on {env['DEVICE']}.

- **CPU reference, tracing**: `causticlab reference --photons {env['REF_PHOTONS']}` (its threads
  in the table, one per core, each taking tasks of 65,536 photons), its
  `trace_seconds`: the photons' tracing and binning into the receiver map, without the BVH
  build before them and the direct light after them; median of {runs} runs (the range in
  brackets).
- **GPU tracer, compute BVH** and **ray queries**: `photon_trace_paths.toml`'s `host rate` at
  {n}² photons: the trace pass submitted alone, from its submit to its fence; its BVH, or its
  acceleration structures, built when the renderer was made.

On lavapipe all three run on the same CPU cores: the ray queries are Mesa's software traversal
of its own acceleration structures, not ray-tracing hardware, and the ratios compare three
traversals of one machine. On a GPU the same script compares the GPU's two paths with this
machine's CPU.

| scene | Fresnel | CPU reference, tracing, M photons/s | GPU compute BVH, M photons/s | compute / CPU | GPU ray queries, M photons/s | ray queries / CPU | compute / ray queries |
|---|---|---|---|---|---|---|---|
""" + "\n".join(table) + f"""

The table behind the GPU columns: [{env['TABLE_MD']}]({env['TABLE_MD']}). This page's rows, unrounded
(the CPU runs' range in `cpu_lo` and `cpu_hi`), are [{data}]({data}), written by the same run; a
page that quotes them cites that file.
"""
open(env["OUT"], "w").write(out)
print(out)
PAGE
