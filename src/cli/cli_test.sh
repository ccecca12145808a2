#!/usr/bin/env bash
# The command line's promises, checked on the built binary (ctest runs this as `cli_test`):
# every command and subcommand answers --help; bad input (a missing, random or truncated file,
# a malformed CSV, a nan, wrong dimensions, an unknown flag) ends with a non-zero exit, one
# line on stderr naming the problem, and no output file; the scripts in scripts/reproduce/ call commands
# and options that exist.
# Usage: src/cli/cli_test.sh VAEGAIL_BINARY REPO_ROOT
set -uo pipefail
[ $# -eq 2 ] || { echo "usage: $0 VAEGAIL_BINARY REPO_ROOT" >&2; exit 2; }
v=$1 root=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# ---- --help on every command ----------------------------------------------------------
helped=0
check_help() {
  local help
  help=$("$v" "$@" --help 2>&1) && grep -q '^Usage:' <<< "$help" || fail "vaegail $* --help"
  helped=$((helped + 1))
  for s in $(sed -n '/^Subcommands:/,$p' <<< "$help" | awk 'NR > 1 && NF { print $1 }'); do check_help "$@" "$s"; done
}
check_help
[ "$helped" -ge 25 ] || fail "only $helped commands answered --help (expected every subcommand, 25 or more)"

# ---- bad input ------------------------------------------------------------------------
# expect_error WHAT_STDERR_MUST_CONTAIN OUTPUT_THAT_MUST_NOT_EXIST -- COMMAND...
expect_error() {
  local needle=$1 output=$2
  shift 3
  "$v" "$@" > "$tmp/stdout" 2> "$tmp/stderr"
  local rc=$? lines
  lines=$(grep -c . "$tmp/stderr")
  if [ $rc -eq 0 ]; then fail "vaegail $*: exit 0"
  elif ! grep -qF -- "$needle" "$tmp/stderr"; then fail "vaegail $*: stderr lacks '$needle': $(cat "$tmp/stderr")"
  elif [ "$lines" -ne 1 ] && ! grep -q '^Run with --help' "$tmp/stderr"; then fail "vaegail $*: $lines lines on stderr"
  elif [ -n "$output" ] && [ -e "$output" ]; then fail "vaegail $*: left $output behind"
  fi
}

# Fixtures of its own, small: one demonstration of a committed walker expert and one arm episode (the published
# demonstration files are not committed).
walker_vae=$root/checkpoints/walker/vae/checkpoints/latest.pt
"$v" demos collect --experts-dir "$root/experts/walker" --only speed-1_logstd-1_seed0 --episodes-per-expert 1 \
  --out "$tmp/one.h5" > /dev/null 2>&1 ||
  fail "demos collect --only speed-1_logstd-1_seed0"
"$v" env rollout --task arm --episodes 1 --out "$tmp/arm.h5" > /dev/null 2>&1 || fail "env rollout --task arm"
head -c 4096 /dev/urandom > "$tmp/random.h5"
head -c "$(($(stat -c %s "$tmp/one.h5") / 2))" "$tmp/one.h5" > "$tmp/truncated.h5"
printf 'episode,expert_id\n0,a\n' > "$tmp/header.csv"
printf 'episode,expert_id,context,achieved_speed,held_out,mu_0,sigma_0\n0,a,1,1,1,nan,0.1\n' > "$tmp/nan.csv"
out=$tmp/out.csv

expect_error "missing.h5" "" -- data info "$tmp/missing.h5"
expect_error "random.h5: not an HDF5 file" "" -- data info "$tmp/random.h5"
expect_error "truncated.h5" "" -- data info "$tmp/truncated.h5"
expect_error "missing.csv" "" -- vae knn --embeddings "$tmp/missing.csv"
expect_error "header.csv: line 1" "" -- vae knn --embeddings "$tmp/header.csv"
expect_error "nan.csv: line 2: mu_0 is not finite" "" -- vae knn --embeddings "$tmp/nan.csv"
expect_error "missing.pt" "$out" -- vae embed --checkpoint "$tmp/missing.pt" --demos "$tmp/one.h5" --out "$out"
expect_error "truncated.h5" "$out" -- vae embed --checkpoint "$walker_vae" --demos "$tmp/truncated.h5" --out "$out"
expect_error "21/9 components, the checkpoint's VAE 18/6" "$out" -- \
  vae embed --checkpoint "$walker_vae" --demos "$tmp/arm.h5" --out "$out"
expect_error "--bogus" "$tmp/run" -- vae train --demos "$tmp/one.h5" --run-dir "$tmp/run" --bogus
expect_error "--k" "" -- vae knn --embeddings "$tmp/nan.csv" --k 0

# One training-expert episode: nothing held out for `vae embed --refine-steps` unless --refine-all.
expect_error "one.h5: no held-out demonstrations to refine" "$out" -- \
  vae embed --checkpoint "$walker_vae" --demos "$tmp/one.h5" --out "$out" --refine-steps 1
"$v" vae embed --checkpoint "$walker_vae" --demos "$tmp/one.h5" --out "$out" --refine-steps 1 --refine-all \
  > "$tmp/stdout" 2>&1 && grep -q "refined by 1 Adam steps" "$tmp/stdout" && [ -s "$out" ] ||
  fail "vae embed --refine-steps 1 --refine-all: $(tail -1 "$tmp/stdout")"

# --only and --passing together: only the named experts that pass (speed-1_logstd-1_seed0 fails the bar).
passing=$root/experts/walker/eval.json
"$v" demos collect --experts-dir "$root/experts/walker" --only speed-1_logstd-1_seed0 speed-1_logstd-1_seed1 \
  --passing "$passing" --episodes-per-expert 1 --out "$tmp/passing.h5" > "$tmp/stdout" 2>&1 &&
  grep -q ": 1 experts x 1 episodes" "$tmp/stdout" ||
  fail "demos collect --only A B --passing: $(tail -1 "$tmp/stdout")"
expect_error "no expert named by --only passes" "$tmp/failing.h5" -- demos collect --experts-dir "$root/experts/walker" \
  --only speed-1_logstd-1_seed0 --passing "$passing" --out "$tmp/failing.h5"

# ---- a body of one's own, end to end (docs/own_body.md at tiny scale) ------------------
# The demonstration file alone rebuilds the body: the later stages run from another directory,
# where the MJCF path the file names does not exist.
body=$root/docs/own_body/hopper.xml
tiny='{"lstm_hidden": 16, "latent_dim": 4, "action_hidden": [32, 32], "wavenet_channels": 8, "wavenet_layers": 2, "mixture_components": 2}'
echo "$tiny" > "$tmp/tiny.json"
mkdir -p "$tmp/elsewhere"
run_in() { (cd "$1" && shift && "$v" "$@") > "$tmp/stdout" 2>&1 || fail "vaegail ${*:2}: $(tail -1 "$tmp/stdout")"; }
run_in "$root" env rollout --task docs/own_body/hopper.xml --policy gait --styles 4 --episodes 8 --seed 3 \
  --out "$tmp/body.h5"
grep -qE '^2 +hop +2 +0 ' "$tmp/stdout" ||
  fail "env rollout --policy gait: no hop row without falls: $(cat "$tmp/stdout")"
expect_error "--styles: Value 0 not in range" "$tmp/b.h5" -- env rollout --task "$body" --policy gait --styles 0 \
  --out "$tmp/b.h5"
expect_error "defines 4 gait styles (vaegail_gait_style_*), fewer than the 5 asked for" "$tmp/b.h5" -- \
  env rollout --task "$body" --policy gait --styles 5 --out "$tmp/b.h5"
expect_error "--styles is for --policy gait" "$tmp/b.h5" -- env rollout --task "$body" --styles 2 --out "$tmp/b.h5"
sed 's/<motor name="hip_motor" joint="hip"/<motor name="hip_motor" joint="rootx"/' "$body" > "$tmp/slide_body.xml"
expect_error "actuator 'hip_motor' is not a motor on a hinge joint" "$tmp/b.h5" -- \
  env rollout --task "$tmp/slide_body.xml" --policy gait --out "$tmp/b.h5"
expect_error "task 'walker' cannot record a style context" "$tmp/b.h5" -- env rollout --policy gait --out "$tmp/b.h5"
run_in "$tmp/elsewhere" vae train --demos "$tmp/body.h5" --run-dir "$tmp/body_vae" --config "$tmp/tiny.json" --epochs 1
run_in "$tmp/elsewhere" gail train --demos "$tmp/body.h5" --vae "$tmp/body_vae/checkpoints/latest.pt" \
  --run-dir "$tmp/body_gail" --iterations 1 --envs 4
run_in "$tmp/elsewhere" eval body --demos "$tmp/body.h5" --vae "$tmp/body_vae/checkpoints/latest.pt" \
  --gail "$tmp/body_gail" --per-expert 3 --out-dir "$tmp/body_eval"
grep -q '^| diverse_gail | 8 |' "$tmp/body_eval/summary.md" && grep -q 'error_torso_height' "$tmp/body_eval/imitation.csv" ||
  fail "eval body: no diverse_gail row or torso_height error in $tmp/body_eval"
# transitions need a task's notion of behaviour (eval/transitions.h): a body of one's own has none
expect_error "has no behaviour judge for transitions" "$tmp/body_transitions" -- eval transitions \
  --demos "$tmp/body.h5" --vae "$tmp/body_vae/checkpoints/latest.pt" --out-dir "$tmp/body_transitions"
sed 's/data="0.35"/data="0.3"/' "$body" > "$tmp/other_body.xml"
expect_error "body.h5: recorded on body docs/own_body/hopper.xml (sha256" "$tmp/g" -- gail train --demos "$tmp/body.h5" \
  --vae "$tmp/body_vae/checkpoints/latest.pt" --run-dir "$tmp/g" --iterations 1 --task "$tmp/other_body.xml"
expect_error "not on --task walker (a built-in task)" "$tmp/g" -- gail train --demos "$tmp/body.h5" \
  --vae "$tmp/body_vae/checkpoints/latest.pt" --run-dir "$tmp/g" --iterations 1 --task walker
expect_error "cannot load MJCF model" "$tmp/b.h5" -- env rollout --task "$tmp/missing.xml" --out "$tmp/b.h5"

# ---- export: weights files that every loader takes ----------------------------------------
run_in "$tmp/elsewhere" export --run-dir "$tmp/body_vae"
run_in "$tmp/elsewhere" export --run-dir "$tmp/body_gail" --out "$tmp/body_gail.pt"
run_in "$tmp" vae embed --checkpoint "$tmp/body_vae" --demos "$tmp/body.h5" --out "$tmp/embed_run.csv"
run_in "$tmp" vae embed --checkpoint "$tmp/body_vae/weights.pt" --demos "$tmp/body.h5" --out "$tmp/embed_weights.csv"
cmp -s "$tmp/embed_run.csv" "$tmp/embed_weights.csv" || fail "vae embed: the exported VAE embeds otherwise"
run_in "$tmp/elsewhere" eval body --demos "$tmp/body.h5" --vae "$tmp/body_vae/weights.pt" --gail "$tmp/body_gail.pt" \
  --per-expert 3 --out-dir "$tmp/body_eval_weights"
cmp -s "$tmp/body_eval/imitation.csv" "$tmp/body_eval_weights/imitation.csv" ||
  fail "eval body: the exported VAE and diverse-GAIL policy imitate otherwise"
expect_error "$tmp/missing: no such run directory" "" -- export --run-dir "$tmp/missing"
head -c 2000 "$tmp/body_gail.pt" > "$tmp/truncated.pt"
expect_error "truncated.pt: damaged checkpoint" "$tmp/e" -- eval body --demos "$tmp/body.h5" \
  --vae "$tmp/body_vae/weights.pt" --gail "$tmp/truncated.pt" --out-dir "$tmp/e"
expect_error "body_gail.pt: the weights of a gail run, not of a VAE" "$tmp/e.csv" -- \
  vae embed --checkpoint "$tmp/body_gail.pt" --demos "$tmp/body.h5" --out "$tmp/e.csv"

# ---- the published demonstrations are made when missing, by walker.sh's command -----------
# Where there are no experts the command is echoed, then fails on them.
(cd "$tmp/elsewhere" && "$v" quickstart --out-dir "$tmp/q") > "$tmp/stdout" 2>&1
collect=$("$root/scripts/reproduce/walker.sh" --dry-run demos | sed -n 's|^+ build/vaegail demos collect |demos collect |p')
grep -qxF "\$ vaegail $collect" "$tmp/stdout" ||
  fail "quickstart without data/walker/demos.h5 does not run walker.sh's demos command: $(head -3 "$tmp/stdout")"

# ---- import and export ----------------------------------------------------------------
run_in "$tmp" data export "$tmp/body.h5" --minari "$tmp/body_minari"
run_in "$tmp" data import "$tmp/body_minari" --out "$tmp/body_back.h5"
grep -q "body stored in the file" "$tmp/stdout" || fail "data import of an exported directory lost the body"
expect_error "body_minari: exists (pass --force" "" -- data export "$tmp/body.h5" --minari "$tmp/body_minari"
expect_error "nothing: no Minari dataset (no $tmp/nothing/data/metadata.json, $tmp/nothing/metadata.json)" "$tmp/i.h5" -- \
  data import "$tmp/nothing" --out "$tmp/i.h5"
fixtures=$root/src/data/testdata/write_foreign_demos.py
if /usr/bin/python3 -c 'import h5py, numpy' 2> /dev/null; then
  /usr/bin/python3 "$fixtures" check_minari "$tmp/body_minari" > /dev/null || fail "exported directory: not Minari's layout"
  /usr/bin/python3 "$fixtures" npz "$tmp/trajectories.npz" && /usr/bin/python3 "$fixtures" minari "$tmp/minari"
  run_in "$tmp" data import "$tmp/trajectories.npz" --out "$tmp/npz.h5"
  run_in "$tmp" data import "$tmp/minari" --out "$tmp/minari.h5"
  # Minari's own root: a dataset ID under $MINARI_DATASETS_PATH.
  mkdir -p "$tmp/minari_root/tiny" && mv "$tmp/minari" "$tmp/minari_root/tiny/expert-v0"
  (cd "$tmp" && MINARI_DATASETS_PATH="$tmp/minari_root" "$v" data import tiny/expert-v0 --out "$tmp/by_id.h5") \
    > "$tmp/stdout" 2>&1 || fail "data import ID under MINARI_DATASETS_PATH: $(cat "$tmp/stdout")"
  expect_error "observations/actions of 2/1 components, task '$body' has 10/2" "$tmp/i.h5" -- \
    data import "$tmp/trajectories.npz" --out "$tmp/i.h5" --task "$body"
  expect_error "npz.h5: recorded on 'imitation', which is neither built in nor stored in the file" "$tmp/g" -- \
    gail train --mode plain --demos "$tmp/npz.h5" --run-dir "$tmp/g" --iterations 1
fi

# ---- PPO on the humanoid: train (its context a style label), eval refused -------------
cat > "$tmp/humanoid.json" <<'JSON'
{"grid": {"groups": [[0, 3]], "init_log_stds": [-1], "seeds": 1, "condition": "one_hot"},
 "training": {"num_envs": 2, "steps_per_env": 32, "hidden": [16, 16], "epochs": 1, "minibatches": 1}}
JSON
expect_error "--config must give a 'grid' or 'grids'" "$tmp/h" -- experts train --task humanoid --out-dir "$tmp/h"
"$v" experts train --task humanoid --config "$tmp/humanoid.json" --out-dir "$tmp/h" --steps 64 > /dev/null 2>&1 &&
  [ -s "$tmp/h/humanoid_ctx0_3_logstd-1_seed0/agent.pt" ] || fail "experts train --task humanoid"
expect_error "whose demonstrators are gait controllers: experts eval --task humanoid --styles" "" -- \
  experts eval --dir "$tmp/h" --episodes 2

# ---- the humanoid's gait controllers: demos collect --styles, demos styles, experts tune -----
styles=("$root/configs/humanoid_styles/train/old.json" "$root/configs/humanoid_styles/train/chicken.json")
"$v" demos collect --task humanoid --styles "${styles[@]}" --episodes-per-expert 4 --threads 2 --out "$tmp/h.h5" > /dev/null 2>&1 &&
  "$v" demos styles --demos "$tmp/h.h5" > "$tmp/stdout" 2>&1 && grep -q "of 2 held-out episodes named right" "$tmp/stdout" &&
  grep -q "train/chicken" "$tmp/stdout" || fail "demos collect --task humanoid --styles, demos styles: $(cat "$tmp/stdout")"
expect_error "--styles is for --task humanoid" "$tmp/w.h5" -- demos collect --styles "${styles[0]}" --out "$tmp/w.h5"
expect_error "--action-noise is for the humanoid's gait controllers" "$tmp/w.h5" -- demos collect --action-noise 0.1 \
  --out "$tmp/w.h5"
run_in "$tmp" demos collect --task humanoid --styles "${styles[0]}" --episodes-per-expert 1 --action-noise 0.1 \
  --out "$tmp/h_dart.h5"
grep -q "execution noise 0.1, clean labels" "$tmp/stdout" || fail "demos collect --action-noise: $(cat "$tmp/stdout")"

# ---- the humanoid's later stages at tiny scale: VAE, GAIL by the humanoid preset, eval humanoid, transitions, bench
run_in "$tmp" demos collect --task humanoid --styles "$root/configs/humanoid_styles/train/walk.json" --episodes-per-expert 2 \
  --threads 2 --out "$tmp/h_eval.h5"
run_in "$tmp" vae train --demos "$tmp/h.h5" --run-dir "$tmp/h_vae" --preset humanoid --config "$tmp/tiny.json" --epochs 1
run_in "$tmp" vae refit-policy --checkpoint "$tmp/h_vae" --demos "$tmp/h_dart.h5" --out-dir "$tmp/h_refit" --epochs 2 \
  --batch-size 64 --state-std-floor 0.05 --z-from "$tmp/h.h5"
grep -q "borrowed from a demonstration of its context" "$tmp/stdout" && [ -e "$tmp/h_refit/weights.pt" ] &&
  [ "$(wc -l < "$tmp/h_refit/metrics.csv")" -eq 3 ] || fail "vae refit-policy: $(cat "$tmp/stdout")"
# DAgger: the refit policy acts on a share of the steps, the controller labels; the aggregate by data merge.
run_in "$tmp" demos collect --task humanoid --styles "${styles[@]}" --episodes-per-expert 2 --learner "$tmp/h_refit" \
  --learner-share 0.5 --z-from "$tmp/h.h5" --out "$tmp/h_dagger.h5"
grep -q "DAgger: the learner acts on 0.5 of the steps" "$tmp/stdout" || fail "demos collect --learner: $(cat "$tmp/stdout")"
expect_error "--learner and --z-from go together" "$tmp/w.h5" -- demos collect --task humanoid --styles "${styles[0]}" \
  --learner "$tmp/h_refit" --out "$tmp/w.h5"
expect_error "h_dart.h5: no demonstration by train/chicken to lend the learner its z" "$tmp/w.h5" -- demos collect --task humanoid --styles "${styles[@]}" \
  --learner "$tmp/h_refit" --z-from "$tmp/h_dart.h5" --out "$tmp/w.h5"
run_in "$tmp" data merge "$tmp/h.h5" "$tmp/h_dagger.h5" --out "$tmp/h_aggregate.h5"
grep -q "6 episodes, .* from 2 files" "$tmp/stdout" || fail "data merge: $(cat "$tmp/stdout")"
expect_error "cannot merge with $tmp/h.h5: task 'walker', not 'humanoid'" "$tmp/w.h5" -- data merge "$tmp/h.h5" \
  "$tmp/one.h5" --out "$tmp/w.h5"
expect_error "exists (pass --force" "" -- data merge "$tmp/h.h5" --out "$tmp/h_aggregate.h5"
expect_error "is the VAE's own run directory" "" -- vae refit-policy --checkpoint "$tmp/h_vae" --demos "$tmp/h.h5" \
  --out-dir "$tmp/h_vae"
run_in "$tmp" gail train --demos "$tmp/h.h5" --vae "$tmp/h_vae" --run-dir "$tmp/h_gail" --iterations 1 --envs 2 \
  --steps-per-env 16
tr -d ' \n' < "$tmp/h_gail/config.json" > "$tmp/h_gail_config"
grep -q '"policy_hidden":\[300,200,100\]' "$tmp/h_gail_config" && grep -q '"discriminator_hidden":\[300,200\]' "$tmp/h_gail_config" &&
  grep -q '"discriminator_state_indices":\[112,113,' "$tmp/h_gail_config" && grep -q ',136\]' "$tmp/h_gail_config" &&
  grep -q '"iterations":1,' "$tmp/h_gail_config" || fail "gail train on the humanoid: not its preset: $(cat "$tmp/h_gail_config")"
run_in "$tmp" eval humanoid --demos "$tmp/h.h5" --eval-demos "$tmp/h_eval.h5" --vae "$tmp/h_vae" --gail "$tmp/h_gail" \
  --episodes-per-style 2 --threads 2 --out-dir "$tmp/h_evaluation"
grep -q '^| train | all | diverse_gail | 4 |' "$tmp/h_evaluation/summary.md" &&
  grep -q '^| eval | train/walk | vae | 2 |' "$tmp/h_evaluation/summary.md" &&
  [ "$(wc -l < "$tmp/h_evaluation/imitation.csv")" -eq 13 ] && grep -q '"summaries"' "$tmp/h_evaluation/summary.json" &&
  grep -q '^train/chicken,diverse_gail,' "$tmp/h_evaluation/falls.csv" && grep -q '^eval: train/walk,vae,' "$tmp/h_evaluation/falls.csv" ||
  fail "eval humanoid: $(cat "$tmp/stdout")"
expect_error "recorded on task 'walker', not on --task humanoid" "$tmp/h_e" -- eval humanoid --demos "$tmp/one.h5" \
  --vae "$walker_vae" --out-dir "$tmp/h_e"
run_in "$tmp" eval transitions --demos "$tmp/h.h5" --vae "$tmp/h_vae" --gail "$tmp/h_gail" --per-expert 2 --pairs 2 \
  --figure-pairs 1 --out-dir "$tmp/h_transitions"
grep -q '| diverse_gail | A, B of different styles | 2 |' "$tmp/h_transitions/summary.md" &&
  grep -qE '^\| vae \| train/(old|chicken) \| train/(old|chicken) \| ' "$tmp/h_transitions/summary.md" ||
  fail "eval transitions on the humanoid: $(cat "$tmp/stdout")"
run_in "$tmp" bench gail --task humanoid --demos "$tmp/h.h5" --vae "$tmp/h_vae" --envs 2 --iterations 1 --physics-seconds 0.1
grep -q '^bench gail: humanoid, diverse mode, 2 environments x 334 steps' "$tmp/stdout" &&
  grep -q 'of the all-core raw physics ceiling' "$tmp/stdout" || fail "bench gail --task humanoid: $(cat "$tmp/stdout")"
expect_error "data/humanoid/train.h5: no such file" "" -- bench gail --task humanoid
expect_error "demos styles reads humanoid demonstrations" "" -- demos styles --demos "$tmp/one.h5"
printf '{"parameters": {}, "targets": {"grace": [1, 1]}, "tune": {"parameters": {}}}' > "$tmp/style.json"
expect_error "$tmp/style.json: target 'grace' is not a style measure" "" -- experts tune "$tmp/style.json" --run-dir "$tmp/tune"

# ---- the humanoid's gait controllers: experts eval --styles -----------------------------
"$v" experts eval --task humanoid --styles "$root/configs/humanoid_styles/train/walk.json" --episodes 1 \
  --replay --raw-seconds 0.2 --csv "$tmp/gait.csv" --json "$tmp/gait.json" > "$tmp/stdout" 2>&1 &&
  grep -qE "^train/walk  *1/1  *[01]/1 " "$tmp/stdout" && grep -q "ratio" "$tmp/stdout" && [ "$(wc -l < "$tmp/gait.csv")" -eq 2 ] &&
  grep -q '"pushed_falls": [01]' "$tmp/gait.json" || fail "experts eval --styles: $(cat "$tmp/stdout")"
echo '{"parameters": {"sped": 1}}' > "$tmp/typo.json"
expect_error "typo.json: 'sped' is not a gait parameter" "" -- experts eval --styles "$tmp/typo.json"
expect_error "gait controllers drive the humanoid, not --task walker" "" -- \
  experts eval --task walker --styles "$root/configs/humanoid_styles/train/walk.json"

# ---- the reproduce scripts call commands and options that exist ------------------------
# Every vaegail line a script prints under --dry-run names a command whose --help lists each of its options
# (or the tool's own, such as --torch-threads), and every other program it calls is there.
declare -A helps
global_help=$("$v" --help 2>&1)
for script in "$root"/scripts/reproduce/*.sh; do
  [ -x "$script" ] || continue
  name=$(basename "$script")
  while read -r line; do
    read -ra words <<< "${line#+ }"
    if [ "${words[0]}" != build/vaegail ]; then
      # a script of the repository's, or a program on the PATH (cp, git)
      { [ -x "$root/${words[0]}" ] || { [[ ${words[0]} != */* ]] && command -v "${words[0]}" > /dev/null; }; } ||
        fail "$name calls ${words[0]}, neither an executable script nor a program on the PATH"
      continue
    fi
    command=() i=1
    while [ $i -lt ${#words[@]} ]; do  # the tool's options, then the command's words up to its first option
      case ${words[i]} in --torch-threads) i=$((i + 2)); continue ;; -*|*/*|*.*) break ;; esac
      command+=("${words[i]}")
      i=$((i + 1))
    done
    key=${command[*]}
    [ -n "${helps[$key]+x}" ] || helps[$key]=$("$v" "${command[@]}" --help 2>&1)
    for w in "${words[@]}"; do
      [[ $w == --* ]] || continue
      grep -qE -- "(^|[^-[:alnum:]_])$w([^-[:alnum:]_]|$)" <<< "${helps[$key]}$global_help" ||
        fail "$name: vaegail $key has no $w"
    done
  done < <("$script" --dry-run all | grep '^+ ')
done

# ---- figures (scripts/plot through the binary) ------------------------------------------
# Without matplotlib: a figure command stops with one line naming the package; a command whose
# main output is a table still writes it, and its figure's CSV, with one warning.
printf '#!/bin/sh\nexit 1\n' > "$tmp/no-matplotlib" && chmod +x "$tmp/no-matplotlib"
printf 'epoch,train_loss,val_loss\n1,10,12\n2,5,7\n' > "$tmp/metrics.csv"
VAEGAIL_PYTHON=$tmp/no-matplotlib expect_error "plot curves: needs python3 with matplotlib (apt-get install python3-matplotlib)" \
  "$tmp/curves.png" -- plot curves --csv "$tmp/metrics.csv" --y train_loss --out "$tmp/curves.png"
VAEGAIL_PYTHON=$tmp/no-matplotlib "$v" data info "$tmp/one.h5" --histogram "$tmp/speeds.png" > "$tmp/stdout" 2> "$tmp/stderr" &&
  grep -q "episodes per bin" "$tmp/stdout" && [ -s "$tmp/speeds.csv" ] && [ ! -e "$tmp/speeds.png" ] &&
  [ "$(grep -c . "$tmp/stderr")" -eq 1 ] && grep -q "python3-matplotlib" "$tmp/stderr" ||
  fail "data info --histogram without matplotlib: $(cat "$tmp/stderr")"
source "$root/scripts/plot/find_python.sh"
if [ -n "$python" ]; then
  run_in "$tmp" plot curves --csv "$tmp/metrics.csv" --y train_loss,val_loss --log-y --out "$tmp/curves.png" --width 300 --height 200
  [ -s "$tmp/curves.png" ] || fail "plot curves: no figure"
  rm -f "$tmp/speeds.csv"
  run_in "$tmp" data info "$tmp/one.h5" --histogram "$tmp/speeds.png"
  [ -s "$tmp/speeds.png" ] && [ -s "$tmp/speeds.csv" ] || fail "data info --histogram: no figure or no CSV"
  # the script's own one-line error, through the binary
  expect_error "metrics.csv: no column 'nope' (columns: epoch, train_loss, val_loss)" "$tmp/c.png" -- \
    plot curves --csv "$tmp/metrics.csv" --y nope --out "$tmp/c.png"
else
  echo "cli_test: figures through the binary skipped: no python3 with matplotlib"
fi

# ---- render: video with no display (Mesa's llvmpipe through EGL), every task kind ---------
check_help render
expect_error "one.h5: no episode 1 (it has 1, from 0)" "$tmp/r.mp4" -- \
  render --demos "$tmp/one.h5" --episodes 1 --out "$tmp/r.mp4"
expect_error "--width: must be even" "$tmp/r.mp4" -- render --demos "$tmp/one.h5" --episodes 0 --width 33 --out "$tmp/r.mp4"
expect_error "--gail needs --vae" "$tmp/r.mp4" -- render --demos "$tmp/one.h5" --episodes 0 --gail "$tmp/g" --out "$tmp/r.mp4"
run_in "$tmp/elsewhere" render --demos "$tmp/body.h5" --episodes 0 1 --vae "$tmp/body_vae/checkpoints/latest.pt" \
  --gail "$tmp/body_gail" --width 64 --height 48 --out "$tmp/body.mp4"
[ -s "$tmp/body.mp4" ] || fail "render of a body of one's own: no video"
# A gait controller's demonstration is replayed by the controller itself (--styles): no departure note.
"$v" render --demos "$tmp/h.h5" --episodes 0 --styles "${styles[@]}" --expert "$tmp/h/humanoid_ctx0_3_logstd-1_seed0" \
  --width 64 --height 48 --out "$tmp/humanoid.mp4" --still "$tmp/humanoid.png" > "$tmp/stdout" 2>&1
[ -s "$tmp/humanoid.mp4" ] && [ -s "$tmp/humanoid.png" ] && ! grep -q "departs" "$tmp/stdout" ||
  fail "render --styles of a humanoid demonstration and its expert: $(cat "$tmp/stdout")"
expect_error "--columns lays out demonstrations alone" "$tmp/c.mp4" -- render --demos "$tmp/h.h5" --episodes 0 2 \
  --columns 2 --expert "$tmp/h/humanoid_ctx0_3_logstd-1_seed0" --out "$tmp/c.mp4"
expect_error "its expert id 'train/old' is none of the --styles files' labels" "$tmp/c.mp4" -- \
  render --demos "$tmp/h.h5" --episodes 0 --styles "${styles[1]}" --out "$tmp/c.mp4"

echo "$helped commands answered --help; $failures failure(s)"
[ "$failures" -eq 0 ]
