#!/usr/bin/env bash
# The main job: installs what is missing, builds the cyclone-world runner and runs a
# stacking scene through it, printing a short report.
#
#   bash scripts/main.sh [SCENE.json]     (default: examples/scenes/pyramid-20-sleep.json)
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
scene=${1:-$root/examples/scenes/pyramid-20-sleep.json}

# One line per phase on stderr: the first build takes minutes and says nothing else.
phase() { echo "main.sh: [$1/4] $2" >&2; }

phase 1 "checking the Debian packages (scripts/deps.sh)"
bash "$root/scripts/deps.sh"
phase 2 "configuring build/ (Release)"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
phase 3 "building cyclone-world with $(nproc) jobs (a few minutes the first time)"
cmake --build "$root/build" --parallel "$(nproc)" --target cyclone-world >/dev/null
phase 4 "running ${scene#"$root"/}"
"$root/build/bin/cyclone-world" report "$scene"
