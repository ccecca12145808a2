#!/usr/bin/env bash
# The walker results of docs/results.md, from the published demonstrations and checkpoints.
# Usage: scripts/walker_results.sh [OUT_DIR]   (default results/walker; about 12 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/walker}
v=build/vaegail
demos=data/walker/demos.h5
vae=checkpoints/walker/vae/checkpoints/latest.pt
mkdir -p "$out"
[ -e $demos ] || scripts/reproduce/walker.sh demos  # not committed: made from the committed experts

# Section 3.1: the embedding space.
$v vae embed --checkpoint $vae --demos $demos --out "$out/embeddings.csv"
$v vae knn --embeddings "$out/embeddings.csv" --k 5 | tee "$out/knn.txt"
# the speed along one direction of z (a ridge regression on mu), where the vote weighs every direction alike
$v vae knn --embeddings "$out/embeddings.csv" --linear | tee -a "$out/knn.txt"
$v plot tsne --embeddings "$out/embeddings.csv" --out "$out/tsne.png" --coords-out "$out/tsne.csv"
$v plot curves --csv checkpoints/walker/vae/metrics.csv --y train_loss,val_loss --log-y \
    --title "walker VAE: loss per epoch" --out "$out/vae_loss.png"
$v plot curves --csv checkpoints/walker/diverse_gail/metrics.csv --x iteration --y speed_error,fall_rate \
    --title "diverse GAIL: rollout speed error and falls" --out "$out/diverse_gail_curves.png"

# The VAE policy alone on every training demonstration (issue 4's bar).
$v vae imitate --checkpoint $vae --demos $demos --out "$out/vae_imitate.csv" | tee "$out/vae_imitate.txt"

# Section 4.2: 11 demonstrations per expert, VAE policy vs diverse GAIL, and the baselines.
$v eval walker --demos $demos --vae $vae --gail checkpoints/walker/diverse_gail \
    --plain checkpoints/walker/plain_gail --bc checkpoints/walker/bc --per-expert 11 --out-dir "$out/eval" \
    | tee "$out/eval.txt"

# The longer diverse-GAIL run with the faster defaults (issue 35), the same evaluation.
$v eval walker --demos $demos --vae $vae --gail checkpoints/walker/diverse_gail_fast --per-expert 11 \
    --out-dir "$out/eval_fast"
