#!/usr/bin/env bash
# The paper's walker experiment (sections 3.1 and 4.2, Figure 4): every published walker artefact and
# result, from the experts to the tables of docs/results.md ("Figure 4").
#
# Usage: scripts/reproduce/walker.sh [--dry-run] [STAGE...]   (default: results transitions spread)
#   experts  29 single-speed PPO experts (24 at -1/0/1 m/s, 5 at 3 m/s) into experts/walker and two
#            context-conditioned ones into experts/walker_context, each graded by `experts eval`:
#            about 67 minutes for the 29 with 2 jobs, plus about 25 for the two 6 M-step context experts
#   demos    data/walker/demos.h5, 20 mean-action episodes of each passing expert, three held out, and the
#            speed histogram docs/figures/walker_speeds.png: under a minute
#   vae      the trajectory VAE, checkpoints/walker/vae (45 epochs): 39 minutes
#   policies diverse GAIL and plain GAIL (800 iterations each, about 25 minutes each) and behaviour cloning
#            (30 epochs) into checkpoints/walker/{diverse_gail,plain_gail,bc}
#   results  scripts/walker_results.sh: embeddings, 5-NN and linear read-out, t-SNE, loss curves, the VAE
#            policy alone and the Figure 4 evaluation into results/walker/: about 10 minutes
#   transitions  the paper's transition experiment (end of section 4.3): 200 seeded pairs of demonstrations of
#            different speeds, z blended from the first's to the second's at mid-episode, for the VAE, diverse-GAIL,
#            plain-GAIL and BC policies, into results/walker/transitions/ (two MP4s in videos/): about 4 minutes
#   spread   the two evaluations above again from fresh starts, evaluation (start) seeds 1, 2, 3, into
#            results/walker/spread/seedN/, and their spread beside the published figures,
#            results/walker/spread/summary.md (scripts/walker_spread.py): about 6 minutes
#   all      every stage above in order: about 3.5 hours on 2 cores
# The experts and checkpoints are committed, and every stage that reads the demonstration file (no longer committed)
# restores the published copy from git history when it is missing (or, in a clone without that history, makes it),
# so `results transitions spread` alone regenerates every walker table and figure of docs/results.md; the earlier stages overwrite the committed artefacts (seeded: runs on another machine or thread
# count may differ in the last digits; the demonstration file is byte-identical on a rerun). The embedding study of
# docs/experiments/walker-embedding.md is scripts/reproduce/walker_embedding.sh.
# --dry-run prints the commands without running them. Run from anywhere; paths are the repository's.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/reproduce/common.sh
parse_stages "results transitions spread" "$@"

v=build/vaegail
demos=data/walker/demos.h5
vae_run=checkpoints/walker/vae

experts() {
  run $v experts train --config configs/walker_experts_published.json --out-dir experts/walker --jobs 2
  run $v experts train --config configs/walker_experts_speed3.json --out-dir experts/walker --jobs 2
  run_to experts/walker/eval.txt $v experts eval --dir experts/walker --episodes 10 --json experts/walker/eval.json
  # kept apart from the demonstration set, which was collected before they were trained
  run $v experts train --config configs/walker_experts_context.json --out-dir experts/walker_context
  run_to experts/walker_context/eval.txt $v experts eval --dir experts/walker_context --episodes 10 \
    --json experts/walker_context/eval.json
}

demos() {
  run $v demos collect --experts-dir experts/walker --passing experts/walker/eval.json --out $demos \
    --episodes-per-expert 20 --force --held-out speed-1_logstd-1_seed3 speed0_logstd-1_seed3 speed1_logstd-1_seed3
  run $v data info $demos --histogram docs/figures/walker_speeds.png
}

vae() {
  ensure_published $demos 993cee9 demos
  run $v vae train --demos $demos --run-dir $vae_run --preset walker --epochs 45 --batch-size 16 --lr 5e-4 --seed 0
}

policies() {
  ensure_published $demos 993cee9 demos
  run $v gail train --mode diverse --demos $demos --vae $vae_run/checkpoints/latest.pt \
    --run-dir checkpoints/walker/diverse_gail --iterations 800 --envs 16 --seed 0
  run $v gail train --mode plain --demos $demos --run-dir checkpoints/walker/plain_gail --iterations 800 --envs 16 \
    --seed 0
  run $v bc train --demos $demos --run-dir checkpoints/walker/bc --epochs 30 --seed 0
}

results() {
  ensure_published $demos 993cee9 demos
  run scripts/walker_results.sh results/walker
}

transitions() {
  ensure_published $demos 993cee9 demos
  run_to results/walker/transitions.txt $v eval transitions --demos $demos --vae $vae_run/checkpoints/latest.pt \
    --gail checkpoints/walker/diverse_gail --plain checkpoints/walker/plain_gail --bc checkpoints/walker/bc \
    --pairs 200 --seed 0 --per-expert 11 --videos 2 --out-dir results/walker/transitions
}

spread() {
  ensure_published $demos 993cee9 demos
  local seed out
  for seed in 1 2 3; do
    out=results/walker/spread/seed$seed
    run $v eval walker --demos $demos --vae $vae_run/checkpoints/latest.pt --gail checkpoints/walker/diverse_gail \
      --plain checkpoints/walker/plain_gail --bc checkpoints/walker/bc --per-expert 11 --start-seed $seed \
      --out-dir $out/eval
    run $v eval transitions --demos $demos --vae $vae_run/checkpoints/latest.pt \
      --gail checkpoints/walker/diverse_gail --plain checkpoints/walker/plain_gail --bc checkpoints/walker/bc \
      --pairs 200 --seed 0 --per-expert 11 --start-seed $seed --figure-pairs 0 --out-dir $out/transitions
  done
  run_to results/walker/spread/summary.md scripts/walker_spread.py results/walker
}

run_stages experts demos vae policies results transitions spread
