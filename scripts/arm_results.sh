#!/usr/bin/env bash
# The arm results of docs/results.md (paper section 4.1; defaults: the free-pose run of
# docs/experiments/arm-imitation.md), from the offset-free demonstrations and a
# VAE run trained by scripts/reproduce/arm.sh (its checkpoint, else its weights.pt).
# Usage: scripts/arm_results.sh [OUT_DIR [DEMOS.h5 VAE_RUN_DIR]]   (default results/arm, data/arm/demos.h5,
# checkpoints/arm/vae; about 15 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/arm}
demos=${2:-data/arm/demos.h5}
run=${3:-checkpoints/arm/vae}
v=build/vaegail
vae=$run  # the loaders take a run directory: its checkpoint, else its weights-only export
mkdir -p "$out"
# the default demonstrations are not committed: made from the committed experts
[ $# -ge 2 ] || [ -e "$demos" ] || scripts/reproduce/arm.sh free_pose_demos

# Linear: the loss can fall below 0 (a density over normalised states; the 60-epoch vae_noise005 run did).
$v plot curves --csv $run/metrics.csv --y train_loss,val_loss \
    --title "arm VAE: loss per epoch" --out "$out/vae_loss.png"
# Does the policy read z? Teacher-forced action error with the own, another and a zero z.
$v vae action-error --checkpoint $vae --demos $demos | tee "$out/action_error.txt"
# Figure 2 (imitation of unseen experts' demonstrations) and Figure 3 (latent interpolation),
# between test experts' demonstrations and between training experts'; beside it the reference that
# blends the demonstrations' final joint commands instead of their embeddings.
$v eval arm --demos $demos --vae $vae --out-dir "$out/eval" | tee "$out/eval.txt"
$v eval arm --demos $demos --vae $vae --out-dir "$out/eval_training_pairs" --pairs-from training \
    --training-per-expert 1 | tee "$out/eval_training_pairs.txt"
$v eval arm --demos $demos --joint-blend --out-dir "$out/joint_blend" | tee "$out/joint_blend.txt"
# Is the miss the encoder's or the decoders'? The same, from z refined towards the mode of
# p(z | demonstration) (about 12 minutes).
$v --torch-threads 1 eval arm --demos $demos --vae $vae --out-dir "$out/eval_refined" --refine-steps 50 \
    --training-per-expert 1 | tee "$out/eval_refined.txt"
