#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The rig across hosts, without Docker (as root):
#   deploy/netns/run.sh SCENARIO OUTDIR [flatsat run options, e.g. --set duration_s=60]
# Makes its own network namespaces, joined by one bridge, and runs SCENARIO
# in lockstep with the components spread over them; the bus goes over UDP
# between the namespaces' addresses (FLATSAT_PEERS: unicast discovery, no
# multicast, no shared memory). Leaves OUTDIR/summary.json as `flatsat run`
# does. The namespaces go away on exit, after a failure or a signal too.
#
#   fs-ID-sw   the bridge (no address: the segment touches nothing else)
#   fs-ID-srv  NET.1  launcher, dynamics_server, recorder
#   fs-ID-sns  NET.2  the sensors
#   fs-ID-ctl  NET.3  every other component (estimator, controllers, ...)
#   fs-ID-ext  NET.4  nothing: for components marked external, started by hand
#
# Environment: FLATSAT_BIN_DIR (default build/bin), FLATSAT_RIG_ID (default
# the script's pid), FLATSAT_RIG_NET (first three octets, default 10.213.7),
# FLATSAT_RIG_CAPTURE=FILE.pcap (capture the UDP crossing the bridge into FILE),
# FLATSAT_RIG_EXTRA_PEERS=a,b (more hosts on the segment, e.g. a real machine
# whose NIC is added to the bridge), FLATSAT_DOMAIN (as for flatsat run).
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 SCENARIO OUTDIR [flatsat run options]" >&2
  exit 2
fi
scenario=$1 out=$2
shift 2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
bin="${FLATSAT_BIN_DIR:-$here/build/bin}"
id="${FLATSAT_RIG_ID:-$$}"
net="${FLATSAT_RIG_NET:-10.213.7}"
ns="fs-$id"
hosts=(srv sns ctl ext)  # host i (from 1) has address NET.i
peers="$net.1,$net.2,$net.3,$net.4${FLATSAT_RIG_EXTRA_PEERS:+,$FLATSAT_RIG_EXTRA_PEERS}"
sensors=(magnetometer sun_sensor gyro wheel_tach)

if [ "$(id -u)" -ne 0 ]; then
  echo "$0: needs root (ip netns)" >&2
  exit 2
fi
for h in sw "${hosts[@]}"; do
  if [ -e "/var/run/netns/$ns-$h" ]; then
    echo "$0: namespace $ns-$h exists: another rig with FLATSAT_RIG_ID=$id?" >&2
    exit 2
  fi
done

capture=""
cleanup() {
  [ -n "$capture" ] && kill -INT "$capture" 2>/dev/null && wait "$capture" 2>/dev/null
  for h in sw "${hosts[@]}"; do ip netns del "$ns-$h" 2>/dev/null || true; done
}
trap cleanup EXIT

ip netns add "$ns-sw"
ip -n "$ns-sw" link add br0 type bridge
ip -n "$ns-sw" link set br0 up
i=1
for h in "${hosts[@]}"; do
  ip netns add "$ns-$h"
  ip -n "$ns-sw" link add "$h" type veth peer name eth0 netns "$ns-$h"
  ip -n "$ns-sw" link set "$h" master br0 up
  ip -n "$ns-$h" addr add "$net.$i/24" dev eth0
  ip -n "$ns-$h" link set eth0 up
  ip -n "$ns-$h" link set lo up
  i=$((i + 1))
done

if [ -n "${FLATSAT_RIG_CAPTURE:-}" ]; then
  # On every bridge port: br0 itself sees only what is addressed to the
  # bridge, not what it forwards. Each datagram shows twice (in and out).
  ip netns exec "$ns-sw" tcpdump -i any -n -p -U -w "$FLATSAT_RIG_CAPTURE" udp 2>/dev/null &
  capture=$!
  sleep 1  # tcpdump listens before the first packet
fi

echo "netns rig $ns: srv $net.1, sns $net.2, ctl $net.3, ext $net.4; FLATSAT_PEERS=$peers" >&2
prefixes=(--prefix "*=ip netns exec $ns-ctl")
for c in dynamics_server recorder; do prefixes+=(--prefix "$c=ip netns exec $ns-srv"); done
for c in "${sensors[@]}"; do prefixes+=(--prefix "$c=ip netns exec $ns-sns"); done

ip netns exec "$ns-srv" env FLATSAT_PEERS="$peers" \
  "$bin/flatsat" run "$scenario" --out "$out" "${prefixes[@]}" "$@" &
launcher=$!
# A signal to this script stops the run the way Ctrl-C stops flatsat run.
trap 'kill -TERM $launcher 2>/dev/null' INT TERM
rc=0
wait "$launcher" || rc=$?
while kill -0 "$launcher" 2>/dev/null; do  # the wait above was cut short by a signal
  rc=0
  wait "$launcher" || rc=$?
done
exit "$rc"
