#!/usr/bin/env bash
# The held-out 5-NN vote of every epoch of a VAE run trained with `vae train --keep-epochs`,
# and the same vote with each training expert left out in turn (`vae knn --leave-one-expert-out`).
# Usage: scripts/knn_per_epoch.sh RUN_DIR DEMOS.h5 OUT.csv [EPOCH...]   (about 30 s an epoch for the walker;
#        every kept epoch unless EPOCHs are named)
# OUT.csv: epoch, the held-out vote's correct / total and per target, then the leave-one-expert-out
# vote's correct / total, the training experts with most of their episodes correct / all, and the
# left-out vote over the experts of one target speed only (its correct / total; the same as the whole
# when the set has no context-conditioned experts), then the linear read-out's correct on the held-out
# rows and with each training expert left out (`vae knn --linear`; totals as the vote's).
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 3 ] || { echo "usage: $0 RUN_DIR DEMOS.h5 OUT.csv [EPOCH...]" >&2; exit 2; }
run=$1 demos=$2 out=$3
shift 3
ls "$run"/checkpoints/epoch_*.pt > /dev/null 2>&1 || { echo "$run: no epoch_N.pt (train with --keep-epochs)" >&2; exit 1; }
v=build/vaegail
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "epoch,correct,total,per_target,loo_correct,loo_total,loo_experts_correct,loo_experts,loo_single_correct,loo_single_total,linear_correct,linear_loo_correct" > "$tmp/out.csv"
# "k-NN ...: 59 / 60 = 98.3% ..." (or "linear read-out ...: "), "  target -1: 20 / 20 = 100.0%" per target, then
# "  experts with most of their rows correct: 3 / 3"; awk prints correct,total,per_target,experts_correct,experts
summary='
  /^(k-NN|linear)/ { split($0, a, ": "); split(a[2], b, " "); c = b[1]; t = b[3] }
  /^  target/ { sub(/^ +/, ""); p = p (p ? "; " : "") $1 " " $2 " " $3 "/" $5 }
  /experts with/ { n = split($0, a, " "); x = a[n - 2]; y = a[n] }
  END { printf "%s,%s,%s,%s,%s\n", c, t, p, x, y }'
# `--by-expert` lines "  expert ID (target T): C / N; ..." ("targets" for a context-conditioned expert)
single='/^  expert .* \(target [^:]*: / { split($0, a, "): "); split(a[2], b, " "); c += b[1]; n += b[3] }
  END { printf "%d,%d\n", c, n }'

for e in ${*:-$(ls "$run"/checkpoints/epoch_*.pt | sed 's/.*epoch_//; s/\.pt$//' | sort -n)}; do
  ckpt=$run/checkpoints/epoch_$e.pt
  [ -f "$ckpt" ] || { echo "$ckpt: no such epoch" >&2; exit 1; }
  $v --torch-threads 1 vae embed --checkpoint "$ckpt" --demos "$demos" --out "$tmp/emb.csv" > /dev/null 2>&1
  IFS=, read -r c t p _ _ < <($v vae knn --embeddings "$tmp/emb.csv" --k 5 | awk "$summary")
  $v vae knn --embeddings "$tmp/emb.csv" --k 5 --leave-one-expert-out --by-expert > "$tmp/loo.txt"
  IFS=, read -r lc lt _ lx ly < <(awk "$summary" "$tmp/loo.txt")
  IFS=, read -r sc st < <(awk "$single" "$tmp/loo.txt")
  IFS=, read -r rc _ < <($v vae knn --embeddings "$tmp/emb.csv" --linear | awk "$summary")
  IFS=, read -r rlc _ < <($v vae knn --embeddings "$tmp/emb.csv" --linear --leave-one-expert-out | awk "$summary")
  echo "$e,$c,$t,$p,$lc,$lt,$lx,$ly,$sc,$st,$rc,$rlc" | tee -a "$tmp/out.csv"
done
mv "$tmp/out.csv" "$out"
