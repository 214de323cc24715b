#!/usr/bin/env bash
# Shows that a refactor kept behaviour: renders every technique in every space and mode
# (`hcm`'s and `adaptive`'s paths, clusterings, splats, metrics and batches, deferred photons and
# deferred refraction, the compute splat, static-light reuse over several frames, throughput
# frames) on the sphere scenes, `two_lights`, the metal octahedron and the pool, each with every
# buffer it can dump, and compares each with the same render recorded before.
#
#   bash scripts/same_maps.sh record DIR   # render every case into DIR/<scene>/<case>/
#   bash scripts/same_maps.sh check DIR    # render again into DIR.now/ and compare with DIR/
#
# The cases: every row of the registry of variants (`causticlab variants`) on its scenes (a
# row needing a device feature this device lacks is skipped, saying so), the
# frame modes and sweeps listed below, and a few cases on other scenes. A case that DIR does
# not have (a row added since it was recorded) is rendered and listed as new, not compared.
#
# `check` runs `causticlab diff --tolerance 1e-5` on each case's folder: final.exr and every
# dump, channel by channel (largest |now - recorded| over the channel's largest |recorded|),
# and the pass names and photon counts of timings.json exactly (the counts the bench reports:
# photons emitted, valid photons, splats drawn, the traversal's list sizes). The lists a compute path appends to with
# an atomic counter (the dumps declared as lists of records, `--unordered-records`: splats,
# hierarchy_lists, adaptive_lists) are compared unordered, and the
# additive splats they feed differ by float rounding (about 1e-6), hence the tolerance; batched,
# which clusters fall into which batch follows that order too, so adaptive_lists is not compared.
# BIN picks the binary (default target/release/causticlab, built if missing); CASES=REGEX runs
# only the cases whose "scene/case" name matches.
set -euo pipefail
cd "$(dirname "$0")/.."

mode="${1:-}"
dir="${2:-}"
if [ -z "$mode" ] || [ -z "$dir" ] || { [ "$mode" != record ] && [ "$mode" != check ]; }; then
    echo "usage: bash scripts/same_maps.sh record|check DIR" >&2
    exit 2
fi
bin="${BIN:-target/release/causticlab}"
if [ ! -x "$bin" ]; then
    cargo build --release
fi

# The registry's rows (crates/caustics/src/techniques/variants.toml, `causticlab variants`):
# every variant, on its scenes. A row added there is rendered here at once.
# A row that needs a device feature beyond its technique's (the fifth field, `-` for none:
# photon-trace-ray-query needs ray queries) is skipped, saying so, where the device refuses it.
all=()
declare -A needs=()
rows=$("$bin" variants --lines)   # a binary without the registry fails here, not silently
while IFS='|' read -r name _ scenes flags row_needs; do
    needs[$name]=$row_needs
    for scene in ${scenes//,/ }; do
        all+=("$scene:$name:$flags")
    done
done <<< "$rows"
# Frame modes over several frames (static-light reuse, temporal filters, throughput) and the
# sweeps of hcm's and adaptive's settings, on the sphere scenes.
cases=(
    "wd-points-throughput-3:--technique wd-points --frames 3 --frame-mode throughput"
    "wd-eye-points-temporal-4:--technique wd-eye-points --temporal-filter on --frames 4"
    "wd-quads-light-static-3:--technique wd-quads --space light --frames 3"
    "wd-gather-eye-temporal-4:--technique wd-gather --space eye --temporal-filter on --frames 4"
    "wd-gather-light-static-3:--technique wd-gather --space light --frames 3"
)
for path in xfb compute; do
    for cluster in none last all; do
        cases+=("hcm-$path-$cluster-fixed:--technique hcm --path $path --cluster $cluster --splat fixed")
        for splat in varying-single varying-multires; do
            for radius in max-distance beam-area; do
                cases+=("hcm-$path-$cluster-$splat-$radius:--technique hcm --path $path --cluster $cluster --splat $splat --varying-radius $radius")
            done
        done
    done
    cases+=("hcm-$path-deferred-photons:--technique hcm --path $path --photon-refraction deferred")
    cases+=("hcm-$path-instances-64:--technique hcm --path $path --instance-vertices 64")
    cases+=("hcm-$path-throughput-3:--technique hcm --path $path --frames 3 --frame-mode throughput")
    for metric in max-traversal max-error; do
        cases+=("adaptive-$path-$metric:--technique adaptive --path $path --metric $metric")
        cases+=("adaptive-$path-$metric-multires:--technique adaptive --path $path --metric $metric --splat varying-multires")
        cases+=("adaptive-$path-$metric-batches-4:--technique adaptive --path $path --metric $metric --photon-batches 4")
        cases+=("adaptive-$path-$metric-memory-limit:--technique adaptive --path $path --metric $metric --photon-memory-limit 1")
    done
    cases+=("adaptive-$path-gbuffer-1:--technique adaptive --path $path --gbuffer-scale 1")
    cases+=("adaptive-$path-throughput-3:--technique adaptive --path $path --frames 3 --frame-mode throughput")
done
for scene in sphere_on_plane sphere_oblique; do
    for c in "${cases[@]}"; do
        all+=("$scene:$c")
    done
done
# Scenes beyond the sphere scenes, each with the cases that matter there.
all+=(
    "two_lights:shah:--technique shah"
    "two_lights:wd-points:--technique wd-points"
    "two_lights:shah-thin-lens:--technique shah --splat thin-lens"
    "two_lights:wd-quads-light:--technique wd-quads --space light"
    "two_lights:wd-gather-eye:--technique wd-gather"
    "two_lights:hcm-xfb:--technique hcm --path xfb --cluster last"
    "two_lights:hcm-compute:--technique hcm --path compute --splat varying-multires"
    "two_lights:adaptive-xfb:--technique adaptive --path xfb"
    "two_lights:adaptive-compute:--technique adaptive --path compute --metric max-error"
    "two_lights:wd-points-deferred-photons:--technique wd-points --photon-refraction deferred --refraction deferred"
    "octahedron:wd-points:--technique wd-points"
    "octahedron:wd-points-plane:--technique wd-points --reflection plane"
    "octahedron:hcm:--technique hcm"
    "stacked_spheres:wd-points-deferred-photons:--technique wd-points --photon-refraction deferred --refraction deferred"
    "stacked_spheres:adaptive:--technique adaptive"
)

out="$dir"
if [ "$mode" = check ]; then
    out="$dir.now"
    rm -rf "$out"
fi
mkdir -p "$out"
failed=()
new=()
skipped=()
ran=0
for c in "${all[@]}"; do
    scene="${c%%:*}"
    rest="${c#*:}"
    name="${rest%%:*}"
    if [ -n "${CASES:-}" ] && ! [[ "$scene/$name" =~ $CASES ]]; then
        continue
    fi
    # shellcheck disable=SC2206 # the flags are words
    flags=(${rest#*:})
    sizes=(--photons 256 --caustic-map-resolution 512)
    if [[ "$scene" == pool* ]]; then
        sizes=(--photons 64)
    fi
    # A row that sets its own photon count or caustic map keeps it (a flag given twice is an
    # error).
    if [[ " ${flags[*]} " == *" --photons "* ]]; then
        sizes=("${sizes[@]:2}")
    fi
    if [[ " ${flags[*]} " == *" --caustic-map-resolution "* ]]; then
        sizes=("${sizes[@]:0:2}")
    fi
    target="$out/$scene/$name"
    rm -rf "$target"
    status=0
    "$bin" render --scene "scenes/$scene.toml" --out "$target" "${sizes[@]}" --dump all "${flags[@]}" \
        >/dev/null 2>"$out/render.err" || status=$?
    if [ "$status" -ne 0 ] && [ "${needs[$name]:--}" != - ] && grep -q 'needs the device feature' "$out/render.err"; then
        printf '%-16s %-44s skipped: %s\n' "$scene" "$name" "$(sed 's/^error: //' "$out/render.err" | head -1)"
        skipped+=("$scene/$name")
        continue
    fi
    if [ "$status" -ne 0 ]; then
        cat "$out/render.err" >&2
        echo "same_maps: $scene/$name failed (exit $status)" >&2
        exit 1
    fi
    cat "$out/render.err" >&2   # a render's warnings, as before its stderr was kept
    ran=$((ran + 1))
    if [ "$mode" = check ] && [ ! -d "$dir/$scene/$name" ]; then
        # A case added since the recording (a new registry row) has nothing to compare with.
        printf '%-16s %-44s new (not in %s)\n' "$scene" "$name" "$dir"
        new+=("$scene/$name")
        continue
    fi
    if [ "$mode" = check ]; then
        unordered=()
        if [[ " ${flags[*]} " == *" compute "* ]]; then
            unordered=(--unordered-records)
            # Batched, the compute traversal's split of the pending clusters into batches
            # follows its append order too: the lists of each batch change from run to run
            # (the maps and the counts do not).
            if [[ " ${flags[*]} " == *" --photon-batches "* || " ${flags[*]} " == *" --photon-memory-limit "* ]]; then
                unordered+=(--ignore adaptive_lists)
            fi
        fi
        if report="$("$bin" diff --tolerance 1e-5 "${unordered[@]}" "$target" "$dir/$scene/$name" 2>&1)"; then
            printf '%-16s %-44s same\n' "$scene" "$name"
        else
            printf '%-16s %-44s DIFFERS\n' "$scene" "$name"
            grep -v -e ': same' <<<"$report" | sed 's/^/    /'
            failed+=("$scene/$name")
        fi
    else
        printf '%-16s %-44s recorded (%s files)\n' "$scene" "$name" "$(ls "$target" | wc -l)"
    fi
done
# A case the recording has and this run did not render (a renamed or removed case) would
# otherwise pass unnoticed.
gone=()
if [ "$mode" = check ] && [ -z "${CASES:-}" ]; then
    for d in "$dir"/*/*/; do
        d=${d%/}
        case=${d#"$dir"/}
        [ -d "$out/$case" ] || [[ " ${skipped[*]} " == *" $case "* ]] || gone+=("$case")
    done
fi
if [ "${#gone[@]}" -ne 0 ]; then
    echo "same_maps: ${#gone[@]} recorded case(s) not rendered now (renamed or removed): ${gone[*]}" >&2
    exit 1
fi
if [ "${#failed[@]}" -ne 0 ]; then
    echo "same_maps: ${#failed[@]} of $ran cases differ: ${failed[*]}" >&2
    exit 1
fi
rm -f "$out/render.err"
echo "same_maps: $mode done ($ran cases${new[0]:+; ${#new[@]} new, not compared: ${new[*]}}${skipped[0]:+; ${#skipped[@]} skipped (a feature this device lacks): ${skipped[*]}})"
