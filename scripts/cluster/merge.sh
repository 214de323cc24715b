#!/usr/bin/env bash
# The merge job of a cluster sweep (scripts/cluster/submit.sh; docs/bench.md, "On a cluster"),
# run after every task of its array has ended, however it ended: for each config, the parts its
# tasks wrote are merged (`causticlab bench merge`) into the tables of
# $CAUSTICLAB_SHARED/results/<device-slug>/. A shard without a part is named, with why: its task
# failed twice (exit codes, node, logs), was killed (scancel, a time limit, preemption), or never
# wrote a status (cancelled before it started, or lost with its node). Such a config gets no
# table (with PARTIAL=1 in the run's target.env, `submit.sh --partial`: a table whose missing
# cells read `not run`), and the job exits 1. A config the device cannot run (a feature it lacks)
# is named and is not a failure. The outcome is also written to runs/<name>/MERGED.
#
# Environment: CAUSTICLAB_SHARED and CAUSTICLAB_RUN, as for scripts/cluster/task.sh. "Task i"
# is line i of tasks.txt: Slurm's array index i, a Kubernetes pod's completion index i - 1.
set -uo pipefail

shared=${CAUSTICLAB_SHARED:?CAUSTICLAB_SHARED is not set (scripts/cluster/submit.sh sets it)}
run_name=${CAUSTICLAB_RUN:?CAUSTICLAB_RUN is not set (scripts/cluster/submit.sh sets it)}
run=$shared/runs/$run_name
[ -f "$run/tasks.txt" ] || { echo "merge: no $run/tasks.txt" >&2; exit 2; }
source "$run/target.env"

pack=$shared/${PACK:?target.env names no PACK}
local_dir=$(mktemp -d "${SLURM_TMPDIR:-${TMPDIR:-/tmp}}/causticlab-merge.XXXXXX") || exit 1
trap 'rm -rf "$local_dir"' EXIT
bin=$local_dir/causticlab
xz -dc "$pack/causticlab.xz" >"$bin" && chmod +x "$bin" || { echo "merge: cannot unpack $pack/causticlab.xz" >&2; exit 1; }
export CAUSTICLAB_FONT=$pack/DejaVuSans.ttf
CAUSTICLAB_COMMIT=$(cat "$pack/COMMIT" 2>/dev/null || echo unknown)
export CAUSTICLAB_COMMIT

field() { sed -n "s/^$1=//p" "$2"; }
fail=0
tables=0
summary=()
mapfile -t configs < <(awk '!seen[$1]++ { print $1, $3 }' "$run/tasks.txt")
for entry in "${configs[@]}"; do
    read -r config shards <<<"$entry"
    parts=()
    problems=()
    lacking=""
    for s in $(seq 1 "$shards"); do
        tag=$config.shard-$s-of-$shards
        task=$(awk -v c="$config" -v s="$s" '$1 == c && $2 == s { print NR; exit }' "$run/tasks.txt")
        st=$run/status/$tag
        if [ ! -f "$st" ]; then
            problems+=("shard $s of $shards missing: task $task never wrote its status (cancelled before it ran, or lost with its node; runs/$run_name/logs/)")
            continue
        fi
        host=$(field host "$st")
        case "$(field state "$st")" in
            ok)
                part=$shared/$(field part "$st")
                if [ -f "$part" ]; then parts+=("$part"); else problems+=("shard $s of $shards missing: task $task wrote $part, which is gone"); fi ;;
            failed) problems+=("shard $s of $shards missing: task $task failed twice on $host (exits $(field exits "$st"); runs/$run_name/logs/$tag.attempt-*.log)") ;;
            killed) problems+=("shard $s of $shards missing: task $task was killed on $host (a signal: scancel, its time limit or preemption)") ;;
            lacks) lacking=$(field feature "$st") ;;
            *) problems+=("shard $s of $shards missing: task $task left an unreadable status ($st)") ;;
        esac
    done
    if [ -n "$lacking" ] && [ "${#parts[@]}" -eq 0 ] && [ "${#problems[@]}" -eq 0 ]; then
        echo "merge: $config: not run: the device lacks $lacking"
        summary+=("$config: not run (lacks $lacking)")
        continue
    fi
    merge_args=()
    if [ -n "$lacking" ] && [ "${#problems[@]}" -eq 0 ]; then
        # Some shards held cells the device cannot run (a feature only some techniques need):
        # those read `not run`, and the device's lack is no failure.
        echo "merge: $config: the shards with cells needing $lacking were not run (the device lacks it); their cells read \`not run\`"
        merge_args=(--partial)
    fi
    if [ "${#problems[@]}" -gt 0 ]; then
        for p in "${problems[@]}"; do echo "merge: $config: $p" >&2; done
        fail=1
        if [ "${PARTIAL:-0}" -ne 1 ] || [ "${#parts[@]}" -eq 0 ]; then
            echo "merge: $config: no table written (${#problems[@]} of $shards shards missing)" >&2
            summary+=("$config: no table (${#problems[@]} of $shards shards missing)")
            continue
        fi
        merge_args=(--partial)
    fi
    # From the shared folder into `results` (submit.sh makes every path here absolute): the tables
    # are copied into the repository's results/, and a table's Regenerate line names its results
    # folder only where it is not `results` (crates/bench/src/report.rs).
    if out=$(cd "$shared" && "$bin" bench merge "${merge_args[@]}" --results results "${parts[@]}" 2>&1); then
        md=$(grep -o "^wrote .*/$config\.md\$" <<<"$out" | tail -n 1 | sed 's/^wrote //')
        echo "merge: $config: ${md:-merged} (${#parts[@]} of $shards shards)"
        summary+=("$config: ${md#"$shared/"}")
        tables=$((tables + 1))
    else
        echo "$out" >&2
        echo "merge: $config: bench merge failed" >&2
        summary+=("$config: bench merge failed")
        fail=1
    fi
done
{ echo "exit=$fail"; echo "tables=$tables"; printf '%s\n' "${summary[@]}"; } >"$run/MERGED"
echo "merge: $tables tables; runs/$run_name/MERGED"
exit "$fail"
