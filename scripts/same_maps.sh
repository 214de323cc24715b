#!/usr/bin/env bash
# Shows that a refactor kept behaviour: renders the receiver map of every technique and every
# `hcm` mode on both sphere scenes, and compares each with the same render recorded before.
#
#   bash scripts/same_maps.sh record DIR   # render every case into DIR/<scene>/<case>/receiver.exr
#   bash scripts/same_maps.sh check DIR    # render again into DIR.now/ and compare with DIR/
#
# `check` fails when any case's relative RMSE against its recording exceeds 1e-5, or its peak
# or caustic flux differ by more than 1e-5 relative (`causticlab compare`, the recording as the
# reference). BIN picks the binary (default target/release/causticlab, built if missing).
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

# case name -> flags. Small sizes: the point is equality, not quality.
cases=(
    "shah:--technique shah"
    "shah-vertex:--technique shah-vertex"
    "wd-points:--technique wd-points"
    "wd-points-compute-splat:--technique wd-points --splat-path compute"
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
done
cases+=("hcm-compute-last-compute-splat:--technique hcm --path compute --cluster last --splat-path compute")

out="$dir"
if [ "$mode" = check ]; then
    out="$dir.now"
    rm -rf "$out"
fi
failed=()
for scene in sphere_on_plane sphere_oblique; do
    for c in "${cases[@]}"; do
        name="${c%%:*}"
        # shellcheck disable=SC2086 # the flags are words
        flags=(${c#*:})
        target="$out/$scene/$name"
        rm -rf "$target"
        "$bin" render --scene "scenes/$scene.toml" --out "$target" --photons 256 \
            --caustic-map-resolution 512 --dump receiver "${flags[@]}" >/dev/null
        if [ "$mode" = check ]; then
            json="$("$bin" compare --json "$target/receiver.exr" "$dir/$scene/$name/receiver.exr")"
            verdict="$(python3 - "$json" <<'EOF'
import json, sys
c = json.loads(sys.argv[1])
bad = []
if c["rel_rmse"] > 1e-5:
    bad.append(f"rel_rmse {c['rel_rmse']:.3g}")
for k in ("peak_ratio", "caustic_flux_ratio"):
    if abs(c[k] - 1.0) > 1e-5:
        bad.append(f"{k} {c[k]:.8f}")
print("; ".join(bad) if bad else "same")
EOF
)"
            printf '%-16s %-48s %s\n' "$scene" "$name" "$verdict"
            if [ "$verdict" != same ]; then
                failed+=("$scene/$name")
            fi
        else
            printf '%-16s %-48s recorded\n' "$scene" "$name"
        fi
    done
done
if [ "${#failed[@]}" -ne 0 ]; then
    echo "same_maps: ${#failed[@]} cases differ: ${failed[*]}" >&2
    exit 1
fi
echo "same_maps: $mode done (${#cases[@]} cases x 2 scenes)"
