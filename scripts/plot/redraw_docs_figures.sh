#!/usr/bin/env bash
# Redraws every figure docs/ and README.md show, and the other committed figures whose data is
# committed as CSV, without rerunning anything: the titles and labels are those the vaegail
# commands that made them give.
# Usage: scripts/plot/redraw_docs_figures.sh   (about 20 s on an idle machine)
#
# Not here, because their data is not committed as CSV: results/arm*/eval*/reach_paths.png and
# interpolation_pair_*.png (the paths; `eval arm` writes them as reach_paths.csv and
# interpolation_pair_N.csv since the figures moved to matplotlib, but the arm VAEs' weights are
# not committed, so rerunning it means retraining); results/walker/dense*/speeds.png (from the
# git-ignored dense demonstration sets); results/walker/dense_root/vae_loss.png (its run is not
# committed).
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/plot/find_python.sh
[ -n "$python" ] || { echo "redraw_docs_figures: needs python3 with matplotlib (apt-get install python3-matplotlib)" >&2; exit 1; }
draw() { echo "${@: -1}"; "$python" "scripts/plot/$1" "${@:2}"; }

# data info data/walker/demos.h5 --histogram docs/figures/walker_speeds.png
draw histogram.py --csv docs/figures/walker_speeds.csv --column value --group-by series --bins 30 \
  --title "distribution of episode mean com_speed" --xlabel "episode mean com_speed" --ylabel episodes \
  --out docs/figures/walker_speeds.png

# scripts/walker_results.sh
draw curves.py --csv checkpoints/walker/vae/metrics.csv --y train_loss,val_loss --log-y \
  --title "walker VAE: loss per epoch" --out results/walker/vae_loss.png
draw curves.py --csv checkpoints/walker/diverse_gail/metrics.csv --x iteration --y speed_error,fall_rate \
  --title "diverse GAIL: rollout speed error and falls" --out results/walker/diverse_gail_curves.png
tsne() {  # the layout `plot tsne` computed (perplexity 30), from its --coords-out
  draw scatter.py --csv "$1/tsne.csv" --x tsne_x --y tsne_y --color achieved_speed --xlabel "t-SNE 1" \
    --ylabel "t-SNE 2" --title "t-SNE of $(($(wc -l < "$1/tsne.csv") - 1)) embeddings (perplexity 30)" --out "$1/tsne.png"
}
tsne results/walker
histograms() {  # the three of `eval walker`, from the CSV files it writes beside them
  local dir=$1
  draw histogram.py --csv "$dir/speed_difference.csv" --column value --group-by series --bins 30 \
    --title "|demo - imitation speed|, training experts" --xlabel m/s --ylabel demonstrations \
    --out "$dir/speed_difference.png"
  draw histogram.py --csv "$dir/speed_difference_held_out.csv" --column value --group-by series --bins 30 \
    --title "|demo - imitation speed|, one-shot (held out)" --xlabel m/s --ylabel demonstrations \
    --out "$dir/speed_difference_held_out.png"
  draw histogram.py --csv "$dir/speeds.csv" --column value --group-by series --bins 30 \
    --title "average speed: demonstrations and imitations" --xlabel m/s --ylabel episodes --out "$dir/speeds.png"
}
histograms results/walker/eval

# scripts/reproduce/walker.sh transitions (eval transitions): blend steps 200..220, measured from 6.5 s
draw timeseries.py --csv results/walker/transitions/speed_over_time.csv --shade 5.0000,5.5000 --smooth 40 \
  --xlabel "time (s)" --ylabel "forward speed (m/s)" --height 720 \
  --title "forward speed through a transition (1 s running mean; blend shaded; measured from 6.50 s)" \
  --out results/walker/transitions/speed_over_time.png

# scripts/walker_dense_results.sh, on the published dense VAE and on the root-only encoder
tsne results/walker/dense
draw curves.py --csv checkpoints/walker/vae_dense/metrics.csv --y train_loss,val_loss --log-y \
  --title "walker VAE, dense set: loss per epoch" --out results/walker/dense/vae_loss.png
tsne results/walker/dense_root

# scripts/arm_results.sh
for run in arm:vae arm_posture:vae_posture; do
  draw curves.py --csv "checkpoints/arm/${run#*:}/metrics.csv" --y train_loss,val_loss \
    --title "arm VAE: loss per epoch" --out "results/${run%:*}/vae_loss.png"
done
