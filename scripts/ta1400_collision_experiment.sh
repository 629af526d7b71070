#!/usr/bin/env bash
# The experiment of Fu, Hu, Chen & Pan 2016 (section 3): the Panasonic TA1400 with its welding
# torch, 500000 Monte Carlo samples checked for collisions (robots/ta1400.yaml: capsule links,
# flange housing and torch). Writes, under OUTPUT_DIR:
#   fig3_p_free.png   P points (flange, frame 6 origin) of the collision-free samples (Fig. 3)
#   fig4_t_free.png   T points (torch tip) of the collision-free samples (Fig. 4)
#   fig5_t_torch.png  T points where the torch hits the arm, whatever the links do (Fig. 5)
#   fig6_t_all.png    T points of every collision, links and torch (Fig. 6)
# the clouds behind them, ta1400_collision_summary.json with the counts, and the collision-free
# volume beside the volume without collision checks and the volumes of the two collision regions
# (mcws_measure).
# Every sample's joint values depend only on --seed and its index, so the P and T clouds and the
# torch-only run label the same 500000 configurations.
# Usage: scripts/ta1400_collision_experiment.sh [OUTPUT_DIR]
#        (default: out/ta1400_collision; MCWS_NO_BUILD=1 skips the build)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/out/ta1400_collision}
bin=$root/build/apps
samples=500000
seed=2
[[ -n ${MCWS_NO_BUILD:-} ]] || "$root/scripts/build.sh" "$root/build"
mkdir -p "$out"
robot=$root/robots/ta1400.yaml

# The torch-only model: the same file with every link-link pair allowed, so that label 2 marks
# every sample in which the torch hits the arm (in the full model a sample where links collide
# too gets the lower code 1).
torch_only=$out/ta1400_torch_only.yaml
{
  cat "$robot"
  echo "  allowed: [[base, j2], [base, j3], [base, j4], [base, j5], [base, j6], [j1, j3], [j1, j4],"
  echo "            [j1, j5], [j1, j6], [j2, j4], [j2, j5], [j2, j6], [j3, j5], [j3, j6], [j4, j6]]"
} >"$torch_only"

sample() {  # sample NAME ROBOT POINT
  "$bin/mcws_sample" --robot "$2" --collision --point "$3" --samples $samples --seed $seed \
    --output "$out/$1.pcd" --json >"$out/.$1.json.tmp"
  mv "$out/.$1.json.tmp" "$out/$1.json"
}
sample t_all "$robot" tool
sample p_all "$robot" flange
sample t_torch_only "$torch_only" tool

"$bin/mcws_select" --input "$out/p_all.pcd" --label 0 --output "$out/p_free.pcd"
"$bin/mcws_select" --input "$out/t_all.pcd" --label 0 --output "$out/t_free.pcd"
"$bin/mcws_select" --input "$out/t_torch_only.pcd" --label 2 --output "$out/t_torch.pcd"
"$bin/mcws_select" --input "$out/t_all.pcd" --label 1,2 --output "$out/t_collisions.pcd"

plot() {  # plot CLOUD PNG TITLE [plot_cloud.sh flags...]
  "$root/scripts/plot_cloud.sh" --input "$out/$1.pcd" --output "$out/$2.png" --view 3d \
    --unit mm --title "$3" "${@:4}"
}
plot p_free fig3_p_free "TA1400: P points (flange), collision-free samples" --color z --label samples
plot t_free fig4_t_free "TA1400: T points (torch tip), collision-free samples" --color z --label samples
plot t_torch fig5_t_torch "TA1400: torch-arm collision region (T points)" --color z --label samples
# Fig. 6 by collision label (t_all's codes: 1 any link-link collision, 2 the torch alone)
plot t_collisions fig6_t_all "TA1400: collisions of links and torch (T points)" --color label \
  --color-names 1=link-link,2=torch-arm

volume() { "$bin/mcws_measure" --input "$out/$1.pcd" --json | sed 's/.*"volume":\([^,}]*\).*/\1/'; }
v_all=$(volume t_all)
v_free=$(volume t_free)
v_torch=$(volume t_torch)
v_collisions=$(volume t_collisions)

count() {  # count SUMMARY LABEL_NAME
  sed "s/.*\"$2\":{\"count\":\([0-9]*\).*/\1/" "$out/$1.json"
}
link_link=$(count t_all link-link)        # any link-link collision (the lowest code)
torch_only_label=$(count t_all tool-link) # the torch hits, no link collides
torch_any=$(count t_torch_only tool-link) # the torch hits, whatever the links do
free=$(count t_all free)
both=$((torch_any - torch_only_label))
cat >"$out/ta1400_collision_summary.json" <<JSON
{"samples":$samples,"seed":$seed,"free":$free,"label_link_link":$link_link,
 "label_tool_link":$torch_only_label,"any_link_link":$link_link,"any_torch_arm":$torch_any,
 "torch_and_links":$both,"collisions":$((samples - free)),
 "volume_without_collision_check_mm3":$v_all,"volume_collision_free_mm3":$v_free,
 "volume_torch_arm_region_mm3":$v_torch,"volume_all_collision_region_mm3":$v_collisions}
JSON
echo "Fu, Hu, Chen & Pan 2016 experiment: TA1400 with torch, $samples samples (seed $seed), written to $out"
echo "  collision-free:                 $free"
echo "  link-link collision (label 1):  $link_link"
echo "  torch-arm only (label 2):       $torch_only_label"
echo "  torch hits the arm (any):       $torch_any  (of which links collide too: $both)"
echo "  link-link outnumber torch-arm:  $([[ $link_link -gt $torch_any ]] && echo yes || echo no)"
echo "  T-point volume without collision checks: $v_all mm^3"
echo "  T-point volume of collision-free samples: $v_free mm^3"
echo "  T-point volume of the torch-arm region (Fig. 5): $v_torch mm^3"
echo "  T-point volume of the all-collision region (Fig. 6): $v_collisions mm^3"
