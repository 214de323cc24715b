#!/usr/bin/env bash
# Mutation testing of the code that judges the numbers (docs/testing.md, "Tests that catch a
# broken rule"): cargo-mutants changes one operator, constant or return value at a time in each
# file below and runs the tests that should notice; a mutant they do not notice ("missed") is a
# rule no test holds. Writes results/mutants/<file stem>.md (mutants, caught, missed, unviable,
# timeouts, the time it took, and every missed mutant) and keeps cargo-mutants' own output in
# target/mutants/<file stem>/.
#
#   bash scripts/mutants.sh                               # every file below (an hour or more on 2 cores)
#   bash scripts/mutants.sh crates/bench/src/plausibility.rs
#
# Needs cargo-mutants (`cargo install cargo-mutants --locked`). It mutates the files in place
# (--in-place: the build reuses target/): do not edit or commit while it runs.
set -euo pipefail
cd "$(dirname "$0")/.."

# file : the tests that judge it (cargo test arguments for its package)
declare -A TESTS=(
    [crates/bench/src/plausibility.rs]="-p bench --lib --test plausibility"
    [crates/bench/src/stats.rs]="-p bench --lib --test plausibility --test tables"
    [crates/bench/src/claims/page.rs]="-p bench --lib --test claims"
    [crates/bench/src/claims/eval.rs]="-p bench --lib --test claims"
    [crates/bench/src/claims/expr.rs]="-p bench --lib --test claims"
    [crates/bench/src/claims/data.rs]="-p bench --lib --test claims"
    [crates/bench/src/steal.rs]="-p bench --lib"
    [crates/bench/src/run.rs]="-p bench --lib --test plausibility"
    [crates/bench/src/results.rs]="-p bench --lib --test plausibility --test tables"
    [crates/bench/src/measure.rs]="-p bench --lib"
    [crates/caustics/src/reference/optics.rs]="-p caustics --lib"
    [crates/caustics/src/compare.rs]="-p caustics --lib"
    [crates/caustics/src/scene/load.rs]="-p caustics --lib --test scene_files"
    [crates/caustics/src/scene/object.rs]="-p caustics --lib --test scene_files"
)
files=("$@")
[ ${#files[@]} -gt 0 ] || files=("${!TESTS[@]}")

command -v cargo-mutants > /dev/null || { echo "mutants.sh: install cargo-mutants first: cargo install cargo-mutants --locked" >&2; exit 1; }
mkdir -p results/mutants
for f in "${files[@]}"; do
    args=${TESTS[$f]:-}
    [ -n "$args" ] || { echo "mutants.sh: no tests listed for $f (edit TESTS in this script)" >&2; exit 2; }
    read -r -a a <<< "$args"
    pkg=${a[1]}
    test_args=()
    for x in "${a[@]:2}"; do test_args+=("--cargo-test-arg=$x"); done
    stem=$(basename "$f" .rs)
    out=target/mutants/$stem
    mkdir -p "$out"
    start=$(date +%s)
    # cargo-mutants exits 2 when mutants are missed: that is a result, not a failure of the run.
    cargo mutants --in-place -f "$f" --test-package "$pkg" "${test_args[@]}" --output "$out" > "$out/run.log" 2>&1 || [ $? -eq 2 ]
    secs=$(( $(date +%s) - start ))
    o=$out/mutants.out
    count() { local n; n=$(grep -c . "$o/$1.txt" 2>/dev/null) || true; echo "${n:-0}"; }
    caught=$(count caught); missed=$(count missed); unviable=$(count unviable); timeout=$(count timeout)
    viable=$((caught + missed + timeout))
    {
        echo "# Mutation testing: \`$f\`"
        echo
        echo "\`bash scripts/mutants.sh $f\` at commit $(git rev-parse --short HEAD), $(date -u +%Y-%m-%d), $(cargo mutants --version);"
        echo "judged by \`cargo test $args\`. $secs s on $(nproc) cores."
        echo
        echo "| mutants | caught | missed | unviable | timeouts | missed of viable |"
        echo "|---|---|---|---|---|---|"
        pct=$(( viable > 0 ? (100 * missed + viable / 2) / viable : 0 ))
        echo "| $((viable + unviable)) | $caught | $missed | $unviable | $timeout | $pct% |"
        echo
        if [ "$missed" -gt 0 ]; then
            echo "Missed (each a change no test noticed):"
            echo
            sed 's/^/- /' "$o/missed.txt"
        else
            echo "No mutant missed."
        fi
    } > "results/mutants/$stem.md"
    echo "mutants.sh: $f: $caught caught, $missed missed, $unviable unviable, $timeout timeouts in ${secs} s: results/mutants/$stem.md"
done
