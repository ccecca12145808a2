#!/usr/bin/env bash
# One markdown row per run scored by scripts/knn_per_epoch.sh: its last scored epoch's held-out 5-NN vote,
# the vote with each training expert left out in turn, how many of its scored epochs meet the 90% bar, and
# the linear read-out's held-out and left-out rates where the run was scored with them ("-" where not).
# Usage: scripts/knn_summary.sh [KNN_PER_EPOCH.csv...]   (default: every results/walker/*/knn_per_epoch*.csv)
set -euo pipefail
cd "$(dirname "$0")/.."
files=("$@")
[ ${#files[@]} -gt 0 ] || files=(results/walker/*/knn_per_epoch*.csv)
for f in "${files[@]}"; do [ -f "$f" ] || { echo "$f: no such file" >&2; exit 1; }; done
echo "| run | last epoch | held-out | left out in turn | experts left out, most rows right | epochs with held-out >= 90% | linear read-out: held-out, left out |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"
for f in "${files[@]}"; do
  # Columns (knn_per_epoch.sh): epoch,correct,total,per_target,loo_correct,loo_total,loo_experts_correct,loo_experts,
  # then in later files loo_single_correct,loo_single_total and later still linear_correct,linear_loo_correct
  awk -F, -v name="$f" '
    NR == 1 { next }
    NF < 8 { print name ": line " NR " has " NF " columns, expected 8 or more" > "/dev/stderr"; bad = 1; exit 1 }
    { n++; if ($2 >= 0.9 * $3) pass++; e = $1; c = $2; t = $3; lc = $5; lt = $6; lx = $7; ly = $8
      linear = NF >= 12 ? sprintf("%.1f%%, %.1f%%", 100 * $11 / t, 100 * $12 / lt) : "-" }
    END {
      if (bad) exit 1
      if (!n) { print name ": no scored epochs" > "/dev/stderr"; exit 1 }
      printf "| %s | %d | %d / %d = %.1f%% | %.1f%% | %d / %d | %d / %d | %s |\n",
             name, e, c, t, 100 * c / t, 100 * lc / lt, lx, ly, pass + 0, n, linear
    }' "$f"
done
