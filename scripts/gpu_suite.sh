#!/usr/bin/env bash
# Runs the most important bench configs on the GPU machine within a fixed time budget, from the
# pack scripts/gpu_pack.sh wrote (.gpu/), and returns one archive. Step by step: docs/bench.md,
# "A GPU run".
#
#   bash scripts/gpu_suite.sh [--quick] [--more | --only A,B] [--pack DIR] [--device NAME] BUDGET_SECONDS OUT_DIR
#   bash scripts/gpu_suite.sh --list-configs      # the configs, in priority order
#   bash scripts/gpu_suite.sh --list-not-run      # the bench configs it leaves out (reasons in this file)
#   bash scripts/gpu_suite.sh --list-shards first|more   # "config shards" of each list (scripts/cluster/)
#
# BUDGET_SECONDS is a whole number of seconds, at least 10. --more runs the second list of
# configs (every config not in the first), --only A,B the named ones.
#
# 1. Unpacks the Vulkan loader (only where none is installed, and only as root), the models and
#    the font; the tables name the commit in the pack's COMMIT file.
# 2. Checks that the device is there (`causticlab devices`; --device, default `nvidia`, or the
#    default device with --quick).
# 3. Runs the configs (listed in this script, with their shards and H100 times) in priority order. Config i gets a share of the time left in
#    proportion to its estimate (so time one config leaves over goes to those after it), and runs
#    as shards, each a separate `causticlab bench --shard s/n` killed at the config's deadline: a
#    cut-off config keeps its finished shards. After every finished shard, OUT_DIR/gpu_suite.tar.gz
#    is rewritten with every part so far, the log and the manifest, so a run killed at any moment
#    returns everything finished until then.
# 4. Prints (and writes into the archive's SKIPPED) what it skipped or cut off for lack of time.
#
# Each cell's time budget is capped at SUITE_CELL_BUDGET seconds (default 0.3; the frame counts of
# the configs still apply): a GPU frame takes milliseconds, so a cell still measures tens of frames.
# SUITE_SHARDS=n runs every config as n shards (default: each config's own count below).
# SUITE_CUT_AFTER_PARTS=n ends the budget 2 s after the n-th finished part, as if it had run out
# then (scripts/gpu_dry_run.sh tests a cut-off run with it).
# Unpack the archive at home with scripts/gpu_unpack.sh.
set -uo pipefail
cd "$(dirname "$0")/.."

# config  shards  seconds on an H100 at SUITE_CELL_BUDGET=0.3. Measured ones are from 2026-11-26
# (c39c4cb; results/nvidia-nvidia-h100-80gb-hbm3-580-159-04/gpu_suite/*/timings.txt); those marked
# `est.` have not run on a GPU yet and are estimated from their cells (about 0.5-0.9 s each there)
# and their exact references (traced on the host's CPU threads). The shares of the budget follow
# these, so correct them after each run (docs/bench.md, "A GPU run").
#
# The first list is what the findings pages (results/*_findings.md) need a GPU column for, the
# figures that have never run on a GPU first; its estimates (about 480 s) fit one call of a lent
# machine's 15 minutes. --more runs the second list.
suite=(
    "photon_trace_paths 1 6"               # est.: 32 cells; only where the device has ray_query
    "photon_trace_moving 1 5"              # est.: 6 cells; only where the device has ray_query
    "wyman_davis2006_fig6 2 15"            # est.: 18 cells, per-pass quads and overdraw counts
    "wyman_davis2006_fig10 2 15"           # est.: 16 cells and two 4M-photon references
    "wyman_nichols2009_fig13 2 10"         # est.: 6 cells
    "wyman2008_fig7 3 40"                  # est.: 24 cells and their references
    "wyman_davis2006_fig8 2 25"            # est.: 12 cells of 11 frames, a reference each
    "wyman_nichols2009_fig8_batched 2 20"  # est.: 8 cells at 4096² and 8192², in batches
    "wyman_davis2006_table1 6 132"
    "wyman_nichols2009_fig10 5 45"
    "wyman2008_table3 5 17"
    "wyman2008_table4 5 15"
    "wyman2008_table5 5 29"
    "wyman_nichols2009_fig9 4 11"
    "wyman_nichols2009_fig11 5 5"
    "wyman_nichols2009_fig8 3 6"
    "wyman_nichols2009_fig8_16384 2 90"    # est.: 8 cells at 8192² and 16384², in batches
)
# The other configs, for a second call with --more (priority order likewise; about 620 s).
suite_more=(
    "hcm_paths 5 18"
    "splat_paths 5 17"
    "wyman_nichols2009_table1 2 15"
    "wyman_nichols2009_adaptive 5 22"
    "trendall_stewart2000_table1 3 7"
    "quality 4 37"                         # est.: 31 s for its 40 cells at c39c4cb, 48 now
    "photon_trace_rate 2 10"               # est.: 16 cells of a few frames
    "wyman2008_table1 3 5"
    "wyman2008_table2 3 8"
    "wyman2008_table3_sparse 5 18"
    "photon_view 3 18"
    "quality_wd2006 4 97"                  # est.: 45 s for its 72 cells at c39c4cb, 156 now
    "quality_faithful 4 60"                # est.: 112 cells
    "quality_adaptive 3 140"
    "front 7 180"                          # est.: 153 cells (126 at the last GPU run, 150 s; 27 added since), per-pass and throughput frames each
)
# Bench configs the suite does not run, each with its reason (the test
# `every_bench_config_is_in_the_gpu_suite_or_says_why_not` checks that every config in
# bench_configs/ is in exactly one of the three lists, and named in docs/bench.md's table).
not_in_suite=(
    "viewer_frame_time"  # the bench's half of scripts/viewer_frame_time.sh, which needs a window
    # Its curves run each cell to 8 s of caustic-stage time (thousands of GPU frames, each one's
    # receiver map read back and compared with the reference on the CPU): not sized for the
    # suite's minutes yet; F1's front in a GPU folder says it has no table of curves to draw.
    "photon_trace_progressive"
    # Added after the last GPU session: per-pass caustic-map times and errors like F1's, to be
    # sized (cells, seconds) on a GPU before it joins a list.
    "photon_trace_reconstructions"
)

if [ "${1:-}" = "--list-configs" ]; then
    for entry in "${suite[@]}" "${suite_more[@]}"; do echo "${entry%% *}"; done
    exit 0
fi
if [ "${1:-}" = "--list-shards" ]; then
    case "${2:-}" in
        first) for entry in "${suite[@]}"; do read -r c n _ <<<"$entry"; echo "$c $n"; done ;;
        more) for entry in "${suite_more[@]}"; do read -r c n _ <<<"$entry"; echo "$c $n"; done ;;
        *) echo "gpu_suite: --list-shards takes first or more" >&2; exit 2 ;;
    esac
    exit 0
fi
if [ "${1:-}" = "--list-not-run" ]; then
    for entry in "${not_in_suite[@]}"; do echo "${entry%% *}"; done
    exit 0
fi

quick=()
pack=.gpu
device=nvidia
device_given=0
while [ $# -gt 0 ]; do
    case "$1" in
        --quick) quick=(--quick); shift ;;
        --more) suite=("${suite_more[@]}"); shift ;;
        --only)
            only=()
            for c in ${2//,/ }; do
                found=""
                for entry in "${suite[@]}" "${suite_more[@]}"; do [ "${entry%% *}" = "$c" ] && found=$entry; done
                [ -n "$found" ] || { echo "gpu_suite: --only: no config '$c' in the suite (--list-configs)" >&2; exit 2; }
                only+=("$found")
            done
            suite=("${only[@]}")
            shift 2 ;;
        --pack|--device|--only) [ $# -ge 2 ] || { echo "gpu_suite: $1 needs a value (see --help)" >&2; exit 2; } ;;&
        --pack) pack=$2; shift 2 ;;
        --device) device=$2; device_given=1; shift 2 ;;
        -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
        -*) echo "gpu_suite: unknown option '$1' (see --help)" >&2; exit 2 ;;
        *) break ;;
    esac
done
if [ $# -ne 2 ] || ! [[ "$1" =~ ^[0-9]+$ ]] || [ "$1" -lt 10 ]; then
    echo "usage: bash scripts/gpu_suite.sh [--quick] [--more | --only A,B] [--pack DIR] [--device NAME] BUDGET_SECONDS OUT_DIR" >&2
    echo "       (BUDGET_SECONDS: a whole number, at least 10; see --help)" >&2
    exit 2
fi
budget=$1
out=$2
start=$(date +%s)
deadline=$((start + budget))
[ -f "$pack/causticlab.xz" ] || { echo "gpu_suite: no $pack/causticlab.xz: run scripts/gpu_pack.sh first" >&2; exit 1; }
mkdir -p "$out" || exit 1
out=$(cd "$out" && pwd)
pack=$(cd "$pack" && pwd)

work=$(mktemp -d "${TMPDIR:-/tmp}/gpu_suite.XXXXXX")
bin=$work/causticlab
xz -dc "$pack/causticlab.xz" >"$bin" && chmod +x "$bin" || { echo "gpu_suite: cannot unpack $pack/causticlab.xz" >&2; exit 1; }
stage=$work/stage   # what the archive holds
mkdir -p "$stage/parts"
log=$stage/suite.log
exec > >(tee -a "$log") 2>&1

archive() {
    cp "$pack/MANIFEST" "$stage/MANIFEST" 2>/dev/null || true
    tar -C "$stage" -czf "$out/gpu_suite.tar.gz.tmp" . && mv "$out/gpu_suite.tar.gz.tmp" "$out/gpu_suite.tar.gz"
}
now() { date +%s; }

echo "gpu_suite: budget ${budget}s, pack $pack, out $out ${quick[*]}"

# 1. The loader, the models, the font, the commit.
if ! ldconfig -p 2>/dev/null | grep -q 'libvulkan\.so\.1'; then
    if [ "$(id -u)" -ne 0 ]; then
        echo "gpu_suite: no Vulkan loader and not root: install libvulkan1 or unpack $pack/debs/*.deb" >&2
        exit 1
    fi
    for f in "$pack"/debs/*.deb; do dpkg -x "$f" /; done
    ldconfig
    echo "gpu_suite: unpacked the Vulkan loader from $pack/debs"
fi
nvidia_icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
if [ -z "${VK_DRIVER_FILES:-}" ] && [ -f "$nvidia_icd" ] && ! ls /usr/share/vulkan/icd.d/nvidia* /etc/vulkan/icd.d/nvidia* >/dev/null 2>&1; then
    export VK_DRIVER_FILES=$nvidia_icd
    echo "gpu_suite: VK_DRIVER_FILES=$nvidia_icd"
fi
mkdir -p "$work/models"
if [ -f "$pack/models.tar.xz" ]; then
    tar -C "$work/models" -xJf "$pack/models.tar.xz"
fi
export CAUSTICLAB_MODELS="$work/models${CAUSTICLAB_MODELS:+:$CAUSTICLAB_MODELS}"
[ -f "$pack/DejaVuSans.ttf" ] && export CAUSTICLAB_FONT=$pack/DejaVuSans.ttf
CAUSTICLAB_COMMIT=$(cat "$pack/COMMIT" 2>/dev/null || echo unknown)
export CAUSTICLAB_COMMIT
echo "gpu_suite: commit $CAUSTICLAB_COMMIT, models: $(ls "$work/models" | tr '\n' ' ')"

# 2. The device.
device_args=()
if [ "${#quick[@]}" -eq 0 ] || [ "$device_given" -eq 1 ]; then
    device_args=(--device "$device")
fi
if ! "$bin" "${device_args[@]}" devices >"$stage/devices.txt" 2>&1; then
    cat "$stage/devices.txt"
    echo "gpu_suite: no usable device ${device_args[*]} (see devices.txt above)" >&2
    archive
    exit 1
fi
cat "$stage/devices.txt"
if [ "${#device_args[@]}" -gt 0 ] && ! grep -q 'selected by --device' "$stage/devices.txt"; then
    echo "gpu_suite: no device matches --device $device" >&2
    archive
    exit 1
fi
archive

# 3. The configs, in priority order.
: >"$stage/SKIPPED"
cell_budget=${SUITE_CELL_BUDGET:-0.3}
total_weight=0
for entry in "${suite[@]}"; do read -r _ _ w <<<"$entry"; total_weight=$((total_weight + w)); done
left_weight=$total_weight
for entry in "${suite[@]}"; do
    read -r config shards weight <<<"$entry"
    [ "${SUITE_SHARDS:-0}" -gt 0 ] && shards=$SUITE_SHARDS
    left=$((deadline - $(now)))
    share=$((left * weight / left_weight))
    left_weight=$((left_weight - weight))
    config_deadline=$(($(now) + share))
    [ "$left_weight" -eq 0 ] && config_deadline=$deadline
    echo "gpu_suite: $config: ${share}s of ${left}s left, $shards shards"
    t0=$(now)
    for s in $(seq 1 "$shards"); do
        remaining=$((config_deadline - $(now)))
        if [ "$remaining" -lt 3 ]; then
            echo "$config shard $s/$shards: not started (no time left)" | tee -a "$stage/SKIPPED"
            continue
        fi
        results=$work/results
        timeout -k 5 "$remaining" "$bin" "${device_args[@]}" bench "bench_configs/$config.toml" "${quick[@]}" \
            --shard "$s/$shards" --max-time-budget "$cell_budget" --results "$results" >"$work/bench.out" 2>&1
        rc=$?
        tail -n 3 "$work/bench.out"
        cat "$work/bench.out" >>"$stage/bench.log"
        part=$(find "$results" -name "$config.shard-$s-of-$shards.json" | head -n 1)
        if [ "$rc" -eq 0 ] && [ -n "$part" ]; then
            mv "$part" "$stage/parts/"
            archive
            if [ -n "${SUITE_CUT_AFTER_PARTS:-}" ] && [ "$(ls "$stage/parts" | wc -l)" -ge "$SUITE_CUT_AFTER_PARTS" ]; then
                deadline=$(($(now) + 2))
                config_deadline=$deadline
            fi
        elif [ "$rc" -eq 2 ] && lacks=$(grep -o 'needs the device feature `[a-z_0-9]*`' "$work/bench.out"); then
            # A config for a feature this device lacks (photon_trace_paths: ray_query) is
            # refused before its first cell: recorded, not a failure.
            echo "$config: not run: the device lacks ${lacks#needs the device feature }" | tee -a "$stage/SKIPPED"
            break
        elif [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
            echo "$config shard $s/$shards: cut off after ${remaining}s" | tee -a "$stage/SKIPPED"
        else
            echo "$config shard $s/$shards: failed (exit $rc; bench.log)" | tee -a "$stage/SKIPPED"
        fi
    done
    echo "gpu_suite: $config took $(($(now) - t0))s" | tee -a "$stage/timings.txt"
done

echo "gpu_suite: done in $(($(now) - start))s of ${budget}s; $(ls "$stage/parts" | wc -l) parts"
if [ -s "$stage/SKIPPED" ]; then
    echo "gpu_suite: skipped or cut off for lack of time or by failure:"
    cat "$stage/SKIPPED"
fi
archive
rm -rf "$work"
echo "gpu_suite: wrote $out/gpu_suite.tar.gz"
