#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The cost of a campaign beyond its runs, here and on Slurm: the same
# campaign (same seeds) run by `flatsat mc` on this host and by `flatsat mc
# --slurm` on a single-node cluster of this host (local-cluster.sh).
#   deploy/slurm/bench.sh [RUNS] [PER_TASK] [ORBITS]    (defaults 40 5 1)
# Prints key=value per campaign:
#   *_runs_per_cpu_s        successful runs per CPU-second the campaign spent
#   *_overhead_fraction     the campaign's CPU beyond its runs' own, over theirs
#                           (flatsat's accounting: mc, mc-task, sbatch, squeue)
#   *_host_overhead_fraction the same from the whole machine's CPU (/proc/stat)
#                           over the campaign: Slurm's daemons and slurmstepd too
#   *_wall_s                start to gathered table
#   slurm_digests_equal     1 when every run recorded the same as its local twin
# Run it on a quiet machine: the host figure counts everything that ran.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
flatsat="${FLATSAT:-$here/build/bin/flatsat}"
runs=${1:-40}
per_task=${2:-5}
orbits=${3:-1}
work=$(mktemp -d /tmp/flatsat-slurm-bench.XXXXXX)
trap 'bash "$here/deploy/slurm/local-cluster.sh" stop "$work/cluster" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT

# Busy CPU-seconds of the whole machine so far (user+nice+system+irq+softirq+steal).
host_cpu() { awk '/^cpu /{printf "%.3f\n", ($2+$3+$4+$7+$8+$9)/100}' /proc/stat; }

campaign() {  # name, then the mc arguments
  local name=$1; shift
  local cpu0 t0 cpu1 t1
  cpu0=$(host_cpu); t0=$(date +%s.%N)
  "$flatsat" mc "$here/deploy/scenarios/default.yaml" --runs "$runs" --out "$work/$name" \
    --set duration_orbits="$orbits" "$@" >"$work/$name.log" 2>&1 || { cat "$work/$name.log" >&2; exit 1; }
  cpu1=$(host_cpu); t1=$(date +%s.%N)
  python3 - "$work/$name/mc_summary.json" "$name" "$cpu0" "$cpu1" "$t0" "$t1" <<'PY'
import json, sys
summary, name = json.load(open(sys.argv[1])), sys.argv[2]
cpu0, cpu1, t0, t1 = map(float, sys.argv[3:7])
host_cpu, wall = cpu1 - cpu0, t1 - t0
cost = summary["cost"]
print(f"{name}_runs={summary['succeeded']}")
print(f"{name}_runs_cpu_s={cost['runs_cpu_s']:.3f}")
print(f"{name}_runs_per_cpu_s={cost['runs_per_cpu_s']:.4f}")
print(f"{name}_overhead_fraction={cost['overhead_fraction']:.4f}")
print(f"{name}_host_overhead_fraction={(host_cpu - cost['runs_cpu_s']) / cost['runs_cpu_s']:.4f}")
print(f"{name}_wall_s={wall:.2f}")
PY
}

bash "$here/deploy/slurm/local-cluster.sh" start "$work/cluster" >/dev/null
export SLURM_CONF="$work/cluster/slurm.conf"
sleep 3  # slurmctld's start-up work is not the campaign's
echo "campaign: $runs runs of default.yaml at $orbits orbit(s); Slurm: $per_task runs per task, $(nproc) CPUs"
campaign local --jobs "$(nproc)"
campaign slurm --slurm --per-task "$per_task"
if diff <(cut -d, -f1-4 "$work/local/mc.csv") <(cut -d, -f1-4 "$work/slurm/mc.csv") >/dev/null; then
  echo "slurm_digests_equal=1"
else
  echo "slurm_digests_equal=0"
fi
