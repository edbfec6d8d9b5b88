#!/usr/bin/env bash
# How long after coming to rest the bodies of examples/scenes/come-to-rest.json fall
# asleep, at the defaults: a unit box slid at 6 m/s on the ground (friction 0.6: it stops
# after 6 / (0.6 g) = 1.02 s), a 0.25 m ball thrown up at 5 m/s (it lands after
# 2 v / g = 1.02 s) and a 0.25 m ball spinning in place at 5 rad/s (the default 5 mm of
# spinning resistance stops it after 5 / (5 mm g / (0.4 r^2)) = 2.55 s). Rest is the end
# of the last step in which the body moved faster than 0.01 m/s or turned faster than
# 0.01 rad/s; "in the air" is asleep more than 1 cm above where it rests. Worked out from
# the trace.
#
#   bash scripts/sleep_latency.sh [BUILD_DIR]      (default build/)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
trace=$(mktemp)
trap 'rm -f "$trace"' EXIT
"$build/bin/cyclone-world" run "$root/examples/scenes/come-to-rest.json" --trace "$trace" >/dev/null
awk -F, '
  NR == 1 { next }
  {
    body = $3; t = $2
    speed = sqrt($11 * $11 + $12 * $12 + $13 * $13); turn = sqrt($14 * $14 + $15 * $15 + $16 * $16)
    rest_height = body == "box" ? 0.5 : 0.25
    if ($17 == 0 && !(body in asleep)) { asleep[body] = t; air[body] = ($5 > rest_height + 0.01) }
    if ($17 == 1 && (speed > 0.01 || turn > 0.01)) moved[body] = t
  }
  END {
    split("box ball spinner", names, " ")
    for (k = 1; k <= 3; ++k) {
      b = names[k]
      if (!(b in asleep)) { printf "%-7s still awake after the run (last moved at %.3f s)\n", b, moved[b]; continue }
      printf "%-7s at rest %.3f s, asleep %.3f s: %.3f s after rest, %s\n", b, moved[b], asleep[b],
             asleep[b] - moved[b], air[b] ? "IN THE AIR" : "on the ground"
    }
  }' "$trace"
