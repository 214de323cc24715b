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
