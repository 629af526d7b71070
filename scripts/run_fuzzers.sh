#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ with clang (AddressSanitizer + UndefinedBehaviorSanitizer,
# in build-fuzz/) and runs each for SECONDS on a copy of its seed corpus (fuzz/corpus/NAME/, which
# is never changed). A crash, a sanitizer report, a leak, a hang (10 s on one input) or more than
# 2 GB of memory fails the run: the input is kept in the work directory named in the message, to
# be added as a regression test.
# Usage: scripts/run_fuzzers.sh [SECONDS per target (default 30)] [NAME...]
#        scripts/run_fuzzers.sh --build-only   (builds them and stops; run_tests.sh does this at
#        low priority while the sanitizer tests run)
#   NAME: robot_yaml robot_urdf pcd scenario behavior_model fault_script mesh study (default all)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
all=(robot_yaml robot_urdf pcd scenario behavior_model fault_script mesh study)
build_only=0
if [[ ${1:-} == --build-only ]]; then
  build_only=1
  shift
fi

seconds=30
if (($#)) && [[ $1 != [a-z]* ]]; then
  seconds=$1
  shift
fi
if [[ ! $seconds =~ ^[1-9][0-9]*$ ]]; then
  echo "run_fuzzers.sh: SECONDS must be a positive whole number of seconds, got '$seconds'" >&2
  exit 2
fi
names=("$@")
((${#names[@]})) || names=("${all[@]}")
for name in "${names[@]}"; do
  if [[ " ${all[*]} " != *" $name "* ]]; then
    echo "run_fuzzers.sh: unknown fuzzer '$name' (one of: ${all[*]})" >&2
    exit 2
  fi
done

build=$root/build-fuzz
# -O1 -gline-tables-only: as OSS-Fuzz builds its fuzzers (line numbers in every report).
"$root/scripts/build.sh" "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DMCWS_BUILD_FUZZERS=ON \
  -DMCWS_BUILD_TESTS=OFF -DMCWS_BUILD_BENCHMARKS=OFF -DMCWS_BUILD_EXAMPLES=OFF \
  --target mcws_fuzzers >"$build.build.log" 2>&1 || { tail -n 40 "$build.build.log" >&2; exit 1; }
((build_only)) && exit 0

# Leaks inside libraries that mcws cannot free, each explained in the file.
export LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
work=$(mktemp -d /tmp/mcws_fuzz_run.XXXXXX)
# One fuzzer per core at a time (each is one process); the reports follow in the order of names.
run_one() {
  local name=$1
  mkdir -p "$work/$name/corpus"
  cp "$root/fuzz/corpus/$name/"* "$work/$name/corpus/"
  if "$build/fuzz/${name}_fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -max_len=65536 -print_final_stats=1 -artifact_prefix="$work/$name/" \
      "$work/$name/corpus" >"$work/$name/log" 2>&1; then
    echo ok >"$work/$name/status"
  else
    echo failed >"$work/$name/status"
  fi
}
cores=$(nproc)
for name in "${names[@]}"; do
  while (($(jobs -rp | wc -l) >= cores)); do wait -n || true; done
  run_one "$name" &
done
wait
failed=()
for name in "${names[@]}"; do
  log=$work/$name/log
  if [[ $(cat "$work/$name/status" 2>/dev/null) == ok ]]; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    rss=$(sed -n 's/^stat::peak_rss_mb: *//p' "$log")
    corpus=$(find "$work/$name/corpus" -type f | wc -l)
    echo "run_fuzzers: $name: ${runs:-?} inputs in $seconds s, corpus $corpus files, peak ${rss:-?} MB;" \
      "no crash, hang or leak" >&2
  else
    failed+=("$name")
    echo "run_fuzzers: $name FAILED; the input is in $work/$name/ (crash-*, timeout-*, leak-*):" >&2
    grep -m 20 -E "ERROR|SUMMARY|runtime error|#[0-9]+ 0x" "$log" >&2 || tail -n 20 "$log" >&2
  fi
done

if ((${#failed[@]})); then
  echo "run_fuzzers: ${#failed[@]} fuzzer(s) failed: ${failed[*]} (logs in $work)" >&2
  exit 1
fi
rm -rf "$work"
