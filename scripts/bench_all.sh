#!/usr/bin/env bash
# Regenerates every table in bench_configs/ on the default device (or --device ...) into
# results/<device-slug>/ (the CPU benchmarks are scripts/criterion.sh). Extra arguments go to every
# `causticlab bench` call, e.g.  bash scripts/bench_all.sh --device 1   or   --quick
# Run it on an otherwise idle machine: on lavapipe the GPU is the CPU.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo build --release -p causticlab
for config in bench_configs/*.toml; do
    ./target/release/causticlab bench "$config" "$@"
done
