#!/usr/bin/env bash
# Scaling of diverse-GAIL fine-tuning over MPI ranks on this machine (issue 35): the same run
# (--envs environments in all) on 1 rank of 1 env thread, on RANKS ranks of 1 env thread each
# (mpirun), and on 1 rank of RANKS env threads, back to back in one window, then
#   efficiency = (env steps/s on RANKS ranks) / (RANKS x env steps/s on 1 rank).
# About 3 minutes on the walker with the defaults. Usage:
#   scripts/bench/gail_ranks.sh [RANKS (default 2)] [extra `vaegail bench gail` options...]
# Run as root, it passes OpenMPI the permission it asks for.
set -euo pipefail
cd "$(dirname "$0")/../.."
ranks=${1:-2}
shift || true
bin=build/vaegail
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

"$bin" bench gail --env-threads 1 --json "$out/one.json" "$@" > "$out/one.txt"
mpirun -np "$ranks" --oversubscribe --bind-to none "$bin" bench gail --env-threads 1 --json "$out/ranks.json" "$@" > "$out/ranks.txt"
"$bin" bench gail --env-threads "$ranks" --json "$out/threads.json" "$@" > "$out/threads.txt"

python3 - "$out" "$ranks" <<'PY'
import json, sys
out, ranks = sys.argv[1], int(sys.argv[2])
one, many, threads = (json.load(open(f"{out}/{name}.json")) for name in ("one", "ranks", "threads"))
print(f"bench gail over ranks: {one['mode']} mode, {one['envs']} environments in all")
print(f"  1 rank  x 1 thread   {one['env_steps_per_s']:8.0f} env steps/s  ({one['seconds_per_iteration']:.3f} s/it)")
print(f"  {ranks} ranks x 1 thread   {many['env_steps_per_s']:8.0f} env steps/s  ({many['seconds_per_iteration']:.3f} s/it)")
print(f"  1 rank  x {ranks} threads  {threads['env_steps_per_s']:8.0f} env steps/s  ({threads['seconds_per_iteration']:.3f} s/it)")
print(f"  scaling efficiency of {ranks} ranks: {many['env_steps_per_s'] / (ranks * one['env_steps_per_s']):.3f} (goal >= 0.9)")
print(f"  all-core raw physics ceiling {one['all_core_control_steps_per_s']:.0f}: {ranks} ranks reach "
      f"{many['env_steps_per_s'] / one['all_core_control_steps_per_s']:.3f} of it")
PY
