#!/usr/bin/env bash
# Balls and a capsule rolling without slipping across a flat floor of 800 triangles
# (examples/scenes/rolling-on-mesh.json, 1 m cells, 3 s, defaults): a 0.25 m ball at
# 4.27 m/s and one at 1.08 m/s, and a capsule (radius 0.25 m) lying across its path at
# 4.27 m/s. On a flat floor each centre stays 0.25 m up and never moves up or down;
# prints the largest height error and vertical speed of each over the run.
#
#   bash scripts/rolling.sh [BUILD_DIR]      (default build/)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
trace=$(mktemp)
trap 'rm -f "$trace"' EXIT
"$build/bin/cyclone-world" run "$root/examples/scenes/rolling-on-mesh.json" --trace "$trace" >/dev/null
awk -F, '
  function abs(a) { return a < 0 ? -a : a }
  NR == 1 { next }
  {
    if (!($3 in height)) order[++n] = $3
    e = abs($5 - 0.25); if (e >= height[$3]) height[$3] = e
    s = abs($12); if (s >= speed[$3]) speed[$3] = s
  }
  END {
    for (k = 1; k <= n; ++k)
      printf "%-9s largest height error %.4f mm, largest |vy| %.5f m/s\n", order[k], 1000 * height[order[k]], speed[order[k]]
  }' "$trace"
