#!/usr/bin/env bash
# The paper's arm experiment (section 4.1, Figures 2 and 3): the published arm artefacts and the tables of
# docs/results.md ("Figures 2 and 3").
#
# Usage: scripts/reproduce/arm.sh [--dry-run] [STAGE...]   (default: results)
#   experts    60 DDPG reaching experts, each for its own random target, their reward charging the pose's
#              distance from home (experts/arm_posture): about 35 minutes with 2 jobs
#   demos      30 demonstrations per expert, the last 10 experts held out: data/arm/demos_posture.h5 (0.05 rad
#              of execution noise) and data/arm/demos_posture_offset05_noise05.h5 (a recorded per-episode
#              command offset, 0.5 rad of unrecorded execution noise): 15 s each, byte-identical on a rerun
#   vae        the VAE with the paper's arm sizes (configs/arm_vae.json), 30 epochs, the learning rate decayed to
#              0, and its weights-only export: checkpoints/arm/vae_posture, about 45 minutes (the 34 MB
#              weights.pt is committed, the 100 MB checkpoint with the optimiser state is not)
#   results    scripts/arm_results.sh from the VAE's weights: imitation of unseen experts (Figure 2), latent
#              interpolation (Figure 3), the joint-blend reference and refined z into results/arm_posture/:
#              about 15 minutes (the demonstrations made first when missing: 30 s)
#   free_pose  the earlier experts without the posture cost (experts/arm), their demonstrations, VAE and results
#              (results/arm/): about 30 + 1 + 45 + 15 minutes
#   free_pose_demos  the free-pose demonstrations alone, from the committed experts/arm: data/arm/demos.h5 and
#              data/arm/demos_offset05_noise05.h5, 15 s each (scripts/arm_results.sh makes them when missing)
#   all        experts, demos, vae, results and free_pose in order: about 3.5 hours on 2 cores
# The experts and the VAE's config.json, metrics.csv and weights.pt are committed, the demonstration files are
# not: `results` (the default) re-evaluates the published VAE in about 15 minutes. --dry-run prints the commands.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/reproduce/common.sh
parse_stages "results" "$@"

v=build/vaegail
held_out="reach_50 reach_51 reach_52 reach_53 reach_54 reach_55 reach_56 reach_57 reach_58 reach_59"

# collect EXPERTS_DIR OUT.h5 [OPTION...]: 30 episodes per expert, the test experts held out.
collect() {
  local dir=$1 out=$2
  shift 2
  # shellcheck disable=SC2086  # the held-out ids split on purpose
  run $v demos collect --task arm --experts-dir "$dir" --out "$out" "$@" --held-out $held_out
}

# train_vae DEMOS.h5 RUN_DIR: the published recipe.
train_vae() {
  run $v --torch-threads 1 vae train --demos "$1" --run-dir "$2" --preset arm --config configs/arm_vae.json \
    --epochs 30 --lr-decay-epochs 30 --batch-size 16 --lr 5e-4 --seed 0
}

experts() {
  run $v experts train --task arm --count 60 --seed 0 --config configs/arm_experts_posture.json \
    --out-dir experts/arm_posture --jobs 2
  run_to experts/arm_posture/eval.txt $v experts eval --dir experts/arm_posture --json experts/arm_posture/eval.json
}

demos() {
  collect experts/arm_posture data/arm/demos_posture.h5
  collect experts/arm_posture data/arm/demos_posture_offset05_noise05.h5 --offset 0.5 --noise 0.5
}

vae() {
  ensure data/arm/demos_posture_offset05_noise05.h5 demos
  train_vae data/arm/demos_posture_offset05_noise05.h5 checkpoints/arm/vae_posture
  run $v export --run-dir checkpoints/arm/vae_posture
}

results() {
  ensure data/arm/demos_posture.h5 demos
  if [ "$dry_run" = 0 ] && [ ! -f checkpoints/arm/vae_posture/weights.pt ] &&
     [ ! -f checkpoints/arm/vae_posture/checkpoints/latest.pt ]; then
    echo "$0: checkpoints/arm/vae_posture: neither weights.pt nor checkpoints/latest.pt (run the vae stage first)" >&2
    exit 1
  fi
  run scripts/arm_results.sh results/arm_posture data/arm/demos_posture.h5 checkpoints/arm/vae_posture
}

free_pose_demos() {
  collect experts/arm data/arm/demos.h5
  collect experts/arm data/arm/demos_offset05_noise05.h5 --offset 0.5 --noise 0.5
}

free_pose() {
  run $v experts train --task arm --count 60 --seed 0 --out-dir experts/arm --jobs 2
  run_to experts/arm/eval.txt $v experts eval --dir experts/arm --json experts/arm/eval.json
  stage free_pose_demos  # from the experts just trained (`all` lists it after free_pose for that)
  train_vae data/arm/demos_offset05_noise05.h5 checkpoints/arm/vae
  run scripts/arm_results.sh
}

run_stages experts demos vae results free_pose free_pose_demos
