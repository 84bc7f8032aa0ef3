#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Lays out what the runtime image holds, from a finished build:
#   deploy/docker/stage.sh BUILD_DIR STAGING_DIR
# STAGING_DIR/ gets the installed tree (executables, data, scenarios under the
# build's install prefix), the Fast DDS discovery server, the container entry
# point, and every shared library those executables load except glibc's own
# (the base image has glibc: both are Debian 12), under lib/flatsat of the
# prefix with an ld.so.conf.d entry. Used by the Dockerfile's build stage and,
# with a build made on this machine, by deploy/compose/run.sh.
set -euo pipefail
build=$(cd "$1" && pwd)
staging=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
prefix=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$build/CMakeCache.txt")
rm -rf "$staging"
mkdir -p "$staging"
staging=$(cd "$staging" && pwd)
DESTDIR="$staging" cmake --install "$build" >/dev/null
bin="$staging$prefix/bin"
lib="$staging$prefix/lib/flatsat"
mkdir -p "$lib" "$staging/etc/ld.so.conf.d"
discovery=$(command -v fast-discovery-server) || {
  echo "$0: fast-discovery-server is missing (apt-get install fastdds-tools)" >&2
  exit 2
}
cp "$discovery" "$bin/"
install -m 0755 "$here/entrypoint.sh" "$bin/flatsat-container"
echo "$prefix/lib/flatsat" >"$staging/etc/ld.so.conf.d/flatsat.conf"

glibc='^(libc|libm|libpthread|libdl|librt|libresolv|libutil|libanl|ld-linux[-a-z0-9_]*)\.so'
for exe in "$bin"/*; do
  [ "$(head -c 4 "$exe" | tail -c 3)" = ELF ] || continue
  ldd "$exe" | awk '$2 == "=>" && $3 ~ /^\// { print $3 }'
done | sort -u | while read -r so; do
  name=$(basename "$so")
  [[ "$name" =~ $glibc ]] && continue
  cp -L "$so" "$lib/$name"
done
echo "stage: $(find "$staging" -type f | wc -l) files, $(du -sh "$staging" | cut -f1) in $staging" >&2
