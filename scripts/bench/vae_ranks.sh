#!/usr/bin/env bash
# Scaling of VAE training over MPI ranks on this machine: `vae train`'s own trainer (the ranks'
# shares of each batch, the gradient all-reduce, Adam) on random trajectories of the humanoid's
# shape (Table 1 sizes, 137 state and 56 action components, 334 steps) at the training batch of 16,
# on 1 rank and then on RANKS ranks back to back in one window, then
#   efficiency = (trajectory-steps/s on RANKS ranks) / (RANKS x trajectory-steps/s on 1 rank).
# Each side trains two epochs of BATCHES batches and keeps the faster; about 4 minutes with the
# defaults on 2 cores. Usage:
#   [PRESET=humanoid] [BATCH=16] [BATCHES=2] scripts/bench/vae_ranks.sh [RANKS (default 2)] [extra `vaegail bench vae` options...]
# Run as root, it passes OpenMPI the permission it asks for.
set -euo pipefail
cd "$(dirname "$0")/../.."
ranks=${1:-2}
shift || true
bin=build/vaegail
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
args=(bench vae --preset "${PRESET:-humanoid}" --batch "${BATCH:-16}" --trainer-batches "${BATCHES:-2}" "$@")

"$bin" "${args[@]}" --json "$out/one.json" > "$out/one.txt"
mpirun -np "$ranks" --oversubscribe --bind-to none "$bin" "${args[@]}" --json "$out/ranks.json" > "$out/ranks.txt"
cat "$out/one.txt" "$out/ranks.txt"

python3 - "$out" "$ranks" <<'PY'
import json, sys
out, ranks = sys.argv[1], int(sys.argv[2])
one, many = (json.load(open(f"{out}/{name}.json")) for name in ("one", "ranks"))
print(f"bench vae over ranks: '{one['preset']}' preset, batch {one['batch']} x {one['steps']} steps, "
      f"{one['batches']} batches per epoch")
print(f"  1 rank    {one['trajectory_steps_per_s']:8.0f} trajectory-steps/s  ({one['seconds'] / one['batches']:.2f} s/batch)")
print(f"  {ranks} ranks   {many['trajectory_steps_per_s']:8.0f} trajectory-steps/s  ({many['seconds'] / many['batches']:.2f} s/batch)")
print(f"  speed-up {many['trajectory_steps_per_s'] / one['trajectory_steps_per_s']:.2f}x, scaling efficiency of {ranks} ranks: "
      f"{many['trajectory_steps_per_s'] / (ranks * one['trajectory_steps_per_s']):.3f}")
PY
