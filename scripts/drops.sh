#!/usr/bin/env bash
# The deepest each body of examples/scenes/drops.json ever got into what it landed on:
# a 0.25 m ball dropped 5 m and a unit crate dropped 10 m onto the ground, a unit box
# dropped 6 m onto another. Depths are worked out from the trace's positions.
#
#   bash scripts/drops.sh [BUILD_DIR]      (default build/)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
trace=$(mktemp)
trap 'rm -f "$trace"' EXIT
"$build/bin/cyclone-world" run "$root/examples/scenes/drops.json" --trace "$trace" >/dev/null
awk -F, '
  function max(a, b) { return a > b ? a : b }
  NR > 1 && $3 == "ball" { ball = max(ball, 0.25 - $5) }
  NR > 1 && $3 == "crate" { crate = max(crate, 0.5 - $5) }
  NR > 1 && $3 == "base" { base = $5 }
  NR > 1 && $3 == "dropped" { box = max(box, (base + 0.5) - ($5 - 0.5)) }
  END {
    printf "ball (0.25 m) from 5 m onto the ground: deepest %.2f mm\n", 1000 * ball
    printf "crate (1 m) from 10 m onto the ground:  deepest %.2f mm\n", 1000 * crate
    printf "box (1 m) from 6 m onto a box:          deepest %.2f mm\n", 1000 * box
  }' "$trace"
