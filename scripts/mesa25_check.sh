#!/usr/bin/env bash
# The Mesa 25 step of the tests (scripts/test.sh runs it after the main suite): with Mesa 25's
# lavapipe beside the system's Mesa 22.3 (scripts/mesa25.sh), selected by its driver
# (`--device "Mesa 25"`), under validation (any message is exit code 3):
#   - `causticlab devices` lists both lavapipes and --device tells them apart;
#   - vkcore's GPU tests (statistics after pushed constants, layered rendering and multiview,
#     compaction, passes) on Mesa 25;
#   - photon-trace's ray-query path (acceleration structures, rayQueryEXT) against its compute
#     path on five scenes (crates/caustics/tests/photon_trace_ray_query.rs), which must not skip;
#   - the conformance suite's rows beyond the papers (photon-trace-ray-query among them), the
#     frame-graph stages and the pass-name table of every registry row, where no row may be
#     skipped for a missing feature (CAUSTICLAB_REQUIRE_FEATURES=1);
#   - every shipped scene rendered with shah, hcm, adaptive and photon-trace (the pool scenes
#     with their pool-convolution), 64² photons, statistics queries on (render always asks);
#   - a --quick run of Wyman 2008 Table 1 (its statistics frame included), and one of
#     photon_trace_paths (the tracer's compute traversal against ray queries) and
#     photon_trace_moving (a moving object's acceleration structures).
# Scenes whose models are missing are skipped with one line, as in scripts/demo.sh. Where Mesa
# 25 cannot be had (scripts/mesa25.sh fails: no network, not Debian 12), the check says so and
# is skipped, except in CI ($CI set), where that fails.
#
#   bash scripts/mesa25_check.sh [BIN]     (default target/debug/causticlab)
set -euo pipefail
cd "$(dirname "$0")/.."

bin=${1:-target/debug/causticlab}
[ -x "$bin" ] || { echo "mesa25_check: $bin is not built (cargo build)" >&2; exit 1; }
if ! env=$(bash scripts/mesa25.sh --env); then
    if [ -n "${CI:-}" ]; then
        echo "mesa25_check: Mesa 25's lavapipe cannot be had (scripts/mesa25.sh failed above)" >&2
        exit 1
    fi
    echo "mesa25_check: skipped: Mesa 25's lavapipe cannot be had here (scripts/mesa25.sh failed above)"
    exit 0
fi
eval "$env"
device=$(bash scripts/mesa25.sh --driver)
start=$SECONDS
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "mesa25_check: devices"
"$bin" devices | grep -E '^\[|driver  ' | tee "$out/devices"
grep -A1 '\[default\]' "$out/devices" | grep -q 'Mesa 22' ||
    { echo "mesa25_check: the default device is not the system's Mesa 22.3 lavapipe" >&2; exit 1; }
"$bin" --device "$device" devices >"$out/selected"
grep -A3 'selected by --device' "$out/selected" | grep -q "driver .*$device" ||
    { echo "mesa25_check: --device \"$device\" did not select Mesa 25's lavapipe" >&2; exit 1; }
if "$bin" --device llvmpipe devices >/dev/null 2>&1; then
    echo "mesa25_check: --device llvmpipe should be refused as matching two devices" >&2
    exit 1
fi

# Runs `cargo test ARGS` on Mesa 25. A test process that dies by a signal inside the driver
# (seen 2 times in about 110 test processes on Mesa 25.0.7's lavapipe here: heap corruption
# reported by malloc, and a SIGSEGV, each while recording a small upload or readback, never
# on Mesa 22.3, and valgrind's memcheck finds no invalid access of ours in a whole run) is run
# once more, after printing its crash report; a second death, or any failing test, fails.
# ARGS select test targets of the whole workspace (`--workspace --test NAME`), never `-p PKG`:
# a package alone resolves its dependencies' features differently (cargo's feature
# unification), so `-p` would build each package's dependency tree a second time (about three
# minutes a package on two cores) instead of running the binaries scripts/test.sh just built.
mesa25_test() {
    local log=$out/cargo-test.log
    for attempt in 1 2; do
        if CAUSTICLAB_TEST_DEVICE="$device" cargo test -q --workspace "$@" >"$log" 2>&1; then
            cat "$log"
            return 0
        fi
        cat "$log"
        if [ "$attempt" -eq 1 ] && grep -q 'process didn.t exit successfully: .*(signal: ' "$log"; then
            echo "mesa25_check: cargo test $* died by a signal on $device (above); running it once more"
            continue
        fi
        return 1
    done
}

echo "mesa25_check: vkcore's GPU tests on $device"
mesa25_test --test statistics --test rendering --test compaction --test passes --test ring

echo "mesa25_check: photon-trace's ray queries against its compute traversal on $device"
CAUSTICLAB_REQUIRE_RAY_QUERY=1 mesa25_test --test photon_trace_ray_query

echo "mesa25_check: the registry rows needing features Mesa 22.3 lacks (photon-trace-ray-query) on $device"
CAUSTICLAB_REQUIRE_FEATURES=1 mesa25_test --test conformance conformance_beyond_the_papers
CAUSTICLAB_REQUIRE_FEATURES=1 mesa25_test --test frame_graph_stages --test pass_table

# The renders run in $lanes lanes, every lanes-th scene each ($lanes processes at a time: a
# render's fixed costs, instance, validation layer and shader compiles, keep one process near a
# single core); each lane writes what it found to its own files, read after all have finished.
lanes=2
render_lane() {   # lane: renders scenes lane, lane + lanes, ... ; writes $out/lane$lane.{ok,skipped,failed}
    local lane=$1 i=0 scene stem t status missing log=$out/lane$1.log
    : >"$out/lane$lane.ok"; : >"$out/lane$lane.skipped"; : >"$out/lane$lane.failed"
    for scene in scenes/*.toml; do
        i=$((i + 1))
        [ $((i % lanes)) -eq "$lane" ] || continue
        stem=$(basename "$scene" .toml)
        local techniques=(shah hcm adaptive photon-trace)
        grep -q '^\[pool\]' "$scene" && techniques=(pool-convolution)
        for t in "${techniques[@]}"; do
            status=0
            "$bin" --device "$device" --validate render --scene "$scene" --technique "$t" --photons 64 \
                --out "$out/$stem-$t" >"$log" 2>&1 || status=$?
            if [ "$status" -ne 0 ] && missing=$(grep -m1 'not found; searched:' "$log"); then
                echo "mesa25_check: skipped $stem: ${missing#error: }"
                echo "$stem" >>"$out/lane$lane.skipped"
                break
            fi
            if [ "$status" -ne 0 ]; then
                cat "$log" >&2
                echo "mesa25_check: FAILED $stem with $t (exit $status)" >&2
                echo "$stem/$t" >>"$out/lane$lane.failed"
            elif ! grep -q "$device" "$log"; then
                echo "mesa25_check: $stem/$t did not run on $device:" >&2
                head -1 "$log" >&2
                echo "$stem/$t" >>"$out/lane$lane.failed"
            else
                echo "$stem/$t" >>"$out/lane$lane.ok"
            fi
            rm -rf "${out:?}/$stem-$t"
        done
    done
}
pids=()
for ((lane = 0; lane < lanes; lane++)); do
    render_lane "$lane" &
    pids+=($!)
done
for lane in "${!pids[@]}"; do
    wait "${pids[$lane]}" || { echo "mesa25_check: render lane $lane stopped early" >&2; exit 1; }
done
mapfile -t failed < <(cat "$out"/lane*.failed)
mapfile -t skipped < <(cat "$out"/lane*.skipped)
renders=$(cat "$out"/lane*.ok | wc -l)
[ "$renders" -gt 0 ] || { echo "mesa25_check: no render ran" >&2; exit 1; }
echo "mesa25_check: $renders renders on $device, validation clean"

echo "mesa25_check: bench --quick wyman2008_table1 on $device"
"$bin" --device "$device" --validate bench bench_configs/wyman2008_table1.toml --quick --results "$out/results" \
    >"$out/bench.log" 2>&1 || { cat "$out/bench.log" >&2; failed+=("bench wyman2008_table1"); }
grep -rq "$device" "$out/results" || { echo "mesa25_check: the quick table does not name Mesa 25" >&2; failed+=("bench device"); }
echo "mesa25_check: bench --quick photon_trace_paths (compute against ray queries) on $device"
"$bin" --device "$device" --validate bench bench_configs/photon_trace_paths.toml --quick --results "$out/results" \
    >"$out/bench.log" 2>&1 || { cat "$out/bench.log" >&2; failed+=("bench photon_trace_paths"); }
echo "mesa25_check: bench --quick photon_trace_moving (a moving object's acceleration structures) on $device"
"$bin" --device "$device" --validate bench bench_configs/photon_trace_moving.toml --quick --results "$out/results" \
    >"$out/bench.log" 2>&1 || { cat "$out/bench.log" >&2; failed+=("bench photon_trace_moving"); }

if [ "${#skipped[@]}" -ne 0 ]; then
    echo "mesa25_check: skipped ${#skipped[@]} scene(s) whose models are missing: ${skipped[*]}"
fi
if [ "${#failed[@]}" -ne 0 ]; then
    echo "mesa25_check: failed: ${failed[*]}" >&2
    exit 1
fi
echo "mesa25_check: ok in $((SECONDS - start)) s"
