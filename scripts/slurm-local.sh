#!/usr/bin/env bash
# A throw-away single-node Slurm cluster on this machine, for tests and trying render-slurm.sh:
#   scripts/slurm-local.sh start DIR   # munged, slurmctld and slurmd with private state under DIR
#   source DIR/env.sh                   # SLURM_CONF and the munge socket for sbatch, squeue, ...
#   scripts/slurm-local.sh stop DIR    # stops the three daemons by their pid files
# Needs Debian's slurm-wlm and munge (scripts/setup.sh) and root (slurmd runs jobs as their users). Nothing
# outside DIR is written: a generated munge key, a generated slurm.conf with non-default free ports, and the
# daemons' spool, state, log and pid files. No systemd, no cgroups (proctrack/linuxproc, task/none).
set -euo pipefail

usage() { echo "usage: $0 start|stop DIR" >&2; exit 2; }
[ $# -eq 2 ] || usage
cmd=$1
dir=$(mkdir -p "$2" && cd "$2" && pwd)

stop() {
  local name pid
  for name in slurmd slurmctld munged; do
    [ -f "$dir/$name.pid" ] || continue
    pid=$(cat "$dir/$name.pid" 2>/dev/null || true)
    if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then
      kill "$pid" 2>/dev/null || true
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -9 "$pid" 2>/dev/null || true
    fi
    rm -f "$dir/$name.pid"
  done
}

free_port() {
  /usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

case "$cmd" in
  stop) stop; exit 0 ;;
  start) ;;
  *) usage ;;
esac

[ "$(id -u)" -eq 0 ] || { echo "slurm-local: needs root (slurmd starts jobs as their users)" >&2; exit 2; }
for exe in munged mungekey slurmctld slurmd sbatch; do
  command -v "$exe" >/dev/null || [ -x "/usr/sbin/$exe" ] || { echo "slurm-local: $exe not found (scripts/setup.sh installs slurm-wlm and munge)" >&2; exit 2; }
done
export PATH="$PATH:/usr/sbin"
stop  # a previous run's daemons in the same DIR

mkdir -p "$dir/munge" "$dir/spool" "$dir/state" "$dir/log"
# munged insists on its files belonging to the user it runs as, and on no group/other write access.
chown munge:munge "$dir/munge" && chmod 0711 "$dir/munge" && chmod 0755 "$dir"
rm -f "$dir/munge/munge.key"
runuser -u munge -- mungekey --create --keyfile="$dir/munge/munge.key" --bits=1024 >/dev/null
runuser -u munge -- munged --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
  --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed"
cp "$dir/munge/munged.pid" "$dir/munged.pid"

host=$(hostname -s)
cpus=$(nproc)
ctld_port=$(free_port)
d_port=$(free_port)
while [ "$d_port" = "$ctld_port" ]; do d_port=$(free_port); done
cat >"$dir/slurm.conf" <<CONF
ClusterName=shadelab-local
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
SlurmdTimeout=60
InactiveLimit=0
KillWait=5
MaxArraySize=100001
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
CONF
cat >"$dir/env.sh" <<ENV
export SLURM_CONF=$dir/slurm.conf
export PATH="\$PATH:/usr/sbin"
ENV
export SLURM_CONF="$dir/slurm.conf"
slurmctld -f "$dir/slurm.conf"
slurmd -f "$dir/slurm.conf"
# Ready when the node is idle (the controller has heard from slurmd).
for _ in $(seq 150); do
  state=$(sinfo -h -n "$host" -o %T 2>/dev/null || true)
  case "$state" in idle*|mixed*|allocated*) echo "slurm-local: cluster up in $dir (node $host, $cpus CPUs)"; exit 0 ;; esac
  sleep 0.2
done
echo "slurm-local: the node did not come up (state '${state:-none}'); logs in $dir/log" >&2
stop
exit 1
