#!/usr/bin/env bash
# The main job: build causticlab, render every scene in scenes/ with Shah et al.'s caustics
# mapping (pool scenes with Trendall & Stewart 2000's pool-convolution; validation on, every
# intermediate buffer dumped) into out/<scene>/, then regenerate a
# quick quality table (scripts/quality_table.sh on sphere_on_plane: shah, shah-vertex, wd-points,
# wd-points with thin-lens splats and three hcm variants against the exact CPU photon reference;
# not wd-eye-points, wd-quads, wd-gather, adaptive, photon-trace or pool-convolution) into
# out/quality/sphere_on_plane.md, and a quick run of Wyman 2008 Table 1 into
# out/results/<device>/quick/.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
cargo build --release
bin=target/release/causticlab

"$bin" devices

failed=()
skipped=()
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
for scene in scenes/*.toml; do
    stem="$(basename "$scene" .toml)"
    echo
    echo "=== $scene -> out/$stem/"
    status=0
    # Pool scenes (Trendall & Stewart 2000) are rendered by pool-convolution, set in the scene.
    flags=(--technique shah --photons 1024)
    grep -q '^\[pool\]' "$scene" && flags=()
    "$bin" render --scene "$scene" --out "out/$stem" --validate --dump all "${flags[@]}" 2>"$log" || status=$?
    # A scene whose model is not on the model search path (../shared/models, $CAUSTICLAB_MODELS)
    # is skipped with one line naming the model and where the search looked; any other failure
    # fails the demo.
    if [ "$status" -ne 0 ] && missing="$(grep -m1 'not found; searched:' "$log")"; then
        echo "demo: skipped $stem: ${missing#error: }"
        skipped+=("$stem")
        continue
    fi
    cat "$log" >&2
    if [ "$status" -ne 0 ]; then
        failed+=("$stem")
    fi
done

# A quick quality table of shah, shah-vertex, wd-points and hcm (not every technique) on
# sphere_on_plane: 2M reference photons instead of the committed tables' 16M; written to
# out/quality/sphere_on_plane.md.
echo '=== quality table: the variants "causticlab variants --quality" lists, against the CPU reference, on sphere_on_plane -> out/quality/'
if ! REF_PHOTONS=2000000 WORK=out/quality RESULTS=out/quality bash scripts/quality_table.sh sphere_on_plane; then
    failed+=("quality table")
fi

# A quick table: Wyman 2008 Table 1 at small sizes (the committed tables: bash scripts/bench_all.sh).
echo "=== quick bench table: Wyman 2008 Table 1 at small sizes -> out/results/<device>/quick/"
if ! "$bin" bench bench_configs/wyman2008_table1.toml --quick --results out/results; then
    failed+=("quick bench table")
fi

echo
if [ "${#failed[@]}" -ne 0 ]; then
    echo "demo: failed: ${failed[*]}" >&2
    exit 1
fi
if [ "${#skipped[@]}" -ne 0 ]; then
    echo "demo: skipped ${#skipped[@]} scene(s) whose models are missing: ${skipped[*]}"
fi
echo "demo: every scene that could run rendered into out/<scene>/; quality table (shah, shah-vertex, wd-points, wd-points thin-lens, hcm against the CPU reference) in out/quality/sphere_on_plane.md; quick Wyman 2008 Table 1 in out/results/<device>/quick/"
