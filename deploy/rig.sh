#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# One entry point for a fresh Debian 12 machine (as root) or a developer box:
#   deploy/rig.sh run [SCENARIO] [flatsat run options]  install, build, run (default scenario)
#   deploy/rig.sh test                                   install, build, run every test (each
#                                                        fuzz target for 30 s among them)
#   deploy/rig.sh package                                install, build, make the Debian package
#                                                        build/flatsat_<version>_amd64.deb
#   deploy/rig.sh fuzz [SECONDS]                         libFuzzer build (clang), each fuzz
#                                                        target for SECONDS (default 600)
#   deploy/rig.sh build | deps                           just those steps
# Safe to re-run: it installs only what is missing and builds incrementally.
set -euo pipefail
# The checkout this script is in, through any symlink to it (a folder of
# links to a checkout must not become a second source tree of its build).
here=$(cd "$(dirname "$(readlink -f "${BASH_SOURCE[0]}")")/.." && pwd -P)
build="${FLATSAT_BUILD_DIR:-$here/build}"
# ccache (when installed) keys on paths relative to the checkout: a fresh
# clone elsewhere (CI) reuses what another clone compiled.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$here}"
jobs="${FLATSAT_JOBS:-2}"

packages=(
  build-essential cmake pkg-config
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools
  libeigen3-dev catch2 libspdlog-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev
  libsqlite3-dev sqlite3 libssl-dev openssl libzstd-dev libwebsocketpp-dev libasio-dev
  iproute2 tcpdump procps
  python3 gnuplot-nox
)
# Only for `test`: the compose rig's engine, base image and network filter, a
# single-node Slurm cluster for
# `flatsat mc --slurm` (deploy/slurm/local-cluster.sh; its daemons start only
# in that test), and Node.js for the interop tier's published readers
# (tests/interop: npm ci of its package-lock.json).
test_packages=(docker.io docker-compose debootstrap nftables munge slurmctld slurmd slurm-client help2man)
# Only for `package` (and the package tests): man pages from each --help.
package_packages=(help2man dpkg-dev)
# Node.js from Debian unless one is installed already (another vendor's
# nodejs carries its own npm, and Debian's npm would conflict with it).
command -v npm >/dev/null 2>&1 || test_packages+=(nodejs npm)
# Only for `fuzz` and `test`: clang with libFuzzer and the sanitizer runtimes.
fuzz_packages=(clang libclang-rt-14-dev)
fuzz_build="${FLATSAT_FUZZ_BUILD_DIR:-$here/build-fuzz}"

deps() {
  local missing=()
  for p in "${packages[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "rig.sh: installing ${missing[*]}" >&2
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
}

# The Docker engine for the compose rig test, started when installed and not
# running (as root); the test says it skipped when none answers.
start_docker() {
  docker info >/dev/null 2>&1 && return 0
  [ "$(id -u)" -eq 0 ] && command -v dockerd >/dev/null || return 0
  echo "rig.sh: starting the Docker engine (log: /tmp/flatsat-dockerd.log)" >&2
  nohup dockerd >/tmp/flatsat-dockerd.log 2>&1 &
  for _ in $(seq 60); do
    docker info >/dev/null 2>&1 && return 0
    sleep 0.5
  done
  echo "rig.sh: the Docker engine did not start; the compose rig test will skip" >&2
}

build() {
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DFLATSAT_TEST_CORES="$jobs" >/dev/null
  cmake --build "$build" -j"$jobs"
}

# The fuzzers, in their own folder: everything they compile is instrumented
# (ASan, UBSan, coverage). -O1 and line tables only: it builds in minutes.
build_fuzzers() {
  CXX=clang++ cmake -S "$here" -B "$fuzz_build" -DCMAKE_BUILD_TYPE=None \
    -DCMAKE_CXX_FLAGS="-O1 -gline-tables-only" -DFLATSAT_FUZZ=ON -DFLATSAT_FUZZ_SECONDS="$1" >/dev/null
  cmake --build "$fuzz_build" -j"$jobs" --target fuzz_all
}

cmd="${1:-run}"
[ $# -gt 0 ] && shift
case "$cmd" in
  deps) deps ;;
  build) deps; build ;;
  run)
    deps; build
    scenario="$here/deploy/scenarios/default.yaml"
    if [ $# -gt 0 ] && [[ "$1" != -* ]]; then scenario="$1"; shift; fi
    exec "$build/bin/flatsat" run "$scenario" "$@"
    ;;
  package)
    deps "${package_packages[@]}"; build
    cmake --build "$build" --target deb
    ls "$build"/flatsat_*_amd64.deb
    ;;
  fuzz)
    deps "${fuzz_packages[@]}"
    build_fuzzers "${1:-600}"
    cd "$fuzz_build"
    exec ctest --output-on-failure -R '^fuzz\.' --timeout 100000
    ;;
  test)
    deps "${test_packages[@]}" "${fuzz_packages[@]}"; build
    build_fuzzers 30
    # The suite runs those fuzzers too (fuzz.<target>), 30 s each: the whole
    # suite then stays under 20 minutes on two cores.
    cmake -S "$here" -B "$build" -DFLATSAT_FUZZERS_DIR="$fuzz_build/bin" -DFLATSAT_FUZZ_SECONDS=30 >/dev/null
    start_docker
    # The interop tier's published readers (tests/interop/package-lock.json); if the
    # npm registry cannot be reached, that tier fails and says so, the rest still runs.
    npm ci --prefix "$here/tests/interop" --no-audit --no-fund >&2 ||
      echo "rig.sh: npm ci failed in tests/interop; interop.* will fail" >&2
    cd "$build"
    # Every test holds a core of this resource spec, so $jobs run at once, and
    # a paced one holds them all; the one slot more is for the soak (10 min
    # paced), which holds none.
    printf '{"version": {"major": 1, "minor": 0}, "local": [{"cores": [{"id": "0", "slots": %d}]}]}\n' \
      "$jobs" > ctest-resources.json
    exec ctest --output-on-failure -j"$((jobs + 1))" --timeout 1500 --resource-spec-file ctest-resources.json
    ;;
  *) echo "usage: $0 run [SCENARIO] [options] | test | package | fuzz [SECONDS] | build | deps" >&2; exit 2 ;;
esac
