#!/bin/sh
# Checks that ParaView opens a Stoss result by itself: pvpython's OpenDataFile on result.xdmf (the
# reader ParaView picks): the first frame's point count without a time and at its time, then the last
# frame's points and every field compared with the HDF5 datasets.
# Not run in CI: it needs Debian's paraview and python3-paraview (large), plus python3-h5py.
#   scripts/check_paraview.sh [DIR]
# DIR holds result.xdmf and result.h5; without it, api/examples/ball_plate_inp.json is run with
# build/stoss (or $STOSS) into a temporary directory first.
set -e
root=$(cd "$(dirname "$0")/.." && pwd)
command -v pvpython > /dev/null || { echo "pvpython not found: apt-get install paraview python3-paraview" >&2; exit 2; }
dir=$1
if [ -z "$dir" ]; then
  dir=$(mktemp -d)
  trap 'rm -rf "$dir"' EXIT
  "${STOSS:-$root/build/stoss}" run "$root/api/examples/ball_plate_inp.json" -o "$dir" > /dev/null
fi
pvpython --force-offscreen-rendering "$root/scripts/check_paraview.py" "$dir"
