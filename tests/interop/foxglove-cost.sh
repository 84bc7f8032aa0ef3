#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# What `flatsat foxglove` with one client subscribed to every channel adds to
# a paced default rig's CPU, in ROUNDS alternating windows of the rig alone
# and watched (the bridge started and stopped each round), so that the
# recorder's share is told from its own noise. Not run by ctest (about 90 s);
# foxglove-check.sh prints one such pair as it checks.
#   tests/interop/foxglove-cost.sh BIN_DIR SCENARIO_DIR [ROUNDS] [-- BRIDGE_ARGS...]
set -euo pipefail
bin=$1 scenarios=$2 rounds=${3:-3}
shift $(($# < 3 ? $# : 3))
[ "${1:-}" = "--" ] && shift
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
work=$(mktemp -d /tmp/flatsat-foxglove-cost.XXXXXX)
rig= bridge= client=
cleanup() {
  for p in $client $bridge $rig; do kill "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
[ -d "$here/node_modules/@foxglove/ws-protocol" ] || npm ci --prefix "$here" --no-audit --no-fund >&2
source "$here/../support/test-domain.sh"
"$bin/flatsat" run "$scenarios/default.yaml" -q --no-plots --out "$work/run" --set mode=paced \
  --set duration_orbits=null --set duration_s=$((10 + 27 * rounds)) >"$work/run.log" 2>&1 &
rig=$!
for _ in $(seq 1 1200); do grep -q "every component ready" "$work/run/logs/dynamics_server.log" 2>/dev/null && break; sleep 0.1; done
sleep 2
value() { grep -o "$1=[0-9.]*" <<<"$2" | cut -d= -f2; }
for round in $(seq 1 "$rounds"); do
  alone=$(bash "$here/cpu-window.sh" "$work/run" 10)
  "$bin/flatsat" foxglove "$@" --port 0 >"$work/bridge.out" 2>"$work/bridge.err" &
  bridge=$!
  for _ in $(seq 1 100); do grep -q "ws://" "$work/bridge.out" && break; sleep 0.1; done
  node "$here/subscribe-all.mjs" "$(grep -o 'ws://[^ ]*' "$work/bridge.out")" >"$work/client.log" 2>&1 &
  client=$!
  sleep 3
  watched=$(bash "$here/cpu-window.sh" "$work/run" 10 "$bridge")
  kill "$client"; kill -INT "$bridge"; wait "$bridge" 2>/dev/null || true
  client= bridge=
  echo "round $round: alone $alone; watched $watched"
  echo "$(value rig_cpu_ms_per_s "$alone") $(value recorder_cpu_ms_per_s "$alone") $(value recorder_cpu_ms_per_s "$watched") $(value watcher_cpu_ms_per_s "$watched")" >>"$work/figures"
  sleep 2
done
awk -v from="${*:+ $*}" '{ rig += $1; rec0 += $2; rec1 += $3; bridge += $4; n++ } END {
  rig /= n; rec0 /= n; rec1 /= n; bridge /= n; feed = rec1 > rec0 ? rec1 - rec0 : 0
  printf "foxglove cost%s over %d rounds: rig_cpu_ms_per_s=%.2f bridge_cpu_ms_per_s=%.3f recorder_cpu_ms_per_s=%.3f->%.3f bridge_fraction_of_rig=%.1f%% added_fraction_of_rig=%.1f%%\n",
         from, n, rig, bridge, rec0, rec1, 100 * bridge / rig, 100 * (bridge + feed) / rig }' "$work/figures"
