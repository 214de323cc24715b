#!/usr/bin/env bash
# Back on a development machine: turns the archive scripts/gpu_suite.sh returned into tables.
# Merges each config's parts (`causticlab bench merge --partial`: cells the suite had no time for
# read `not run`), draws the tables and plots into <results>/<device-slug>/, rebuilds the index,
# and keeps the suite's manifest, log, device listing, timings and skipped list (not bench.log) in
# <results>/<device-slug>/gpu_suite/<archive name>/.
# The tables name the commit the binary was built from (the pack's COMMIT), not this checkout's.
#
#   bash scripts/gpu_unpack.sh ARCHIVE [--results DIR]
#
# Needs no device. Uses target/release/causticlab (built if missing), or $CAUSTICLAB_BIN.
set -euo pipefail
cd "$(dirname "$0")/.."

archive=""
results=results
while [ $# -gt 0 ]; do
    case "$1" in
        --results) [ $# -ge 2 ] || { echo "gpu_unpack: --results needs a value" >&2; exit 2; }; results=$2; shift 2 ;;
        -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
        -*) echo "gpu_unpack: unknown option '$1' (see --help)" >&2; exit 2 ;;
        *) [ -z "$archive" ] || { echo "gpu_unpack: one archive at a time" >&2; exit 2; }; archive=$1; shift ;;
    esac
done
[ -n "$archive" ] || { echo "usage: bash scripts/gpu_unpack.sh ARCHIVE [--results DIR]" >&2; exit 2; }
[ -f "$archive" ] || { echo "gpu_unpack: $archive: no such file" >&2; exit 1; }

bin=${CAUSTICLAB_BIN:-target/release/causticlab}
if [ ! -x "$bin" ]; then
    cargo build --release -p causticlab
    bin=target/release/causticlab
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tar -xzf "$archive" -C "$work" 2>/dev/null || { echo "gpu_unpack: $archive: not a gpu_suite archive (tar could not read it)" >&2; exit 1; }
[ -d "$work/parts" ] || { echo "gpu_unpack: $archive has no parts/ folder: not a gpu_suite archive" >&2; exit 1; }

mapfile -t configs < <(find "$work/parts" -name '*.shard-*-of-*.json' -printf '%f\n' | sed 's/\.shard-.*//' | sort -u)
if [ "${#configs[@]}" -eq 0 ]; then
    echo "gpu_unpack: $archive holds no finished part (see its suite.log and SKIPPED)" >&2
    [ -f "$work/SKIPPED" ] && cat "$work/SKIPPED" >&2
    exit 1
fi

device_dir=""
tables=0
for c in "${configs[@]}"; do
    out=$("$bin" bench merge --partial --results "$results" "$work"/parts/"$c".shard-*-of-*.json)
    md=$(grep -o "^wrote .*/$c\.md$" <<<"$out" | sed 's/^wrote //')
    [ -n "$md" ] || { echo "$out"; echo "gpu_unpack: $c: no table written" >&2; exit 1; }
    device_dir=$(dirname "$md")
    if grep -q '^\*\*Partial table' "$md"; then
        echo "gpu_unpack: $md ($(grep -o '[0-9]* of [0-9]* cells were not run' "$md"))"
    else
        echo "gpu_unpack: $md"
    fi
    tables=$((tables + 1))
done

keep=$device_dir/gpu_suite/$(basename "$archive" .tar.gz)
mkdir -p "$keep"
for f in MANIFEST suite.log SKIPPED timings.txt devices.txt; do
    if [ -f "$work/$f" ]; then cp "$work/$f" "$keep/$f"; fi
done
commit=$(sed -n 's/^commit: //p' "$work/MANIFEST" 2>/dev/null || true)
echo "gpu_unpack: $tables tables in $device_dir (binary built from ${commit:-an unknown commit}); the suite's log in $keep/"
