#!/usr/bin/env bash
# Runs bench configs on a cluster: each config as shards, one array task per shard, then a merge
# job that writes the tables (docs/bench.md, "On a cluster"). Slurm job arrays by default; with
# --k8s it writes Kubernetes Indexed Job manifests instead of submitting.
#
#   bash scripts/cluster/submit.sh --shared DIR [options] CONFIG...       # names or bench_configs/*.toml
#   bash scripts/cluster/submit.sh --shared DIR [options] --suite first|more|all
#
# --shared DIR     a folder every node sees (created): packs/<name>/ (the pack and the two job
#                  scripts of one submission), runs/<name>.<k>/, results/
# --target DEV[=CONSTRAINT]   one array per target (repeatable; default one, the default device):
#                  DEV is passed to `causticlab --device` (a name substring or an index),
#                  CONSTRAINT to sbatch --constraint (Kubernetes: the node label
#                  nvidia.com/gpu.product), so that each array runs on one GPU model and each
#                  device folder holds whole tables
# --shards N       shards per config (default: the GPU suite's count for its configs, else 4)
# --throttle K     at most K tasks of an array at once (sbatch --array=1-M%K; Kubernetes parallelism)
# --partition P, --gres G, --time T, --account A   passed to sbatch for the array tasks (the
#                  merge job gets --partition, --account and --time only: it needs no GPU)
# --quick          the configs' [quick] sizes (tables under <slug>/quick/)
# --cell-budget S  `bench --max-time-budget S`
# --partial        the merge writes a table with `not run` cells when shards are missing (it
#                  still names them and exits 1)
# --binary B       the binary to pack (default target/release/causticlab, built if missing);
#                  --pack DIR uses a pack gpu_pack.sh --cluster already wrote. The nodes need
#                  a Vulkan loader (libvulkan1) and their GPU's driver.
# --name NAME      the run's name (default: the date and time); runs/<NAME>.<k>/ per target
# --wait           wait for the merge jobs, print their summaries, exit 1 if any failed
# --k8s            write Indexed Job manifests into runs/<NAME>.<k>/k8s-{array,merge}.yaml instead of
#                  submitting; with --image IMG (required), --pvc CLAIM (the shared folder's
#                  PersistentVolumeClaim, mounted at --mount PATH, default /causticlab)
#
# Each task unpacks the pack into node-local storage ($SLURM_TMPDIR, $TMPDIR or /tmp), runs
# `causticlab bench CONFIG --shard i/n`, and copies its part into its run's
# runs/<name>.<k>/results/<device-slug>[/quick]/parts/; a failed bench is run once more
# (scripts/cluster/task.sh). The merge job (scripts/cluster/merge.sh, `afterany` the array, and
# after the previous target's merge so that two merges never rebuild results/README.md at once)
# writes the tables into results/<device-slug>/ and names every missing shard.
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
start_dir=$(pwd)
cd "$repo"

usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; }
die() { echo "submit: $*" >&2; exit 2; }

shared="" targets=() shards="" throttle="" partition="" gres="" time_limit="" account=""
quick=0 cell_budget="" partial=0 binary="" pack_in="" name="" wait=0
k8s=0 image="" pvc="" mount=/causticlab suite="" configs=()
while [ $# -gt 0 ]; do
    case "$1" in
        --shared|--target|--shards|--throttle|--partition|--gres|--time|--account|--cell-budget|--binary|--pack|--name|--image|--pvc|--mount|--suite)
            [ $# -ge 2 ] || die "$1 needs a value (see --help)" ;;&
        --shared) shared=$2; shift 2 ;;
        --target) targets+=("$2"); shift 2 ;;
        --shards) shards=$2; shift 2 ;;
        --throttle) throttle=$2; shift 2 ;;
        --partition) partition=$2; shift 2 ;;
        --gres) gres=$2; shift 2 ;;
        --time) time_limit=$2; shift 2 ;;
        --account) account=$2; shift 2 ;;
        --cell-budget) cell_budget=$2; shift 2 ;;
        --binary) binary=$2; shift 2 ;;
        --pack) pack_in=$2; shift 2 ;;
        --name) name=$2; shift 2 ;;
        --image) image=$2; shift 2 ;;
        --pvc) pvc=$2; shift 2 ;;
        --mount) mount=$2; shift 2 ;;
        --suite) suite=$2; shift 2 ;;
        --quick) quick=1; shift ;;
        --partial) partial=1; shift ;;
        --wait) wait=1; shift ;;
        --k8s) k8s=1; shift ;;
        -h|--help) usage; exit 0 ;;
        -*) die "unknown option '$1' (see --help)" ;;
        *) configs+=("$1"); shift ;;
    esac
done
[ -n "$shared" ] || die "--shared DIR is required (a folder every node sees; see --help)"
# Paths the user gave are relative to where they ran this, not to the repository.
absolute() { case "$1" in /*) echo "$1" ;; *) echo "$start_dir/$1" ;; esac; }
shared=$(absolute "$shared")
[ -z "$pack_in" ] || pack_in=$(absolute "$pack_in")
[ -z "$binary" ] || binary=$(absolute "$binary")
case "$shared" in *,*|*%*) die "--shared: '$shared' has a ',' or '%' (sbatch's --export and --output would split or expand it)" ;; esac
[ -z "$shards" ] || [[ "$shards" =~ ^[1-9][0-9]*$ ]] || die "--shards: '$shards' is not a whole number above 0"
[ -z "$throttle" ] || [[ "$throttle" =~ ^[1-9][0-9]*$ ]] || die "--throttle: '$throttle' is not a whole number above 0"
[ -z "$name" ] || [[ "$name" =~ ^[A-Za-z0-9._-]+$ ]] || die "--name: '$name' may hold letters, digits, '.', '_' and '-' only"
if [ "$k8s" -eq 1 ]; then
    [ -n "$image" ] || die "--k8s needs --image (a container image with bash, xz, tar and libvulkan1; docs/bench.md)"
    [ -n "$pvc" ] || die "--k8s needs --pvc (the PersistentVolumeClaim that holds --shared)"
    [ "$wait" -eq 0 ] || die "--wait is for Slurm (with --k8s: kubectl wait, docs/bench.md)"
else
    command -v sbatch >/dev/null || die "no sbatch on this machine: submit from a Slurm login node, or write manifests with --k8s"
fi

# The configs and their shard counts: "config shards" per line.
entries=()
suite_shards() { bash scripts/gpu_suite.sh --list-shards "$1"; }
case "$suite" in
    "") ;;
    first|more) mapfile -t entries < <(suite_shards "$suite") ;;
    all) mapfile -t entries < <(suite_shards first; suite_shards more) ;;
    *) die "--suite takes first, more or all, not '$suite'" ;;
esac
[ -z "$suite" ] || [ "${#configs[@]}" -eq 0 ] || die "give configs or --suite, not both"
for c in "${configs[@]}"; do
    c=$(basename "$c" .toml)
    [ -f "bench_configs/$c.toml" ] || die "no bench config bench_configs/$c.toml"
    n=$( { suite_shards first; suite_shards more; } | awk -v c="$c" '$1 == c { print $2 }')
    entries+=("$c ${n:-4}")
done
[ "${#entries[@]}" -gt 0 ] || die "no configs given (names, bench_configs/*.toml, or --suite; see --help)"
if [ -n "$shards" ]; then
    for i in "${!entries[@]}"; do entries[$i]="${entries[$i]%% *} $shards"; done
fi
[ "${#targets[@]}" -gt 0 ] || targets=("")

# 1. The submission's own pack (binary, tree, models, font, commit) and the two job scripts, in
#    packs/<name>/ of the shared folder: a later submission never replaces what a queued one runs.
mkdir -p "$shared/runs" "$shared/results" "$shared/packs"
shared=$(cd "$shared" && pwd)
[ -n "$name" ] || name=$(date -u +%Y%m%d-%H%M%S)
[ ! -e "$shared/packs/$name" ] || die "$shared/packs/$name exists: give another --name"
for k in $(seq 1 "${#targets[@]}"); do
    [ ! -e "$shared/runs/$name.$k" ] || die "$shared/runs/$name.$k exists: give another --name"
done
pack=$shared/packs/$name
if [ -n "$pack_in" ]; then
    [ -f "$pack_in/causticlab.xz" ] && [ -f "$pack_in/tree.tar.xz" ] || die "$pack_in is not a cluster pack (gpu_pack.sh --cluster writes one)"
    mkdir -p "$pack"
    cp -r "$pack_in"/. "$pack/"
else
    if [ -z "$binary" ]; then
        [ -x target/release/causticlab ] || cargo build --release -p causticlab
        binary=target/release/causticlab
    fi
    bash scripts/gpu_pack.sh --binary "$binary" --out "$pack" --cluster --no-loader
fi
cp scripts/cluster/task.sh scripts/cluster/merge.sh "$pack/"

# 2. One run folder per target: its task list and settings.
ntasks=0
for e in "${entries[@]}"; do ntasks=$((ntasks + ${e##* })); done
runs=()
k=0
for target in "${targets[@]}"; do
    k=$((k + 1))
    run_name=$name.$k
    run=$shared/runs/$run_name
    mkdir -p "$run/status" "$run/logs"
    for e in "${entries[@]}"; do
        read -r c n <<<"$e"
        for s in $(seq 1 "$n"); do echo "$c $s $n"; done
    done >"$run/tasks.txt"
    {
        printf 'PACK=%q\n' "packs/$name"
        printf 'DEVICE=%q\n' "${target%%=*}"
        printf 'CONSTRAINT=%q\n' "$( [[ "$target" == *=* ]] && echo "${target#*=}" )"
        printf 'QUICK=%q\nPARTIAL=%q\nCELL_BUDGET=%q\n' "$quick" "$partial" "$cell_budget"
    } >"$run/target.env"
    runs+=("$run_name")
done

# 3a. Kubernetes: manifests, not submitted.
if [ "$k8s" -eq 1 ]; then
    for run_name in "${runs[@]}"; do
        constraint=$(source "$shared/runs/$run_name/target.env"; echo "$CONSTRAINT")
        for job in array merge; do
            bash scripts/cluster/k8s_manifest.sh --job "$job" --run "$run_name" --pack "packs/$name" --tasks "$ntasks" --image "$image" \
                --pvc "$pvc" --mount "$mount" ${throttle:+--parallelism "$throttle"} ${constraint:+--constraint "$constraint"} \
                >"$shared/runs/$run_name/k8s-$job.yaml"
        done
        echo "submit: wrote $shared/runs/$run_name/k8s-array.yaml ($ntasks indexed completions) and k8s-merge.yaml (apply it once the array has ended; docs/bench.md, On a cluster)"
    done
    exit 0
fi

# 3b. Slurm: an array per target, and its merge job.
merges=()
previous=""
for run_name in "${runs[@]}"; do
    run=$shared/runs/$run_name
    { IFS= read -r device; IFS= read -r constraint; } < <(source "$run/target.env"; printf '%s\n%s\n' "$DEVICE" "$CONSTRAINT")
    common=(--export="ALL,CAUSTICLAB_SHARED=$shared,CAUSTICLAB_RUN=$run_name")
    [ -n "$partition" ] && common+=(--partition "$partition")
    [ -n "$account" ] && common+=(--account "$account")
    [ -n "$time_limit" ] && common+=(--time "$time_limit")
    task_args=(--array "1-$ntasks${throttle:+%$throttle}" --job-name "causticlab-$run_name"
        --output "$run/logs/slurm-%A_%a.out")
    [ -n "$gres" ] && task_args+=(--gres "$gres")
    [ -n "$constraint" ] && task_args+=(--constraint "$constraint")
    array=$(sbatch --parsable "${common[@]}" "${task_args[@]}" "$pack/task.sh")
    array=${array%%;*}
    merge=$(sbatch --parsable "${common[@]}" --job-name "causticlab-$run_name-merge" \
        --dependency "afterany:$array${previous:+:$previous}" --output "$run/logs/merge-%j.out" "$pack/merge.sh")
    merge=${merge%%;*}
    echo "$array" >"$run/ARRAY_JOB"
    echo "$merge" >"$run/MERGE_JOB"
    echo "submit: $run_name: device '${device:-default}'${constraint:+, constraint $constraint}: array job $array ($ntasks tasks${throttle:+, $throttle at a time}), merge job $merge"
    merges+=("$merge")
    previous=$merge
done
echo "submit: tables will be in $shared/results/<device-slug>/; each run's outcome in $shared/runs/<name>/MERGED"
[ "$wait" -eq 1 ] || exit 0

# --wait: until every merge job has left the queue (a failing squeue, say the controller busy for
# a moment, is asked again, not read as an empty queue).
while true; do
    if queued=$(squeue -h -j "$(IFS=,; echo "${merges[*]}")" 2>/dev/null); then
        [ -n "$queued" ] || break
    elif ! squeue -h -u "$(id -un)" >/dev/null 2>&1; then
        sleep 5
        continue
    else
        break   # the jobs are gone from the controller's memory: ended
    fi
    sleep 2
done
status=0
for run_name in "${runs[@]}"; do
    m=$shared/runs/$run_name/MERGED
    if [ -f "$m" ]; then
        echo "submit: $run_name: $(tail -n +2 "$m" | paste -sd ';' -)"
        [ "$(sed -n 's/^exit=//p' "$m")" = 0 ] || status=1
    else
        echo "submit: $run_name: the merge job wrote no MERGED (see $shared/runs/$run_name/logs/merge-*.out)" >&2
        status=1
    fi
done
exit "$status"
