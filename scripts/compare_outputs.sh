#!/usr/bin/env bash
# Proof that a reshaping changed no output: runs the same stage-tool commands with two builds and
# compares every file they write, their stdout and stderr (JSON and plain text, with the wall-time
# fields and stderr's progress lines taken out) and their exit codes, byte for byte. Covers every
# tool (envelope, reach maps and studies, base placement, the tiled boundary, traj --to-pose,
# sample --quality, behave with plots among them), the boundary of the 1e6-point disk and ball,
# and a set of bad inputs. Prints one line per command and exits 1 on any
# difference.
# Usage: scripts/compare_outputs.sh OLD_BUILD NEW_BUILD [WORK_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
[[ $# -ge 2 ]] || { echo "usage: $0 OLD_BUILD NEW_BUILD [WORK_DIR]" >&2; exit 2; }
old=$(cd "$1" && pwd)
new=$(cd "$2" && pwd)
work=${3:-$(mktemp -d)}
mkdir -p "$work"

# One command per line; @B@ is the build's apps directory, @O@ its output directory, @R@ the
# repository. Clouds the later commands read are written by the earlier ones.
commands=$(cat <<'EOF'
@B@/mcws_sample --shape disk --samples 1000000 --seed 1 --output @O@/disk.pcd --json
@B@/mcws_sample --shape ball --samples 1000000 --seed 1 --output @O@/ball.pcd --json
@B@/mcws_sample --shape annulus --samples 20000 --seed 2 --output @O@/annulus.pcd --ascii
@B@/mcws_sample --robot @R@/robots/deicing.yaml --samples 100000 --seed 1 --fix theta3=0 --output @O@/xz.pcd --json
@B@/mcws_sample --robot @R@/robots/deicing.yaml --samples 50000 --seed 2 --output @O@/d3.pcd --threads 1
@B@/mcws_sample --robot @R@/robots/ta1400.yaml --samples 20000 --seed 3 --point flange --output @O@/ta.pcd
@B@/mcws_sample --robot @R@/robots/ta1400.yaml --samples 5000 --seed 4 --collision --output @O@/tac.pcd --json
@B@/mcws_boundary --input @O@/disk.pcd --plane xy --output @O@/disk_b.pcd --json
@B@/mcws_boundary --input @O@/ball.pcd --output @O@/ball_b.pcd --interior @O@/ball_i.pcd --json
@B@/mcws_boundary --input @O@/xz.pcd --plane xz --output @O@/xz_b.pcd --json
@B@/mcws_boundary --input @O@/d3.pcd --output @O@/d3_b.pcd --threads 1 --json
@B@/mcws_boundary --input @O@/annulus.pcd --plane xy --auto-radius 4 --output @O@/an_auto.pcd --json
@B@/mcws_boundary --input @O@/annulus.pcd --plane xy --radius 0.08 --outer-radius 0.12 --output @O@/an_r.pcd --json
@B@/mcws_boundary --input @O@/annulus.pcd --plane xy --min-gap 90 --hull-depth 0 --tree-search --output @O@/an_t.pcd
@B@/mcws_boundary --input @O@/annulus.pcd --plane xy --adaptive 12 --outer-radius 1.5 --output @O@/an_a.pcd --json
@B@/mcws_boundary --input @O@/d3.pcd --auto-radius 0 --output @O@/d3_auto.pcd --json
@B@/mcws_boundary --input @O@/annulus.pcd --plane xy --method grid --output @O@/an_g.pcd --json
@B@/mcws_boundary --input @O@/annulus.pcd --plane xy --method extremum --output @O@/an_e.pcd --json
@B@/mcws_boundary --input @O@/d3.pcd --method grid --cell 5 --output @O@/d3_g.pcd --json
@B@/mcws_refine --robot @R@/robots/deicing.yaml --input @O@/d3_b.pcd --cloud @O@/d3.pcd --samples 50000 --seed 3 --output @O@/d3_r.pcd --json
@B@/mcws_refine --robot @R@/robots/deicing.yaml --input @O@/xz_b.pcd --samples 20000 --spread 0.05 --threads 1 --output @O@/xz_r.pcd
@B@/mcws_measure --input @O@/d3_r.pcd --correction none --json
@B@/mcws_measure --input @O@/xz.pcd --plane xz --json
@B@/mcws_measure --input @O@/xz.pcd --plane xz
@B@/mcws_measure --input @O@/d3.pcd --threads 1 --json
@B@/mcws_measure --input @O@/d3.pcd --leave-one-out reinsert --json
@B@/mcws_measure --input @O@/xz.pcd --plane xz --leave-one-out reinsert --threads 1 --json
@B@/mcws_measure --input @O@/xz.pcd --plane xz --method column --json
@B@/mcws_select --input @O@/tac.pcd --label 0 --output @O@/tac_free.pcd --json
@B@/mcws_fk --robot @R@/robots/ta1400.yaml --q "0.1 0.2 0.3 0.4 0.5 0.6"
@B@/mcws_fk --robot @R@/robots/deicing.yaml --q "0.1 0.2 0.3" --frame flange --json
@B@/mcws_ik --robot @R@/robots/ta1400.yaml --pose "800 200 900 0 1.5 0" --json
@B@/mcws_ik --robot @R@/robots/deicing.yaml --pose "60 0 40 0 0 0" --position-only
@B@/mcws_traj --robot @R@/robots/ta1400.yaml --from "0 0 0 0 0 0" --to "0.5 0.4 0.3 0.2 0.1 0" --duration 2 --rate 50 --output @O@/traj.csv --json
@B@/mcws_traj --robot @R@/robots/ta1400.yaml --from "0 0 0 0 0 0" --via "0.2 0.2 0.2 0 0 0" --to "0.5 0.4 0.3 0.2 0.1 0" --duration 2 --rate 20 --profile cubic --output @O@/traj2.csv
@B@/mcws_collide --robot @R@/robots/ta1400.yaml --q "0 0.3 0.2 0 0.5 0" --all --json
@B@/mcws_plan --scenario @R@/scenarios/planar2.yaml --output @O@/planar2.csv --json
@B@/mcws_behave --model @R@/robots/insulator_cleaner_behaviors.yaml --insulators 3 --log @O@/behave.jsonl --timeline @O@/behave.csv --json
@B@/mcws_behave --model @R@/robots/insulator_cleaner_behaviors.yaml --check --json
@B@/mcws_sample --robot @R@/robots/deicing.yaml --samples -5 --output @O@/bad1.pcd
@B@/mcws_sample --robot @R@/robots/nothere.yaml --output @O@/bad2.pcd
@B@/mcws_boundary --input @O@/disk.pcd --plane xq --output @O@/bad3.pcd
@B@/mcws_boundary --input @O@/disk.pcd --radius 0 --output @O@/bad4.pcd
@B@/mcws_boundary --input @O@/annulus.pcd --method grid --radius 2 --output @O@/bad5.pcd
@B@/mcws_boundary --input @O@/nothere.pcd --output @O@/bad6.pcd
@B@/mcws_boundary --input @O@/disk.pcd --output @O@/bad7.pcd
@B@/mcws_measure --input @O@/disk.pcd --alpha -1
@B@/mcws_refine --robot @R@/robots/deicing.yaml --input @O@/xz_b.pcd --samples 10 --spread 2 --output @O@/bad8.pcd
@B@/mcws_traj --robot @R@/robots/ta1400.yaml --from "0 0 0" --to "1 1 1" --duration 1 --rate 10 --output @O@/bad9.csv
@B@/mcws_ik --robot @R@/robots/ta1400.yaml --pose "1 2 3"
@B@/mcws_fk --robot @R@/robots/ta1400.yaml --q "0 0"
@B@/mcws_boundary --input @O@/annulus.pcd --plane xy --radius 1e6 --output @O@/bad10.pcd
@B@/mcws_boundary --input @O@/annulus.pcd --plane xy --auto-radius 1e9 --output @O@/bad11.pcd
@B@/mcws_boundary --input @O@/annulus.pcd --plane xy --radius 0.08 --outer-radius 0.05 --output @O@/bad12.pcd
@B@/mcws_boundary --input @O@/annulus.pcd --plane xy --adaptive 12 --outer-radius 1e6 --output @O@/bad13.pcd
@B@/mcws_boundary --input @O@/annulus.pcd --plane xy --method grid --cell 1e-9 --output @O@/bad14.pcd
@B@/mcws_boundary --input @O@/annulus.pcd --plane xy --method extremum --gap 1e6 --output @O@/bad15.pcd
@B@/mcws_sample --shape disk --samples 50 --seed 5 --output @O@/small.pcd
@B@/mcws_boundary --input @O@/small.pcd --plane xy --adaptive 60 --output @O@/bad16.pcd
@B@/mcws_sample --robot @R@/robots/deicing.yaml --samples 30000 --seed 2 --output @O@/d3e.pcd
@B@/mcws_envelope --input @O@/d3e.pcd --output @O@/env.ply --json
@B@/mcws_sample --robot @R@/robots/inspection6.yaml --samples 3000 --quality --output @O@/q.pcd --json
@B@/mcws_sample --robot @R@/robots/maintenance4.yaml --samples 3000 --quality --quality-task full --output @O@/q2.pcd --json
@B@/mcws_envelope --input @O@/d3e.pcd --output @O@/env.stl --drawing @O@/env.svg --azimuth 30 --json
@B@/mcws_envelope --input @O@/d3e.pcd --drawing @O@/env2.svg --unit m
@B@/mcws_envelope --input @O@/d3e.pcd --output @O@/env.vtk --correction none
@B@/mcws_envelope --input @O@/d3e.pcd
@B@/mcws_envelope --input @O@/d3e.pcd --output @O@/bad.txt
@B@/mcws_reach --robot @R@/robots/planar2.yaml --resolution 2cm --orientations 16 --samples 200000 --output @O@/m.pcd --map @O@/m.bin --json
@B@/mcws_reach --robot @R@/robots/inspection6.yaml --resolution 20cm --samples 30000 --output @O@/i.pcd --halfcut @O@/i.png --histogram @O@/ih.png --checkpoint @O@/ck --checkpoint-every 7000 --json
@B@/mcws_reach --robot @R@/robots/ta1400.yaml --resolution 20cm --samples 20000 --collision --output @O@/t.pcd
@B@/mcws_reach --robot @R@/robots/ta1400.yaml --resolution 20cm --samples 20000 --checkpoint-every 5 --output @O@/t2.pcd
@B@/mcws_reach --robot @R@/robots/maintenance4.yaml --targets @R@/robots/maintenance4_damper_targets.pcd --output @O@/heat.pcd --json
@B@/mcws_reach --robot @R@/robots/maintenance4.yaml --targets @R@/robots/maintenance4_damper_targets.pcd --output @O@/heat2.pcd
@B@/mcws_place --robot @R@/robots/maintenance4.yaml --targets @R@/robots/maintenance4_damper_targets.pcd --along "-30 30 10" --resolution 5cm --samples 200000 --output @O@/bases.pcd --plot @O@/place.png --json
@B@/mcws_place --robot @R@/robots/maintenance4.yaml --targets @R@/robots/maintenance4_damper_targets.pcd --along "-30 30 10" --resolution 5cm --samples 200000 --output @O@/bases2.pcd --confirm all
@B@/mcws_place --robot @R@/robots/planar2.yaml --targets @R@/robots/maintenance4_damper_targets.pcd --along "-30 70 2" --map @O@/m.bin --output @O@/b3.pcd --json
@B@/mcws_boundary --input @O@/d3e.pcd --tiles 3 --output @O@/d3_t.pcd --json
@B@/mcws_boundary --input @O@/d3e.pcd --tiles 2 --adaptive 8 --output @O@/d3_t2.pcd
@B@/mcws_boundary --input @O@/d3e.pcd --tiles 2 --auto-radius 3 --output @O@/d3_t3.pcd
@B@/mcws_traj --robot @R@/robots/ta1400.yaml --from "0 0.3 0.2 0 0.5 0" --to-pose "320 50 -950 3.141592653589793 0.47640122440170124 0" --duration 1 --rate 20 --output @O@/line.csv --plot @O@/line.png --json
@B@/mcws_traj --robot @R@/robots/ta1400.yaml --from "0 0.3 0.2 0 0.5 0" --to-pose "3200 50 -950 0 0 0" --duration 1 --rate 20 --output @O@/line2.csv
@B@/mcws_behave --model @R@/robots/insulator_cleaner_behaviors.yaml --insulators 2 --log @O@/b2.jsonl --timeline @O@/b2.csv --plot @O@/b2.png --timeline-period 0.5 --json
@B@/mcws_behave --model @R@/robots/insulator_cleaner_behaviors.yaml --insulators 1 --plot @O@/b3.png --plot-all
@B@/mcws_boundary --input @O@/d3e.pcd --tiles 3 --radius 9 --output @O@/d3_t4.pcd --interior @O@/d3_t4i.pcd --json
EOF
)

# Runs every command with one build; writes stdout, stderr (timing removed) and exit codes.
run_all() {  # build, output dir
  local apps=$1/apps out=$2 k=0 line
  rm -rf "$out" "$out.cache" && mkdir -p "$out"
  # mcws_place's map cache: a fresh one per build, so that no build reuses the other's maps.
  export XDG_CACHE_HOME=$out.cache
  while IFS= read -r line; do
    k=$((k + 1))
    line=${line//@B@/$apps}
    line=${line//@O@/$out}
    line=${line//@R@/$root}
    local rc=0
    eval "$line" >"$out/stdout.$k" 2>"$out/stderr.$k" || rc=$?
    echo "$rc" >"$out/rc.$k"
    sed -i -E 's/"[a-z_]*seconds":[-0-9.e+]+,?//g; s/, *[0-9.]+ ?(ms|s) *\)//g' "$out/stdout.$k"
    # stderr: progress lines ("mcws_x: 40% (...)") come as time allows: dropped; wall times out.
    sed -i -E '/^mcws_[a-z]+: [0-9]+% \(/d; s/\[done, [0-9]+ ms/[done, X ms/' "$out/stderr.$k"
    # mcws_place's estimate of its map's time, from the rate of its first samples.
    sed -i -E '/^mcws_place: the map will take about /d' "$out/stderr.$k"
    sed -i -E 's/, *[0-9.]+ ?(ms|s) *\)//g' "$out/stderr.$k"
    # Paths differ between the two runs only by the output directory (and gnuplot's temporary
    # names).
    sed -i -E "s#$out#OUT#g; s#mcws_plot_[A-Za-z0-9]+#P#g" "$out/stdout.$k" "$out/stderr.$k"
  done <<<"$commands"
}

echo "compare_outputs: old build $old" >&2
run_all "$old" "$work/old"
echo "compare_outputs: new build $new" >&2
run_all "$new" "$work/new"

status=0
k=0
while IFS= read -r line; do
  k=$((k + 1))
  for f in stdout stderr rc; do
    if ! cmp -s "$work/old/$f.$k" "$work/new/$f.$k"; then
      echo "DIFFERS ($f): $line"
      status=1
    fi
  done
done <<<"$commands"
for f in "$work/old"/*; do
  name=$(basename "$f")
  [[ $name == stdout.* || $name == stderr.* || $name == rc.* ]] && continue
  if [[ ! -e $work/new/$name ]]; then
    echo "MISSING in new: $name"
    status=1
  elif ! cmp -s <(sed -E "s#$work/old#OUT#g; s#mcws_plot_[A-Za-z0-9]+#P#g" "$f") \
    <(sed -E "s#$work/new#OUT#g; s#mcws_plot_[A-Za-z0-9]+#P#g" "$work/new/$name"); then
    echo "DIFFERS (file): $name"
    status=1
  fi
done
for f in "$work/new"/*; do
  [[ -e $work/old/$(basename "$f") ]] || { echo "EXTRA in new: $(basename "$f")"; status=1; }
done
files=$(find "$work/old" -maxdepth 1 -type f ! -name 'stdout.*' ! -name 'stderr.*' ! -name 'rc.*' |
  wc -l)
echo "compare_outputs: $k commands, $files files written;" \
  "$([[ $status == 0 ]] && echo "all byte-identical" || echo "differences above")"
exit $status
