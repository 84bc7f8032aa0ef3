#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# CPU time of a paced rig's processes and, if given, of one more process over
# a window of wall time, from the kernel's per-thread run times
# (/proc/PID/task/TID/schedstat, nanoseconds; the tick counts of
# /proc/PID/stat are too coarse for a bridge's few milliseconds a second).
#   tests/interop/cpu-window.sh RUN_DIR SECONDS [PID]
# prints: rig_cpu_ms_per_s=… recorder_cpu_ms_per_s=… [watcher_cpu_ms_per_s=…]
set -euo pipefail
run_dir=$1 seconds=$2 watcher=${3:-}
rig_pids() { pgrep -f -- "--scenario $run_dir/" || true; pgrep -f -- "flatsat run .*--out $run_dir( |\$)" || true; }
recorder_pid() { pgrep -f -- "flatsat-recorder --scenario $run_dir/" || true; }
cpu_ns() {  # PID...: the run time of every thread now alive
  local total=0 pid task
  for pid in "$@"; do
    for task in /proc/"$pid"/task/*/schedstat; do
      [ -r "$task" ] && total=$((total + $(cut -d' ' -f1 "$task" 2>/dev/null || echo 0)))
    done
  done
  echo "$total"
}
mapfile -t rig < <(rig_pids)
recorder=$(recorder_pid)
[ ${#rig[@]} -gt 0 ] || { echo "cpu-window: no rig process of $run_dir" >&2; exit 1; }
rig0=$(cpu_ns "${rig[@]}") rec0=$(cpu_ns $recorder) w0=0
[ -n "$watcher" ] && w0=$(cpu_ns "$watcher")
sleep "$seconds"
rig1=$(cpu_ns "${rig[@]}") rec1=$(cpu_ns $recorder) w1=0
[ -n "$watcher" ] && w1=$(cpu_ns "$watcher")
line=$(awk -v r=$((rig1 - rig0)) -v c=$((rec1 - rec0)) -v s="$seconds" \
  'BEGIN { printf "rig_cpu_ms_per_s=%.2f recorder_cpu_ms_per_s=%.3f", r / s / 1e6, c / s / 1e6 }')
[ -n "$watcher" ] && line+=$(awk -v w=$((w1 - w0)) -v s="$seconds" 'BEGIN { printf " watcher_cpu_ms_per_s=%.3f", w / s / 1e6 }')
echo "$line"
