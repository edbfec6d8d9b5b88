#!/usr/bin/env bash
# The deepest each body of examples/scenes/drops.json ever got into what it landed on:
# a 0.25 m ball dropped 5 m and a unit crate dropped 10 m onto the ground, a unit box
# dropped 6 m onto another. Then the same for examples/scenes/tilted-drops.json: planks,
# a bar, capsules and cylinders dropped nearly lying, tilted onto one end, so that they
# land on it and turn. Depths are worked out from the trace's positions and orientations.
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

# Tilted drops: the lowest point lies below the centre by, with R the rotation's middle
# row (the world y of each body axis): a box's sum of |R_i| h_i; a capsule's (radius r,
# core L along z) |R_z| L/2 + r; a cylinder's |R_z| L/2 + r sqrt(1 - R_z^2).
"$build/bin/cyclone-world" run "$root/examples/scenes/tilted-drops.json" --trace "$trace" >/dev/null
awk -F, '
  function abs(a) { return a < 0 ? -a : a }
  NR > 1 && $3 != "ground" {
    w = $7; x = $8; y = $9; z = $10
    rx = 2 * (x * y + w * z); ry = 1 - 2 * (x * x + z * z); rz = 2 * (y * z - w * x)
    if ($3 ~ /^plank/) below = 0.5 * abs(rx) + 0.1 * abs(ry) + 0.1 * abs(rz)
    else if ($3 ~ /^bar/) below = 0.6 * abs(rx) + 0.1 * abs(ry) + 0.2 * abs(rz)
    else if ($3 ~ /^capsule/) below = abs(rz) * 0.5 + 0.2
    else below = abs(rz) * 0.5 + 0.2 * sqrt(1 - rz * rz)
    depth = below - $5
    if (!($3 in deepest) || depth > deepest[$3]) deepest[$3] = depth
    if (!($3 in order)) { order[$3] = ++n; names[n] = $3 }
  }
  END {
    for (i = 1; i <= n; ++i) printf "%-19s onto the ground: deepest %.2f mm\n", names[i], 1000 * max0(deepest[names[i]])
  }
  function max0(a) { return a > 0 ? a : 0 }' "$trace"
