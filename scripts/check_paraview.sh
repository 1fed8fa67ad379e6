#!/bin/sh
# Checks that ParaView opens a Stoss result by itself: pvpython's OpenDataFile on result.xdmf (the
# reader ParaView picks): the first frame's point count without a time and at its time, then the last
# frame's points and every field compared with the HDF5 datasets, the same frames in other XDMF layouts
# read without a time, and last the pvpython snippet of docs/results.md run as printed.
# Not run in CI: it needs Debian's paraview and python3-paraview (large), plus python3-h5py.
#   scripts/check_paraview.sh [DIR]
# DIR holds result.xdmf and result.h5; without it, api/examples/ball_plate_inp.json is run with
# build/stoss (or $STOSS) into a temporary directory first.
set -e
root=$(cd "$(dirname "$0")/.." && pwd)
command -v pvpython > /dev/null || { echo "pvpython not found: apt-get install paraview python3-paraview" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
dir=$1
if [ -z "$dir" ]; then
  dir=$work/out
  "${STOSS:-$root/build/stoss}" run "$root/api/examples/ball_plate_inp.json" -o "$dir" > "$work/run.log" 2>&1 ||
    { cat "$work/run.log" >&2; exit 1; }
fi
dir=$(cd "$dir" && pwd)
pvpython --force-offscreen-rendering "$root/scripts/check_paraview.py" "$dir"
# The snippet under "ParaView from Python" in docs/results.md, as printed, in a folder whose out/ is DIR.
mkdir -p "$work/snippet"
[ -e "$work/snippet/out" ] || ln -s "$dir" "$work/snippet/out"
awk '/^\*\*ParaView from Python/ { found = 1 } found && /^```python$/ { inside = 1; next }
     inside && /^```$/ { exit } inside { print }' "$root/docs/results.md" > "$work/snippet/snippet.py"
[ -s "$work/snippet/snippet.py" ] || { echo "no pvpython snippet found in docs/results.md" >&2; exit 1; }
echo "docs/results.md's snippet, run as printed:"
output=$(cd "$work/snippet" && pvpython --force-offscreen-rendering snippet.py 2>&1 | grep -v '^$')
echo "  $output"
echo "$output" | grep -Eq '^[0-9]+ frames; [1-9][0-9]* points at t = ' || exit 1
