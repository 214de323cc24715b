# The judging code under mutation testing (sourced by scripts/mutants.sh and
# scripts/mutants_diff.sh): each file and the cargo test arguments of the tests that judge it.
# A file added here is judged from its next change on (CI's mutants_diff.sh).
# shellcheck disable=SC2034
# file : the tests that judge it (cargo test arguments for its package)
declare -A TESTS=(
    [crates/bench/src/plausibility.rs]="-p bench --lib --test plausibility"
    [crates/bench/src/stats.rs]="-p bench --lib --test plausibility --test tables"
    [crates/bench/src/claims/page.rs]="-p bench --lib --test claims"
    [crates/bench/src/claims/eval.rs]="-p bench --lib --test claims"
    [crates/bench/src/claims/expr.rs]="-p bench --lib --test claims"
    [crates/bench/src/claims/data.rs]="-p bench --lib --test claims"
    [crates/bench/src/steal.rs]="-p bench --lib"
    [crates/bench/src/run.rs]="-p bench --lib --test plausibility --test tables"
    [crates/bench/src/results.rs]="-p bench --lib --test plausibility --test tables"
    [crates/bench/src/measure.rs]="-p bench --lib"
    [crates/caustics/src/reference/optics.rs]="-p caustics --lib"
    [crates/caustics/src/compare.rs]="-p caustics --lib"
    [crates/caustics/src/scene/load.rs]="-p caustics --lib --test scene_files"
    [crates/caustics/src/scene/object.rs]="-p caustics --lib --test scene_files"
)

# The cargo-mutants arguments that name FILE's tests: sets `judge` to (--test-package PKG
# --cargo-test-arg=... ...).
judge_of() {
    local a x
    read -r -a a <<< "${TESTS[$1]}"
    judge=(--test-package "${a[1]}")
    for x in "${a[@]:2}"; do judge+=("--cargo-test-arg=$x"); done
}

# How many mutants a run's output folder lists as KIND (caught, missed, unviable, timeout).
count_in() {
    local n
    n=$(grep -c . "$1/$2.txt" 2> /dev/null) || true
    echo "${n:-0}"
}
