#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The Debian package as a user gets it: build/flatsat_<version>_amd64.deb
# (made here by `deploy/rig.sh package`, as the README says),
# installed with apt into a clean Debian 12 minbase root (debootstrap), with
# no source or build tree in sight. There, in a network namespace of its own
# (only lo) and a private /dev/shm:
#   flatsat --version           the build tree's version
#   flatsat field ...           the build tree's figures (data found under /usr/share/flatsat)
#   flatsat run default --composed / as processes (lockstep): both the
#                               build tree's recording_sha256
#   man page and bash completion present and working
#   usage: tests/package/install-check.sh BUILD_DIR
# Exit 77 (skipped) without root or debootstrap.
set -euo pipefail
build=$(cd "$1" && pwd)
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
fail() { echo "FAIL: $*" >&2; exit 1; }
if [ "$(id -u)" -ne 0 ] || ! command -v debootstrap >/dev/null || ! command -v unshare >/dev/null; then
  echo "skipped: needs root, debootstrap and unshare" >&2
  exit 77
fi

# As the README says to make it.
FLATSAT_BUILD_DIR="$build" bash "$here/deploy/rig.sh" package >/dev/null
deb=$(ls "$build"/flatsat_*_amd64.deb)
echo "package: $deb ($(du -h "$deb" | cut -f1))"

root=$(mktemp -d /tmp/flatsat-package-root.XXXXXX)
trap 'rm -rf "$root"' EXIT
mirror=$(bash "$here/deploy/debian-mirror.sh")
start=$(date +%s)
debootstrap --variant=minbase bookworm "$root" "$mirror" >"$root.log" 2>&1 || {
  tail -n 20 "$root.log" >&2
  rm -f "$root.log"
  fail "debootstrap from $mirror"
}
rm -f "$root.log"
echo "debootstrap: $(($(date +%s) - start)) s"
cp "$deb" "$root/tmp/"
cp /etc/resolv.conf "$root/etc/resolv.conf"

# Every mount lives in this private mount namespace and goes with it.
in_root() {
  unshare --mount --propagation private "$@" -- bash -c '
    set -e
    root=$1; shift
    mount -t proc proc "$root/proc"
    mount --bind /dev "$root/dev"
    mount -t tmpfs -o size=512m tmpfs "$root/dev/shm"
    if [ -n "${NETNS_LO:-}" ]; then ip link set lo up; fi
    exec chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 "$@"
  ' in_root "$root" "${ARGS[@]}"
}

start=$(date +%s)
ARGS=(sh -c "apt-get -o APT::Sandbox::User=root update -qq && DEBIAN_FRONTEND=noninteractive apt-get -o APT::Sandbox::User=root install -y -qq --no-install-recommends /tmp/$(basename "$deb") >/tmp/apt.log 2>&1 || { tail -n 30 /tmp/apt.log; exit 1; }")
in_root || fail "apt-get install of the package into the minbase root"
echo "apt-get install: $(($(date +%s) - start)) s"
[ -e "$root$here" ] && fail "the source tree is visible in the root"

# The rest runs with no network but lo: the rig's DDS stays in there.
NETNS_LO=1
export NETNS_LO
run_in_root() { ARGS=("$@"); in_root --net; }

version_here=$("$build/bin/flatsat" --version)
version_there=$(run_in_root flatsat --version)
[ "$version_there" = "$version_here" ] || fail "flatsat --version: '$version_there', the build's '$version_here'"
echo "flatsat --version: $version_there"

field=(field --lat 48.1 --lon 11.6 --alt-km 560 --date 2026.5)
field_here=$("$build/bin/flatsat" "${field[@]}")
field_there=$(run_in_root flatsat "${field[@]}") || fail "flatsat field in the root"
[ "$field_there" = "$field_here" ] || fail "flatsat field differs: $field_there"
echo "flatsat field: as the build tree"

sets=(--set duration_s=120 --set duration_orbits=null -q --no-plots)
domain=$(( ($$ % 150) + 60 ))
reference=$(mktemp -d /tmp/flatsat-package-ref.XXXXXX)
trap 'rm -rf "$root" "$reference"' EXIT
"$build/bin/flatsat" run default --composed --out "$reference/c" "${sets[@]}" >/dev/null
sha() { sed -n 's/.*"recording_sha256": *"\([0-9a-f]*\)".*/\1/p' "$1"; }
want=$(sha "$reference/c/summary.json")
[ -n "$want" ] || fail "no recording_sha256 in the build tree's summary"
for how in composed processes; do
  extra=()
  [ "$how" = composed ] && extra=(--composed)
  SECONDS=0
  run_in_root env FLATSAT_DOMAIN=$domain flatsat run default "${extra[@]}" --out /tmp/run-$how "${sets[@]}" ||
    fail "flatsat run default ($how) in the root"
  got=$(sha "$root/tmp/run-$how/summary.json")
  [ "$got" = "$want" ] || fail "recording_sha256 ($how): $got, the build tree's $want"
  grep -q '"completed": *true' "$root/tmp/run-$how/summary.json" || fail "the $how run did not complete"
  echo "flatsat run default ($how): recording_sha256 $got as the build tree ($SECONDS s)"
done

[ -s "$root/usr/share/man/man1/flatsat.1.gz" ] || fail "no man page flatsat.1.gz"
zcat "$root/usr/share/man/man1/flatsat.1.gz" | grep -q '^\.SS "flatsat run"' || fail "flatsat.1 lacks its COMMANDS"
completion=$(run_in_root bash -c 'source /usr/share/bash-completion/completions/flatsat
  COMP_WORDS=(flatsat run def); COMP_CWORD=2; _flatsat; echo "${COMPREPLY[*]}"')
[ "$completion" = default ] || fail "bash completion of 'flatsat run def': '$completion'"
echo "man page and bash completion: present ('flatsat run def' completes to '$completion')"
echo "ok: the package installs with apt into a clean Debian 12 root and runs there"
