#!/usr/bin/env bash
# The paper's humanoid experiment (section 4.3, Figure 5), as far as it exists: the gait controllers of the CMU
# humanoid in eleven movement styles (six training, five evaluation; configs/humanoid_styles/), their evaluation and
# their demonstrations (issue 49; docs/humanoid_controllers.md).
#
# Usage: scripts/reproduce/humanoid.sh [--dry-run] [STAGE...]   (default: controllers demos)
#   tune   CMA-ES over each style's parameters from its file's 'tune' section (`experts tune`, 2 candidates at once),
#          the result written into the style file; resumable from runs/tune/SET_STYLE: 5-10 minutes a style on
#          2 idle cores, the evaluation set's drunk and old after its normal (they start from it)
#   controllers  `experts eval --task humanoid --styles`: per style, 20 ten-second episodes from perturbed starts without
#          and with a 200 N push, gait measures, signature, control steps/s against raw physics, the held-mean
#          replay figure, into results/humanoid/controllers.{txt,csv,json}: about 10 minutes
#   demos  data/humanoid/train.h5 (250 episodes of the six training controllers) and data/humanoid/eval.h5 (250 of
#          the five evaluation controllers), 334 steps each, clean, style as context; `data info` and `demos styles`
#          (the nearest-centroid style classifier) of each into results/humanoid/: about 3 minutes
#   video  one demonstration of each of the eleven styles side by side (`render --styles`: each replayed by its own
#          controller), results/humanoid/styles.mp4 (not committed) and its still docs/figures/humanoid_styles.png:
#          about 5 minutes
#   vae    the humanoid VAE (Table 1 sizes) on data/humanoid/train.h5, both cores (mpirun -np 2) into
#          checkpoints/humanoid/vae: about 2.5 minutes an epoch on 2 idle cores, 60 epochs; resumed by the same command
#          from its checkpoint, or from the committed weights.pt when the checkpoints are gone (Adam restarts)
#   embedding  the training demonstrations' embeddings, their t-SNE coloured by style (the context), the loss
#          curves, into results/humanoid/vae/
#   gail   diverse GAIL on the frozen VAE (the humanoid preset: Tables 2-3, the discriminator on the root and end
#          effectors), 2 ranks, into checkpoints/humanoid/diverse_gail; GAIL_ITERATIONS (default 2000) in total,
#          resumed by the same command; every 200 iterations' checkpoint kept in snapshots/it_N (not committed)
#   course  `eval humanoid` of each snapshot on 5 training demonstrations a style: falls and style kept per style
#          along training; the discriminator's accuracies, the reward and the episode length by iteration; into
#          results/humanoid/course/
#   imitation  `eval humanoid` (Figure 5 right): falls and style kept, VAE policy against fine-tuned, on the
#          training demonstrations and one-shot on the evaluation ones, into results/humanoid/imitation/
#   figure5  Figure 5 left: a demonstration of every style beside its VAE and fine-tuned imitations (`render`), the
#          videos results/humanoid/imitation_{train,eval}.mp4 (not committed), their stills in docs/figures/
#   transitions  `eval transitions` between styles, into results/humanoid/transitions/
#   refit  the VAE policy trained on (`vae refit-policy`): its action decoder on single shuffled steps of the clean
#          demonstrations, encoder and state decoder frozen, its input std floored at 0.05, into
#          checkpoints/humanoid/vae_refit: about 15 minutes; `eval humanoid` of it into results/humanoid/imitation_refit/
#   dart   the DART demonstrations: data/humanoid/train_dart.h5, 1500 episodes of the training styles recorded under
#          Gaussian noise (std 0.2) on every motor command, each step labelled with the clean controller's command:
#          about 6 minutes
#   vae_dart  the VAE policy refit as in `refit` on the DART demonstrations, each one's z borrowed from a clean
#          demonstration of its style (the encoder cannot tell the noisy ones' styles apart), into
#          checkpoints/humanoid/vae_dart (weights.pt committed: the GAIL run below rests on it): about 15 minutes
#   gail_dart  diverse GAIL as `gail` with the DART-refit VAE policy as its base, into
#          checkpoints/humanoid/diverse_gail_dart; GAIL_DART_ITERATIONS (default 2000) in total, resumed by the same command
#   imitation_dart  `eval humanoid` and `eval transitions` of the DART-refit VAE policy and its fine-tuned one, into
#          results/humanoid/imitation_dart/ and results/humanoid/transitions_dart/; their Figure 5 left as figure5's,
#          docs/figures/humanoid_imitation_dart_{train,eval}.png
#   dagger  DAgger (Ross et al. 2011) from the DART-refit policy, with each style's own controller as the oracle:
#          DAGGER_ITERATIONS (default 2) rounds of 600 episodes in which the current policy acts on a share of the
#          control steps (0.5, 0.75, 0.9, then 1: the reference experiment's beta) and the controller labels every
#          state (`demos collect --learner`), aggregated with the clean demonstrations (`data merge`), the policy
#          refit on the aggregate (15 epochs on from the previous round's) into checkpoints/humanoid/vae_dagger_N
#          and evaluated (`eval humanoid`, results/humanoid/imitation_dagger/round_N/): about 8 minutes a round;
#          a round's files are kept, so the same command resumes
#   gail_dagger  diverse GAIL as `gail` with the last DAgger round's policy as its base, into
#          checkpoints/humanoid/diverse_gail_dagger; GAIL_DAGGER_ITERATIONS (default 2000) in total, resumed by the same
#          command
#   imitation_dagger  as imitation_dart for the last DAgger round's policy and its fine-tuned one: results/humanoid/
#          imitation_dagger/, transitions_dagger/, docs/figures/humanoid_imitation_dagger_{train,eval}.png
#   all    every stage above in order
# The style files are committed with their tuned parameters, so `controllers demos` regenerates every published humanoid
# figure; the demonstration files are not committed (they are remade in minutes). --dry-run prints the commands.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/reproduce/common.sh
parse_stages "controllers demos" "$@"

v=build/vaegail
train_styles=(configs/humanoid_styles/train/{walk,cat,chicken,drunk,old,graceful}.json)
eval_styles=(configs/humanoid_styles/eval/{drunk,normal,old,swagger,strong}.json)

tune() {
  for s in "${train_styles[@]}" configs/humanoid_styles/eval/{normal,drunk,old,swagger,strong}.json; do
    run $v experts tune "$s" --jobs 2
  done
}

controllers() {
  [ "$dry_run" = 1 ] || mkdir -p results/humanoid
  run_to results/humanoid/controllers.txt $v experts eval --task humanoid --styles "${train_styles[@]}" \
    "${eval_styles[@]}" --episodes 20 --replay --csv results/humanoid/controllers.csv \
    --json results/humanoid/controllers.json
}

demos() {
  for set in train eval; do
    local styles=("${train_styles[@]}")
    [ $set = eval ] && styles=("${eval_styles[@]}")
    run $v demos collect --task humanoid --styles "${styles[@]}" --episodes-per-expert 250 --threads 2 \
      --out data/humanoid/$set.h5 --force
    run_to results/humanoid/${set}_demos.txt $v data info data/humanoid/$set.h5
    run_to results/humanoid/${set}_styles.txt $v demos styles --demos data/humanoid/$set.h5
  done
}

video() {
  local all=("${train_styles[@]}" "${eval_styles[@]}")
  run $v demos collect --task humanoid --styles "${all[@]}" --episodes-per-expert ${#all[@]} --threads 2 \
    --out data/humanoid/styles.h5 --force
  run $v render --demos data/humanoid/styles.h5 --episodes $(seq -s ' ' 0 $((${#all[@]} - 1))) --styles "${all[@]}" \
    --columns 4 --azimuth 120 --elevation -15 --out results/humanoid/styles.mp4 \
    --still docs/figures/humanoid_styles.png --still-frame 200
}

mpi="mpirun -np 2 --bind-to none"
[ "$(id -u)" = 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
vae_run=checkpoints/humanoid/vae
gail_run=checkpoints/humanoid/diverse_gail

vae() {
  run $mpi $v vae train --demos data/humanoid/train.h5 --run-dir $vae_run --preset humanoid --epochs 60 \
    --batch-size 16 --lr 5e-4 --seed 0
}

embedding() {
  local out=results/humanoid/vae
  [ "$dry_run" = 1 ] || mkdir -p $out
  run $v vae embed --checkpoint $vae_run --demos data/humanoid/train.h5 --out $out/embeddings.csv
  run $v plot tsne --embeddings $out/embeddings.csv --color context --out $out/tsne.png
  run $v plot curves --csv $vae_run/metrics.csv --y train_loss,val_loss --out $out/loss.png
}

# In chunks of 200 iterations, each chunk's checkpoint kept in $gail_run/snapshots/it_N for the course stage (the
# trainer keeps only its latest): a run interrupted mid-chunk resumes inside it.
gail_chunk=200

gail() {
  local total=${GAIL_ITERATIONS:-2000} n
  for ((n = gail_chunk; n <= total; n += gail_chunk)); do
    run $mpi $v gail train --demos data/humanoid/train.h5 --vae $vae_run --run-dir $gail_run --envs 16 \
      --iterations $n --seed 0
    local snap=$gail_run/snapshots/it_$n
    [ "$dry_run" = 1 ] || [ -e $snap/checkpoints/latest.pt ] || {
      mkdir -p $snap/checkpoints && cp $gail_run/config.json $snap/ &&
        cp $gail_run/checkpoints/latest.pt $snap/checkpoints/latest.pt.tmp &&
        mv $snap/checkpoints/latest.pt.tmp $snap/checkpoints/latest.pt
    }
  done
}

# Whether the styles survive fine-tuning (the walker lost two of its four speeds): `eval humanoid` on each kept
# snapshot, 5 training demonstrations a style, into results/humanoid/course/it_N/; and the run's discriminator
# accuracies, reward and episode length by iteration.
course() {
  local snap
  [ "$dry_run" = 1 ] || mkdir -p results/humanoid/course
  run $v plot curves --csv $gail_run/metrics.csv --x iteration --y gail_reward,disc_policy_accuracy,disc_demo_accuracy \
    --out results/humanoid/course/discriminator.png
  run $v plot curves --csv $gail_run/metrics.csv --x iteration --y episode_length \
    --out results/humanoid/course/episode_length.png
  for snap in $gail_run/snapshots/it_*; do
    [ -e "$snap/checkpoints/latest.pt" ] || continue
    run $v eval humanoid --demos data/humanoid/train.h5 --vae $vae_run --gail "$snap" --episodes-per-style 5 \
      --threads 2 --out-dir "results/humanoid/course/$(basename "$snap")"
  done
}

imitation() {
  run $v eval humanoid --demos data/humanoid/train.h5 --eval-demos data/humanoid/eval.h5 --vae $vae_run \
    --gail $gail_run --episodes-per-style 10 --threads 2 --out-dir results/humanoid/imitation
}

# Figure 5 left: the first demonstration of each style (episode i is style i mod K; replayed by its controller)
# beside its VAE and fine-tuned imitations, training styles and, one-shot, evaluation styles; the videos (not
# committed) and a still of each.
figure5() {
  imitation_strips $vae_run $gail_run imitation
}

# imitation_strips VAE GAIL NAME: for the training and, one-shot, the evaluation styles, results/humanoid/NAME_SET.mp4
# and its still docs/figures/humanoid_NAME_SET.png.
imitation_strips() {
  local set
  for set in train eval; do
    local styles=("${train_styles[@]}")
    [ $set = eval ] && styles=("${eval_styles[@]}")
    run $v render --demos data/humanoid/$set.h5 --episodes $(seq -s ' ' 0 $((${#styles[@]} - 1))) --vae "$1" \
      --gail "$2" --styles "${styles[@]}" --azimuth 120 --elevation -15 --out results/humanoid/$3_$set.mp4 \
      --width 240 --height 180 --still docs/figures/humanoid_$3_$set.png --still-frame 15 45 150
  done
}

# The VAE policy trained on past the joint VAE (`vae refit-policy`): the joint training gives the action decoder under
# a thousand Adam steps, and without a floor on its input std the hand joints (std 1e-3 in the demonstrations) saturate
# it as soon as a state leaves them. On the clean demonstrations (behaviour cloning: falls) and on DART ones.
vae_refit_run=checkpoints/humanoid/vae_refit
vae_dart_run=checkpoints/humanoid/vae_dart
gail_dart_run=checkpoints/humanoid/diverse_gail_dart
std_floor=0.05

refit() {
  run $v vae refit-policy --checkpoint $vae_run --demos data/humanoid/train.h5 --out-dir $vae_refit_run \
    --state-std-floor $std_floor --epochs 30 --seed 0
  run $v eval humanoid --demos data/humanoid/train.h5 --eval-demos data/humanoid/eval.h5 --vae $vae_refit_run \
    --episodes-per-style 10 --threads 2 --out-dir results/humanoid/imitation_refit
}

# DART (issue 50, item 3): the training styles recorded while Gaussian noise (std 0.2) perturbs every motor command,
# each step labelled with the clean controller's command from the state the noise led to (`demos collect
# --action-noise`), so that the policy learns what to do off the demonstrator's path.
dart() {
  run $v demos collect --task humanoid --styles "${train_styles[@]}" --episodes-per-expert 1500 --threads 2 \
    --action-noise 0.2 --out data/humanoid/train_dart.h5 --force
  run_to results/humanoid/train_dart_demos.txt $v data info data/humanoid/train_dart.h5
}

vae_dart() {
  ensure data/humanoid/train_dart.h5 dart
  ensure data/humanoid/train.h5 demos
  run $v vae refit-policy --checkpoint $vae_run --demos data/humanoid/train_dart.h5 --out-dir $vae_dart_run \
    --state-std-floor $std_floor --epochs 30 --seed 0 --z-from data/humanoid/train.h5
}

gail_dart() {
  run $mpi $v gail train --demos data/humanoid/train.h5 --vae $vae_dart_run --run-dir $gail_dart_run --envs 16 \
    --iterations "${GAIL_DART_ITERATIONS:-2000}" --seed 0
}

# imitation_of VAE GAIL NAME: `eval humanoid` of the VAE policy and its fine-tuned one into results/humanoid/imitation_NAME/,
# the GAIL run's discriminator curves and episode length, their Figure 5 left (imitation_strips, NAME imitation_NAME) and `eval transitions`
# into results/humanoid/transitions_NAME/.
imitation_of() {
  run $v eval humanoid --demos data/humanoid/train.h5 --eval-demos data/humanoid/eval.h5 --vae "$1" \
    --gail "$2" --episodes-per-style 10 --threads 2 --out-dir results/humanoid/imitation_$3
  run $v plot curves --csv "$2"/metrics.csv --x iteration --y gail_reward,disc_policy_accuracy,disc_demo_accuracy \
    --out results/humanoid/imitation_$3/discriminator.png
  run $v plot curves --csv "$2"/metrics.csv --x iteration --y episode_length --out results/humanoid/imitation_$3/episode_length.png
  imitation_strips "$1" "$2" imitation_$3
  run_to results/humanoid/transitions_$3.txt $v eval transitions --demos data/humanoid/train.h5 --vae "$1" \
    --gail "$2" --pairs 200 --per-expert 11 --out-dir results/humanoid/transitions_$3
}

imitation_dart() {
  imitation_of $vae_dart_run $gail_dart_run dart
}

dagger() {
  ensure data/humanoid/train.h5 demos
  ensure $vae_dart_run/weights.pt vae_dart
  local learner=$vae_dart_run/weights.pt aggregate=data/humanoid/train.h5 shares=(0.5 0.75 0.9) round share
  for ((round = 1; round <= ${DAGGER_ITERATIONS:-2}; round++)); do
    share=${shares[round - 1]:-1}  # the learner's share of the steps: beta = 0.5, 0.25, 0.1, then 0
    [ -e data/humanoid/dagger_$round.h5 ] ||
      run $v demos collect --task humanoid --styles "${train_styles[@]}" --episodes-per-expert 600 --threads 2 \
        --seed $((100 + round)) --learner $learner --learner-share $share --z-from data/humanoid/train.h5 \
        --out data/humanoid/dagger_$round.h5
    [ -e data/humanoid/dagger_aggregate_$round.h5 ] ||
      run $v data merge $aggregate data/humanoid/dagger_$round.h5 --out data/humanoid/dagger_aggregate_$round.h5
    aggregate=data/humanoid/dagger_aggregate_$round.h5
    run $v vae refit-policy --checkpoint $learner --demos $aggregate --out-dir checkpoints/humanoid/vae_dagger_$round \
      --epochs 15 --seed 0 --z-from data/humanoid/train.h5
    learner=checkpoints/humanoid/vae_dagger_$round/weights.pt
    run $v eval humanoid --demos data/humanoid/train.h5 --eval-demos data/humanoid/eval.h5 --vae $learner \
      --episodes-per-style 10 --threads 2 --out-dir results/humanoid/imitation_dagger/round_$round
  done
}

# Diverse GAIL on the last DAgger round's policy (its weights.pt committed: the run rests on it).
vae_dagger_run=checkpoints/humanoid/vae_dagger_${DAGGER_ITERATIONS:-2}
gail_dagger_run=checkpoints/humanoid/diverse_gail_dagger

gail_dagger() {
  ensure $vae_dagger_run/weights.pt dagger
  run $mpi $v gail train --demos data/humanoid/train.h5 --vae $vae_dagger_run --run-dir $gail_dagger_run --envs 16 \
    --iterations "${GAIL_DAGGER_ITERATIONS:-2000}" --seed 0
}

imitation_dagger() {
  imitation_of $vae_dagger_run $gail_dagger_run dagger
}

transitions() {
  run_to results/humanoid/transitions.txt $v eval transitions --demos data/humanoid/train.h5 --vae $vae_run \
    --gail $gail_run --pairs 200 --per-expert 11 --out-dir results/humanoid/transitions
}

run_stages tune controllers demos video vae embedding gail course imitation figure5 transitions refit dart vae_dart \
  gail_dart imitation_dart dagger gail_dagger imitation_dagger
