#!/usr/bin/env bash
# Fuzzes one reader of user files with AFL++ through cargo-afl (fuzz/README.md), on the stable
# toolchain: scene, scene_values, obj, bench_config or exr, for SECONDS (default 600), on one core.
#
#   bash scripts/fuzz.sh TARGET [SECONDS]
#
# Starts from the committed corpus (fuzz/corpus/TARGET) where there is one, else from the seeds
# (the shipped scenes or bench configs; fuzz/seeds/TARGET for models, EXR files and the
# structured scene's choices). Afterwards
# it minimizes the queue into fuzz/corpus/TARGET (afl-cmin), copies AFL's fuzzer_stats to
# fuzz/stats/TARGET.txt, and lists every crash and hang in fuzz/out/TARGET: commit each, made
# small (afl-tmin), under crates/causticlab/tests/fuzz_regressions/TARGET/ with its fix; the
# test command replays them all. Run it alone: it keeps a core busy.
set -euo pipefail
cd "$(dirname "$0")/.."
target=${1:-}
seconds=${2:-600}
case "$target" in
    scene | scene_values | obj | bench_config | exr) ;;
    *)
        echo "usage: bash scripts/fuzz.sh scene|scene_values|obj|bench_config|exr [SECONDS]" >&2
        exit 2
        ;;
esac
[[ "$seconds" =~ ^[0-9]+$ ]] || { echo "fuzz.sh: SECONDS must be a whole number, got '$seconds'" >&2; exit 2; }

bash scripts/setup.sh >/dev/null
afl_version=0.18.2
if ! cargo afl --version 2>/dev/null | grep -q "$afl_version"; then
    echo "fuzz.sh: installing cargo-afl $afl_version (builds AFL++ once)"
    cargo install --locked cargo-afl --version "$afl_version"
fi
# cargo-afl builds AFL++ when it is installed; `config --build` refuses to build it twice, and
# `cargo afl build` below says so if it is missing.
cargo afl config --build >/dev/null 2>&1 || true

(cd fuzz && cargo afl build --release --bin "$target")
bin=fuzz/target/release/$target

seeds=$(mktemp -d)
trap 'rm -rf "$seeds"' EXIT
if [ -n "$(ls -A "fuzz/corpus/$target" 2>/dev/null)" ]; then
    cp "fuzz/corpus/$target"/* "$seeds"/
else
    case "$target" in
        scene) cp scenes/*.toml "$seeds"/ ;;
        bench_config) cp bench_configs/*.toml "$seeds"/ ;;
        obj | exr | scene_values) cp "fuzz/seeds/$target"/* "$seeds"/ ;;
    esac
fi

out=fuzz/out/$target
rm -rf "$out"
mkdir -p "$out" fuzz/stats
# No core dumps to wait for, no CPU governor to set on a VM; -t: a hang is over 10 s;
# -m: an input may not make the reader use more than 4 GiB.
export AFL_I_DONT_CARE_ABOUT_MISSING_CRASHES=1 AFL_SKIP_CPUFREQ=1 AFL_NO_UI=1 AFL_NO_AFFINITY=1
cargo afl fuzz -i "$seeds" -o "$out" -V "$seconds" -t 10000 -m 4096 "$bin" | tail -n 20

stats=$out/default/fuzzer_stats
cp "$stats" "fuzz/stats/$target.txt"
rm -rf "fuzz/corpus/$target"
mkdir -p "fuzz/corpus/$target"
AFL_I_DONT_CARE_ABOUT_MISSING_CRASHES=1 cargo afl cmin -i "$out/default/queue" -o "fuzz/corpus/$target" -t 10000 -m 4096 -- "$bin" >/dev/null
# Name each input by its content (AFL's names hold ':' and ','): stable, and the same input twice
# is one file.
for f in "fuzz/corpus/$target"/*; do
    mv -n "$f" "fuzz/corpus/$target/$(sha1sum "$f" | cut -c1-16)" 2>/dev/null || true
done
crashes=$(find "$out/default/crashes" -type f ! -name README.txt | wc -l)
hangs=$(find "$out/default/hangs" -type f | wc -l)
grep -E "^(execs_done|run_time|bitmap_cvg|corpus_count|saved_crashes|saved_hangs) " "$stats"
echo "fuzz.sh: $target: corpus of $(ls "fuzz/corpus/$target" | wc -l) inputs in fuzz/corpus/$target, stats in fuzz/stats/$target.txt"
if [ "$crashes" -gt 0 ] || [ "$hangs" -gt 0 ]; then
    echo "fuzz.sh: $crashes crashes and $hangs hangs in $out/default/{crashes,hangs}: replay one with" >&2
    echo "  $bin < FILE" >&2
    exit 1
fi
