#!/usr/bin/env bash
# The project's test command: installs missing packages, configures, builds with all
# cores and runs the whole suite with ctest.
#
#   bash scripts/test.sh [--sanitize] [--build-dir DIR] [-- CMAKE_ARGS...]
#
#   --sanitize       Debug build (-Og) with AddressSanitizer + UBSan in build-asan/;
#                    any sanitizer report fails the run.
#   --build-dir DIR  build directory (default build/, or build-asan/ with --sanitize;
#                    a relative DIR is taken from the current directory).
#   -- CMAKE_ARGS    further arguments for the configure step, e.g. -DCYCLONE_BUILD_WORLD=OFF.
#
# With CI=true in the environment, compiler warnings are errors.
set -euo pipefail

usage() { sed -n '5,13s/^# \{0,1\}//p' "${BASH_SOURCE[0]}"; }

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
sanitize=false
build_dir=
extra_cmake_args=()

while (($# > 0)); do
  case $1 in
    --sanitize) sanitize=true ;;
    --build-dir)
      if (($# < 2)); then
        echo "test.sh: --build-dir needs a directory" >&2
        exit 2
      fi
      build_dir=$2
      shift ;;
    --build-dir=*) build_dir=${1#--build-dir=} ;;
    -h | --help) usage; exit 0 ;;
    --) shift; extra_cmake_args=("$@"); break ;;
    *)
      echo "test.sh: unknown argument '$1'" >&2
      usage >&2
      exit 2 ;;
  esac
  shift
done

bash "$root/scripts/deps.sh"

cmake_args=(-DCYCLONE_BUILD_TESTS=ON)
if [[ $sanitize == true ]]; then
  build_dir=${build_dir:-$root/build-asan}
  # -Og optimises what does not slow the compiler down: the instrumented build takes about
  # 40 % less processor time than at -O1, the suite longer (docs/ci.md). -g1
  # keeps the line tables and function names that the sanitizers' stack traces print and
  # leaves out the variables and types a debugger would need (a third of the build's time).
  cmake_args+=(-DCMAKE_BUILD_TYPE=Debug -DCYCLONE_SANITIZE=ON "-DCMAKE_CXX_FLAGS_DEBUG=-Og -g1")
  # Any report is fatal; ours come last so that they win over the caller's.
  export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}halt_on_error=1:abort_on_error=1:detect_leaks=1"
  export UBSAN_OPTIONS="${UBSAN_OPTIONS:+$UBSAN_OPTIONS:}halt_on_error=1:print_stacktrace=1"
else
  build_dir=${build_dir:-$root/build}
  cmake_args+=(-DCMAKE_BUILD_TYPE=Release)
fi

# Warnings are errors in CI only, never for users; set either way so that a build
# directory configured once by CI does not keep the setting.
if [[ ${CI:-} == true ]]; then
  cmake_args+=(-DCMAKE_COMPILE_WARNING_AS_ERROR=ON)
else
  cmake_args+=(-DCMAKE_COMPILE_WARNING_AS_ERROR=OFF)
fi

jobs=$(nproc 2>/dev/null || echo 2)

cmake -S "$root" -B "$build_dir" "${cmake_args[@]}" ${extra_cmake_args[@]+"${extra_cmake_args[@]}"}
cmake --build "$build_dir" --parallel "$jobs"
ctest --test-dir "$build_dir" --output-on-failure --parallel "$jobs"
