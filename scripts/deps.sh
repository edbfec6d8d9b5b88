#!/usr/bin/env bash
# Installs the Debian packages the project needs (Debian 12), and only those missing:
# nothing is downloaded, and no root is needed, when everything is already there.
set -euo pipefail

packages=(
  build-essential    # compiler and make
  cmake
  ninja-build        # builds both cores' worth of work at once (scripts/test.sh)
  libeigen3-dev      # math types of the dynamics core
  libfcl-dev         # World: narrowphase collision
  libccd-dev         # World: GJK/EPA used by FCL
  libgtest-dev       # the test suite
  libqhull-dev       # World: convex hulls
  nlohmann-json3-dev # runner: scene files
  libbullet-dev      # benchmarks: reference engine
  libbenchmark-dev   # benchmarks
  gnuplot-nox        # examples: trajectory plots
  doxygen            # API documentation (docs/Doxyfile), checked by the test suite
  libglfw3-dev       # viewer: window and input
  libgl-dev          # viewer: OpenGL 3.3 core
  libgl1-mesa-dri    # viewer: Mesa's drivers (llvmpipe renders without a GPU)
  libimgui-dev       # viewer: Dear ImGui overlay (with its GLFW and OpenGL 3 backends)
  libstb-dev         # viewer: PNG screenshots (stb_image_write); Dear ImGui needs it too
  pkgconf            # viewer: finds Dear ImGui and stb (pkg-config files)
  xvfb               # viewer: headless runs and its test (xvfb-run)
  xauth              # viewer: xvfb-run needs it
)

missing=()
for package in "${packages[@]}"; do
  # dpkg -s also knows removed packages whose configuration files remain; only
  # "install ok installed" means the package is usable.
  if ! dpkg -s "$package" 2>/dev/null | grep -q '^Status: install ok installed$'; then
    missing+=("$package")
  fi
done

if ((${#missing[@]} == 0)); then
  exit 0
fi

echo "deps.sh: installing ${missing[*]}" >&2
if [[ $(id -u) -eq 0 ]]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo)
else
  echo "deps.sh: missing packages (${missing[*]}) and neither root nor sudo;" \
       "install them as root: apt-get install ${missing[*]}" >&2
  exit 1
fi

# sudo resets the environment, so DEBIAN_FRONTEND goes through env.
apt=(${as_root[@]+"${as_root[@]}"} env DEBIAN_FRONTEND=noninteractive apt-get)
if ! "${apt[@]}" update; then
  echo "deps.sh: apt-get update failed; trying the install with the current package lists" >&2
fi
"${apt[@]}" install -y -q "${missing[@]}"
