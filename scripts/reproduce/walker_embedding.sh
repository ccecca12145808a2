#!/usr/bin/env bash
# The walker embedding study (docs/experiments/walker-embedding.md): are unseen experts placed by their speed in
# the VAE's latent space? Regenerates the tables' CSVs under results/walker/{dense,dense_root,denser,posture,
# context}/ from the committed experts; the VAE runs go to runs/walker_embedding/ (not committed).
#
# Usage: scripts/reproduce/walker_embedding.sh [--dry-run] [STAGE...]   (default: summary)
#   dense    12 more experts (22 minutes with 2 jobs), the published dense VAE (checkpoints/walker/vae_dense,
#            36 minutes) and its results (4 minutes), then five runs kept epoch by epoch: seeds 0 and 1, KL
#            weight 1 with the learning rate decayed, the root-only encoder at two seeds and on a second split
#   denser   24 more experts (32 minutes); six runs at a constant and a decayed learning rate (seeds 0 and 1, the
#            ten-expert split), the 45-epoch decay and the ten-expert split at seeds 1 and 2 (70 minutes a pair)
#   densest  24 more experts (37.5 minutes); the decayed run on both splits at 8 episodes per expert
#   paper    the same 77 experts at 16 episodes each (the paper's scale), 15 epochs on both splits (75 minutes a
#            run beside two others), then the held-out rows' z refined towards the mode of p(z | demonstration)
#   posture  24 experts trained with a posture cost (84 minutes), the decayed run on them and on the matched set
#            without the cost, two splits each
#   context  8 more context-conditioned experts (2 M steps, then continued to 4 M), the decayed run with them
#   seeds    the matched set at more seeds: three runs side by side, 112 minutes
#   summary  scripts/knn_summary.sh: every scored run at its last epoch (docs/experiments/walker-embedding.md): seconds
#   all      every stage in order: about a day on 2 cores
# A run of 30 epochs takes about 36 minutes alone on 2 cores (one Torch thread), scoring its epochs about 30 s
# each (scripts/knn_per_epoch.sh). --dry-run prints the commands without running them.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/reproduce/common.sh
parse_stages summary "$@"

v=build/vaegail
shared_std=configs/walker_vae_shared_std.json
split2=$(cat results/walker/denser/split2_held_out.txt)
last_eleven="20 21 22 23 24 25 26 27 28 29 30"

# kept_run OUT_DIR TAG DEMOS.h5 SEED EPOCHS DECAY_EPOCHS CONFIG [SCORED_EPOCH...]: a VAE run that keeps every
# epoch's checkpoint (DECAY_EPOCHS 0: a constant learning rate), scored by scripts/knn_per_epoch.sh into
# OUT_DIR/knn_per_epoch_TAG.csv (TAG "": knn_per_epoch.csv), its losses copied to OUT_DIR/vae_metrics_TAG.csv.
kept_run() {
  local out=$1 tag=${2:+_$2} demos=$3 seed=$4 epochs=$5 decay=$6 config=$7
  local run_dir
  run_dir=runs/walker_embedding/$(basename "$out")/${2:-run}
  shift 7
  local decay_option=()
  [ "$decay" = 0 ] || decay_option=(--lr-decay-epochs "$decay")
  run $v --torch-threads 1 vae train --demos "$demos" --run-dir "$run_dir" --preset walker --config "$config" \
    --epochs "$epochs" --batch-size 16 --lr 5e-4 --seed "$seed" --keep-epochs "${decay_option[@]}"
  run scripts/knn_per_epoch.sh "$run_dir" "$demos" "$out/knn_per_epoch$tag.csv" "$@"
  run cp "$run_dir/metrics.csv" "$out/vae_metrics$tag.csv"
}

# experts_of SET: train and grade configs/walker_experts_SET.json into experts/walker_SET.
experts_of() {
  run $v experts train --config "configs/walker_experts_$1.json" --out-dir "experts/walker_$1" --jobs 2 "${@:2}"
  run_to "experts/walker_$1/eval.txt" $v experts eval --dir "experts/walker_$1" --episodes 10 \
    --json "experts/walker_$1/eval.json"
}

dense() {
  local out=results/walker/dense demos=data/walker/demos_dense.h5
  experts_of dense
  run scripts/walker_demos.sh dense
  run $v --torch-threads 1 vae train --demos $demos --run-dir checkpoints/walker/vae_dense --preset walker \
    --config $shared_std --epochs 30 --batch-size 16 --lr 5e-4 --seed 0
  run scripts/walker_dense_results.sh
  kept_run $out "" $demos 0 30 0 $shared_std
  kept_run $out seed1 $demos 1 30 0 $shared_std
  kept_run $out kl1_decay $demos 0 30 30 $shared_std
  # The second split holds out four other experts, one of them at 3 m/s.
  run scripts/walker_demos.sh dense data/walker/demos_dense_split2.h5 \
    speed-1_logstd0_seed3 speed0_logstd0_seed3 speed1_logstd0_seed3 speed3_logstd0_seed4
  local root=configs/walker_vae_root_encoder.json some="1 5 10 15 $last_eleven"
  kept_run $out root_encoder $demos 0 30 30 $root
  # shellcheck disable=SC2086  # the epoch lists split on purpose
  kept_run $out root_encoder_seed1 $demos 1 30 30 $root $some
  # shellcheck disable=SC2086
  kept_run $out root_encoder_split2 data/walker/demos_dense_split2.h5 0 30 30 $root $some
  run scripts/walker_dense_results.sh results/walker/dense_root runs/walker_embedding/dense/root_encoder
}

denser() {
  local out=results/walker/denser demos=data/walker/demos_denser.h5 split=data/walker/demos_denser_split2.h5
  local some="1 5 10 15 $last_eleven"
  experts_of denser
  run scripts/walker_demos.sh denser
  # shellcheck disable=SC2086  # the held-out ids and the epoch lists split on purpose
  {
    run scripts/walker_demos.sh denser $split $split2
    kept_run $out "" $demos 0 30 0 $shared_std $some
    kept_run $out seed1 $demos 1 30 0 $shared_std $some
    kept_run $out split2 $split 0 30 0 $shared_std $some
    kept_run $out decay $demos 0 30 30 $shared_std $last_eleven
    kept_run $out decay_seed1 $demos 1 30 30 $shared_std $last_eleven
    kept_run $out decay_split2 $split 0 30 30 $shared_std $last_eleven
    kept_run $out decay45_split2 $split 0 45 45 $shared_std $(seq 30 45)
    kept_run $out decay_seed1_split2 $split 1 30 30 $shared_std $last_eleven
    kept_run $out decay_seed2_split2 $split 2 30 30 $shared_std $last_eleven
  }
}

densest() {
  experts_of densest
  run scripts/walker_demos.sh densest
  # shellcheck disable=SC2086
  {
    run scripts/walker_demos.sh densest data/walker/demos_densest_split2.h5 $split2
    kept_run results/walker/denser densest data/walker/demos_densest.h5 0 30 30 $shared_std $last_eleven
    kept_run results/walker/denser densest_split2 data/walker/demos_densest_split2.h5 0 30 30 $shared_std $last_eleven
  }
}

# by_expert RUN_DIR DEMOS.h5 OUT.txt [EMBED_OPTION...]: epoch 15's per-expert vote.
by_expert() {
  local emb=$1/embeddings_epoch15${4:+_refined}.csv
  run $v vae embed --checkpoint "$1/checkpoints/epoch_15.pt" --demos "$2" --out "$emb" "${@:4}"
  run_to "$3" $v vae knn --embeddings "$emb" --k 5 --by-expert
}

paper() {
  local out=results/walker/denser
  run scripts/walker_demos.sh paper
  # shellcheck disable=SC2086
  run scripts/walker_demos.sh paper data/walker/demos_paper_split2.h5 $split2
  for split in "" split2; do
    local tag=paper${split:+_$split}
    local demos=data/walker/demos_$tag.h5 run_dir=runs/walker_embedding/denser/$tag
    kept_run $out "$tag" "$demos" 0 15 15 $shared_std
    by_expert "$run_dir" "$demos" "$out/knn_by_expert_${tag}_epoch15.txt"
    by_expert "$run_dir" "$demos" "$out/knn_by_expert_${tag}_epoch15_refined.txt" --refine-steps 50
  done
}

posture() {
  local out=results/walker/posture scored="10 20 25 26 27 28 29 30"
  experts_of posture
  run scripts/walker_demos.sh posture
  run scripts/walker_demos.sh posture data/walker/demos_posture_split2.h5 \
    speed-1_logstd-1_seed1 speed0_logstd-1_seed1 speed1_logstd-1_seed1
  run scripts/walker_demos.sh posture_control
  run scripts/walker_demos.sh posture_control data/walker/demos_posture_control_split2.h5 \
    speed-1_logstd-1_seed1 speed0_logstd-1_seed2 speed1_logstd-1_seed1
  # shellcheck disable=SC2086
  {
    kept_run $out posture data/walker/demos_posture.h5 0 30 30 $shared_std $scored
    kept_run $out posture_split2 data/walker/demos_posture_split2.h5 0 30 30 $shared_std $scored
    kept_run $out control data/walker/demos_posture_control.h5 0 30 30 $shared_std $scored
    kept_run $out control_split2 data/walker/demos_posture_control_split2.h5 0 30 30 $shared_std $scored
  }
}

context() {
  local out=results/walker/context
  experts_of context_more --steps 2000000
  experts_of context_more  # continued to the config's 4 M steps
  run scripts/walker_demos.sh context
  run scripts/walker_demos.sh context data/walker/demos_context_split2.h5 \
    speed-1_logstd-1_seed1 speed0_logstd-1_seed2 speed1_logstd-1_seed1
  kept_run $out context data/walker/demos_context.h5 0 30 30 $shared_std 1 5 10 15 20 25 30
  # stopped after 8 of its 30 epochs to free a core for the tests
  kept_run $out context_split2 data/walker/demos_context_split2.h5 0 8 30 $shared_std 1 5 8
}

seeds() {
  local out=results/walker/posture scored="1 10 $last_eleven"
  ensure data/walker/demos_posture_control_split2.h5 posture
  # shellcheck disable=SC2086
  {
    kept_run $out control_seed1 data/walker/demos_posture_control.h5 1 30 30 $shared_std $scored
    kept_run $out control_seed1_split2 data/walker/demos_posture_control_split2.h5 1 30 30 $shared_std $scored
    kept_run $out control_seed2_split2 data/walker/demos_posture_control_split2.h5 2 30 30 $shared_std $scored
  }
}

summary() {
  run scripts/knn_summary.sh
}

run_stages dense denser densest paper posture context seeds summary
