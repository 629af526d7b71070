#!/usr/bin/env bash
# Scaling of the MPI runs for BENCHMARKS.md (issue 18): whole-process wall times of mcws_sample
# and mcws_reach on one process (2 threads, no mpirun), and under mpirun on 1 process (2 threads)
# (--bind-to none: Open MPI binds a process to one core otherwise) and 2 processes (1 thread
# each), with the launcher alone (mpirun -np 2 true) for its start-up cost; strong scaling (the same work) and weak scaling (the work per
# process fixed). The configurations' runs are interleaved, median of RUNS each. The samples go to
# /dev/shm so that the disk does not hide the processes' work. Then, once, a 1e9-sample map on
# 2 processes with each process's peak memory (/usr/bin/time around each rank).
# Usage: scripts/bench_mpi.sh [RUNS (default 5)] [BUILD_DIR]   (needs a release build with MPI)
set -euo pipefail
# shellcheck source=lib/bench_common.sh
source "$(dirname "$0")/lib/bench_common.sh" "${1:-5}" "${2:-}"
mpirun=(mpirun --oversubscribe)
[[ $(id -u) -ne 0 ]] || mpirun+=(--allow-run-as-root)
out=$(mktemp -d /dev/shm/mcws_bench_mpi.XXXXXX)
trap 'rm -rf "$tmp" "$out"' EXIT
sample=("$build/apps/mcws_sample" --robot "$root/robots/ta1400.yaml" --output "$out/s.pcd")
reach=("$build/apps/mcws_reach" --robot "$root/robots/inspection6.yaml" --resolution 10cm
  --output "$out/m.pcd")

# name | command... : one configuration; its wall times are appended to $tmp/<name>.
configs=()
add() { configs+=("$*"); }
add "mpirun-np2-true|${mpirun[*]} -np 2 true"
add "sample-10M-alone|${sample[*]} --samples 10000000 --threads 2"
add "sample-10M-np1|${mpirun[*]} -np 1 --bind-to none ${sample[*]} --samples 10000000 --threads 2"
add "sample-10M-np2|${mpirun[*]} -np 2 ${sample[*]} --samples 10000000 --threads 1"
add "sample-5M-np1-t1|${mpirun[*]} -np 1 ${sample[*]} --samples 5000000 --threads 1"
add "reach-2e7-alone|${reach[*]} --samples 20000000 --threads 2"
add "reach-2e7-np1|${mpirun[*]} -np 1 --bind-to none ${reach[*]} --samples 20000000 --threads 2"
add "reach-2e7-np2|${mpirun[*]} -np 2 ${reach[*]} --samples 20000000 --threads 1"
add "reach-1e7-np1-t1|${mpirun[*]} -np 1 ${reach[*]} --samples 10000000 --threads 1"

for _ in $(seq "$runs"); do
  for config in "${configs[@]}"; do
    name=${config%%|*}
    read -r -a command <<<"${config#*|}"
    wall_time "$tmp/$name" "${command[@]}" >/dev/null 2>&1
  done
done
echo "load average after the timed runs: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| configuration | median wall s (of $runs) |"
echo "|---|---|"
for config in "${configs[@]}"; do
  name=${config%%|*}
  echo "| $name | $(median <"$tmp/$name") |"
done

echo
echo "1e9 samples into a map (inspection6, 10 cm, 200 directions), 2 processes x 1 thread, once:"
"${mpirun[@]}" -np 2 /usr/bin/time -f "rank peak RSS %M KB, wall %e s" "${reach[@]}" \
  --samples 1000000000 --threads 1 --json 2>&1 | grep -E "^rank|voxels" |
  sed -E 's/.*"seconds":([0-9.]+).*"voxels":([0-9]+).*/tool: \1 s, \2 voxels/'
