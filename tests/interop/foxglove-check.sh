#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The Foxglove WebSocket interop check: a paced default rig, `flatsat
# foxglove` beside it, and foxglove-check.mjs connecting with the published
# client. Prints the bridge's CPU beside the rig's (the bridge with one
# client subscribed to every topic; docs/recordings.md).
#   tests/interop/foxglove-check.sh BIN_DIR SCENARIO_DIR
set -euo pipefail
bin=$1
scenarios=$2
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
# A domain of this test's own, held by a lock as tests/support/TestDomain.hpp holds one.
for i in $(seq 0 109); do
  domain=$((10 + 2 * (($$ + i) % 110)))
  exec 9>"/tmp/flatsat-test-domain-$domain.lock"
  flock -n 9 && break
done
export FLATSAT_DOMAIN=$domain

waitFor() {  # FILE TEXT SECONDS
  for _ in $(seq 1 $((10 * $3))); do
    grep -q "$2" "$1" 2>/dev/null && return 0
    sleep 0.1
  done
  echo "foxglove-check: no '$2' in $1 within $3 s" >&2
  cat "$1" >&2 || true
  return 1
}

( TIMEFORMAT='rig_cpu_s %U %S'
  time "$bin/flatsat" run "$scenarios/default.yaml" -q --no-plots --out "$work/run" \
    --set mode=paced --set duration_orbits=null --set duration_s=45 >"$work/run.log" 2>&1 || true
) 2>"$work/rig-cpu.txt" &
rig=$!
waitFor "$work/run/logs/dynamics_server.log" "every component ready" 120
"$bin/flatsat" foxglove --port 0 >"$work/bridge.out" 2>"$work/bridge.err" &
bridge=$!
waitFor "$work/bridge.out" "ws://" 30
url=$(grep -o 'ws://[^ ]*' "$work/bridge.out")
status=0
node "$here/foxglove-check.mjs" "$url" "$work/run" || status=$?
wait "$rig" || true
rig=
kill -INT "$bridge"
wait "$bridge" || true
bridge=
cat "$work/bridge.err" >&2
rig_cpu=$(awk '/rig_cpu_s/ {print $2 + $3}' "$work/rig-cpu.txt")
bridge_cpu=$(grep -o 'cpu_s [0-9.e+-]*' "$work/bridge.err" | awk '{print $2}')
awk -v r="$rig_cpu" -v b="$bridge_cpu" 'BEGIN {
  printf "foxglove bridge: rig_cpu_s=%.2f bridge_cpu_s=%.2f bridge_fraction_of_rig=%.1f%%\n", r, b, 100 * b / r }'
exit "$status"
