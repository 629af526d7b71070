#!/usr/bin/env bash
# plot_cloud.sh - render a PCD point cloud to a PNG with gnuplot (pngcairo),
# in the style of the paper's figures: a plane view such as "point cloud of
# workspace in X-Z plane" (Fig. 5) or a 3-D view (Fig. 6). The points can be
# coloured by any field of the cloud (z, label, manipulability, ...) under a
# named colour bar, or, for a whole-number field with few values (collision
# labels), one colour per value named in the key. 3-D views are coloured by z
# unless told otherwise, as a depth cue. An optional second cloud (e.g.
# boundary points) is drawn on top in a contrasting colour; the key names the
# clouds by --label and --overlay-label.
# Binary or ASCII PCD is read via pcl_convert_pcd_ascii_binary (pcl-tools).
set -euo pipefail

usage() {
  cat <<'EOF'
Usage: plot_cloud.sh --input CLOUD.pcd --output OUT.png [--view xz|xy|yz|3d]
                     [--title TEXT] [--unit cm] [--overlay OTHER.pcd] [--size W,H]
                     [--color FIELD|none] [--color-label TEXT] [--color-names V=NAME,...]
                     [--label TEXT] [--overlay-label TEXT] [--angles ROT_X,ROT_Z]
                     [--keep-script FILE]
  --input          point cloud to draw (binary or ASCII PCD with x, y, z fields)
  --output         PNG to write (written atomically; its directory must exist)
  --view           xz, xy, yz (plane view, equal axes) or 3d (default: 3d)
  --title          plot title (default: none)
  --unit           unit of the coordinates, e.g. cm -> "x [cm]" (default: none)
  --overlay        second cloud drawn on top with bigger points: red, or black when
                   the input is coloured by a field
  --size           image size in pixels (default: 900,700)
  --color          colour the input's points by this field of its PCD FIELDS line
                   (x, y, z, label, manipulability, reachability, ...) under a colour
                   bar; a whole-number field (TYPE I or U) with at most 10 distinct
                   values gets one colour per value, named in the key, instead; none:
                   one colour (default: z in the 3d view, none in plane views)
  --color-label    title of the colour bar, or the word before each value in the key
                   (default: the field's name, with the unit for x, y, z: "z [cm]")
  --color-names    names of a whole-number field's values in the key, e.g. for
                   mcws_sample --collision: 0=free,1=link-link,2=tool-link,3=environment
  --label          key entry of the input cloud (default: samples)
  --overlay-label  key entry of the overlay (default: boundary)
  --angles         3d view: gnuplot's "set view ROT_X,ROT_Z" in degrees (default:
                   60,60, which sees no face of the de-icing arm's +-60 deg yaw
                   sector edge-on; gnuplot's own 60,30 shows the -60 deg face as a
                   vertical line)
  --keep-script    also write the gnuplot script to FILE (it names temporary data
                   files, removed at exit)
The key is drawn when there is an overlay, when --label is given, or when a
whole-number field is coloured by value (its values then stand for the input
cloud in the key, instead of --label). Points whose --color field is NaN or
infinite are left out (with a note on stderr). Exit status: 0 done, 2 usage
error (a bad flag or value, a --color field the cloud does not have), 1 other
errors (an unreadable or empty cloud, gnuplot failing).
EOF
}
die() { echo "plot_cloud: $*" >&2; exit 1; }
usage_err() { echo "plot_cloud: $*" >&2; exit 2; }

input="" output="" view="3d" title="" unit="" overlay="" size="900,700" color=""
color_label="" color_names="" label="samples" overlay_label="boundary" angles="60,60"
keep_script="" label_given=0
while (($#)); do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --input|--output|--view|--title|--unit|--overlay|--size|--color|--color-label|--color-names|\
    --label|--overlay-label|--angles|--keep-script)
      (($# >= 2)) || usage_err "$1 needs a value"
      [[ $1 != --label ]] || label_given=1
      flag=${1#--}
      declare "${flag//-/_}=$2"; shift 2 ;;
    *) usage_err "unknown argument: $1 (see --help)" ;;
  esac
done
[[ -n $input ]] || usage_err "--input is required"
[[ -n $output ]] || usage_err "--output is required"
[[ $view =~ ^(xz|xy|yz|3d)$ ]] || usage_err "--view must be xz, xy, yz or 3d, not '$view'"
[[ $size =~ ^[1-9][0-9]*,[1-9][0-9]*$ ]] || usage_err "--size must be W,H in pixels, not '$size'"
[[ -z $color || $color =~ ^[A-Za-z_][A-Za-z0-9_]*$ ]] \
  || usage_err "--color must be a field name or none, not '$color'"
num='[0-9]+([.][0-9]*)?'
if ! [[ $angles =~ ^($num),($num)$ ]] || ! awk -v a="${BASH_REMATCH[1]}" -v b="${BASH_REMATCH[3]}" \
     'BEGIN { exit !(a <= 180 && b < 360) }'; then
  usage_err "--angles must be ROT_X,ROT_Z in degrees, 0 <= ROT_X <= 180," \
    "0 <= ROT_Z < 360, not '$angles'"
fi
declare -A value_name=()
if [[ -n $color_names ]]; then
  [[ -n $color && $color != none ]] || usage_err "--color-names needs --color FIELD"
  IFS=, read -r -a pairs <<<"$color_names"
  for pair in "${pairs[@]}"; do
    [[ $pair =~ ^(-?(0|[1-9][0-9]*))=(.+)$ ]] \
      || usage_err "--color-names must be VALUE=NAME[,VALUE=NAME...] with whole-number" \
           "values, not '$pair'"
    value_name[${BASH_REMATCH[1]}]=${BASH_REMATCH[3]}
  done
fi
[[ -n $color ]] || { [[ $view != 3d ]] || color=z; }   # depth cue by default in 3-D
[[ $color != none ]] || color=""
outdir=$(dirname -- "$output")
[[ -d $outdir ]] || die "output directory does not exist: $outdir"
[[ ! -d $output ]] || die "output is a directory, expected a PNG file name: $output"
[[ -z $keep_script || -d $(dirname -- "$keep_script") ]] \
  || die "--keep-script directory does not exist: $(dirname -- "$keep_script")"

tmpdir=$(mktemp -d) tmppng=""
trap 'rm -rf "$tmpdir"; [[ -z $tmppng ]] || rm -f "$tmppng"' EXIT

# load_cloud IN.pcd OUT.dat [FIELD]: write "x y z" lines (and FIELD's value as a fourth column)
# of the points of a PCD file with finite coordinates, checking the file first. With FIELD,
# writes "TYPE SKIPPED" (the field's PCD type, points left out for a non-finite value) to
# $tmpdir/field_info.
load_cloud() {
  local in=$1 out=$2 field=${3:-} ascii="$tmpdir/conv.pcd" status=0
  [[ -f $in && -r $in ]] || die "cannot read input file: $in"
  # Sanity-check the header ourselves: the converter crashes on non-PCD input.
  LC_ALL=C head -c 8192 -- "$in" | LC_ALL=C grep -aq '^DATA \(ascii\|binary\|binary_compressed\)' \
    || die "not a PCD file (no DATA line in header): $in"
  { pcl_convert_pcd_ascii_binary "$in" "$ascii" 0 >"$tmpdir/conv.log" 2>&1 && [[ -s $ascii ]]; } \
    || { cat "$tmpdir/conv.log" >&2; die "failed to convert $in to ASCII PCD"; }
  # Column of each field = 1 + sum of COUNTs of the fields before it (a field with COUNT > 1
  # is coloured by its first value).
  LC_ALL=C awk -v src="$in" -v cf="$field" -v info="$tmpdir/field_info" '
    $1 == "FIELDS" { nf = NF - 1; for (i = 2; i <= NF; i++) name[i-1] = $i; next }
    $1 == "TYPE"   { for (i = 2; i <= NF; i++) type[i-1] = $i; next }
    $1 == "COUNT"  { for (i = 2; i <= NF; i++) cnt[i-1] = $i; next }
    $1 == "DATA" {
      c = 1
      for (i = 1; i <= nf; i++) {
        col[name[i]] = c; ty[name[i]] = type[i]; c += ((i in cnt) ? cnt[i] : 1)
        names = names (i > 1 ? " " : "") name[i]
      }
      if (!("x" in col && "y" in col && "z" in col)) {
        print "plot_cloud: no x/y/z fields in " src > "/dev/stderr"; exit 3
      }
      if (cf != "" && !(cf in col)) {
        printf "plot_cloud: --color %s: %s has no such field (its fields: %s)\n", cf, src, names \
          > "/dev/stderr"
        exit 4
      }
      xi = col["x"]; yi = col["y"]; zi = col["z"]; ci = (cf != "") ? col[cf] : 0; data = 1; next
    }
    data && NF {
      if (tolower($xi $yi $zi) ~ /nan/) next
      if (!ci) { print $xi, $yi, $zi; next }
      if (tolower($ci) ~ /nan|inf/) { skipped++; next }
      print $xi, $yi, $zi, $ci
    }
    END { if (data && cf != "") print ty[cf], skipped + 0 > info }
  ' "$ascii" >"$out" || status=$?
  ((status != 4)) || exit 2   # an unknown --color field is a usage error
  ((status == 0)) || exit 1
  [[ -s $out ]] \
    || die "point cloud is empty (0 points with finite x, y, z${field:+ and $field}): $in"
}

load_cloud "$input" "$tmpdir/main.dat" "$color"
[[ -z $overlay ]] || load_cloud "$overlay" "$tmpdir/overlay.dat"

# Colouring: "" (one colour), "values" (one colour per value of a whole-number field, classes
# written to $tmpdir/class.V.cls) or "bar" (a palette and a colour bar).
coloring="" values=()
if [[ -n $color ]]; then
  read -r field_type skipped <"$tmpdir/field_info"
  ((skipped == 0)) || echo "plot_cloud: note: $skipped points with a non-finite $color left out" >&2
  coloring=bar
  if [[ $field_type == [IU] ]]; then
    mapfile -t values < <(cut -d' ' -f4 "$tmpdir/main.dat" | sort -n -u | head -n 11)
    if ((${#values[@]} <= 10)); then
      coloring=values
      awk -v dir="$tmpdir" '{ print $1, $2, $3 > (dir "/class." $4 ".cls") }' "$tmpdir/main.dat"
    fi
  fi
  [[ -z $color_names || $coloring == values ]] || echo "plot_cloud: note: --color-names" \
    "ignored, $color is not a whole-number field with at most 10 values" >&2
fi
if [[ -z $color_label && -n $color ]]; then
  color_label=$color
  [[ ! ($color =~ ^[xyz]$ && -n $unit) ]] || color_label="$color [$unit]"
fi

q() { printf "'%s'" "${1//\'/\'\'}"; }   # quote a string for gnuplot
# key COLOUR TEXT: a key entry (bigger than the plotted points, so that its colour shows) and a
# comma; nothing when TEXT is empty.
key() { [[ -z $2 ]] || echo "keyentry with points pt 7 ps 1.5 lc rgb '$1' title $(q "$2"), "; }
axis_label() { if [[ -n $unit ]]; then q "$1 [$unit]"; else q "$1"; fi; }
tmppng=$(mktemp -- "$outdir/.plot_cloud.XXXXXX.png")

{
  echo "set terminal pngcairo noenhanced size $size font 'Sans,12'"
  echo "set output $(q "$tmppng")"
  [[ -z $title ]] || echo "set title $(q "$title")"
  echo "set grid; set border lw 1"
  # The key names the clouds (and the values of a field coloured by value); one cloud drawn in
  # one colour under a title needs none.
  if [[ -z $overlay && $label_given == 0 && $coloring != values ]]; then echo "unset key"
  elif [[ $view == 3d ]]; then echo "set key top left box opaque Left reverse"
  else echo "set key below horizontal height 1 Left reverse"; fi
  if [[ $view == 3d ]]; then
    cols=1:2:3 axes="x y z" frac=0.02
    echo "set view ${angles}; set view equal xyz; set xyplane relative 0"
    echo "set xtics offset -1,-0.3; set ytics offset 1,-0.3"
    echo "set xlabel $(axis_label x) offset -1,-1; set ylabel $(axis_label y) offset 3,-1"
    echo "set zlabel $(axis_label z) rotate parallel"
  else
    declare -A idx=([x]=1 [y]=2 [z]=3)
    a=${view:0:1} b=${view:1:1} axes="x y" frac=0.05 cols=${idx[$a]}:${idx[$b]}
    echo "set size ratio -1"
    echo "set xlabel $(axis_label "$a"); set ylabel $(axis_label "$b")"
  fi
  # Tight ranges with the same margin on every axis (a fraction of the largest
  # extent); a flat axis (e.g. y of the X-Z cloud) gets +-10% of it instead.
  cat "$tmpdir"/*.dat | awk -v cols="${cols//:/ }" -v axes="$axes" -v frac="$frac" '
    BEGIN { n = split(cols, c, " "); split(axes, ax, " ") }
    { for (i = 1; i <= n; i++) { v = $c[i] + 0
        if (NR == 1 || v < lo[i]) lo[i] = v; if (NR == 1 || v > hi[i]) hi[i] = v } }
    END { for (i = 1; i <= n; i++) if (hi[i] - lo[i] > s) s = hi[i] - lo[i]
      p = (s > 0) ? frac * s : 1
      for (i = 1; i <= n; i++) { q = p; flat = (hi[i] - lo[i] < 0.01 * s)
        if (flat) { q = 0.1 * s; m = (lo[i] + hi[i]) / 2; if (m * m < 1e-12 * s * s) m = 0
                    printf "set %stics (%.4g)\n", ax[i], m }   # one tic at its value
        printf "set %srange [%.10g:%.10g]\n", ax[i], lo[i] - q, hi[i] + q } }'
  if [[ $coloring == bar ]]; then
    # viridis: ordered in lightness, readable in grey and by colour-blind readers
    echo "set palette defined (0 '#440154', 1 '#472c7a', 2 '#3b518b', 3 '#2c718e', 4 '#21908d'," \
      "5 '#27ad81', 6 '#5cc863', 7 '#aadc32', 8 '#fde725')"
    echo "set cblabel $(q "$color_label")"
    # A constant field gets a range of +-0.5 around its value.
    awk '{ v = $4 + 0; if (NR == 1 || v < lo) lo = v; if (NR == 1 || v > hi) hi = v }
      END { if (hi == lo) { lo -= 0.5; hi += 0.5 }
            printf "set cbrange [%.10g:%.10g]\n", lo, hi }' "$tmpdir/main.dat"
  fi
  # Small dots for dense clouds, a bit bigger for sparse ones; overlay bigger still.
  ps=0.25 ops=0.55
  (( $(wc -l <"$tmpdir/main.dat") >= 2000 )) || ps=0.5 ops=0.8
  cmd=plot; [[ $view != 3d ]] || cmd=splot
  plots=""
  case $coloring in
    "")
      plots+="$(key '#1f77b4' "$label")$(q "$tmpdir/main.dat") using $cols notitle"
      plots+=" with points pt 7 ps $ps lc rgb '#1f77b4'" ;;
    bar)
      plots+="$(key '#21908d' "$label")$(q "$tmpdir/main.dat") using $cols:4 notitle"
      plots+=" with points pt 7 ps $ps lc palette" ;;
    values)
      # tab10, the categorical colours of matplotlib: value V gets colour V when all values are
      # 0..9 (so a collision label has the same colour in every picture), else by rank.
      palette=('#1f77b4' '#ff7f0e' '#2ca02c' '#d62728' '#9467bd' '#8c564b' '#e377c2' '#7f7f7f'
               '#bcbd22' '#17becf')
      by_value=1
      for v in "${values[@]}"; do [[ $v == [0-9] ]] || by_value=0; done
      for rank in "${!values[@]}"; do
        v=${values[$rank]} entry="$color_label ${values[$rank]}"
        colour=${palette[$rank]}; ((by_value == 0)) || colour=${palette[$v]}
        [[ -z ${value_name[$v]+set} ]] || entry="${value_name[$v]} ($entry)"
        plots+="$(key "$colour" "$entry")$(q "$tmpdir/class.$v.cls") using $cols notitle"
        plots+=" with points pt 7 ps $ps lc rgb '$colour', "
      done
      plots=${plots%, } ;;
  esac
  if [[ -n $overlay ]]; then
    ocolor='#d62728'; [[ -z $coloring ]] || ocolor='#000000'
    plots+=", $(key "$ocolor" "$overlay_label")$(q "$tmpdir/overlay.dat") using $cols notitle"
    plots+=" with points pt 7 ps $ops lc rgb '$ocolor'"
  fi
  echo "$cmd $plots"
} >"$tmpdir/plot.gp"
[[ -z $keep_script ]] || cp -- "$tmpdir/plot.gp" "$keep_script" \
  || die "cannot write the gnuplot script to $keep_script"

{ gnuplot "$tmpdir/plot.gp" >"$tmpdir/gnuplot.log" 2>&1 && [[ -s $tmppng ]]; } \
  || { cat "$tmpdir/gnuplot.log" >&2; die "gnuplot failed to render $output"; }
chmod "$(printf '%o' $((0666 & ~0$(umask))))" "$tmppng"
mv -f -- "$tmppng" "$output"
tmppng=""
