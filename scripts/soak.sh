#!/usr/bin/env bash
# A soak run on the default device: 10,000 animated throughput frames of a small scene
# (sphere_on_plane, shah, 64² photons, a 64² eye, light, camera and sphere orbiting), with the
# resident memory, the device memory and the Vulkan objects made sampled every 500 frames.
# Writes results/soak/<device-slug>.csv and .md; a real-time loop holds all three flat after
# the first 1,000 frames (within 1%, no object made). Run it on an otherwise idle machine.
#
#   bash scripts/soak.sh [FRAMES] [EVERY]
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-10000}
every=${2:-500}
bash scripts/setup.sh >/dev/null
cargo build --release -p causticlab
bin=target/release/causticlab
slug=$("$bin" devices | sed -n 's/^\[0\] //p' | head -n1 | tr '[:upper:]' '[:lower:]' | sed -E 's/\[.*\]//; s/[^a-z0-9]+/-/g; s/^-+//; s/-+$//')
mkdir -p results/soak
csv=results/soak/$slug.csv
out=$("$bin" soak --scene scenes/sphere_on_plane.toml --technique shah --photons 64 --caustic-map-resolution 128 \
    --size 64 --frames "$frames" --every "$every" --after 1000 --period 60 --csv "$csv")
echo "$out"
source scripts/commit.sh
commit=$(code_commit)
{
    echo "# Soak: $frames throughput frames on $("$bin" devices | sed -n 's/^\[0\] //p' | head -n1 | sed -E 's/ *\[[a-z ]*\]$//')"
    echo
    echo "- command: \`bash scripts/soak.sh $frames $every\` (\`causticlab soak\`: sphere_on_plane, shah, 64² photons, 64² eye, light, camera and object orbits of 60 frames)"
    echo "- commit: $commit; date: $(date -u +%Y-%m-%dT%H:%M:%SZ); samples: [$slug.csv]($slug.csv)"
    echo
    echo '```'
    echo "$out" | grep -v '^wrote '
    echo '```'
} >"results/soak/$slug.md"
echo "soak.sh: wrote $csv and results/soak/$slug.md"
