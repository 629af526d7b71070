#!/usr/bin/env bash
# Behaviour-run benchmark (Wang et al. 2018) for BENCHMARKS.md: a 28-disc XWP2-160 string (a 220 kV
# suspension string) cleaned by mcws_behave on the shipped model, as whole-process runs:
# (1) the run and its summary only; (2) with the event log and the 0.1 s timeline written;
# (3) also the Figure-10 PNG (gnuplot). Medians of RUNS (default 5) runs of wall time and peak
# memory; the simulated duration divided by the wall time (how much faster than the robot) is
# the comparison. The load average is printed because the machine may be shared.
# Usage: scripts/bench_behave.sh [RUNS] [BUILD_DIR]   (needs a release build)
set -euo pipefail
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh"
model=$root/robots/insulator_cleaner_behaviors.yaml

echo
echo "| mcws_behave --insulators 28 | wall [s] | peak memory [MB] | simulated [s] | simulated / wall |"
echo "|---|---|---|---|---|"
for mode in summary outputs plot; do
  args=()
  [[ $mode != summary ]] && args+=(--log "$tmp/run.jsonl" --timeline "$tmp/run.csv")
  [[ $mode == plot ]] && args+=(--plot "$tmp/run.png")
  : >"$tmp/wall"; : >"$tmp/rss"
  for _ in $(seq "$runs"); do
    wall_time "$tmp/wall" /usr/bin/time -f "%M" -o "$tmp/time" "$build/apps/mcws_behave" \
      --model "$model" --insulators 28 --json "${args[@]}" >"$tmp/out.json" 2>/dev/null
    cat "$tmp/time" >>"$tmp/rss"
  done
  simulated=$(python3 -c "import json; print(json.load(open('$tmp/out.json'))['duration_s'])")
  w=$(median <"$tmp/wall")
  awk -v m="$mode" -v w="$w" -v r="$(median <"$tmp/rss")" -v s="$simulated" \
    'BEGIN {printf "| %s | %.3f | %.1f | %.2f | %.0f x |\n", m, w, r / 1024, s, (w > 0 ? s / w : 0)}'
done
echo
echo "log: $(wc -l <"$tmp/run.jsonl") lines, $(du -k "$tmp/run.jsonl" | cut -f1) kB;" \
  "timeline: $(wc -l <"$tmp/run.csv") lines, $(du -k "$tmp/run.csv" | cut -f1) kB"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
