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
fuzz_build=""
report() {
  if [[ -n $fuzz_build ]]; then  # stopped early: end the fuzzers' build (its process group)
    kill -- "-$fuzz_build" 2>/dev/null || true
  fi
  echo "run_tests: wall time per phase" >&2
  for line in "${phases[@]}"; do echo "  $line" >&2; done
  echo "  $(printf '%-22s %5d s' total "$SECONDS")" >&2
}
trap report EXIT

# tests/slow_tests.txt: CTest's cost data for a new build directory, so that the longest tests
# start first.
costs() {
  local file=$1/Testing/Temporary/CTestCostData.txt
  [[ -e $file ]] && return
  mkdir -p "$(dirname "$file")"
  grep -v '^#' "$root/tests/slow_tests.txt" >"$file"
}

phase "dependencies" "$root/scripts/install_deps.sh"
phase "release build" "$root/scripts/build.sh" "$root/build"
costs "$root/build"
# The fuzzers' clang build (fuzz/, about 180 s of CPU) runs from here on at the lowest priority,
# on what the test phases leave of the cores (tests that wait on subprocesses, files, MPI); the
# fuzzer phase at the end waits for it.
fuzz_log=$(mktemp /tmp/mcws_fuzz_build.XXXXXX)
# set -m: a process group of its own, to be ended as one (report). Not setsid: a new session is
# a new scheduler autogroup, which Linux gives an equal share of the CPU whatever its nice value.
set -m
nice -n 19 "$root/scripts/run_fuzzers.sh" --build-only >"$fuzz_log" 2>&1 &
fuzz_build=$!
set +m
fuzz() {
  local status=0
  wait "$fuzz_build" || status=$?
  fuzz_build=""
  if ((status)); then
    cat "$fuzz_log" >&2
    return 1
  fi
  rm -f "$fuzz_log"
  "$root/scripts/run_fuzzers.sh" 20
}

phase "release tests" ctest --test-dir "$root/build" --output-on-failure -j "$(nproc)"

# clang (installed for the fuzzers anyway): it compiles the instrumented tree in about 60 % of
# GCC's time (docs/testing.md). -O1: the sanitizers' instrumentation of large functions makes -O2
# two to four times slower to compile (the CGAL and PCL template code most); every check is the
# same at -O1. -g1: line tables only, enough for the reports (file and line of every frame). The
# examples are run by the release suite; the benchmarks are not tests.
phase "sanitizer build" "$root/scripts/build.sh" "$root/build-asan" \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DMCWS_SANITIZE=ON \
  -DMCWS_BUILD_BENCHMARKS=OFF -DMCWS_BUILD_EXAMPLES=OFF
costs "$root/build-asan"
# OMP_WAIT_POLICY=passive: clang's OpenMP runtime (libomp) keeps an idle thread spinning for
# 200 ms, which takes the core from the other test CTest runs beside it; passive puts it to sleep.
phase "sanitizer tests" env OMP_WAIT_POLICY=passive \
  ctest --test-dir "$root/build-asan" --output-on-failure -j "$(nproc)"

# The file loaders under libFuzzer (fuzz/): 20 s each on the seed corpus, in a clang build.
phase "fuzzers (build's rest, run)" fuzz
