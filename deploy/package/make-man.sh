#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Man pages from the executables' own --help (help2man), so they never drift
# from what the programs say:
#   deploy/package/make-man.sh BIN_DIR OUT_DIR
# OUT_DIR/flatsat.1.gz holds `flatsat --help` and, in its COMMANDS section,
# every command's --help; OUT_DIR/flatsat-<component>.1.gz one per component.
set -euo pipefail
bin=$1
out=$2
command -v help2man >/dev/null || {
  echo "$0: help2man is missing (apt-get install help2man)" >&2
  exit 2
}
mkdir -p "$out"
rm -f "$out"/*.1 "$out"/*.1.gz
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Text as roff that shows it verbatim: backslashes doubled, and a line that
# starts with . or ' would be read as a request.
verbatim() { sed -e 's/\\/\\e/g' -e "s/^\([.']\)/\\\\\\&\1/"; }

# The commands, as `flatsat --help` lists them (the indented names before the
# description; aliases after a comma are left out).
commands=$("$bin/flatsat" --help | awk '/^Subcommands:/ {on = 1; next} on && /^  [a-z]/ {sub(/,.*/, "", $1); print $1}')
{
  echo "[COMMANDS]"
  for c in $commands; do
    echo ".SS \"flatsat $c\""
    echo ".nf"
    PATH="$bin:$PATH" flatsat "$c" --help 2>&1 | verbatim  # by name: its usage says "flatsat"
    echo ".fi"
  done
  cat <<'ROFF'
[FILES]
.TP
.I PREFIX/share/flatsat/scenarios
the scenarios `flatsat run NAME` finds (`flatsat scenarios` lists them)
.TP
.I PREFIX/share/flatsat/data
IGRF-14, WMM2025, SGP4 and atmosphere tables
.TP
.I PREFIX/share/flatsat/devices
serial device descriptions for hardware in the loop
[ENVIRONMENT]
.TP
.B FLATSAT_SCENARIO_PATH
folders (separated by :) searched for a scenario named without a path, before the installed ones
.TP
.B FLATSAT_DATA_DIR
folders searched for data files before the installed ones
.TP
.B FLATSAT_DEVICES_DIR
folders searched for device descriptions before the installed ones
.TP
.B FLATSAT_DOMAIN
the DDS domain of a rig and of the tools that meet it
ROFF
} >"$work/flatsat.h2m"
help2man --no-info --no-discard-stderr --section 1 --name "a flight-network attitude and orbit control rig" \
  --include "$work/flatsat.h2m" --output "$out/flatsat.1" "$bin/flatsat"

for exe in "$bin"/flatsat-*; do
  component=${exe##*/flatsat-}
  help2man --no-info --no-discard-stderr --section 1 \
    --name "the flatsat rig's $component component (started by flatsat run)" \
    --output "$out/flatsat-$component.1" "$exe"
done
gzip -9n "$out"/*.1
echo "make-man: $(ls "$out" | wc -l) pages in $out" >&2
