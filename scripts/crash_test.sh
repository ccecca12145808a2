#!/usr/bin/env bash
# Crash test (issue 51): a kill at any moment loses nothing. For each long job -- experts train,
# demos collect, vae train, gail train (diverse and plain), bc train -- at small scale:
#   1. run it to completion once, into JOB/reference (timed: T);
#   2. in a fresh JOB/roundR, start it, SIGKILL it after a random delay in [S, T) (S: vaegail's
#      start-up, `--help`'s time; a kill before it touches nothing), rerun the same command, kill
#      that too, ... until --kills kills have landed, then rerun it to completion (a rerun that
#      finishes before its kill ends the round; the next round starts afresh);
#   3. compare each round's outputs with the reference (scripts/crash_test/compare.py): weights
#      (`vaegail export`'s weights file and the checkpoints), metrics CSV (timings aside), configs
#      and demonstrations equal where the job is deterministic; complete (same files, one metrics
#      row per iteration, the same tensors) and loadable where it is not; no `*.tmp-*` file left.
# The delays come from --seed, one stream per job, and every kill is logged with its delay, so a
# failure reproduces (as far as a kill's moment can). Prints a table of the figures; exits 1 if
# any round lost or mixed output.
#
# experts train is deterministic but not resumable exactly (docs/crash_test.md): a resumed PPO
# expert restarts its environments' episodes and its Adam moments at the checkpoint, and draws
# its streams from the iteration count, so its outputs are checked for completeness only.
#
# Usage: scripts/crash_test.sh [--kills N] [--seed S] [--jobs "experts demos vae gail_diverse gail_plain bc"]
#                              [--work EMPTY_DIR] [--vaegail PATH] [--table FILE]
# Needs python3 with h5py (Debian's python3-h5py; exits 77, skipped, without). The work folder is
# kept with --work, or when a job fails. Time on 2 cores: about 5 minutes at --kills 5.
set -euo pipefail

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; }

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
kills=5
seed=1
jobs="experts demos vae gail_diverse gail_plain bc"
work=""
vaegail=$root/build/vaegail
table=""
while [ $# -gt 0 ]; do
  case $1 in
    -h|--help) usage; exit 0 ;;
    --kills) kills=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --vaegail) vaegail=$2; shift 2 ;;
    --table) table=$2; shift 2 ;;
    *) echo "crash_test.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
case $kills in ''|*[!0-9]*) echo "crash_test.sh: --kills must be a whole number" >&2; exit 2 ;; esac
[ -x "$vaegail" ] || { echo "crash_test.sh: $vaegail: no vaegail binary (build it, or pass --vaegail)" >&2; exit 2; }
python=/usr/bin/python3
"$python" -c 'import h5py' 2> /dev/null || { echo "crash_test.sh: skipped: needs python3-h5py" >&2; exit 77; }
compare=$root/scripts/crash_test/compare.py
keep=1
if [ -z "$work" ]; then
  work=$(mktemp -d "${TMPDIR:-/tmp}/vaegail_crash.XXXXXX")
  keep=0  # removed when every job passes
elif [ -n "$(ls -A "$work" 2> /dev/null)" ]; then
  echo "crash_test.sh: $work: not empty (pass a new or empty --work folder)" >&2; exit 2
else
  mkdir -p "$work"
fi
inputs=$work/inputs
mkdir -p "$inputs"
log=$work/crash_test.log
say() { echo "$*" | tee -a "$log"; }

# ---- the jobs at small scale ------------------------------------------------------------
expert=speed1_logstd-1_seed0
cat > "$inputs/experts.json" <<'JSON'
{"training": {"total_steps": 1200, "num_envs": 2, "steps_per_env": 50, "hidden": [16, 16], "epochs": 2,
              "minibatches": 2, "checkpoint_every": 3}}
JSON
cat > "$inputs/vae.json" <<'JSON'
{"lstm_hidden": 16, "latent_dim": 4, "action_hidden": [32, 32], "wavenet_channels": 8, "wavenet_layers": 2,
 "mixture_components": 2}
JSON

# cmd=(the arguments of vaegail for job $1 writing into $2).
set_command() {
  local out=$2
  case $1 in
    experts) cmd=(experts train --config "$inputs/experts.json" --grid small --only "$expert" --out-dir "$out") ;;
    demos) cmd=(demos collect --experts-dir "$root/experts/walker" --only speed0_logstd-1_seed0 speed1_logstd-1_seed0
                --episodes-per-expert 3 --out "$out/demos.h5" --force) ;;
    vae) cmd=(vae train --demos "$inputs/demos.h5" --run-dir "$out" --config "$inputs/vae.json" --epochs 8) ;;
    gail_diverse) cmd=(gail train --mode diverse --demos "$inputs/demos.h5" --vae "$inputs/vae" --run-dir "$out"
                       --iterations 6 --envs 2 --steps-per-env 50) ;;
    gail_plain) cmd=(gail train --mode plain --demos "$inputs/demos.h5" --run-dir "$out" --iterations 6 --envs 2
                     --steps-per-env 50) ;;
    bc) cmd=(bc train --demos "$inputs/demos.h5" --run-dir "$out" --epochs 8) ;;
    *) echo "crash_test.sh: unknown job '$1' (experts demos vae gail_diverse gail_plain bc)" >&2; exit 2 ;;
  esac
}

# compare_options=(what compare.py may take loosely for job $1, and why).
set_compare_options() {
  case $1 in
    experts) compare_options=(--loose '*/agent.pt' --loose '*/metrics.csv') ;;  # resumed PPO: not the uninterrupted run
    gail_*) compare_options=(--timed 'checkpoints/*.pt') ;;                    # the checkpoint keeps the run's seconds
    *) compare_options=() ;;
  esac
}

# After a job completed: what proves its outputs whole and loadable, beyond the comparison.
finish_job() {
  local job=$1 out=$2
  case $job in
    vae|gail_*|bc) "$vaegail" export --run-dir "$out" > /dev/null ;;  # loads the checkpoint, writes weights.pt
    experts) "$vaegail" demos collect --experts-dir "$out" --episodes-per-expert 1 --out "$out.loads.h5" > /dev/null &&
      rm "$out.loads.h5" ;;
  esac
}

# The inputs of the later jobs: demonstrations and a tiny VAE.
for job in demos vae; do
  set_command $job "$inputs"
  [ $job = vae ] && set_command vae "$inputs/vae"
  "$vaegail" "${cmd[@]}" > "$inputs/$job.log" 2>&1 || { cat "$inputs/$job.log"; exit 1; }
done

now_ms() { date +%s%3N; }

# vaegail's start-up (loading LibTorch and MuJoCo: `--help`'s time): a kill before it ends touches
# nothing, so the kills land after it.
start=$(now_ms)
"$vaegail" --help > /dev/null
S=$(( $(now_ms) - start ))
say "start-up ${S} ms"

# ---- one job: the reference, then rounds of kills ---------------------------------------
rows=()
failures=0
job_index=0
for job in $jobs; do
  job_index=$((job_index + 1))
  RANDOM=$((seed * 1000 + job_index))  # the job's own stream of delays
  dir=$work/$job
  mkdir -p "$dir/reference"
  set_command "$job" "$dir/reference"
  set_compare_options "$job"
  start=$(now_ms)
  "$vaegail" "${cmd[@]}" > "$dir/reference.log" 2>&1 ||
    { say "$job: the reference run failed: $(tail -1 "$dir/reference.log")"; exit 1; }
  T=$(( $(now_ms) - start ))
  finish_job "$job" "$dir/reference" >> "$dir/reference.log" 2>&1
  say "$job: reference run ${T} ms"
  landed=0 round=0 mismatches=0 lost=0 temporaries=0
  while [ $landed -lt "$kills" ]; do
    round=$((round + 1))
    out=$dir/round$round
    mkdir -p "$out"
    set_command "$job" "$out"
    while :; do
      "$vaegail" "${cmd[@]}" >> "$out.log" 2>&1 &
      pid=$!
      if [ $landed -lt "$kills" ]; then
        delay=$(( S + (RANDOM * 32768 + RANDOM) % (T > S ? T - S : 1) ))
        sleep "$(printf '%d.%03d' $((delay / 1000)) $((delay % 1000)))"
        kill -9 "$pid" 2> /dev/null || true  # too late when the run has finished
      fi
      rc=0
      wait "$pid" 2> /dev/null || rc=$?  # (bash's "Killed" notice aside)
      if [ $rc -eq 137 ]; then
        landed=$((landed + 1))
        say "$job: round $round: kill $landed at ${delay} ms"
        continue
      fi
      [ $rc -eq 0 ] && break
      lost=$((lost + 1))
      say "$job: round $round: a rerun failed (exit $rc): $(tail -1 "$out.log")"
      break
    done
    left=$(find "$out" -name '*.tmp-*' | wc -l)
    temporaries=$((temporaries + left))
    if finish_job "$job" "$out" >> "$out.log" 2>&1 &&
       "$python" "$compare" "${compare_options[@]}" "$dir/reference" "$out" > "$out.diff"; then
      say "$job: round $round: outputs as the reference's"
    else
      mismatches=$((mismatches + 1))
      say "$job: round $round: outputs differ from the reference's ($out.diff):"
      sed 's/^/  /' "$out.diff" | tee -a "$log"
    fi
  done
  [ $((mismatches + lost + temporaries)) -eq 0 ] || failures=$((failures + 1))
  case $job in experts) compared="complete, loadable" ;; *) compared="equal" ;; esac
  rows+=("| \`$job\` | $T | $landed | $round | $compared | $mismatches | $lost | $temporaries |")
done

{
  echo "| job | reference run (ms) | kills | rounds | outputs checked | mismatches | failed reruns | temporary files left |"
  echo "| --- | ---: | ---: | ---: | --- | ---: | ---: | ---: |"
  printf '%s\n' "${rows[@]}"
} | tee -a "$log" > "$work/table.md"
cat "$work/table.md"
[ -z "$table" ] || cp "$work/table.md" "$table"
if [ $failures -eq 0 ] && [ $keep -eq 0 ]; then
  rm -rf "$work"
  exit 0
fi
echo "log: $log"
[ $failures -eq 0 ]
