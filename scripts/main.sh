#!/usr/bin/env bash
# The main job: installs what is missing, builds the cyclone-world runner and runs a
# stacking scene through it, printing a short report.
#
#   bash scripts/main.sh [SCENE.json]     (default: examples/scenes/pyramid-20-sleep.json)
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
scene=${1:-$root/examples/scenes/pyramid-20-sleep.json}

bash "$root/scripts/deps.sh"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$root/build" -j"$(nproc)" --target cyclone-world >/dev/null
"$root/build/bin/cyclone-world" report "$scene"
