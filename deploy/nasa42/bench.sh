#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# A simulated day in NASA's 42 and in a composed flatsat rig, in turns, for
# the CPU each takes (issue 36, item 3: flatsat at most a third of 42's).
#   deploy/nasa42/bench.sh 42_SOURCE [ROUNDS]        (ROUNDS defaults to 5)
# 42_SOURCE is a checkout of 42 (github.com/ericstoneking/42; its Model/
# folder may lack the large meshes: the case below draws nothing). It is
# copied and built here with -O2 and no graphics, and runs its Standalone
# case as NASA ships it (SC_CfsSat0 and its flight software, IGRF 8x8, the
# environmental forces off) for 86,400 s in steps of 0.1 s, writing its
# files every second, one spacecraft. flatsat runs the default scenario
# composed for the same day and step, recording at 1 Hz.
# The two alternate, so that the machine's slow and fast phases fall on both
# (this 2-vCPU guest's speed drifts by a quarter within an hour). Prints a
# line per round, then key=value:
#   nasa42_cpu_s, flatsat_cpu_s   medians of user + system CPU seconds
#   cpu_ratio                     median of the rounds' flatsat/42 ratios
#   rounds_within_a_third         rounds whose ratio was at most 1/3
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
flatsat="${FLATSAT:-$here/build/bin/flatsat}"
source_dir=${1:?usage: $0 42_SOURCE [ROUNDS]}
rounds=${2:-5}
if [ ! -f "$source_dir/Makefile" ] || [ ! -d "$source_dir/Standalone" ]; then
  echo "$0: $source_dir: not a checkout of 42 (no Makefile or Standalone/)" >&2
  exit 2
fi
[ -x /usr/bin/time ] || { echo "$0: needs /usr/bin/time (apt install time)" >&2; exit 2; }
[ -x "$flatsat" ] || { echo "$0: $flatsat: not built (bash deploy/rig.sh build)" >&2; exit 2; }
work=$(mktemp -d /tmp/flatsat-nasa42.XXXXXX)
trap 'rm -rf "$work"' EXIT

cp -r "$source_dir" "$work/42"
sed -i 's/-g -O0 -fpic/-O2 -fpic/' "$work/42/Makefile"
make -C "$work/42" -j2 GUIFLAG= SHADERFLAG= >"$work/build.log" 2>&1 ||
  { tail -20 "$work/build.log" >&2; exit 1; }
case_dir="$work/42/Day"
cp -r "$work/42/Standalone" "$case_dir"
python3 - "$case_dir/Inp_Sim.txt" <<'PY'
import sys
path = sys.argv[1]
out = []
for line in open(path).read().split("\n"):
    if "Sim Duration, Step Size" in line:
        line = "86400.0   0.1                   !  Sim Duration, Step Size [sec]"
    elif "Graphics Front End" in line:
        line = "FALSE                           !  Graphics Front End?"
    elif "Number of Spacecraft" in line:
        line = "1                               !  Number of Spacecraft"
    elif "Input file for SC 1" in line:
        continue
    out.append(line)
open(path, "w").write("\n".join(out))
PY

cpu() { awk '{printf "%.2f\n", $1 + $2}' "$1"; }
for round in $(seq 1 "$rounds"); do
  (cd "$work/42" && /usr/bin/time -o "$work/42.time" -f "%U %S" ./42 Day >"$work/42.log" 2>&1) ||
    { tail -5 "$work/42.log" >&2; exit 1; }
  rm -rf "$work/day"
  /usr/bin/time -o "$work/flatsat.time" -f "%U %S" "$flatsat" run default --composed --no-plots -q \
    --out "$work/day" --set duration_orbits=null --set duration_s=86400 \
    --set components.recorder.record_every_steps=10 >"$work/flatsat.log" 2>&1 ||
    { tail -5 "$work/flatsat.log" >&2; exit 1; }
  echo "round $round: 42 $(cpu "$work/42.time") s, flatsat $(cpu "$work/flatsat.time") s of CPU"
  echo "$(cpu "$work/42.time") $(cpu "$work/flatsat.time")" >>"$work/rounds"
done
python3 - "$work/rounds" <<'PY'
import statistics, sys
rounds = [tuple(map(float, line.split())) for line in open(sys.argv[1])]
ratios = [f / n for n, f in rounds]
print(f"nasa42_cpu_s={statistics.median(n for n, _ in rounds):.2f}")
print(f"flatsat_cpu_s={statistics.median(f for _, f in rounds):.2f}")
print(f"cpu_ratio={statistics.median(ratios):.3f}")
print(f"rounds_within_a_third={sum(r <= 1 / 3 for r in ratios)}/{len(ratios)}")
PY
