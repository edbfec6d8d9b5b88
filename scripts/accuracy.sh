#!/usr/bin/env bash
# The accuracy report: error against cost. Installs what is missing, builds
# cyclone-accuracy (Release, -DCYCLONE_BUILD_BENCH=ON) in build-accuracy/, runs every
# reference scene over the sweep of step sizes, solver settings and integrators, and draws
# one log-log plot per scene and measure with gnuplot. Outputs: results.csv, README.md
# (tables and plots) and the plots (*.svg), in BUILD_DIR/accuracy/; with --update-docs,
# in docs/accuracy/ (tracked files: the report the docs link to).
#
#   bash scripts/accuracy.sh [--quick] [--update-docs] [--build-dir DIR]
#
#   --quick          three step sizes instead of seven (a smoke test; do not commit it)
#   --update-docs    write into docs/accuracy/, replacing the report kept there
#   --build-dir DIR  build directory (default build-accuracy/)
set -euo pipefail

usage() { sed -n '9,13s/^# \{0,1\}//p' "${BASH_SOURCE[0]}"; }
phase() { echo "accuracy.sh: [$1/5] $2" >&2; }

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=$root/build-accuracy
args=()
update_docs=false
while (($# > 0)); do
  case $1 in
    --quick) args+=(--quick) ;;
    --update-docs) update_docs=true ;;
    --build-dir)
      if (($# < 2)); then
        echo "accuracy.sh: --build-dir needs a directory" >&2
        exit 2
      fi
      build_dir=$2
      shift ;;
    -h | --help) usage; exit 0 ;;
    *)
      echo "accuracy.sh: unknown argument '$1'" >&2
      usage >&2
      exit 2 ;;
  esac
  shift
done

phase 1 "checking the Debian packages (scripts/deps.sh)"
bash "$root/scripts/deps.sh"
# ccache, when installed, makes a rebuild after a small change take seconds.
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# Only what cyclone-accuracy links is configured and built: no tests, examples, viewer,
# install rules or Bullet comparison.
phase 2 "configuring ${build_dir#"$root"/}"
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DCYCLONE_BUILD_BENCH=ON \
  -DCYCLONE_BUILD_TESTS=OFF -DCYCLONE_BUILD_EXAMPLES=OFF -DCYCLONE_BUILD_VIEWER=OFF -DCYCLONE_INSTALL=OFF \
  -DCYCLONE_BENCH_BULLET=OFF ${launcher[@]+"${launcher[@]}"} >/dev/null
phase 3 "building cyclone-accuracy"
cmake --build "$build_dir" --parallel "$(nproc 2>/dev/null || echo 2)" --target cyclone-accuracy

if [[ $update_docs == true ]]; then
  out=$root/docs/accuracy
else
  out=$build_dir/accuracy
fi
plots=$build_dir/accuracy-plots
mkdir -p "$out" "$plots"
rm -f "$out"/*.svg "$plots"/*.gp "$plots"/*.dat
phase 4 "running the sweep into ${out#"$root"/}/ (minutes)"
"$build_dir/bench/cyclone-accuracy" --out "$out" --plots "$plots" ${args[@]+"${args[@]}"}
phase 5 "drawing the plots (gnuplot)"
for script in "$plots"/*.gp; do
  gnuplot "$script"
done
echo "accuracy.sh: $(ls "$out"/*.svg | wc -l) plots, tables and CSV in ${out#"$root"/}/"
