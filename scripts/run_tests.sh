#!/usr/bin/env bash
# Installs the dependencies, builds, and runs the whole test suite twice: in the release build and
# in a build with AddressSanitizer and UndefinedBehaviorSanitizer (-DMCWS_SANITIZE=ON); then the
# file loaders under libFuzzer. Prints the wall time of each phase on stderr at the end.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

phases=()
phase() {  # phase NAME COMMAND...: runs the command, notes its wall time
  local name=$1 start=$SECONDS
  shift
  "$@"
  phases+=("$(printf '%-22s %5d s' "$name" $((SECONDS - start)))")
}
report() {
  echo "run_tests: wall time per phase" >&2
  for line in "${phases[@]}"; do echo "  $line" >&2; done
  echo "  $(printf '%-22s %5d s' total "$SECONDS")" >&2
}
trap report EXIT

phase "dependencies" "$root/scripts/install_deps.sh"
phase "release build" "$root/scripts/build.sh" "$root/build"
phase "release tests" ctest --test-dir "$root/build" --output-on-failure -j "$(nproc)"

# -g1: line tables only, enough for the sanitizers' reports (file and line of every frame), and a
# fifth less compile time than -g on the CGAL-heavy files.
phase "sanitizer build" "$root/scripts/build.sh" "$root/build-asan" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DMCWS_SANITIZE=ON -DMCWS_BUILD_BENCHMARKS=OFF
phase "sanitizer tests" ctest --test-dir "$root/build-asan" --output-on-failure -j "$(nproc)"

# The file loaders under libFuzzer (fuzz/): 20 s each on the seed corpus, in a clang build.
phase "fuzzers (build, run)" "$root/scripts/run_fuzzers.sh" 20
