#!/usr/bin/env bash
# The project's test command: installs missing packages, configures, builds with all
# cores and runs the whole suite with ctest.
#
#   bash scripts/test.sh [--sanitize] [--build-dir DIR] [-- CMAKE_ARGS...]
#
#   --sanitize       Debug build (-Og) with AddressSanitizer + UBSan in build-asan/;
#                    tests run in shards; any sanitizer report fails the run.
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

# One line per phase on stderr, so that a long build is not silent.
phase() { echo "test.sh: [$1/4] $2" >&2; }

phase 1 "checking the Debian packages (scripts/deps.sh)"
bash "$root/scripts/deps.sh"

cmake_args=(-DCYCLONE_BUILD_TESTS=ON)
if [[ $sanitize == true ]]; then
  build_dir=${build_dir:-$root/build-asan}
  # -Og optimises what does not slow the compiler down: the instrumented build takes about
  # 40 % less processor time than at -O1, the suite longer (docs/ci.md). -g1
  # keeps the line tables and function names that the sanitizers' stack traces print and
  # leaves out the variables and types a debugger would need (a third of the build's time).
  cmake_args+=(-DCMAKE_BUILD_TYPE=Debug -DCYCLONE_SANITIZE=ON "-DCMAKE_CXX_FLAGS_DEBUG=-Og -g1")
  # Each test executable runs as 12 shards, not one process per test: a sanitized
  # process costs about 0.05-0.08 s of processor time to start and end (docs/ci.md).
  cmake_args+=(-DCYCLONE_TEST_SHARDS=12)
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

# A new build directory is generated for Ninja, which starts a target's own compiles
# while the libraries it links are still being built (Make waits for them): the sanitized
# build takes about a tenth less wall time on 2 cores (docs/ci.md). A directory that
# exists keeps the generator it was made with, and a caller's choice (CMAKE_GENERATOR, or
# -G among the CMAKE_ARGS) wins.
generator=()
if [[ ! -f $build_dir/CMakeCache.txt && -z ${CMAKE_GENERATOR:-} ]] && command -v ninja >/dev/null; then
  generator=(-G Ninja)
  for arg in ${extra_cmake_args[@]+"${extra_cmake_args[@]}"}; do
    if [[ $arg == -G* ]]; then generator=(); fi
  done
fi

phase 2 "configuring ${build_dir#"$root"/}"
cmake -S "$root" -B "$build_dir" ${generator[@]+"${generator[@]}"} "${cmake_args[@]}" ${extra_cmake_args[@]+"${extra_cmake_args[@]}"}
phase 3 "building everything with $jobs jobs"
cmake --build "$build_dir" --parallel "$jobs"
phase 4 "running the suite (ctest, $jobs at a time)"
ctest --test-dir "$build_dir" --output-on-failure --parallel "$jobs"
