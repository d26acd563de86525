#!/usr/bin/env bash
# The real Slurm test (docs/sweeps.md, "Distributed runs"): installs Debian's slurm-wlm and
# munge, starts munged, slurmctld and slurmd for one node on loopback, submits a small sweep as
# a job array with the script `msbench sweep --emit-slurm` prints, waits for it, writes the index
# with a plain `msbench sweep` call, and checks that every run's determinism hash equals the one
# of the same sweep run locally with --jobs 2. Needs root (it configures system daemons).
# Usage: tests/slurm/slurm_array_test.sh [BUILD_DIR]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
msbench=$(realpath "$build/bin/msbench")
work=$(mktemp -d /tmp/msb_slurm.XXXXXX)
echo "slurm-test: work directory $work"

# Packages (idempotent).
need=()
for p in slurm-wlm munge; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${need[@]}"
fi

# munge: a key and the daemon.
if [ ! -s /etc/munge/munge.key ]; then
  dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
fi
chown munge:munge /etc/munge/munge.key && chmod 400 /etc/munge/munge.key
mkdir -p /run/munge && chown munge:munge /run/munge
pgrep -x munged >/dev/null || runuser -u munge -- /usr/sbin/munged --force
munge -n | unmunge >/dev/null

# Slurm: one node (this machine) on loopback, no cgroups, state under the work directory.
host=$(hostname -s)
cpus=$(nproc)
mem=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 - 512 ))
mkdir -p "$work/state" "$work/spool" /etc/slurm
cat > /etc/slurm/slurm.conf <<CONF
ClusterName=msbtest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
cleanup() {
  [ -f "$work/slurmd.pid" ] && kill "$(cat "$work/slurmd.pid")" 2>/dev/null || true
  [ -f "$work/slurmctld.pid" ] && kill "$(cat "$work/slurmctld.pid")" 2>/dev/null || true
}
trap cleanup EXIT
/usr/sbin/slurmctld -c
/usr/sbin/slurmd -c
for _ in $(seq 60); do
  sinfo -h -o %T 2>/dev/null | grep -qE "idle|mixed" && break
  sleep 1
done
sinfo

# A small sweep: 2 variants x 2 seeds of a short mission.
cat > "$work/sweep.yaml" <<YAML
scenario: $(pwd)/scenarios/missions/test_world_short.yaml
set: {duration_s: 4}
axes:
  - name: method
    variants: {a: {}, b: {mission.metric_rate_hz: 2}}
seeds: 2
YAML

# Submitted as a job array, waited for.
"$msbench" sweep "$work/sweep.yaml" --out "$work/slurm" --emit-slurm > "$work/job.sh"
cat "$work/job.sh"

job=$(sbatch --parsable --wait "$work/job.sh")
echo "slurm-test: job array $job finished"
"$msbench" sweep "$work/sweep.yaml" --out "$work/slurm" > "$work/index.log" 2>&1 || { cat "$work/index.log"; exit 1; }
grep -q "4 complete, 0 to run" "$work/index.log" || { echo "slurm-test: FAIL: not every array task completed"; cat "$work/index.log"; exit 1; }

# The same sweep locally; the determinism hashes must agree run by run.
"$msbench" sweep "$work/sweep.yaml" --out "$work/local" --jobs 2 > "$work/local.log" 2>&1
hashes() { awk -F, 'NR > 1 {print $1, $(NF-2)}' "$1/runs.csv"; }
if diff <(hashes "$work/slurm") <(hashes "$work/local"); then
  echo "slurm-test: PASS: 4 array tasks, determinism hashes equal to the local run's"
  hashes "$work/slurm"
else
  echo "slurm-test: FAIL: hashes differ"
  exit 1
fi
