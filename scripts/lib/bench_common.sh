# shellcheck shell=bash disable=SC2034  # sourced: the scripts use what it sets
# Shared start of the benchmark scripts (sourced, not run): arguments [RUNS] [BUILD_DIR], a
# scratch directory removed at exit, the machine and load average printed (the machine may be
# shared), and the helpers below. A script with other arguments passes these two explicitly:
#   source "$(dirname "$0")/lib/bench_common.sh" 5 "${1:-}"
# Sets: root, runs (default 5), build (default build/), tmp.
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
runs=${1:-5}
build=${2:-$root/build}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/mcws_bench.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

echo "machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p'), $(date -u +%Y-%m-%d)"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

# The median of the numbers on stdin, one a line.
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

# Runs a command (or function) and appends its wall time [s] to FILE; the command's own output
# goes where the caller redirects it.
wall_time() {  # file, command...
  local file=$1 start
  shift
  start=$(date +%s.%N)
  "$@"
  awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {print b - a}' >>"$file"
}

# A Google Benchmark binary's medians over $runs repetitions, one line a benchmark.
benchmark_medians() {  # binary
  "$1" --benchmark_repetitions="$runs" --benchmark_report_aggregates_only=true \
    --benchmark_min_time=0.5 2>/dev/null | grep -E "_median" | sed 's/_median//'
}

# Runs a command once under /usr/bin/time -v, its stdout to $tmp/out; appends its wall time [s]
# to WALL_FILE and its peak RSS [MB] to RSS_FILE.
time_once() {  # wall_file, rss_file, command...
  local wall=$1 rss=$2
  shift 2
  /usr/bin/time -v "$@" 2>"$tmp/time.log" >"$tmp/out"
  awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; print s}' \
    "$tmp/time.log" >>"$wall"
  awk -F': ' '/Maximum resident set size/ {print $2 / 1024}' "$tmp/time.log" >>"$rss"
}

# Runs a command $runs times under /usr/bin/time -v, its stdout to $tmp/out (the last run's);
# prints "median wall s, median peak RSS MB".
time_runs() {  # command...
  : >"$tmp/wall"; : >"$tmp/rss"
  for _ in $(seq "$runs"); do time_once "$tmp/wall" "$tmp/rss" "$@"; done
  echo "$(median <"$tmp/wall") $(median <"$tmp/rss")"
}
