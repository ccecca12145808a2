#!/usr/bin/env bash
# The arm results of docs/results.md (paper section 4.1), from the published demonstrations and VAE.
# Usage: scripts/arm_results.sh [OUT_DIR]   (default results/arm; about a minute on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/arm}
v=build/vaegail
demos=data/arm/demos.h5
vae=checkpoints/arm/vae/checkpoints/latest.pt
mkdir -p "$out"

$v plot curves --csv checkpoints/arm/vae/metrics.csv --y train_loss,val_loss --log-y \
    --title "arm VAE: loss per epoch" --out "$out/vae_loss.png"
# Figure 2 (imitation of unseen experts' demonstrations) and Figure 3 (latent interpolation).
$v eval arm --demos $demos --vae $vae --out-dir "$out/eval" | tee "$out/eval.txt"
