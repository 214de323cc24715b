#!/usr/bin/env bash
# Mutation testing of a commit's own changes to the judging code (docs/testing.md, "Tests that
# catch a broken rule"): cargo-mutants on the lines that BASE..HEAD changed in the files of
# scripts/mutants_files.sh, each judged by its tests. Fails when a mutant of a changed line is
# missed: a rule changed without a test that holds it. scripts/test.sh runs it after the tests
# (CI); a commit that changes none of those files costs nothing.
#
#   bash scripts/mutants_diff.sh [BASE]     # BASE defaults to HEAD~1, the previous commit
#
# Installs cargo-mutants (27.1.0, from crates.io) when a judged file changed and it is missing.
# Builds in the test profile, as scripts/test.sh has just done, so only the mutated crate is
# rebuilt per mutant.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/mutants_files.sh

base=${1:-HEAD~1}
if ! git rev-parse -q --verify "$base^{commit}" > /dev/null; then
    echo "mutants_diff.sh: no commit $base in this clone (shallow?): no diff to judge, skipped"
    exit 0
fi
changed=()
for f in "${!TESTS[@]}"; do
    git diff --quiet "$base" HEAD -- "$f" || changed+=("$f")
done
if [ ${#changed[@]} -eq 0 ]; then
    echo "mutants_diff.sh: $base..HEAD changes none of the judged files"
    exit 0
fi
command -v cargo-mutants > /dev/null || cargo install cargo-mutants --locked --version 27.1.0
mkdir -p target/mutants/diff
patch=target/mutants/diff/changes.patch
git diff "$base" HEAD -- "${changed[@]}" > "$patch"
# At about 8 s a mutant on two cores, a commit that adds a whole file (hundreds of mutants)
# would take CI past its budget: past MUTANTS_DIFF_MAX mutants, every k-th is tested (cargo
# mutants --shard 0/k), and the run says so; scripts/mutants.sh tests such a file in full.
total=0
for f in "${changed[@]}"; do
    total=$((total + $(cargo mutants --list -f "$f" --in-diff "$patch" 2> /dev/null | grep -c . || true)))
done
max=${MUTANTS_DIFF_MAX:-80}
k=$(( (total + max - 1) / max ))
[ "$k" -ge 1 ] || k=1
shard=()
if [ "$k" -gt 1 ]; then
    shard=(--shard "0/$k")
    echo "mutants_diff.sh: $total mutants on the changed lines, over $max: testing every ${k}th (run scripts/mutants.sh on ${changed[*]} for all of them)"
fi
missed_all=0
start=$(date +%s)
for f in "${changed[@]}"; do
    judge_of "$f"
    out=target/mutants/diff/$(basename "$f" .rs)
    # A run that finds no mutant writes no mutants.out: an earlier run's must not be read as its.
    rm -rf "$out"
    mkdir -p "$out"
    # Exit 2: mutants missed, 3: some timed out (counted below); anything else but 0 is a failed run.
    # A run that fails for another reason (its unmutated baseline did not build or pass: a
    # test process killed by a signal inside the driver, a full disk) is said with what it
    # printed, its baseline's last lines but cargo's `Fresh` ones, and the disk's free space,
    # then tried once more: the judged code is not at fault until a second run fails too.
    for attempt in 1 2; do
        rc=0
        cargo mutants --in-place -f "$f" --in-diff "$patch" "${shard[@]}" "${judge[@]}" \
            --output "$out" > "$out/run.log" 2>&1 || rc=$?
        if [ $rc -eq 0 ] || [ $rc -eq 2 ] || [ $rc -eq 3 ] || grep -q "No mutants" "$out/run.log"; then
            break
        fi
        # Each of these may find nothing (no baseline log, nothing but Fresh lines): never fatal.
        {
            echo "mutants_diff.sh: cargo mutants failed on $f (exit $rc, attempt $attempt of 2); it printed:"
            grep -v '^ *Fresh ' "$out/run.log" | tail -30 || true
            echo "mutants_diff.sh: the end of its baseline's log (cargo's Fresh lines left out):"
            grep -v '^ *Fresh ' "$out/mutants.out/log/baseline.log" 2> /dev/null | tail -30 | cut -c1-400 || true
            df -h . | sed 's/^/mutants_diff.sh: disk: /' || true
        } >&2
        [ $attempt -eq 2 ] && { echo "mutants_diff.sh: cargo mutants failed twice on $f: $out/run.log" >&2; exit 1; }
    done
    # No mutant on the changed lines (a comment, a test) is not a failure.
    if [ $rc -ne 0 ] && [ $rc -ne 2 ] && [ $rc -ne 3 ]; then
        echo "mutants_diff.sh: $f: no mutant on the changed lines"
        continue
    fi
    o=$out/mutants.out
    # cargo-mutants exits 0 and writes no mutants.out when the diff leaves no mutant in the file.
    [ -d "$o" ] || { echo "mutants_diff.sh: $f: no mutant on the changed lines"; continue; }
    n() { count_in "$o" "$1"; }
    split_missed "$o"
    echo "mutants_diff.sh: $f: $(n caught) caught, $(n missed_left) missed, $(n missed_named) named in .cargo/mutants.toml, $(n unviable) unviable, $(n timeout) timeouts"
    if [ "$(n missed_left)" -gt 0 ]; then
        sed 's/^/  missed: /' "$o/missed_left.txt"
        missed_all=$((missed_all + $(n missed_left)))
    fi
done
echo "mutants_diff.sh: $base..HEAD, ${#changed[@]} file(s), $total mutant(s) on changed lines${shard:+ (1 in $k tested)}, $(( $(date +%s) - start )) s"
if [ $missed_all -gt 0 ]; then
    echo "mutants_diff.sh: $missed_all mutant(s) of changed lines missed: add tests that catch them, or name them as equivalent in .cargo/mutants.toml with the reason" >&2
    exit 1
fi
