#!/usr/bin/env bash
# The GPU run's three scripts, rehearsed on lavapipe with the test build (scripts/test.sh runs
# this after the tests; CI never has a GPU):
# 1. scripts/gpu_pack.sh --dry-run: the pack's size against the 64 MiB a device call carries;
# 2. scripts/gpu_suite.sh --quick with a 120-second budget, then scripts/gpu_unpack.sh on its
#    archive: at least three tables;
# 3. a suite cut off after its second part (SUITE_CUT_AFTER_PARTS): the archive still holds the
#    finished parts, and they merge into a table whose other cells read `not run`.
# Fails, naming the check, if any of these does not hold.
#
#   bash scripts/gpu_dry_run.sh [BINARY]     # default target/debug/causticlab (cargo test builds it)
set -euo pipefail
cd "$(dirname "$0")/.."

bin=${1:-target/debug/causticlab}
[ -x "$bin" ] || { echo "gpu_dry_run: no binary at $bin (run cargo test or cargo build first)" >&2; exit 1; }
fail() { echo "gpu_dry_run: FAILED: $*" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "== 1. gpu_pack.sh --dry-run"
bash scripts/gpu_pack.sh --dry-run --binary "$bin" | tee "$tmp/pack.txt"
grep -q 'transfer .* of 64 MiB' "$tmp/pack.txt" || fail "gpu_pack.sh printed no transfer size"

bash scripts/gpu_pack.sh --binary "$bin" --out "$tmp/pack" --no-loader >/dev/null

echo "== 2. gpu_suite.sh --quick, 120 s, then gpu_unpack.sh"
SUITE_SHARDS=2 bash scripts/gpu_suite.sh --quick --pack "$tmp/pack" 120 "$tmp/out" >"$tmp/suite.txt" 2>&1 \
    || { tail -n 30 "$tmp/suite.txt"; fail "gpu_suite.sh exited non-zero"; }
grep '^gpu_suite: ' "$tmp/suite.txt" || true
[ -f "$tmp/out/gpu_suite.tar.gz" ] || fail "gpu_suite.sh wrote no archive"
CAUSTICLAB_BIN=$bin bash scripts/gpu_unpack.sh "$tmp/out/gpu_suite.tar.gz" --results "$tmp/results" | tee "$tmp/unpack.txt"
tables=$(find "$tmp/results" -path '*/quick/*.md' | wc -l)
echo "gpu_dry_run: $tables tables from the 120-second suite"
[ "$tables" -ge 3 ] || fail "the 120-second suite gave $tables tables, fewer than 3"

echo "== 3. a suite cut off after its second part"
SUITE_CUT_AFTER_PARTS=2 SUITE_SHARDS=4 bash scripts/gpu_suite.sh --quick --only wyman2008_table3 \
    --pack "$tmp/pack" 600 "$tmp/cut" >"$tmp/cut.txt" 2>&1 || { tail -n 30 "$tmp/cut.txt"; fail "the cut-off suite exited non-zero"; }
parts=$(tar -tzf "$tmp/cut/gpu_suite.tar.gz" | grep -c '^\./parts/.*\.json$' || true)
[ "$parts" -eq 2 ] || fail "the cut-off archive holds $parts parts, not the 2 finished"
tar -xzOf "$tmp/cut/gpu_suite.tar.gz" ./SKIPPED | grep -q 'wyman2008_table3 shard 3/4: not started' \
    || fail "the cut-off archive's SKIPPED does not name shard 3/4"
CAUSTICLAB_BIN=$bin bash scripts/gpu_unpack.sh "$tmp/cut/gpu_suite.tar.gz" --results "$tmp/cut_results" >"$tmp/cut_unpack.txt" \
    || { cat "$tmp/cut_unpack.txt"; fail "gpu_unpack.sh failed on the cut-off archive"; }
md=$(find "$tmp/cut_results" -name wyman2008_table3.md)
[ -n "$md" ] || fail "no wyman2008_table3.md from the cut-off archive"
grep -q '^\*\*Partial table: [0-9]* of [0-9]* cells were not run' "$md" || fail "$md does not say it is partial"
grep -q '| *not run *|' "$md" || fail "$md marks no cell \`not run\`"
grep -E '^\| [0-9]+²' "$md" | grep -vq 'not run' || fail "$md has no measured row"
echo "gpu_dry_run: the cut-off suite kept its 2 parts; $(grep -o '[0-9]* of [0-9]* cells were not run' "$md")"
echo "gpu_dry_run: ok"
