#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# A single-node Slurm cluster on this host, for trying `flatsat mc --slurm`
# and for its system test: munged, slurmctld and slurmd from Debian's
# packages (munge, slurmctld, slurmd, slurm-client), every file under DIR,
# every socket on 127.0.0.1 (CommunicationParameters=NoInAddrAny), run as the
# calling user (root here).
#   local-cluster.sh start DIR [PORT]   start it (ports PORT and PORT+1; default 16817)
#   local-cluster.sh stop DIR           stop it and remove its state
# After start, point Slurm's commands at it:  export SLURM_CONF=DIR/slurm.conf
# Exit status of start: 0 running (the node idle), 1 when a daemon would not
# start (its log is printed).
set -euo pipefail

usage() { echo "usage: $0 start DIR [PORT] | stop DIR" >&2; exit 2; }
[ $# -ge 2 ] || usage
cmd=$1
dir=$(realpath -m "$2")
port=${3:-16817}

stop() {
  for daemon in slurmd slurmctld; do
    [ -f "$dir/$daemon.pid" ] && kill "$(cat "$dir/$daemon.pid")" 2>/dev/null || true
  done
  [ -S "$dir/munge/munge.sock" ] && munged --stop --socket="$dir/munge/munge.sock" >/dev/null 2>&1 || true
  # The daemons leave after their pid files' owners are gone.
  for _ in $(seq 50); do
    alive=0
    for daemon in slurmd slurmctld; do
      [ -f "$dir/$daemon.pid" ] && kill -0 "$(cat "$dir/$daemon.pid")" 2>/dev/null && alive=1
    done
    [ $alive -eq 0 ] && break
    sleep 0.1
  done
  rm -rf "$dir"
}

fail() {
  echo "local-cluster.sh: $1" >&2
  for log in "$dir"/log/*.log; do
    [ -f "$log" ] && { echo "--- $log" >&2; tail -n 20 "$log" >&2; }
  done
  stop
  exit 1
}

start() {
  for program in munged slurmctld slurmd sinfo; do
    command -v "$program" >/dev/null || { echo "local-cluster.sh: $program not installed (apt install munge slurmctld slurmd slurm-client)" >&2; exit 1; }
  done
  mkdir -p "$dir"/{munge,state,spool,log}
  chmod 700 "$dir/munge"
  chmod 755 "$dir"
  # A key of this cluster's own: nothing else on the host can speak to it.
  head -c 1024 /dev/urandom > "$dir/munge/munge.key"
  chmod 600 "$dir/munge/munge.key"
  munged --force --socket="$dir/munge/munge.sock" --key-file="$dir/munge/munge.key" \
    --log-file="$dir/log/munged.log" --pid-file="$dir/munge/munged.pid" --seed-file="$dir/munge/seed" \
    || fail "munged would not start"
  cat > "$dir/slurm.conf" <<CONF
# Written by deploy/slurm/local-cluster.sh: one node, this host, loopback only.
ClusterName=flatsat-local
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
CommunicationParameters=NoInAddrAny
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.sock
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=flatsat Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF="$dir/slurm.conf"
  slurmctld -f "$SLURM_CONF" -i || fail "slurmctld would not start"
  slurmd -f "$SLURM_CONF" || fail "slurmd would not start"
  for _ in $(seq 100); do
    state=$(sinfo -h -N -o %t 2>/dev/null || true)
    [ "$state" = idle ] && { echo "local-cluster.sh: up; export SLURM_CONF=$SLURM_CONF"; return 0; }
    sleep 0.2
  done
  fail "the node did not come up (sinfo: ${state:-no answer})"
}

case "$cmd" in
  start) start ;;
  stop) stop ;;
  *) usage ;;
esac
