#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# A local Debian 12 base image for machines that reach Debian's archive but no
# image registry (as root):
#   deploy/docker/make-base.sh [IMAGE]        (default flatsat-base:bookworm)
# debootstrap --variant=minbase into a temporary folder, then `docker import`.
# Does nothing when IMAGE exists. The Dockerfile takes it as
# --build-arg BASE=IMAGE; with a registry, BASE defaults to debian:bookworm-slim.
# Environment: FLATSAT_DEBIAN_MIRROR (default: the first http(s) archive in
# this machine's apt sources, deploy/debian-mirror.sh; there is no other), DOCKER.
set -euo pipefail
image="${1:-flatsat-base:bookworm}"
docker="${DOCKER:-docker}"
if "$docker" image inspect "$image" >/dev/null 2>&1; then
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "$0: needs root (debootstrap)" >&2
  exit 2
fi
command -v debootstrap >/dev/null || {
  echo "$0: debootstrap is missing (apt-get install debootstrap)" >&2
  exit 2
}
mirror=$(bash "$(dirname "${BASH_SOURCE[0]}")/../debian-mirror.sh")
root=$(mktemp -d /tmp/flatsat-base.XXXXXX)
trap 'rm -rf "$root"' EXIT
echo "make-base: debootstrap bookworm from $mirror" >&2
debootstrap --variant=minbase bookworm "$root" "$mirror" >"$root.log" 2>&1 || {
  tail -n 20 "$root.log" >&2
  rm -f "$root.log"
  exit 1
}
rm -f "$root.log"
# Slim like debian:bookworm-slim: no apt lists or caches in the image.
rm -rf "$root"/var/lib/apt/lists/* "$root"/var/cache/apt/*.bin "$root"/var/cache/apt/archives/*.deb
tar -C "$root" -c . | "$docker" import --change 'CMD ["/bin/bash"]' - "$image" >/dev/null
echo "make-base: $image" >&2
