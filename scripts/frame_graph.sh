#!/usr/bin/env bash
# Draws the frame graph (`causticlab render --graph`) of TECHNIQUE on sphere_on_plane at 256²
# photons and a 512² caustic map into docs/images/frame_graph_<technique>.png: every pass in
# recording order, the resources it read and wrote (each write a new version), the frame's
# inputs in a note. Needs graphviz (`dot`); pngquant, where installed, shrinks the PNG.
#   bash scripts/frame_graph.sh [TECHNIQUE ...]     (default: hcm adaptive)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${BIN:-target/release/causticlab}
[ -x "$bin" ] || cargo build --release
command -v dot > /dev/null || { echo "frame_graph.sh: needs graphviz's dot (apt-get install graphviz)" >&2; exit 1; }
techniques=("$@")
[ ${#techniques[@]} -gt 0 ] || techniques=(hcm adaptive)
for t in "${techniques[@]}"; do
    out=out/frame_graph/$t
    "$bin" render --scene scenes/sphere_on_plane.toml --technique "$t" --photons 256 \
        --caustic-map-resolution 512 --out "$out" --graph > /dev/null
    png=docs/images/frame_graph_$t.png
    dot -Tpng -Gdpi=40 "$out/graph.dot" -o "$png"
    if command -v pngquant > /dev/null; then
        pngquant --force --quality=40-70 16 --output "$png" "$png" || true   # 99: kept as drawn
    fi
    echo "wrote $png ($(wc -c < "$png") bytes) from $out/graph.dot"
done
