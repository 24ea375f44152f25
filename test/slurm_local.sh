#!/usr/bin/env bash
# test/slurm_local.sh -- a one-node SLURM cluster on this machine, for real,
# and a small afv sweep run through it (issue 20).  Also a readable example
# of a local SLURM: everything the cluster needs is below, in order.
#
#   test/slurm_local.sh [AFV]    (as root, from anywhere; AFV default ./afv)
#
# 1. installs Debian's slurm-wlm and munge if missing;
# 2. writes a slurm.conf into a temporary folder (SLURM_CONF points every
#    SLURM command at it; /etc/slurm is left alone): this host as the only
#    node with its CPU count, proctrack/linuxproc and task/none (no cgroups
#    needed), no accounting, daemons running as root;
# 3. starts munged (authentication; unless one runs already), slurmctld
#    (the controller) and slurmd (the node), and waits for the node;
# 4. writes a small sweep (afv sweep, 2 jobs per array task, 1 task per
#    array, an account and a partition), submits it from another
#    directory with sh slurm.sh --throttle 1 --wait (two arrays), and
#    collects it (afv collect: exit 0 only if every job finished and was
#    verified);
# 5. stops the daemons it started, by their process ids, and removes the
#    folder.
# Exit status 0 if the sweep finished through SLURM.
set -euo pipefail
afv=$(realpath "${1:-./afv}")

if [ "$(id -u)" != 0 ]; then
  echo "slurm_local.sh: run as root (it starts munged, slurmctld, slurmd)" >&2
  exit 2
fi
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  echo "installing: slurm-wlm munge"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge \
    > /dev/null
fi

work=$(mktemp -d /tmp/afv-slurm.XXXXXX)
chmod 755 "$work"
pids=()
stop() {
  local p
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do
    while kill -0 "$p" 2>/dev/null; do sleep 0.2; done
  done
  rm -rf "$work"
}
trap stop EXIT

host=$(hostname -s)
cpus=$(nproc)
# the node's memory in MB: slurm.sh asks for --mem (afv sweep's estimate),
# which a node without RealMemory (1 MB) refuses
mem=$(awk '/^MemTotal:/ { print int($2 / 1024) }' /proc/meminfo)
mkdir -p "$work/state" "$work/spool"
export SLURM_CONF="$work/slurm.conf"
cat > "$SLURM_CONF" <<EOF
# One node, this host; root runs the daemons; nothing but the basics.
ClusterName=afvlocal
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
# process tracking without cgroups; no task binding
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
# no accounting database, no job accounting
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF

# munge: the daemon runs as the munge user, with the key the package made
if ! pgrep -x munged >/dev/null; then
  mkdir -p /run/munge
  chown munge:munge /run/munge
  runuser -u munge -- /usr/sbin/munged
  for _ in $(seq 50); do [ -s /run/munge/munged.pid ] && break; sleep 0.1; done
  pids+=("$(cat /run/munge/munged.pid)")
fi

# the controller and the node, in the foreground (-D) of background jobs
slurmctld -D > "$work/slurmctld.out" 2>&1 &
pids+=("$!")
slurmd -D > "$work/slurmd.out" 2>&1 &
pids+=("$!")
state=""
for _ in $(seq 100); do
  state=$(sinfo -h -n "$host" -o %T 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.3
done
if [ "$state" != idle ]; then
  echo "slurm_local.sh: node $host not idle (state '$state'):" >&2
  tail -5 "$work/slurmctld.log" "$work/slurmd.log" >&2 || true
  exit 1
fi
echo "SLURM up: node $host, $cpus CPUs, partition local"

# 4 jobs, 2 per array task, at most 1 task per array: slurm.sh submits two
# arrays; the account and partition go into its #SBATCH lines (with no
# accounting database SLURM takes any account name).
"$afv" sweep --out "$work/sweep" --P0 4,8 --v0 0.5,2.6 --N 100 --steps 2000 \
  --frame_every 100 --svg_every 0 --steady-from 5 --lag 5 --per-task 2 \
  --array-max 1 --account afvtest --partition local \
  > /dev/null
grep '^#SBATCH' "$work/sweep/slurm.sh"
start=$(date +%s)
# submitted from another directory: every path of a job is relative to the
# sweep's folder (sbatch --chdir); --throttle 1 gives each array %1;
# --wait and --time pass through to sbatch
(cd / && timeout 300 sh "$work/sweep/slurm.sh" --throttle 1 --wait \
  --time=10:00)
echo "array jobs finished in $(( $(date +%s) - start )) s"
arrays=$(ls "$work"/sweep/logs/slurm-*_0.out | wc -l)
if [ "$arrays" != 2 ]; then
  echo "slurm_local.sh: $arrays job arrays ran, want 2 (--array-max 1)" >&2
  exit 1
fi
"$afv" collect "$work/sweep"
cut -d, -f1-5,18- "$work/sweep/table.csv"
