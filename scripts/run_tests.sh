#!/usr/bin/env bash
# Installs the dependencies, builds, and runs the whole test suite twice: in the release build and
# in a build with AddressSanitizer and UndefinedBehaviorSanitizer (-DMCWS_SANITIZE=ON).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

"$root/scripts/install_deps.sh"
"$root/scripts/build.sh" "$root/build"
ctest --test-dir "$root/build" --output-on-failure -j "$(nproc)"

"$root/scripts/build.sh" "$root/build-asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMCWS_SANITIZE=ON \
  -DMCWS_BUILD_BENCHMARKS=OFF
ctest --test-dir "$root/build-asan" --output-on-failure -j "$(nproc)"

# The file loaders under libFuzzer (fuzz/): 20 s each on the seed corpus, in a clang build.
"$root/scripts/run_fuzzers.sh" 20
