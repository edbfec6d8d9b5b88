#!/usr/bin/env bash
# How far any log of examples/scenes/crossed-logs.json creeps in 10 s: six crossed layers
# of three capsule logs (radius 0.1 m, 1.2 m long) on the ground, sleep off, defaults.
# Prints the largest distance of any body from where it was after the first step, with
# the body and the step.
#
#   bash scripts/creep.sh [BUILD_DIR]      (default build/)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
trace=$(mktemp)
trap 'rm -f "$trace"' EXIT
"$build/bin/cyclone-world" run "$root/examples/scenes/crossed-logs.json" --trace "$trace" >/dev/null
awk -F, '
  NR == 1 { next }
  !($3 in x) { x[$3] = $4; y[$3] = $5; z[$3] = $6; next }
  {
    d = sqrt(($4 - x[$3]) ^ 2 + ($5 - y[$3]) ^ 2 + ($6 - z[$3]) ^ 2)
    if (d > worst) { worst = d; who = $3; when = $1 }
  }
  END { printf "largest move in 10 s: %.3f mm (%s, step %d)\n", 1000 * worst, who, when }' "$trace"
