#!/usr/bin/env bash
# Runs every test of the workspace: unit tests, vkcore's GPU tests on lavapipe (or a real GPU),
# and the causticlab CLI tests that render scenes and check them against analytic answers.
# The default test profile is used: the workspace builds dependencies with opt-level 3 and its
# own crates with opt-level 1, so there is no need for --release here. --no-fail-fast runs
# every test binary and still exits non-zero if any test failed. A full run (no arguments) then
# rehearses the GPU run's scripts on lavapipe with the test build (scripts/gpu_dry_run.sh), and
# runs the tests and renders of scripts/mesa25_check.sh on Mesa 25's lavapipe, unpacked beside
# the system's Mesa 22.3 by scripts/mesa25.sh (docs/testing.md), runs the cluster scripts on a
# one-node Slurm of its own and validates their Kubernetes manifests (scripts/cluster/*_check.sh,
# docs/bench.md "On a cluster"), and mutation-tests the last
# commit's changes to the code that judges the numbers (scripts/mutants_diff.sh; nothing to do
# when the commit leaves that code alone).
set -euo pipefail
cd "$(dirname "$0")/.."

# Each step says how long it took (CI keeps its total under 45 minutes: docs/testing.md).
step() {
    local start=$SECONDS
    "$@"
    echo "test.sh: $* took $((SECONDS - start)) s"
}

bash scripts/setup.sh
unset VK_LOADER_DEBUG
step cargo test --workspace --no-fail-fast "$@"
if [ $# -eq 0 ]; then
    step bash scripts/gpu_dry_run.sh target/debug/causticlab
    step bash scripts/mesa25_check.sh target/debug/causticlab
    step bash scripts/cluster/slurm_check.sh target/debug/causticlab
    step bash scripts/cluster/k8s_check.sh
    step bash scripts/mutants_diff.sh
fi
