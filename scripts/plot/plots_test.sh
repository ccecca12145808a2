#!/usr/bin/env bash
# Each figure script draws a figure of the requested size from a tiny CSV, and bad input ends in
# one line on stderr with no figure left behind (ctest runs this as `plot_scripts_test`).
# Skipped, with a message, when no python3 imports matplotlib (the rule of src/cli/figures.h).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/find_python.sh"
if [ -z "$python" ]; then
  echo "plots_test: skipped: no python3 with matplotlib (apt-get install python3-matplotlib)"
  exit 0
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# draws SCRIPT ARGS...: the script writes $tmp/out.png of 320 x 240 pixels.
draws() {
  local script=$1
  shift
  rm -f "$tmp/out.png"
  "$python" "$here/$script" "$@" --width 320 --height 240 --out "$tmp/out.png" 2> "$tmp/stderr" ||
    { fail "$script $*: $(cat "$tmp/stderr")"; return; }
  local size
  size=$("$python" -c 'import sys, matplotlib.image as m; h, w = m.imread(sys.argv[1]).shape[:2]; print(f"{w}x{h}")' \
    "$tmp/out.png") || { fail "$script: no readable PNG"; return; }
  [ "$size" = 320x240 ] || fail "$script: a $size figure, not 320x240"
}

printf 'epoch,train_loss,val_loss\n1,10,12\n2,5,7\n3,2.5,4\n' > "$tmp/metrics.csv"
draws curves.py --csv "$tmp/metrics.csv" --y train_loss,val_loss --log-y --title "loss"

printf 'episode,expert_id,achieved_speed,tsne_x,tsne_y\n0,a,-1,0.5,1\n1,a,0,1.5,-2\n2,b,3,-4,0.25\n' > "$tmp/tsne.csv"
draws scatter.py --csv "$tmp/tsne.csv" --color achieved_speed

printf 'series,value\ndemonstrations,1\ndemonstrations,1.5\n"a=1, b=2",3\nvae,-1\n' > "$tmp/values.csv"
draws histogram.py --csv "$tmp/values.csv" --column value --group-by series --bins 5

printf 'path,group,label,style,x,y\n0,0,demonstration,solid,0,0\n0,0,demonstration,solid,1,1\n1,0,imitation,dashed,0,0\n1,0,imitation,dashed,0.9,1.1\n2,1,,solid,0,0\n2,1,,solid,-1,0.5\n' \
  > "$tmp/paths.csv"
draws paths.py --csv "$tmp/paths.csv" --xlabel "grip x (m)"
printf 'path,group,label,style,x,y\n0,0,a,solid,0,0\n0,0,a,solid,1,1\n1,0.50,alpha 0.50,dashed,0,0\n1,0.50,alpha 0.50,dashed,0.5,0.6\n' \
  > "$tmp/interpolation.csv"
draws paths.py --csv "$tmp/interpolation.csv" --colormap viridis

printf 'panel,series,style,x,y\nA to B,vae,solid,0,1\nA to B,vae,solid,1,2\nA to B,demonstration B,dashed,0,3\nA to B,demonstration B,dashed,1,3\nB to A,vae,solid,0,0\nB to A,vae,solid,1,-1\nC to A,vae,solid,0,0\n' \
  > "$tmp/series.csv"
draws timeseries.py --csv "$tmp/series.csv" --shade 0.25,0.5 --smooth 2 --columns 2

printf 'group,series,value\ntrain/walk,vae,40\ntrain/walk,diverse_gail,5\neval/old,vae,60\neval/old,diverse_gail,0\ntrain/cat,vae,10\n' \
  > "$tmp/bars.csv"
draws bars.py --csv "$tmp/bars.csv" --ylabel "falls (%)"

# Vector output by the extension.
"$python" "$here/curves.py" --csv "$tmp/metrics.csv" --y val_loss --out "$tmp/out.svg" && grep -q '<svg' "$tmp/out.svg" ||
  fail "curves.py --out out.svg: no SVG"

# Bad input: exit 1, one line naming the file and column, no figure.
rm -f "$tmp/out.png"
"$python" "$here/curves.py" --csv "$tmp/tsne.csv" --x tsne_x --y expert_id --out "$tmp/out.png" 2> "$tmp/stderr"
rc=$?
[ $rc -eq 1 ] && [ "$(grep -c . "$tmp/stderr")" -eq 1 ] && grep -q "tsne.csv: line 2: expert_id is not a finite number" \
  "$tmp/stderr" && [ ! -e "$tmp/out.png" ] || fail "curves.py on a text column: exit $rc, stderr: $(cat "$tmp/stderr")"
"$python" "$here/histogram.py" --csv "$tmp/missing.csv" --column value --out "$tmp/out.png" 2> "$tmp/stderr"
grep -q "missing.csv: No such file" "$tmp/stderr" && [ ! -e "$tmp/out.png" ] ||
  fail "histogram.py on a missing file: $(cat "$tmp/stderr")"
"$python" "$here/paths.py" --csv "$tmp/metrics.csv" --out "$tmp/out.png" 2> "$tmp/stderr"
grep -q "metrics.csv: no column 'path'" "$tmp/stderr" || fail "paths.py without a path column: $(cat "$tmp/stderr")"
"$python" "$here/timeseries.py" --csv "$tmp/series.csv" --shade 1 --out "$tmp/out.png" 2> "$tmp/stderr"
grep -q "shade: two numbers" "$tmp/stderr" || fail "timeseries.py --shade 1: $(cat "$tmp/stderr")"
"$python" "$here/bars.py" --csv "$tmp/metrics.csv" --out "$tmp/out.png" 2> "$tmp/stderr"
grep -q "metrics.csv: no column 'group'" "$tmp/stderr" || fail "bars.py without a group column: $(cat "$tmp/stderr")"
ls "$tmp" | grep -q 'tmp-' && fail "a temporary figure was left behind: $(ls "$tmp")"

echo "plots_test: $failures failure(s)"
[ "$failures" -eq 0 ]
