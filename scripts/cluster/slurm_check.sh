#!/usr/bin/env bash
# Tests scripts/cluster/ against a real Slurm on this machine (scripts/test.sh runs it; CI too):
# installs and starts munge, slurmctld and slurmd as a one-node cluster of its own (a private
# configuration, key, ports and folders under a temporary folder; nothing under /etc is
# changed), then
# 1. submits a --quick config as a 4-task job array, one task at a time (--throttle 1: two cores
#    cannot run four timed tasks honestly), and its merge job, waits, and checks with
#    `causticlab bench same` that the merged table equals the unsharded --quick run of the same
#    config cell for cell in everything but the timings;
# 2. submits it again, kills task 2 while it runs (scancel), and checks that the merge job names
#    shard 2 of 4 as missing, writes no table for the config, and exits non-zero; and submits it
#    for a device that does not exist: each task's bench fails, is run once more, fails again,
#    and the merge names the shard as failed twice with both exit codes;
# 3. where Mesa 25's lavapipe is unpacked (scripts/mesa25.sh), a two-device run: one array per
#    lavapipe (--target "Mesa 22.3" --target "Mesa 25"), giving two device folders.
# It stops the daemons it started, whatever happens.
#
#   bash scripts/cluster/slurm_check.sh [BINARY]    # default target/debug/causticlab
#
# Slurm 22.05 (Debian 12) without systemd or cgroup delegation: proctrack/linuxproc, task/none,
# no accounting, select/cons_tres over the machine's cores, root as SlurmUser, munged on a
# private socket with a fresh key (AuthInfo=socket=...). CONFIG picks the config (default
# wyman2008_fig7: its quick run has 8 cells of times, relative RMSE, flux, peak ratio and FLIP).
set -euo pipefail
cd "$(dirname "$0")/../.."
repo=$(pwd)

bin=${1:-target/debug/causticlab}
[ -x "$bin" ] || { echo "slurm_check: no binary at $bin (cargo build first)" >&2; exit 1; }
bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
config=${CONFIG:-wyman2008_fig7}
fail() { echo "slurm_check: FAILED: $*" >&2; exit 1; }

if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v munged >/dev/null || ! command -v sbatch >/dev/null; then
    [ "$(id -u)" -eq 0 ] || fail "Slurm is not installed and this is not root (apt-get install slurmctld slurmd slurm-client munge)"
    echo "slurm_check: installing slurmctld, slurmd, slurm-client and munge"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends slurmctld slurmd slurm-client munge >/dev/null
fi

tmp=$(mktemp -d /tmp/slurm_check.XXXXXX)
chmod 755 "$tmp"
export SLURM_CONF=$tmp/slurm.conf
stop() {
    scancel --user "$(id -un)" >/dev/null 2>&1 || true
    for p in slurmd slurmctld; do
        [ -f "$tmp/$p.pid" ] && kill "$(cat "$tmp/$p.pid")" 2>/dev/null || true
    done
    sleep 1
    munged --socket="$tmp/munge/socket" --stop >/dev/null 2>&1 || true
    rm -rf "$tmp"
}
trap stop EXIT

# The cluster: munge, then slurmctld and slurmd on ports no default Slurm uses.
mkdir -p "$tmp/munge" "$tmp/state" "$tmp/spool" "$tmp/log"
chmod 700 "$tmp/munge"
head -c 1024 /dev/urandom >"$tmp/munge/munge.key"
chmod 400 "$tmp/munge/munge.key"
munged --force --socket="$tmp/munge/socket" --key-file="$tmp/munge/munge.key" --log-file="$tmp/log/munged.log" \
    --pid-file="$tmp/munge/munged.pid" --seed-file="$tmp/munge/seed" || fail "munged did not start ($tmp/log/munged.log)"
node=$(hostname -s)
cat >"$SLURM_CONF" <<CONF
ClusterName=causticlab-check
SlurmctldHost=$node
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge/socket
SlurmctldPort=16817
SlurmdPort=16818
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
KillWait=10
NodeName=$node CPUs=$(nproc) RealMemory=1024 State=UNKNOWN
PartitionName=check Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start ($tmp/log/slurmctld.log)"
slurmd -f "$SLURM_CONF" || fail "slurmd did not start ($tmp/log/slurmd.log)"
for _ in $(seq 1 30); do
    sinfo -h -o %t 2>/dev/null | grep -q idle && break
    sleep 1
done
sinfo -h -o %t | grep -q idle || { cat "$tmp/log/slurmctld.log" "$tmp/log/slurmd.log" >&2; fail "the node did not become idle"; }
echo "slurm_check: Slurm $(sinfo -V | cut -d' ' -f2) up: node $node, $(nproc) CPUs"

t0=$(date +%s)
bash scripts/gpu_pack.sh --binary "$bin" --out "$tmp/pack" --no-loader --cluster
wait_for() {   # job id: until it has left the queue
    while [ -n "$(squeue -h -j "$1" 2>/dev/null)" ]; do sleep 1; done
}

echo "== 1. $config --quick as a 4-task array, one at a time, merged; against an unsharded run"
bash scripts/cluster/submit.sh --shared "$tmp/shared" --pack "$tmp/pack" --quick --shards 4 --throttle 1 \
    --name whole --wait "$config" || { tail -n 20 "$tmp"/shared/runs/whole.1/logs/*; fail "the sweep's merge failed"; }
merged=$(find "$tmp/shared/results" -path "*/quick/$config.json.gz")
[ -n "$merged" ] || fail "the merge wrote no $config.json.gz"
[ "$(find "$tmp/shared/runs/whole.1/results" -name "$config.shard-[1-4]-of-4.json" | wc -l)" -eq 4 ] || fail "not 4 parts in the run's folder"
CAUSTICLAB_COMMIT=$(cat "$tmp/pack/COMMIT") "$bin" bench "bench_configs/$config.toml" --quick --results "$tmp/direct" >"$tmp/direct.log" 2>&1 \
    || { tail -n 20 "$tmp/direct.log"; fail "the unsharded run failed"; }
direct=$(find "$tmp/direct" -path "*/quick/$config.json.gz")
"$bin" bench same "$direct" "$merged" || fail "the merged table differs from the unsharded run"
# The tables are copied into the repository's results/: their Regenerate line must be that
# folder's, not name the shared folder they were merged in.
regenerate=$(grep "^Regenerate: " "${merged%.json.gz}.md")
[[ $regenerate == *"causticlab bench merge results/"* && $regenerate != *"$tmp"* ]] \
    || { echo "$regenerate"; fail "the merged table's Regenerate line names the shared folder"; }
echo "slurm_check: 1 ok ($(($(date +%s) - t0)) s so far)"

echo "== 2. the same sweep with task 2 killed while it runs"
bash scripts/cluster/submit.sh --shared "$tmp/killed" --pack "$tmp/pack" --quick --shards 4 --throttle 1 \
    --name killed "$config" >"$tmp/killed.txt"
cat "$tmp/killed.txt"
array=$(cat "$tmp/killed/runs/killed.1/ARRAY_JOB")
merge=$(cat "$tmp/killed/runs/killed.1/MERGE_JOB")
for _ in $(seq 1 600); do
    [ "$(squeue -h -j "${array}_2" -o %T 2>/dev/null)" = RUNNING ] && break
    sleep 0.2
done
[ "$(squeue -h -j "${array}_2" -o %T)" = RUNNING ] || fail "task 2 never ran"
# Killed while its bench runs: after task.sh has said so (its signal trap is set by then), not a
# fixed wait, which a loaded machine can outlast before the trap.
task_log=$tmp/killed/runs/killed.1/logs/slurm-${array}_2.out
for _ in $(seq 1 600); do
    grep -q '^cluster task 2: ' "$task_log" 2>/dev/null && break
    sleep 0.2
done
grep -q '^cluster task 2: ' "$task_log" || fail "task 2 never started its bench ($task_log)"
sleep 0.5
scancel "${array}_2"
echo "slurm_check: cancelled task ${array}_2 while it ran"
wait_for "$merge"
merged_out=$(cat "$tmp"/killed/runs/killed.1/logs/merge-*.out)
echo "$merged_out"
grep -q "^exit=1$" "$tmp/killed/runs/killed.1/MERGED" || fail "the merge did not record a failure"
grep -q "$config: shard 2 of 4 missing: task 2 was killed" <<<"$merged_out" || fail "the merge did not name shard 2 of 4 as killed"
[ -z "$(find "$tmp/killed/results" -name "$config.md")" ] || fail "the merge wrote a table with a shard missing"
ok_parts=$(find "$tmp/killed/runs" -name "$config.shard-*-of-4.json" | wc -l)
[ "$ok_parts" -eq 3 ] || fail "$ok_parts parts, not the 3 of the tasks that ran"
"$bin" bench merge --results "$tmp/killed/try" "$(dirname "$(find "$tmp/killed/runs" -name "$config.shard-1-of-4.json")")"/*.json \
    >"$tmp/merge3.txt" 2>&1 && fail "bench merge of 3 of 4 shards succeeded"
grep -q "(shard 2 of 4 missing)" "$tmp/merge3.txt" || { cat "$tmp/merge3.txt"; fail "bench merge did not name shard 2 of 4"; }
echo "== 2b. a task whose bench fails: run twice, then named"
bash scripts/cluster/submit.sh --shared "$tmp/failing" --pack "$tmp/pack" --quick --shards 2 --throttle 1 \
    --name failing --target no-such-device --wait "$config" >"$tmp/failing.txt" 2>&1 && fail "a sweep on a device that does not exist succeeded"
cat "$tmp"/failing/runs/failing.1/logs/merge-*.out
grep -q "$config: shard 1 of 2 missing: task 1 failed twice on $(hostname) (exits 2 2;" "$tmp"/failing/runs/failing.1/logs/merge-*.out \
    || fail "the merge did not name shard 1 of 2 as failed twice with exit 2"
ls "$tmp"/failing/runs/failing.1/logs/"$config".shard-1-of-2.attempt-2.log >/dev/null || fail "no second attempt's log"
echo "slurm_check: 2 ok ($(($(date +%s) - t0)) s so far)"

echo "== 3. two devices: one array per lavapipe"
if mesa_env=$(bash scripts/mesa25.sh --env 2>/dev/null); then
    eval "$mesa_env"
    bash scripts/cluster/submit.sh --shared "$tmp/two" --pack "$tmp/pack" --quick --shards 2 --throttle 1 \
        --name two --target "Mesa 22.3" --target "Mesa 25" --wait "$config" || fail "the two-device sweep failed"
    mapfile -t tables < <(find "$tmp/two/results" -path "*/quick/$config.md" | sort)
    printf 'slurm_check: %s\n' "${tables[@]#"$tmp/two/"}"
    [ "${#tables[@]}" -eq 2 ] || fail "${#tables[@]} device folders with $config.md, not 2"
    echo "slurm_check: 3 ok"
else
    echo "slurm_check: 3 not run: Mesa 25's lavapipe cannot be had here (scripts/mesa25.sh)"
fi
echo "slurm_check: ok in $(($(date +%s) - t0)) s"
