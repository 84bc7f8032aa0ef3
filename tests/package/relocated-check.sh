#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# An install moved to a prefix the build never saw works: `cmake --install
# BUILD --prefix P`, then P/bin/flatsat, from another folder, finds its
# scenarios and data under P/share/flatsat (and FLATSAT_SCENARIO_PATH /
# FLATSAT_DATA_DIR first); no executable holds a path of the build machine.
#   usage: tests/package/relocated-check.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
source=$(cd "$2" && pwd)
fail() { echo "FAIL: $*" >&2; exit 1; }
prefix=$(mktemp -d /tmp/flatsat-prefix.XXXXXX)
elsewhere=$(mktemp -d /tmp/flatsat-cwd.XXXXXX)
trap 'rm -rf "$prefix" "$elsewhere"' EXIT
cmake --install "$build" --prefix "$prefix" >/dev/null

for exe in "$prefix"/bin/*; do
  if grep -q -a -F -e "$source" -e "$build" "$exe"; then
    fail "$exe holds a path of the build machine: $(grep -a -o -F -e "$source" -e "$build" "$exe" | head -1)"
  fi
done
echo "no build-machine path in $(ls "$prefix/bin" | wc -l) executables"

cd "$elsewhere"
flatsat="$prefix/bin/flatsat"
out=$("$flatsat" check default) || fail "flatsat check default: $out"
[ "$out" = "$prefix/share/flatsat/scenarios/default.yaml: ok (9 components)" ] || fail "check default: '$out'"
"$flatsat" field --lat 0 --lon 0 --alt-km 500 --date 2026.0 >/dev/null || fail "flatsat field from the moved install"
"$flatsat" run default --composed --out run -q --no-plots --set duration_s=20 --set duration_orbits=null ||
  fail "flatsat run default from the moved install"
echo "check, field and run default from $prefix: ok"

# The user's own folders come first.
mkdir -p mine data/igrf
sed 's/^name: default$/name: mine/' "$prefix/share/flatsat/scenarios/default.yaml" >mine/default.yaml
out=$(FLATSAT_SCENARIO_PATH="$elsewhere/mine" "$flatsat" check default)
[ "$out" = "$elsewhere/mine/default.yaml: ok (9 components)" ] || fail "FLATSAT_SCENARIO_PATH: '$out'"
: >data/igrf/igrf14coeffs.txt  # an empty table: the error proves it was this one that was read
if err=$(FLATSAT_DATA_DIR="$elsewhere/data" "$flatsat" field --lat 0 --lon 0 --alt-km 500 --date 2026.0 2>&1); then
  fail "FLATSAT_DATA_DIR was not read first: $err"
fi
echo "FLATSAT_SCENARIO_PATH and FLATSAT_DATA_DIR come first: ok"

err=$("$flatsat" run nonesuch 2>&1) && fail "run nonesuch succeeded"
rc=$("$flatsat" run nonesuch >/dev/null 2>&1; echo $?) || true
[ "$rc" = 2 ] || fail "run nonesuch exit $rc, not 2"
grep -q "no scenario of that name in $prefix/share/flatsat/scenarios" <<<"$err" || fail "run nonesuch says: $err"
echo "an unknown scenario name: exit 2, naming where it looked"
