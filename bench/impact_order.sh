#!/usr/bin/env bash
# The order table of docs/theory.md §4.6.4: final-position error of every impact mode and scheme against the
# same mode and scheme at one eighth of the coarsest step (issue 22 §1). A benchmark, not a test: the seed
# example takes minutes per row.
#   bench/impact_order.sh STOSS_BINARY SCENE.json "h1,h2,h3" "scheme,..." "mode,..."
# e.g. bench/impact_order.sh build/stoss api/examples/hollow_ball_plate.json 0.01,0.005,0.0025 \
#        energy_momentum,midpoint located,persist,exact,velocity_correction
set -euo pipefail
stoss=$1 scene=$2 steps=$3 schemes=$4 modes=$5
coarsest=$(echo "$steps" | tr ',' '\n' | sort -g | tail -1)
reference=$(python3 -c "print($coarsest / 8)")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for mode in ${modes//,/ }; do
  python3 - "$scene" "$mode" "$work/$mode.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
for pair in scene["contact"]:
    pair["impact"] = sys.argv[2]
json.dump(scene, open(sys.argv[3], "w"))
PY
  for scheme in ${schemes//,/ }; do
    echo "## impact $mode, $scheme (reference h = $reference)"
    "$stoss" study "$work/$mode.json" --steps "$steps" --schemes "$scheme" --reference "$reference" ||
      echo "(not available: $mode with $scheme)"
  done
done
