#!/usr/bin/env bash
# The measuring stage (issue 13): whole-process wall time and peak memory of mcws_measure on the
# 1e6-point unit ball and unit disk, median of RUNS runs, for this build and, given a second
# build directory, for that one in the same run (before/after, runs interleaved); then the volume
# error of the 1e6 ball over 10 seeds for each build.
# Usage: scripts/bench_measure.sh [RUNS] [BUILD_DIR] [OTHER_BUILD_DIR]
set -euo pipefail
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh"
other=${3:-}
builds=("$build")
[[ -n $other ]] && builds+=("$other")
sample=$build/apps/mcws_sample
"$sample" --shape ball --samples 1000000 --seed 1 --output "$tmp/ball.pcd" 2>/dev/null
"$sample" --shape disk --samples 1000000 --seed 1 --output "$tmp/disk.pcd" 2>/dev/null

# One run: prints "seconds kilobytes".
measure_once() {  # build, cloud, flags...
  local b=$1 cloud=$2
  shift 2
  /usr/bin/time -f '%e %M' -o "$tmp/time" "$b/apps/mcws_measure" --input "$tmp/$cloud" "$@" \
    >/dev/null 2>&1
  cat "$tmp/time"
}
echo
echo "| cloud | build | wall, median of $runs [s] | peak memory, median [MB] |"
echo "|---|---|---|---|"
for cloud in "ball.pcd" "disk.pcd --plane xy"; do
  for k in "${!builds[@]}"; do : >"$tmp/runs.$k"; done
  for _ in $(seq "$runs"); do
    for k in "${!builds[@]}"; do
      # shellcheck disable=SC2086  # the cloud entry carries its flags
      measure_once "${builds[$k]}" $cloud >>"$tmp/runs.$k"
    done
  done
  for k in "${!builds[@]}"; do
    f=$tmp/runs.$k
    printf '| %s | %s | %s | %.0f |\n' "${cloud%% *}" "${builds[$k]}" "$(cut -d' ' -f1 "$f" | median)" \
      "$(cut -d' ' -f2 "$f" | median | awk '{print $1 / 1024}')"
  done
done

echo
echo "Volume of the unit ball (4/3 pi) from 10^6 uniform samples, seeds 1 to 10:"
echo
echo "| build | mean error [%] | mean absolute error [%] | largest absolute error [%] |"
echo "|---|---|---|---|"
for b in "${builds[@]}"; do
  for seed in $(seq 1 10); do
    "$sample" --shape ball --samples 1000000 --seed "$seed" --output "$tmp/s.pcd" 2>/dev/null
    "$b/apps/mcws_measure" --input "$tmp/s.pcd" --json 2>/dev/null
  done | python3 -c '
import json, math, sys
errors = [100 * (json.loads(line)["volume"] / (4 / 3 * math.pi) - 1) for line in sys.stdin]
print("| %s | %+.4f | %.4f | %.4f |" % (sys.argv[1], sum(errors) / len(errors),
      sum(map(abs, errors)) / len(errors), max(map(abs, errors))))' "$b"
done
echo
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
