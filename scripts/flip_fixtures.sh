#!/usr/bin/env bash
# The fixtures that hold our FLIP (crates/caustics/src/flip/) to NVIDIA's reference implementation:
# image pairs and flip-evaluator's error maps, means and exposures of them, written to
# crates/caustics/tests/fixtures/flip/ (read by crates/caustics/tests/flip_reference.rs;
# docs/flip.md). Real data: the glass sphere of scenes/sphere_on_plane.toml, its receiver map
# narrowed to the caustic (48x48 texels over [-1, 1]² m) traced by `causticlab reference` (the
# "exact" caustic) and rendered by `--technique shah`, and its eye view (48x48 pixels) rendered
# by shah and wd-points. The shifted, noisy and HDR pairs are made from the exact caustic by
# scripts/flip_fixtures.py (seeded); the ramp pair is synthetic (green against a green-to-blue
# ramp, for the colour map's entries).
#   bash scripts/flip_fixtures.sh
# BIN (default target/release/causticlab; needs `cargo build --release`), OUT (the fixture
# folder), VENV (default a throwaway one under a temporary folder, removed at the end).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${BIN:-target/release/causticlab}
out=${OUT:-crates/caustics/tests/fixtures/flip}
flip_version=1.7    # flip-evaluator on PyPI: FLIP.h of NVlabs/flip v1.6 plus the median's f32 epsilon floor
numpy_version=2.4.6
[ -x "$bin" ] || { echo "flip_fixtures.sh: $bin is missing: cargo build --release, or set BIN" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
venv=${VENV:-$tmp/venv}
python3 -m venv "$venv"
"$venv/bin/pip" install --quiet "flip-evaluator==$flip_version" "numpy==$numpy_version"
echo "flip-evaluator $("$venv/bin/python" -c 'import importlib.metadata as m; print(m.version("flip-evaluator"))'), numpy $("$venv/bin/python" -c 'import numpy; print(numpy.__version__)')"

# The shipped scene at 48x48: the receiver map over the caustic, the camera narrowed onto the sphere.
scene=$tmp/receiver.toml
sed -e 's/^resolution = 256$/resolution = 48/' \
    -e 's/^x_range = \[-2.0, 2.0\]$/x_range = [-1.0, 1.0]/' -e 's/^z_range = \[-2.0, 2.0\]$/z_range = [-1.0, 1.0]/' \
    -e 's/^resolution = \[512, 512\]$/resolution = [48, 48]/' scenes/sphere_on_plane.toml > "$scene"
sed -e 's/^fov_y = 40.0$/fov_y = 22.0/' -e 's/^target = \[0.0, 0.4, 0.0\]$/target = [0.0, 0.6, 0.0]/' "$scene" > "$tmp/eye.toml"
for edit in 'resolution = 48' 'x_range = \[-1.0, 1.0\]' 'resolution = \[48, 48\]'; do
  grep -q "^$edit" "$scene" || { echo "flip_fixtures.sh: scenes/sphere_on_plane.toml changed: '$edit' not applied" >&2; exit 1; }
done
grep -q '^fov_y = 22.0' "$tmp/eye.toml" || { echo "flip_fixtures.sh: the eye view's fov not applied" >&2; exit 1; }

set -x
"$bin" reference --scene "$scene" --photons 4000000 --fresnel false --seed 1 --out "$tmp/exact" > /dev/null
"$bin" render --scene "$scene" --technique shah --photons 512 --fresnel false --dump receiver --out "$tmp/shah" > /dev/null
"$bin" render --scene "$tmp/eye.toml" --technique shah --photons 512 --fresnel false --out "$tmp/eye_shah" > /dev/null
"$bin" render --scene "$tmp/eye.toml" --technique wd-points --photons 256 --fresnel false --out "$tmp/eye_wd" > /dev/null
set +x

mkdir -p "$out"
"$venv/bin/python" scripts/flip_fixtures.py "$tmp" "$out" "$flip_version" "$numpy_version"
echo "fixtures: $(du -cb "$out"/* | tail -1 | cut -f1) bytes in $out"
