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
    [crates/bench/src/same.rs]="-p bench --lib"
    [crates/bench/src/front_curves.rs]="-p bench --lib --test front_curves"
    [crates/bench/src/drift.rs]="-p bench --lib"
    [crates/bench/src/one_cpu.rs]="-p bench --test tables"
    [crates/bench/src/explain.rs]="-p bench --lib --test plausibility --test front_curves"
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

# cargo-mutants 27.1 applies .cargo/mutants.toml's exclude_re to every mutant but the deletion
# of a struct field in a struct literal ("delete field X from struct Y expression in F"), which
# it mutates and reports whatever the config says. Splits OUT/missed.txt of a run into
# OUT/missed_left.txt (no test noticed them: each needs a test or a reason) and
# OUT/missed_named.txt (their name matches an exclusion, whose reason the config gives).
split_missed() {
    local out=$1 patterns
    patterns=$(mktemp)
    # The config's patterns, one per line, with TOML's `\\` read as `\`.
    sed -n '/^exclude_re/,/^]/s/^ *"\(.*\)",* *$/\1/p' .cargo/mutants.toml | sed 's/\\\\/\\/g' > "$patterns"
    touch "$out/missed.txt"
    if [ -s "$patterns" ]; then
        grep -E -f "$patterns" "$out/missed.txt" > "$out/missed_named.txt" || true
        grep -v -E -f "$patterns" "$out/missed.txt" > "$out/missed_left.txt" || true
    else
        : > "$out/missed_named.txt"
        cp "$out/missed.txt" "$out/missed_left.txt"
    fi
    rm -f "$patterns"
}
