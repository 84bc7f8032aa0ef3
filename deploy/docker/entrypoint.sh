#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The flatsat image's entry point (installed as flatsat-container):
#   COMPONENT            run flatsat-COMPONENT on the rig's resolved scenario
#   launcher [ARGS]      flatsat run with every component external (each in a
#                        container of its own); ARGS, and the lines of
#                        /rig/launcher.args, go to flatsat run
#   discovery-server     Fast DDS discovery server 0 on this container's
#                        address, port FLATSAT_DISCOVERY_PORT (11811)
#   anything else        run as a command (flatsat health, bash, ...)
# The run directory is /out (FLATSAT_OUT); the user's scenario is
# /rig/scenario.yaml (FLATSAT_SCENARIO); the launcher resolves it into
# /out/scenario.yaml, which every component reads.
set -euo pipefail
out="${FLATSAT_OUT:-/out}"
resolved="$out/scenario.yaml"

case "${1:-}" in
  launcher)
    shift
    extra=()
    if [ -f /rig/launcher.args ]; then mapfile -t extra </rig/launcher.args; fi
    exec flatsat run "${FLATSAT_SCENARIO:-/rig/scenario.yaml}" --out "$out" --external '*' \
      --no-plots "${extra[@]}" "$@"
    ;;
  discovery-server)
    shift
    address=$(hostname -i | cut -d' ' -f1)
    exec fast-discovery-server -i 0 -l "$address" -p "${FLATSAT_DISCOVERY_PORT:-11811}" "$@"
    ;;
  "" | -h | --help)
    sed -n '3,13p' "$0" | sed 's/^# \{0,1\}//'
    exit 0
    ;;
esac

if [ -x "/usr/local/bin/flatsat-$1" ] || command -v "flatsat-$1" >/dev/null 2>&1; then
  name=$1
  shift
  # The launcher writes the resolved scenario at once (renamed into place, so
  # it is whole when it appears); compose starts components after it.
  for _ in $(seq 600); do
    [ -f "$resolved" ] && break
    sleep 0.1
  done
  [ -f "$resolved" ] || { echo "flatsat-container: $resolved did not appear within 60 s" >&2; exit 2; }
  exec "flatsat-$name" --scenario "$resolved" --name "$name" --out "$out" \
    --log "${FLATSAT_LOG_LEVEL:-info}" "$@"
fi
exec "$@"
