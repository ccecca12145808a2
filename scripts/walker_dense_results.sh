#!/usr/bin/env bash
# Issue 4's bar on the dense walker set: the embedding space of a VAE trained on it.
# Usage: scripts/walker_dense_results.sh [OUT_DIR [RUN_DIR [SET]]]   (defaults results/walker/dense,
# checkpoints/walker/vae_dense and the dense set; about 4 minutes on 2 cores, plus 30 s to regenerate
# data/walker/demos_SET.h5 from the committed experts with scripts/walker_demos.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/walker/dense}
v=build/vaegail
run=${2:-checkpoints/walker/vae_dense}
set_name=${3:-dense}
demos=data/walker/demos_$set_name.h5
mkdir -p "$out"

[ -f "$demos" ] || scripts/walker_demos.sh "$set_name"
$v data info $demos --histogram "$out/speeds.png" > "$out/data_info.txt"
$v vae embed --checkpoint "$run"/checkpoints/latest.pt --demos $demos --out "$out/embeddings.csv"
$v vae knn --embeddings "$out/embeddings.csv" --k 5 | tee "$out/knn.txt"
# the speed along one direction of z (a ridge regression on mu), where the vote weighs every direction alike
$v vae knn --embeddings "$out/embeddings.csv" --linear | tee -a "$out/knn.txt"
$v plot tsne --embeddings "$out/embeddings.csv" --out "$out/tsne.png" --coords-out "$out/tsne.csv"
$v plot curves --csv "$run"/metrics.csv --y train_loss,val_loss --log-y \
    --title "walker VAE, dense set: loss per epoch" --out "$out/vae_loss.png"
$v vae imitate --checkpoint "$run"/checkpoints/latest.pt --demos $demos --out "$out/vae_imitate.csv" \
    | tee "$out/vae_imitate.txt"
