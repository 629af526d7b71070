#!/usr/bin/env bash
# Configures and builds mcws.
# Usage: scripts/build.sh [BUILD_DIR (default build/)] [extra cmake args...] [--target NAME...]
# Without --target every target is built (tools, tests, benchmarks, examples, as the MCWS_BUILD_*
# options say); with it only the named targets and what they link. The cache is not changed by
# --target, so a later full build in the same directory still builds everything.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build
if [[ $# -gt 0 && $1 != -* ]]; then
  build=$1
  shift
fi
cmake_args=() targets=()
while (($#)); do
  if [[ $1 == --target ]]; then
    (($# >= 2)) || { echo "build.sh: --target needs a target name" >&2; exit 2; }
    targets+=("$2")
    shift 2
  else
    cmake_args+=("$1")
    shift
  fi
done
# Ninja, when installed, for a new build directory: it compiles a target's sources while the
# libraries it links are still being built, where make waits for them, so both cores stay busy.
generator=()
if [[ ! -e $build/CMakeCache.txt && -z ${CMAKE_GENERATOR:-} ]] && command -v ninja >/dev/null; then
  generator=(-G Ninja)
fi
# Release unless the build directory already has a build type (a RelWithDebInfo sanitizer tree
# keeps its own flags when this script runs again); a -DCMAKE_BUILD_TYPE argument wins either way.
build_type=()
if ! grep -qs '^CMAKE_BUILD_TYPE:STRING=.' "$build/CMakeCache.txt"; then
  build_type=(-DCMAKE_BUILD_TYPE=Release)
fi
cmake -S "$root" -B "$build" "${generator[@]}" "${build_type[@]}" "${cmake_args[@]}" \
  >"$build.configure.log" 2>&1 || { cat "$build.configure.log" >&2; exit 1; }
if ((${#targets[@]})); then
  cmake --build "$build" -j "$(nproc)" --target "${targets[@]}"
else
  cmake --build "$build" -j "$(nproc)"
fi
