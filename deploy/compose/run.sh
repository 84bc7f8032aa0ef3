#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The rig in Docker containers, one per component (as root, or a docker user):
#   deploy/compose/run.sh SCENARIO OUTDIR [flatsat run options, e.g. --set duration_s=60]
# Builds the image when needed, brings up deploy/compose/docker-compose.yml on
# an internal network of its own, runs SCENARIO in lockstep to its end and
# leaves OUTDIR/summary.json (the keys of `flatsat run`), recording.sqlite,
# scenario.yaml, logs/<service>.log and logs/<service>.health.json (the
# container health checks' results). Exit status: the launcher's (0 done,
# 1 failed, 2 bad input); 1 too when a container dies or the run times out.
# The compose file holds the default scenario's components; a scenario with
# others fails with the launcher naming the components that never joined.
#
# Environment:
#   FLATSAT_COMPOSE_DISCOVERY  server (default): Fast DDS discovery server,
#                              no multicast needed; multicast: SPDP multicast
#                              on the compose network
#   FLATSAT_COMPOSE_NO_MULTICAST=1  drop every IPv4 multicast datagram on the
#                              rig's bridge (nftables), to show a rig does
#                              without it; prints how many were dropped
#   FLATSAT_IMAGE              image to run (default flatsat:local). Built
#                              from FLATSAT_BUILD_DIR (default build/) when
#                              that holds a build, else from the sources
#   FLATSAT_BASE_IMAGE         base of a new image (default: made by
#                              deploy/docker/make-base.sh with debootstrap)
#   FLATSAT_RIG_ID             names the compose project and bridge (default pid)
#   FLATSAT_COMPOSE_TIMEOUT_S  wall-clock limit of the run (default 3600)
#   FLATSAT_DOMAIN, DOCKER (docker client), DOCKER_COMPOSE (compose command)
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 SCENARIO OUTDIR [flatsat run options]" >&2
  exit 2
fi
scenario=$1 out=$2
shift 2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
docker="${DOCKER:-docker}"
read -r -a compose <<<"${DOCKER_COMPOSE:-docker-compose}"
id="${FLATSAT_RIG_ID:-$$}"
project="flatsat$id"
bridge="fsrig$id"
discovery="${FLATSAT_COMPOSE_DISCOVERY:-server}"
image="${FLATSAT_IMAGE:-flatsat:local}"
build_dir="${FLATSAT_BUILD_DIR:-$here/build}"
timeout_s="${FLATSAT_COMPOSE_TIMEOUT_S:-3600}"

[ -f "$scenario" ] || { echo "$0: $scenario: no such scenario file" >&2; exit 2; }
[ ${#bridge} -le 15 ] || { echo "$0: FLATSAT_RIG_ID=$id is too long for a bridge name" >&2; exit 2; }
"$docker" info >/dev/null 2>&1 || {
  echo "$0: no Docker engine answers (start it: dockerd &)" >&2
  exit 2
}

# --- the image ---------------------------------------------------------------
base="${FLATSAT_BASE_IMAGE:-flatsat-base:bookworm}"
[ -n "${FLATSAT_BASE_IMAGE:-}" ] || DOCKER="$docker" "$here/deploy/docker/make-base.sh" "$base"
if [ -x "$build_dir/bin/flatsat" ]; then
  # Always from this build: the image never lags behind the executables.
  staging=$(mktemp -d /tmp/flatsat-staging.XXXXXX)
  "$here/deploy/docker/stage.sh" "$build_dir" "$staging"
  "$docker" build -q -f "$here/deploy/docker/Dockerfile" --target prebuilt \
    --build-arg BASE="$base" -t "$image" "$staging" >/dev/null
  rm -rf "$staging"
elif ! "$docker" image inspect "$image" >/dev/null 2>&1; then
  "$docker" build -f "$here/deploy/docker/Dockerfile" --build-arg BASE="$base" -t "$image" "$here"
fi

# --- the rig -----------------------------------------------------------------
mkdir -p "$out"
out=$(cd "$out" && pwd)
rig=$(mktemp -d /tmp/flatsat-rig.XXXXXX)
cp "$scenario" "$rig/scenario.yaml"
printf '%s\n' "$@" >"$rig/launcher.args"
chmod -R a+rX "$rig"

export FLATSAT_IMAGE="$image" FLATSAT_OUT="$out" FLATSAT_RIG_DIR="$rig" FLATSAT_BRIDGE="$bridge"
case "$discovery" in
  server) export FLATSAT_DISCOVERY_SERVER=discovery:11811 FLATSAT_NETWORK= ;;
  multicast) export FLATSAT_NETWORK=1 FLATSAT_DISCOVERY_SERVER= ;;
  *) echo "$0: FLATSAT_COMPOSE_DISCOVERY=$discovery: server or multicast" >&2; exit 2 ;;
esac
dc() { "${compose[@]}" -p "$project" -f "$here/deploy/compose/docker-compose.yml" "$@"; }

declare -A containers  # service -> container id, once compose made them
nft_table="flatsat_$id"
# Docker drops whatever an internal network's bridge forwards to an address
# outside its subnet (DOCKER-ISOLATION-STAGE-1), multicast groups included:
# multicast discovery needs it let through, from the rig's bridge to itself only.
multicast_within_rig=(-i "$bridge" -o "$bridge" -d 224.0.0.0/4 -j ACCEPT)
cleanup() {
  mkdir -p "$out/logs"
  for service in "${!containers[@]}"; do
    "$docker" logs "${containers[$service]}" >"$out/logs/$service.log" 2>&1 || true
    # The health checks' results (probes of the health topic), kept for review.
    "$docker" inspect -f '{{json .State.Health}}' "${containers[$service]}" \
      >"$out/logs/$service.health.json" 2>/dev/null || true
  done
  dc down --volumes --remove-orphans >/dev/null 2>&1 || true
  nft delete table ip "$nft_table" 2>/dev/null || true
  [ "$discovery" = multicast ] && iptables -D DOCKER-USER "${multicast_within_rig[@]}" 2>/dev/null
  true
  rm -rf "$rig"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

dc up --no-start >/dev/null 2>&1 || dc up --no-start
if [ "${FLATSAT_COMPOSE_NO_MULTICAST:-0}" = 1 ]; then
  # Docker's bridges run with br_netfilter: frames bridged between two
  # containers pass the IPv4 forward hook with the bridge as their input
  # interface, frames to the host the input hook. Drop IPv4 multicast at both,
  # before Docker's own rules (ARP and unicast go on).
  nft -f - <<NFT
table ip $nft_table {
  chain forward {
    type filter hook forward priority -10; policy accept;
    iifname "$bridge" ip daddr 224.0.0.0/4 meta l4proto udp counter drop
    iifname "$bridge" ip daddr 224.0.0.0/4 counter drop
  }
  chain input {
    type filter hook input priority -10; policy accept;
    iifname "$bridge" ip daddr 224.0.0.0/4 meta l4proto udp counter drop
    iifname "$bridge" ip daddr 224.0.0.0/4 counter drop
  }
}
NFT
  echo "compose rig: IPv4 multicast dropped on bridge $bridge" >&2
fi
if [ "$discovery" = multicast ] && [ "${FLATSAT_COMPOSE_NO_MULTICAST:-0}" != 1 ]; then
  iptables -I DOCKER-USER 1 "${multicast_within_rig[@]}"
fi
echo "compose rig $project: discovery $discovery, bridge $bridge, out $out" >&2
# A launcher that refuses the scenario never becomes healthy and compose says
# so; its exit status and log below tell why.
dc up -d >"$rig/up.log" 2>&1 || true

# The launcher ends the run; a component container that exits with an error
# ends it too (the launcher would wait for it until its join limit).
while read -r container service; do
  containers[$service]=$container
done < <("$docker" ps -a --filter "label=com.docker.compose.project=$project" \
           --format '{{.ID}} {{.Label "com.docker.compose.service"}}')
launcher=${containers[launcher]:-}
if [ -z "$launcher" ]; then
  cat "$rig/up.log" >&2
  exit 1
fi
rc=""
start=$SECONDS
all_done_at=""
while [ -z "$rc" ]; do
  if [ "$("$docker" inspect -f '{{.State.Status}}' "$launcher")" = exited ]; then
    rc=$("$docker" inspect -f '{{.State.ExitCode}}' "$launcher")
    break
  fi
  running=0
  for service in "${!containers[@]}"; do
    [ "$service" = launcher ] || [ "$service" = discovery ] && continue
    container=${containers[$service]}
    read -r status code < <("$docker" inspect -f '{{.State.Status}} {{.State.ExitCode}}' "$container")
    if [ "$status" = running ] || [ "$status" = created ] || [ "$status" = restarting ]; then
      running=$((running + 1))
    elif [ "$code" != 0 ]; then
      echo "$0: $service exited with code $code; its last lines:" >&2
      "$docker" logs --tail 8 "$container" 2>&1 | sed 's/^/    /' >&2
      rc=1
    fi
  done
  # Every component finished: the launcher has its last health samples within
  # seconds, or never will.
  if [ "$running" -eq 0 ] && [ -z "$rc" ]; then
    all_done_at=${all_done_at:-$SECONDS}
    if [ $((SECONDS - all_done_at)) -gt 30 ]; then
      echo "$0: every component exited but the launcher still waits for them after 30 s" >&2
      rc=1
    fi
  fi
  if [ $((SECONDS - start)) -gt "$timeout_s" ]; then
    echo "$0: the run took more than $timeout_s s; stopping it" >&2
    rc=1
  fi
  [ -n "$rc" ] || sleep 1
done
"$docker" logs "$launcher" 2>&1 | tail -n 40 >&2 || true
if [ "${FLATSAT_COMPOSE_NO_MULTICAST:-0}" = 1 ]; then
  # UDP is what multicast discovery (SPDP to 239.255.0.1) would send; the rest
  # is the kernel's own IGMP membership reports.
  nft list table ip "$nft_table" | awk -v bridge="$bridge" '
    /counter packets/ { n = $0; sub(/.*counter packets /, "", n); sub(/ .*/, "", n)
                        if ($0 ~ /l4proto udp/) udp += n; else other += n }
    END { printf "compose rig: IPv4 multicast dropped on %s: %d UDP datagrams, %d others (IGMP)\n",
                 bridge, udp, other }' >&2
fi
exit "$rc"
