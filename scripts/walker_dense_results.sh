#!/usr/bin/env bash
# Issue 4's bar on the dense walker set: the embedding space of a VAE trained on it.
# Usage: scripts/walker_dense_results.sh [OUT_DIR [RUN_DIR]]   (defaults results/walker/dense and
# checkpoints/walker/vae_dense; about 4 minutes on 2 cores, plus 30 s to regenerate
# data/walker/demos_dense.h5 from the committed experts)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/walker/dense}
v=build/vaegail
demos=data/walker/demos_dense.h5
run=${2:-checkpoints/walker/vae_dense}
mkdir -p "$out"

if [ ! -f $demos ]; then
  $v demos collect --experts-dir experts/walker experts/walker_dense experts/walker_context \
      --passing experts/walker/eval.json experts/walker_dense/eval.json experts/walker_context/eval.json \
      --out $demos --episodes-per-expert 20 \
      --held-out speed-1_logstd-1_seed3 speed0_logstd-1_seed3 speed1_logstd-1_seed3
fi
$v data info $demos --histogram "$out/speeds.png" > "$out/data_info.txt"
$v vae embed --checkpoint "$run"/checkpoints/latest.pt --demos $demos --out "$out/embeddings.csv"
$v vae knn --embeddings "$out/embeddings.csv" --k 5 | tee "$out/knn.txt"
$v plot tsne --embeddings "$out/embeddings.csv" --out "$out/tsne.png" --coords-out "$out/tsne.csv"
$v plot curves --csv "$run"/metrics.csv --y train_loss,val_loss --log-y \
    --title "walker VAE, dense set: loss per epoch" --out "$out/vae_loss.png"
$v vae imitate --checkpoint "$run"/checkpoints/latest.pt --demos $demos --out "$out/vae_imitate.csv" \
    | tee "$out/vae_imitate.txt"
