#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The Foxglove WebSocket interop check: a paced default rig, `flatsat
# foxglove` beside it, and foxglove-check.mjs connecting with the published
# client. Prints what the bridge with one client subscribed to every topic
# adds to the rig's CPU, in steady state (docs/recordings.md).
#   tests/interop/foxglove-check.sh BIN_DIR SCENARIO_DIR [--bus]
# --bus: the bridge reads every topic from the bus, not from the recorder's feed.
set -euo pipefail
bin=$1
scenarios=$2
bridge_args=("${@:3}")
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
work=$(mktemp -d /tmp/flatsat-interop-foxglove.XXXXXX)
rig= bridge=
cleanup() {
  [ -n "$bridge" ] && kill "$bridge" 2>/dev/null || true
  [ -n "$rig" ] && kill "$rig" 2>/dev/null || true
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
if [ ! -d "$here/node_modules/@foxglove/ws-protocol" ]; then
  npm ci --prefix "$here" --no-audit --no-fund >&2
fi
source "$here/../support/test-domain.sh"

waitFor() {  # FILE TEXT SECONDS
  for _ in $(seq 1 $((10 * $3))); do
    grep -q "$2" "$1" 2>/dev/null && return 0
    sleep 0.1
  done
  echo "foxglove-check: no '$2' in $1 within $3 s" >&2
  cat "$1" >&2 || true
  return 1
}

"$bin/flatsat" run "$scenarios/default.yaml" -q --no-plots --out "$work/run" \
  --set mode=paced --set duration_orbits=null --set duration_s=65 >"$work/run.log" 2>&1 &
rig=$!
waitFor "$work/run/logs/dynamics_server.log" "every component ready" 120
sleep 2
alone=$(bash "$here/cpu-window.sh" "$work/run" 10)
echo "the rig alone: $alone"
"$bin/flatsat" foxglove "${bridge_args[@]}" --port 0 >"$work/bridge.out" 2>"$work/bridge.err" &
bridge=$!
waitFor "$work/bridge.out" "ws://" 30
url=$(grep -o 'ws://[^ ]*' "$work/bridge.out")
status=0
want="the recorder's live feed"
[ ${#bridge_args[@]} -gt 0 ] && want="from the bus"
grep -q "$want" "$work/bridge.out" || { echo "foxglove-check: the bridge does not read $want: $(cat "$work/bridge.out")" >&2; status=1; }
node "$here/foxglove-check.mjs" "$url" "$work/run" "$bridge" | tee "$work/check.log" || status=$?
wait "$rig" || true
rig=
kill -INT "$bridge"
wait "$bridge" || true
bridge=
cat "$work/bridge.err" >&2
watched=$(grep -o 'watching every channel: .*' "$work/check.log" || true)
value() { grep -o "$1=[0-9.]*" <<<"$2" | cut -d= -f2; }
if [ -n "$watched" ]; then
  awk -v rig="$(value rig_cpu_ms_per_s "$alone")" -v rec0="$(value recorder_cpu_ms_per_s "$alone")" \
      -v rec1="$(value recorder_cpu_ms_per_s "$watched")" -v from="${bridge_args[*]:+ ${bridge_args[*]}}" -v bridge="$(value watcher_cpu_ms_per_s "$watched")" 'BEGIN {
    feed = rec1 > rec0 ? rec1 - rec0 : 0  # what feeding the bridge cost the recorder (within noise)
    printf "foxglove bridge%s: rig_cpu_ms_per_s=%.2f bridge_cpu_ms_per_s=%.3f recorder_cpu_ms_per_s=%.3f->%.3f bridge_fraction_of_rig=%.1f%% added_fraction_of_rig=%.1f%%\n",
           from, rig, bridge, rec0, rec1, 100 * bridge / rig, 100 * (bridge + feed) / rig }'
fi
exit "$status"
