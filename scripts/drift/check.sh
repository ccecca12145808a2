#!/usr/bin/env bash
# The published figures have not drifted: a small slice of each reproduce script, rerun on today's build and
# compared with the values it gave when results/ was last regenerated (expected.txt, beside this script). ctest
# runs this as `figures_drift` (40 s of CPU; 2.5 to 3.5 minutes on a busy 2-core machine).
#   walker (scripts/reproduce/walker.sh): two demonstrations of each of four training experts (one per target
#     speed) and of one held-out expert, collected from the committed experts as the demos stage does; their
#     embeddings (mu), the Figure 4 evaluation of the committed VAE, diverse-GAIL, plain-GAIL and BC policies
#     (eval walker, from the demonstrations' own starts and with start seed 1 as the spread stage) and the
#     transition experiment over all ordered pairs of five of them (eval transitions)
#   arm (scripts/reproduce/arm.sh): two demonstrations of one training and three test experts, imitated and
#     interpolated by the committed VAE's weights (eval arm: Figures 2 and 3)
# Every value must equal the expected one exactly, as printed (the embeddings to 9 significant digits, speeds and
# distances to 6 decimals; the tool runs one Torch thread by default, so a build gives the same digits every run).
# A walker rollout amplifies a change of 1e-7 anywhere on its way (the dynamics, a network, the encoder) into a
# different speed or fall, so any drift of the published numbers shows here. Self-contained: the demonstration
# files are made from the committed experts, not read from data/ or git history.
# Usage: scripts/drift/check.sh VAEGAIL_BINARY REPO_ROOT [--update]
#   --update rewrites expected.txt from today's build: only together with the regenerated results/
#   (scripts/reproduce/walker.sh and arm.sh) that it vouches for.
set -uo pipefail
[ $# -ge 2 ] || { echo "usage: $0 VAEGAIL_BINARY REPO_ROOT [--update]" >&2; exit 2; }
v=$1 root=$2 update=${3:-}
expected=$root/scripts/drift/expected.txt
tolerance=0  # exact; a number differing by more fails
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
started=$SECONDS

# step NAME COMMAND...: run quietly; on failure show its output and stop.
step() {
  local name=$1
  shift
  if ! "$v" "$@" > "$tmp/$name.log" 2>&1; then
    echo "FAIL: vaegail $* (exit $?):"
    tail -20 "$tmp/$name.log"
    exit 1
  fi
}

# values CSV PREFIX "KEY_COLUMNS" "VALUE_COLUMNS": one "PREFIX/KEY/.../COLUMN VALUE" line per row and value column.
values() {
  awk -F, -v prefix="$2" -v keys="$3" -v vals="$4" -v file="$1" '
    NR == 1 {
      for (i = 1; i <= NF; i++) col[$i] = i
      nk = split(keys, k, " "); nv = split(vals, w, " ")
      for (i = 1; i <= nk; i++) if (!(k[i] in col)) { print file ": no column " k[i] > "/dev/stderr"; exit 1 }
      for (i = 1; i <= nv; i++) if (!(w[i] in col)) { print file ": no column " w[i] > "/dev/stderr"; exit 1 }
      next
    }
    {
      key = prefix
      for (i = 1; i <= nk; i++) key = key "/" $(col[k[i]])
      for (i = 1; i <= nv; i++) print key "/" w[i], $(col[w[i]])
    }' "$1"
}

# ---- walker -----------------------------------------------------------------------------------------------------
walker=(speed-1_logstd-1_seed1 speed0_logstd0_seed0 speed1_logstd-1_seed0 speed3_logstd0_seed0)
held_out=speed1_logstd-1_seed3
vae=$root/checkpoints/walker/vae/checkpoints/latest.pt
policies=(--gail "$root/checkpoints/walker/diverse_gail" --plain "$root/checkpoints/walker/plain_gail"
          --bc "$root/checkpoints/walker/bc")
step walker_demos demos collect --experts-dir "$root/experts/walker" --only "${walker[@]}" "$held_out" \
  --episodes-per-expert 2 --held-out "$held_out" --out "$tmp/walker.h5"
step walker_embed vae embed --checkpoint "$vae" --demos "$tmp/walker.h5" --out "$tmp/embeddings.csv"
step walker_eval eval walker --demos "$tmp/walker.h5" --vae "$vae" "${policies[@]}" --per-expert 2 \
  --out-dir "$tmp/eval"
step walker_eval_seed1 eval walker --demos "$tmp/walker.h5" --vae "$vae" "${policies[@]}" --per-expert 2 \
  --start-seed 1 --out-dir "$tmp/eval_seed1"
step walker_transitions eval transitions --demos "$tmp/walker.h5" --vae "$vae" "${policies[@]}" \
  --episodes 0 2 4 6 8 --figure-pairs 0 --out-dir "$tmp/transitions"

# ---- arm --------------------------------------------------------------------------------------------------------
arm_test=(reach_50 reach_51 reach_52)
step arm_demos demos collect --task arm --experts-dir "$root/experts/arm_posture" --only reach_00 "${arm_test[@]}" \
  --episodes-per-expert 2 --held-out "${arm_test[@]}" --out "$tmp/arm.h5"
step arm_eval eval arm --demos "$tmp/arm.h5" --vae "$root/checkpoints/arm/vae_posture" --training-per-expert 2 \
  --out-dir "$tmp/arm_eval"

{
  values "$tmp/embeddings.csv" walker/embedding "episode" "$(head -1 "$tmp/embeddings.csv" | tr , '\n' |
    grep -E '^(achieved_speed|mu_)' | tr '\n' ' ')"
  values "$tmp/eval/imitation.csv" walker/eval "policy episode" "demo_speed achieved_speed fell"
  values "$tmp/eval_seed1/imitation.csv" walker/eval_seed1 "policy episode" "achieved_speed fell"
  values "$tmp/transitions/transitions.csv" walker/transitions "policy from_episode to_episode" \
    "fell fall_step speed_after matched"
  values "$tmp/arm_eval/reaches.csv" arm/reaches "episode" "imitation_end_x imitation_end_y imitation_end_z final_distance"
  values "$tmp/arm_eval/interpolation.csv" arm/interpolation "pair alpha" "end_x end_y end_z"
} > "$tmp/actual.txt" || { echo "FAIL: an output lacks a column"; exit 1; }

if [ "$update" = --update ]; then
  { sed -n '/^#/p' "$expected" 2> /dev/null | grep -q . && sed -n '/^#/p' "$expected" ||
      echo "# scripts/drift/check.sh's values (name value); regenerate with --update only beside results/"
    cat "$tmp/actual.txt"; } > "$tmp/expected.txt" && mv "$tmp/expected.txt" "$expected"
  echo "wrote $expected ($(grep -vc '^#' "$expected") values, $((SECONDS - started)) s)"
  exit 0
fi

# Compare: every expected name present with its value (numbers within the tolerance), nothing extra.
awk -v tol="$tolerance" '
  function number(s) { return s ~ /^-?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?$/ }
  NR == FNR { if ($0 !~ /^#/ && NF) { want[$1] = $2; order[++n] = $1 } next }
  { got[$1] = $2; if (!($1 in want)) extra[++m] = $1 }
  END {
    bad = 0
    for (i = 1; i <= n; i++) {
      name = order[i]
      if (!(name in got)) { msg = "missing" }
      else if (number(want[name]) && number(got[name])) {
        d = want[name] - got[name]; if (d < 0) d = -d
        if (d <= tol) continue
        msg = "expected " want[name] ", got " got[name]
      } else if (want[name] == got[name]) continue
      else msg = "expected " want[name] ", got " got[name]
      if (++bad <= 20) print "FAIL: " name ": " msg
    }
    for (i = 1; i <= m; i++) if (++bad <= 20) print "FAIL: " extra[i] ": not expected"
    if (bad > 20) print "... " bad - 20 " more"
    print (bad ? "drift: " bad " of " n " values moved" : "no drift: " n " values as expected")
    exit bad ? 1 : 0
  }' "$expected" "$tmp/actual.txt"
rc=$?
echo "($((SECONDS - started)) s)"
exit $rc
