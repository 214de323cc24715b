#!/usr/bin/env bash
# One task of a cluster sweep (scripts/cluster/submit.sh wrote the run; docs/bench.md, "On a
# cluster"): one shard of one bench config, run from a node-local copy of the pack, its part
# written to the shared results folder under the device's slug.
#
# Environment: CAUSTICLAB_SHARED (the shared folder, as this node mounts it), CAUSTICLAB_RUN (the
# run's name: $CAUSTICLAB_SHARED/runs/<name>/ holds tasks.txt and target.env), and the task's
# index: SLURM_ARRAY_TASK_ID (1-based) or JOB_COMPLETION_INDEX (a Kubernetes Indexed Job's,
# 0-based: task i is its pod index i - 1). Line <index> of tasks.txt is "config shard shards".
# The part goes to runs/<name>/results/<device-slug>[/quick]/parts/, the run's own: two runs
# never share a part.
#
# A bench that fails is run once more (a second attempt, same node); a device that lacks a
# feature the config needs (exit 2, "needs the device feature") is recorded, not retried. The
# task writes runs/<name>/status/<config>.shard-<i>-of-<n> (state=ok|failed|lacks|killed, the
# part's path, each attempt's exit code, the node) for the merge job, and keeps each attempt's
# output in runs/<name>/logs/.
set -uo pipefail

shared=${CAUSTICLAB_SHARED:?CAUSTICLAB_SHARED is not set (scripts/cluster/submit.sh sets it)}
run_name=${CAUSTICLAB_RUN:?CAUSTICLAB_RUN is not set (scripts/cluster/submit.sh sets it)}
run=$shared/runs/$run_name
if [ -n "${SLURM_ARRAY_TASK_ID:-}" ]; then
    index=$SLURM_ARRAY_TASK_ID
elif [ -n "${JOB_COMPLETION_INDEX:-}" ]; then
    index=$((JOB_COMPLETION_INDEX + 1))
else
    echo "cluster task: no SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX: not an array task" >&2
    exit 2
fi
[ -f "$run/tasks.txt" ] || { echo "cluster task: no $run/tasks.txt" >&2; exit 2; }
read -r config shard shards < <(sed -n "${index}p" "$run/tasks.txt")
[ -n "${shards:-}" ] || { echo "cluster task: $run/tasks.txt has no line $index" >&2; exit 2; }
# PACK, DEVICE, QUICK, CELL_BUDGET (written by submit.sh with printf %q).
source "$run/target.env"
tag=$config.shard-$shard-of-$shards
status=$run/status/$tag
mkdir -p "$run/status" "$run/logs"
host=$(hostname)
exits=()
write_status() {   # state [part] [feature]
    { echo "state=$1"; echo "part=${2:-}"; echo "feature=${3:-}"; echo "exits=${exits[*]}"; echo "host=$host"
      echo "task=$index"; echo "job=${SLURM_ARRAY_JOB_ID:-${HOSTNAME:-?}}"; } >"$status.tmp.$host.$$" && mv "$status.tmp.$host.$$" "$status"
}

# The node-local copy of the pack: binary, tree (bench_configs, scenes, shaders_glsl), models, font.
local_dir=$(mktemp -d "${SLURM_TMPDIR:-${TMPDIR:-/tmp}}/causticlab-task.XXXXXX") || exit 1
child=""
on_signal() {
    [ -n "$child" ] && kill -TERM "$child" 2>/dev/null
    write_status killed
    rm -rf "$local_dir"
    exit 143
}
trap on_signal TERM INT
trap 'rm -rf "$local_dir"' EXIT
pack=$shared/${PACK:?target.env names no PACK}
bin=$local_dir/causticlab
mkdir -p "$local_dir/tree" "$local_dir/models" "$local_dir/results"
xz -dc "$pack/causticlab.xz" >"$bin" && chmod +x "$bin" \
    && tar -C "$local_dir/tree" -xJf "$pack/tree.tar.xz" \
    && { [ ! -f "$pack/models.tar.xz" ] || tar -C "$local_dir/models" -xJf "$pack/models.tar.xz"; } \
    && cp "$pack/DejaVuSans.ttf" "$local_dir/" \
    || { exits+=(unpack); write_status failed; echo "cluster task: cannot unpack $pack on $host" >&2; exit 1; }
export CAUSTICLAB_MODELS=$local_dir/models CAUSTICLAB_FONT=$local_dir/DejaVuSans.ttf
CAUSTICLAB_COMMIT=$(cat "$pack/COMMIT" 2>/dev/null || echo unknown)
export CAUSTICLAB_COMMIT

args=()
[ -n "${DEVICE:-}" ] && args+=(--device "$DEVICE")
args+=(bench "bench_configs/$config.toml" --shard "$shard/$shards" --results "$local_dir/results")
[ "${QUICK:-0}" -eq 1 ] && args+=(--quick)
[ -n "${CELL_BUDGET:-}" ] && args+=(--max-time-budget "$CELL_BUDGET")

echo "cluster task $index: $config shard $shard/$shards on $host (device '${DEVICE:-default}')"
for attempt in 1 2; do
    log=$run/logs/$tag.attempt-$attempt.log
    (cd "$local_dir/tree" && exec "$bin" "${args[@]}") >"$log" 2>&1 &
    child=$!
    wait "$child"
    rc=$?
    child=""
    exits+=("$rc")
    tail -n 2 "$log"
    part=$(find "$local_dir/results" -name "$tag.json" | head -n 1)
    if [ "$rc" -eq 0 ] && [ -n "$part" ]; then
        rel=runs/$run_name/results/${part#"$local_dir/results/"}   # ...<slug>[/quick]/parts/<tag>.json
        mkdir -p "$shared/$(dirname "$rel")"
        cp "$part" "$shared/$rel.tmp.$host.$$" && mv "$shared/$rel.tmp.$host.$$" "$shared/$rel" \
            || { write_status failed; exit 1; }
        write_status ok "$rel"
        echo "cluster task $index: wrote $rel"
        exit 0
    fi
    if [ "$rc" -eq 2 ] && lacks=$(grep -o 'needs the device feature `[a-z_0-9]*`' "$log" | head -n 1); then
        feature=$(tr -d '`' <<<"${lacks#needs the device feature }")
        write_status lacks "" "$feature"
        echo "cluster task $index: $config shard $shard/$shards not run: the device lacks $feature"
        exit 0
    fi
    [ "$attempt" -eq 1 ] && echo "cluster task $index: attempt 1 failed (exit $rc, $log); running it once more"
done
write_status failed
echo "cluster task $index: $config shard $shard/$shards failed twice (exits ${exits[*]}; $run/logs/$tag.attempt-*.log)" >&2
exit 1
