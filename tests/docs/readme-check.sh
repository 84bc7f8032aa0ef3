#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Every command in the README, run as a newcomer would run it. Each ```sh
# block of README.md must follow a marker saying how this test treats it:
#   <!-- readme-test: run -->          run here, in order, in one bash session
#                                      (so `export` and `&` carry on), every
#                                      command to exit 0
#   <!-- readme-test: ci (why) -->     not run here, and why (`rig.sh test`
#                                      is the suite itself: .ci/run runs it)
# A block without a marker fails the test: no command goes untried unsaid.
#   usage: tests/docs/readme-check.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source=$(cd "$1" && pwd -P)
build=$(cd "$2" && pwd -P)
readme="$source/README.md"
fail() { echo "FAIL: $*" >&2; exit 1; }

work=$(mktemp -d /tmp/flatsat-readme.XXXXXX)
script="$work/readme.sh"
cleanup() {
  # A block's background rig, if a command failed before it was stopped.
  pkill -INT -f -- "--out runs/live" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

# The blocks, with their markers, as one script (awk: a marker arms the next block).
awk -v out="$script" '
  /^<!-- readme-test: / { mode = $3; sub(/ -->$/, "", mode); next }
  /^```sh$/ {
    if (mode == "") { printf "README.md:%d: a sh block with no readme-test marker\n", NR > "/dev/stderr"; bad = 1 }
    inside = 1; run = (mode == "run"); if (run) print "echo \"+ README.md:" NR + 1 "\"" >> out
    blocks[mode]++; mode = ""; next
  }
  /^```$/ { inside = 0; next }
  inside && run { print >> out }
  END {
    for (m in blocks) printf "%s: %d blocks\n", m, blocks[m] > "/dev/stderr"
    exit bad
  }' "$readme" || fail "README.md has sh blocks this test does not know how to treat"
[ -s "$script" ] || fail "README.md has no block to run"

# A folder of the newcomer's own: the checkout's entries, runs/ written here.
for entry in "$source"/*; do ln -s "$entry" "$work/$(basename "$entry")"; done
rm -f "$work/build" && ln -s "$build" "$work/build"
cd "$work"
source "$source/tests/support/test-domain.sh"  # FLATSAT_DOMAIN, held
export FLATSAT_BUILD_DIR="$build"
echo "running $(grep -vc '^echo "+ README' "$script") README commands in $work on domain $FLATSAT_DOMAIN"
SECONDS=0
# errexit: the first command that fails ends the test, naming its line.
bash -e -o pipefail "$script" 2>&1 | tee "$work/readme.log" ||
  fail "a README command failed (the last '+ README.md:N' above is its block)"
echo "every README command ran and exited 0 ($SECONDS s)"
grep -q '^exit status 130$' "$work/readme.log" || fail "the interrupted live run did not exit 130"
[ -s runs/tour/run.mcap ] || fail "the tour's MCAP export is missing"
grep -q '"completed": false' runs/live/summary.json || fail "the interrupted live run's summary does not say completed: false"
ls build/flatsat_*_amd64.deb >/dev/null || fail "rig.sh package made no .deb"
