#!/usr/bin/env bash
# The run directory's promises, checked on the built binary (ctest runs this as `storage_test`):
# - a full file system (a 300 KB tmpfs, mounted here when run as root, as CI runs; skipped
#   otherwise) ends `gail train` with exit 1, at most two lines on stderr naming the cause and
#   no temporary file; the same command resumes to completion once the run directory has room;
# - two `gail train` on one run directory: the second is refused at once in one line naming the
#   first's pid, and the first finishes with its own metrics rows only; `vae train`, `bc train`,
#   `experts train` and `demos collect` are refused likewise on a run another process holds.
# Usage: src/cli/storage_test.sh VAEGAIL_BINARY REPO_ROOT
set -uo pipefail
[ $# -eq 2 ] || { echo "usage: $0 VAEGAIL_BINARY REPO_ROOT" >&2; exit 2; }
v=$1 root=$2
tmp=$(mktemp -d)
small=""
cleanup() {
  [ -z "$small" ] || umount "$small"
  rm -rf "$tmp"
}
trap cleanup EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
cd "$root" || exit 2

# The published walker demonstrations when this checkout has them (they are not committed), else
# a few episodes of three committed experts: the same sizes of observation and action.
demos=data/walker/demos.h5
if [ ! -f "$demos" ]; then
  demos=$tmp/demos.h5
  "$v" demos collect --experts-dir experts/walker --episodes-per-expert 2 --out "$demos" \
    --only speed-1_logstd-1_seed0 speed0_logstd-1_seed0 speed1_logstd-1_seed0 > /dev/null 2>&1 ||
    { echo "FAIL: demos collect"; exit 1; }
fi
# gail_train RUN_DIR ITERATIONS: the issue's reproduction.
gail_train() {
  "$v" gail train --mode plain --demos "$demos" --run-dir "$1" --iterations "$2" --envs 2 --steps-per-env 50
}

# ---- a full file system ---------------------------------------------------------------
if [ "$(id -u)" -ne 0 ]; then
  echo "SKIP full file system: mounting a tmpfs needs root"
elif ! { mkdir "$tmp/small" && mount -t tmpfs -o size=300k tmpfs "$tmp/small"; }; then
  echo "SKIP full file system: cannot mount a tmpfs here"
else
  small=$tmp/small
  gail_train "$small/g" 3 > "$tmp/stdout" 2> "$tmp/stderr"
  rc=$?
  lines=$(grep -c . "$tmp/stderr")
  temporaries=$(find "$small/g" -name '*tmp*' | wc -l)
  echo "300 KB tmpfs: exit $rc, $lines line(s) on stderr, $temporaries temporary file(s)"
  sed 's/^/  stderr: /' "$tmp/stderr"
  [ "$rc" -eq 1 ] || fail "gail train on a full file system: exit $rc (expected 1)"
  [ "$lines" -le 2 ] || fail "gail train on a full file system: $lines lines on stderr"
  grep -q "^vaegail: error: $small/g/.*: No space left on device$" "$tmp/stderr" ||
    fail "gail train on a full file system: no one-line error naming the file and the cause"
  [ "$temporaries" -eq 0 ] || fail "gail train on a full file system left $(find "$small/g" -name '*tmp*')"
  # The run directory moved to a file system with room: the same command finishes the run.
  cp -a "$small/g" "$tmp/g"
  umount "$small" && small=""
  gail_train "$tmp/g" 3 > "$tmp/stdout" 2>&1 || fail "gail train resumed with room: $(tail -1 "$tmp/stdout")"
  grep -q "^3/3 iterations" "$tmp/stdout" || fail "gail train resumed with room: not 3/3 iterations"
  [ "$(cut -d, -f1 "$tmp/g/metrics.csv" | tr '\n' ' ')" = "iteration 1 2 3 " ] ||
    fail "gail train resumed with room: metrics.csv rows $(cut -d, -f1 "$tmp/g/metrics.csv" | tr '\n' ' ')"
fi

# ---- two runs on one run directory ----------------------------------------------------
run=$tmp/two
iterations=40
gail_train "$run" "$iterations" > "$tmp/first.out" 2> "$tmp/first.err" &
first=$!
for _ in $(seq 600); do  # until the first holds the run directory (its pid in RUN/.lock)
  [ -s "$run/.lock" ] && break
  sleep 0.1
done
holder=$(head -1 "$run/.lock")
[ "$(cat "/proc/$holder/comm" 2> /dev/null)" = vaegail ] || fail "RUN/.lock holds '$holder', not the first run's pid"
gail_train "$run" "$iterations" > "$tmp/second.out" 2> "$tmp/second.err"
rc=$?
wait "$first"
first_rc=$?
echo "second run: exit $rc: $(cat "$tmp/second.err")"
[ "$rc" -ne 0 ] || fail "a second gail train on one run directory: exit 0"
[ "$(cat "$tmp/second.err")" = "vaegail: error: $run: in use by process $holder (another vaegail run)" ] ||
  fail "a second gail train on one run directory: '$(cat "$tmp/second.err")'"
[ "$first_rc" -eq 0 ] || fail "the first gail train: exit $first_rc: $(tail -1 "$tmp/first.err")"
[ "$(cut -d, -f1 "$run/metrics.csv" | tr '\n' ' ')" = "iteration $(seq -s ' ' "$iterations") " ] ||
  fail "the first gail train's metrics.csv: rows $(cut -d, -f1 "$run/metrics.csv" | tr '\n' ' ')"
[ ! -e "$run/.lock" ] || fail "the first gail train left its lock file"

# ---- every training command holds its run ---------------------------------------------
# This shell takes the lock (flock(1), no pid in the file: "another process") as another run would.
# expect_refused SUBJECT -- COMMAND...: exit non-zero, the one line naming SUBJECT, nothing written.
expect_refused() {
  local subject=$1
  shift 2
  "$v" "$@" > "$tmp/stdout" 2> "$tmp/stderr"
  local rc=$?
  if [ $rc -eq 0 ]; then fail "vaegail $*: exit 0 on a run in use"
  elif [ "$(cat "$tmp/stderr")" != "vaegail: error: $subject: in use by another process (another vaegail run)" ]; then
    fail "vaegail $*: '$(cat "$tmp/stderr")'"
  fi
}
held=$tmp/held
mkdir -p "$held"
exec {run_lock}> "$held/.lock" {file_lock}> "$held/.demos.h5.lock"
flock -n "$run_lock" && flock -n "$file_lock" || fail "flock(1) could not take the locks"
expect_refused "$held" -- vae train --demos "$demos" --run-dir "$held" --epochs 1
expect_refused "$held" -- bc train --demos "$demos" --run-dir "$held" --epochs 1
expect_refused "$held" -- experts train --out-dir "$held" --only speed-1_logstd-1_seed0 --steps 1000
expect_refused "$held/demos.h5" -- demos collect --experts-dir experts/walker --only speed-1_logstd-1_seed0 \
  --episodes-per-expert 1 --out "$held/demos.h5"
exec {run_lock}>&- {file_lock}>&-
[ "$(ls -A "$held")" = "$(printf '.demos.h5.lock\n.lock')" ] || fail "a refused command wrote into $held: $(ls -A "$held")"

[ "$failures" -eq 0 ] && echo "storage_test: all passed"
exit $((failures > 0))
