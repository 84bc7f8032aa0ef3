#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Prints the Debian archive this machine already installs from (the first
# http(s) one in its apt sources): the only archive a debootstrap here may
# reach. FLATSAT_DEBIAN_MIRROR, when set, is printed instead. There is no
# fallback: with neither, it says so and exits 2.
set -euo pipefail
if [ -n "${FLATSAT_DEBIAN_MIRROR:-}" ]; then
  echo "$FLATSAT_DEBIAN_MIRROR"
  exit 0
fi
mirror=$(grep -hoE '^(URIs:|deb) +https?://[^ ]+/debian/?( |$)' /etc/apt/sources.list \
           /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources 2>/dev/null |
         grep -oE 'https?://[^ ]+' | head -n1 || true)
if [ -z "$mirror" ]; then
  echo "$0: no http(s) Debian archive in /etc/apt/sources.list{,.d/*}: set FLATSAT_DEBIAN_MIRROR" >&2
  exit 2
fi
echo "$mirror"
