#!/usr/bin/env bash
# Planning benchmarks for BENCHMARKS.md (the maintenance-arm patent), on the maintenance4 scenario:
# (1) the full evaluation (roadmap, m candidates, free states for n base poses, shared-node merge)
# as a whole run of mcws_plan without validation; (2) the whole run with the 10000-pose
# validation of the chosen, shortest and padded paths. Medians of RUNS (default 5) whole-process
# runs with 2 threads, the phases as the tool reports them in --json; the padded planner's own
# planning time (its roadmap and shortest path, obstacles padded) is the peer, as a ratio in the
# same runs. The load average is printed because the machine may be shared.
# Usage: scripts/bench_plan.sh [RUNS] [BUILD_DIR]   (needs a release build)
set -euo pipefail
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh"
scenario=$root/scenarios/maintenance4.yaml
field() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }

for mode in evaluation validation; do
  : >"$tmp/wall"; : >"$tmp/roadmap"; : >"$tmp/segments"; : >"$tmp/validation"; : >"$tmp/padded"
  args=(--validation-poses 0)
  [[ $mode == validation ]] && args=()
  for _ in $(seq "$runs"); do
    wall_time "$tmp/wall" "$build/apps/mcws_plan" --scenario "$scenario" --output "$tmp/path.csv" \
      --threads 2 --json "${args[@]}" >"$tmp/out.json" 2>/dev/null
    field "$tmp/out.json" "d['rounds'][0]['roadmap_seconds']" >>"$tmp/roadmap"
    field "$tmp/out.json" "d['rounds'][0]['evaluation_seconds']" >>"$tmp/segments"
    if [[ $mode == validation ]]; then
      field "$tmp/out.json" "d['validation']['seconds']" >>"$tmp/validation"
      field "$tmp/out.json" "[r for r in d['validation']['rows'] if r['name']=='padded'][0]['planning_seconds']" >>"$tmp/padded"
    fi
  done
  echo
  echo "## mcws_plan --threads 2, $mode (median of $runs whole runs)"
  echo "wall: $(median <"$tmp/wall") s; roadmap: $(median <"$tmp/roadmap") s; free states of the segments: $(median <"$tmp/segments") s"
  if [[ $mode == validation ]]; then
    echo "validation (3 paths x 10000 poses, padded planner included): $(median <"$tmp/validation") s"
    echo "padded planner (peer): roadmap and shortest path $(median <"$tmp/padded") s;" \
      "ratio of our roadmap to the peer's: $(awk -v a="$(median <"$tmp/roadmap")" -v b="$(median <"$tmp/padded")" 'BEGIN {printf "%.2f", a / b}')"
    python3 - "$tmp/out.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
print("| path | length D | collision probability | 95 % interval |")
print("|---|---|---|---|")
for r in d["validation"]["rows"]:
    if r["planned"]:
        print(f"| {r['name']} | {r['length']:.2f} | {r['collision_probability']:.4f} | "
              f"[{r['interval_95'][0]:.4f}, {r['interval_95'][1]:.4f}] |")
    else:
        print(f"| {r['name']} | no path ({r['roadmap_status']}) | | |")
PY
  fi
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
