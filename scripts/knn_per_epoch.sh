#!/usr/bin/env bash
# The held-out 5-NN vote of every epoch of a VAE run trained with `vae train --keep-epochs`.
# Usage: scripts/knn_per_epoch.sh RUN_DIR DEMOS.h5 OUT.csv   (about 30 s an epoch for the walker)
# OUT.csv: epoch, then the vote's correct / total for all held-out episodes and per target.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -eq 3 ] || { echo "usage: $0 RUN_DIR DEMOS.h5 OUT.csv" >&2; exit 2; }
run=$1 demos=$2 out=$3
ls "$run"/checkpoints/epoch_*.pt > /dev/null 2>&1 || { echo "$run: no epoch_N.pt (train with --keep-epochs)" >&2; exit 1; }
v=build/vaegail
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "epoch,correct,total,per_target" > "$tmp/out.csv"
for e in $(ls "$run"/checkpoints/epoch_*.pt | sed 's/.*epoch_//; s/\.pt$//' | sort -n); do
  ckpt=$run/checkpoints/epoch_$e.pt
  $v --torch-threads 1 vae embed --checkpoint "$ckpt" --demos "$demos" --out "$tmp/emb.csv" > /dev/null 2>&1
  # "k-NN ...: 59 / 60 = 98.3% ..." then "  target -1: 20 / 20 = 100.0%" per target
  $v vae knn --embeddings "$tmp/emb.csv" --k 5 | awk -v e="$e" '
    /^k-NN/ { split($0, a, ": "); split(a[2], b, " "); c = b[1]; t = b[3] }
    /target/ { sub(/^ +/, ""); p = p (p ? "; " : "") $1 " " $2 " " $3 "/" $5 }
    END { printf "%s,%s,%s,%s\n", e, c, t, p }' | tee -a "$tmp/out.csv"
done
mv "$tmp/out.csv" "$out"
