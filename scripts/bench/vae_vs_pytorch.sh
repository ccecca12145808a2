#!/usr/bin/env bash
# The VAE's training speed beside a plain PyTorch implementation of the same model, measured in
# the same run: `vaegail bench vae --preset walker` (the walker's shapes: 18 state and 6 action
# components, batch 32 x 400 steps, 1 thread), then the reference script with the same shapes
# (`ref_vae_bench.py 18 6 32 400 2`: one warm-up step, two timed), then both rates and the ratio.
#
# The reference needs Debian's python3-torch (the same LibTorch 1.13 underneath):
#   apt-get install python3-torch
# It is not in scripts/setup.sh: nothing else uses it.
# Usage: scripts/bench/vae_vs_pytorch.sh [REFERENCE.py]
#   (default ../shared/bench/ref_vae_bench.py from the repository root; about 2 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/../.."
reference=${1:-../shared/bench/ref_vae_bench.py}
[ -f "$reference" ] || { echo "vae_vs_pytorch: $reference: no such reference script" >&2; exit 1; }
python=
for candidate in ${VAEGAIL_PYTHON:-python3 /usr/bin/python3}; do
  if "$candidate" -c 'import torch' 2> /dev/null; then python=$candidate; break; fi
done
[ -n "$python" ] || { echo "vae_vs_pytorch: needs python3 with torch (apt-get install python3-torch)" >&2; exit 1; }

ours=$(build/vaegail bench vae --preset walker --state-dim 18 --action-dim 6 --batch 32 --steps 400)
echo "$ours"
theirs=$("$python" "$reference" 18 6 32 400 2)
echo "$theirs"
# "training step  3.151 s (forward + backward + Adam) = 4062 trajectory-steps/s"
our_rate=$(sed -n 's/^training step .* = \([0-9.]*\) trajectory-steps\/s.*/\1/p' <<< "$ours")
# "pytorch-python reference VAE: 1913 trajectory-steps/s (...)"
their_rate=$(sed -n 's/^pytorch-python reference VAE: \([0-9.]*\) trajectory-steps\/s.*/\1/p' <<< "$theirs")
[ -n "$our_rate" ] && [ -n "$their_rate" ] ||
  { echo "vae_vs_pytorch: could not read a rate (vaegail: '$our_rate', reference: '$their_rate')" >&2; exit 1; }
awk -v a="$our_rate" -v b="$their_rate" 'BEGIN {
  printf "\nvaegail %.0f trajectory-steps/s, PyTorch reference %.0f trajectory-steps/s: vaegail is %.2fx the reference\n", a, b, a / b }'
