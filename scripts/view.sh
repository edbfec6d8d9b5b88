#!/usr/bin/env bash
# Opens a scene in cyclone-viewer: installs the packages missing (scripts/deps.sh), builds
# the viewer (Release, in build/) and runs it.
#
#   bash scripts/view.sh [SCENE.json] [VIEWER_OPTIONS...]
#
# SCENE.json defaults to examples/scenes/pyramid-20.json; the other options go to the
# viewer (cyclone-viewer --help lists them).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
scene=$root/examples/scenes/pyramid-20.json
if (($# > 0)) && [[ $1 != -* ]]; then
  scene=$1
  shift
fi

phase() { echo "view.sh: [$1/4] $2" >&2; }

phase 1 "checking the Debian packages (scripts/deps.sh)"
bash "$root/scripts/deps.sh"
phase 2 "configuring build/ (Release)"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DCYCLONE_BUILD_VIEWER=ON >/dev/null
phase 3 "building cyclone-viewer"
cmake --build "$root/build" --target cyclone-viewer --parallel "$(nproc 2>/dev/null || echo 2)"

viewer=$root/build/bin/cyclone-viewer
if [[ ! -x $viewer ]]; then
  echo "view.sh: the viewer was not built (see the configure step's 'cyclone-viewer skipped' line)" >&2
  exit 1
fi
if [[ -z ${DISPLAY:-} && -z ${WAYLAND_DISPLAY:-} ]]; then
  echo "view.sh: no display (DISPLAY is not set); for a picture without one:" >&2
  echo "  xvfb-run -s '-screen 0 1280x720x24' $viewer $scene --frames 90 --screenshot out.png" >&2
  exit 1
fi
phase 4 "opening ${scene#"$root"/}"
exec "$viewer" "$scene" "$@"
