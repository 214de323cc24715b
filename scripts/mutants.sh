#!/usr/bin/env bash
# Mutation testing of the code that judges the numbers (docs/testing.md, "Tests that catch a
# broken rule"): cargo-mutants changes one operator, constant or return value at a time in each
# file below and runs the tests that should notice; a mutant they do not notice ("missed") is a
# rule no test holds. Writes results/mutants/<file stem>.md (mutants, caught, missed, unviable,
# timeouts, the time it took, and every missed mutant) and <file stem>.csv (the same figures as
# data) and keeps cargo-mutants' own output in
# target/mutants/<file stem>/.
#
#   bash scripts/mutants.sh                               # every file below (an hour or more on 2 cores)
#   bash scripts/mutants.sh crates/bench/src/plausibility.rs
#   MUTANTS_ARGS=--iterate bash scripts/mutants.sh FILE    # only the mutants its last run did not catch
#
# Needs cargo-mutants (`cargo install cargo-mutants --locked`). It mutates the files in place
# (--in-place: the build reuses target/): do not edit or commit while it runs.
set -euo pipefail
cd "$(dirname "$0")/.."

# The files and the tests that judge each: scripts/mutants_files.sh.
source scripts/mutants_files.sh
files=("$@")
[ ${#files[@]} -gt 0 ] || files=("${!TESTS[@]}")

command -v cargo-mutants > /dev/null || { echo "mutants.sh: install cargo-mutants first: cargo install cargo-mutants --locked" >&2; exit 1; }
mkdir -p results/mutants
for f in "${files[@]}"; do
    args=${TESTS[$f]:-}
    [ -n "$args" ] || { echo "mutants.sh: no tests listed for $f (edit TESTS in this script)" >&2; exit 2; }
    judge_of "$f"
    stem=$(basename "$f" .rs)
    # A run of the last run's survivors only is kept beside the full run, not over it.
    page=$stem
    [[ "${MUTANTS_ARGS:-}" != *--iterate* ]] || page=${stem}_iterate
    out=target/mutants/$stem
    mkdir -p "$out"
    start=$(date +%s)
    # cargo-mutants exits 2 when mutants are missed and 3 when some timed out (a mutant that
    # loops forever): results, not failures of the run.
    read -r -a extra <<< "${MUTANTS_ARGS:-}"
    cargo mutants --in-place --profile mutants -f "$f" "${judge[@]}" "${extra[@]}" --output "$out" > "$out/run.log" 2>&1 || { rc=$?; [ $rc -eq 2 ] || [ $rc -eq 3 ]; }
    secs=$(( $(date +%s) - start ))
    o=$out/mutants.out
    count() { count_in "$o" "$1"; }
    split_missed "$o"
    caught=$(count caught); missed=$(count missed_left); named=$(count missed_named)
    unviable=$(count unviable); timeout=$(count timeout)
    viable=$((caught + missed + named + timeout))
    pct=$(( viable > 0 ? (100 * missed + viable / 2) / viable : 0 ))
    commit=$(git rev-parse --short HEAD)
    day=$(date -u +%Y-%m-%d)
    tool=$(cargo mutants --version)
    # The run's figures as data (the page below is written from the same values; a page that
    # quotes them quotes this file: docs/claims.md, "Data files").
    {
        echo "file,commit,date,tool,judge,seconds,cores,mutants,caught,missed,unviable,timeouts,missed_pct,named"
        echo "$f,$commit,$day,$tool,cargo test $args,$secs,$(nproc),$((viable + unviable)),$caught,$missed,$unviable,$timeout,$pct,$named"
    } > "results/mutants/$page.csv"
    {
        echo "# Mutation testing: \`$f\`"
        echo
        echo "\`${MUTANTS_ARGS:+MUTANTS_ARGS=\"$MUTANTS_ARGS\" }bash scripts/mutants.sh $f\` at commit $commit, $day, $tool;"
        echo "judged by \`cargo test $args\`. $secs s on $(nproc) cores. Data: [$page.csv]($page.csv)."
        echo
        echo "| mutants | caught | missed | unviable | timeouts | missed of viable |"
        echo "|---|---|---|---|---|---|"
        echo "| $((viable + unviable)) | $caught | $missed | $unviable | $timeout | $pct% |"
        echo
        if [ "$missed" -gt 0 ]; then
            echo "Missed (each a change no test noticed):"
            echo
            sed 's/^/- /' "$o/missed_left.txt"
        else
            echo "No mutant missed."
        fi
        if [ "$named" -gt 0 ]; then
            echo
            echo "Not caught, and named in .cargo/mutants.toml with the reason (cargo-mutants 27.1 does not"
            echo "apply its exclude_re to struct-field deletions; the run's 'missed' counts them):"
            echo
            sed 's/^/- /' "$o/missed_named.txt"
        fi
    } > "results/mutants/$page.md"
    echo "mutants.sh: $f: $caught caught, $missed missed, $unviable unviable, $timeout timeouts in ${secs} s: results/mutants/$page.md"
done
