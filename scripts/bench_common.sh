# Shared start of the benchmark scripts (sourced, not run): arguments [RUNS] [BUILD_DIR], a
# scratch directory removed at exit, the machine and load average printed (the machine may be
# shared), and median(), which reads numbers on stdin.
# Sets: root, runs (default 5), build (default build/), tmp.
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
runs=${1:-5}
build=${2:-$root/build}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/mcws_bench.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

echo "machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p'), $(date -u +%Y-%m-%d)"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
