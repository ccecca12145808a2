# shellcheck shell=bash
# Sourced by the scripts in scripts/reproduce/: stage selection, --dry-run, echoed commands.
# A script defines one shell function per stage, calls `parse_stages "DEFAULT STAGES" "$@"`, then
# `run_stages STAGE...` with every stage in the order `all` runs them.

dry_run=0
stages=()

parse_stages() {
  local default=$1
  shift
  for arg in "$@"; do
    case $arg in
      --dry-run) dry_run=1 ;;
      -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
      -*) echo "$0: unknown option $arg (--dry-run, --help)" >&2; exit 2 ;;
      *) stages+=("$arg") ;;
    esac
  done
  [ ${#stages[@]} -gt 0 ] || read -ra stages <<< "$default"
}

# run COMMAND...: print it, then run it unless --dry-run.
run() {
  echo "+ $*"
  [ "$dry_run" = 1 ] || "$@"
}

# run_to FILE COMMAND...: the same, standard output also written to FILE.
run_to() {
  local file=$1
  shift
  echo "+ $* > $file"
  [ "$dry_run" = 1 ] || "$@" | tee "$file"
}

ran=" "

# stage NAME: run a stage's function once per invocation.
stage() {
  [[ $ran == *" $1 "* ]] && return
  ran+="$1 "
  "$1"
}

# ensure FILE STAGE: run STAGE first when FILE is not there (a file that is not committed).
ensure() {
  [ -e "$1" ] || stage "$2"
}

# ensure_published FILE COMMIT STAGE: a file that was committed until COMMIT's successor. The published results were
# computed on that copy and today's build regenerates it only to about 1e-6 (amplified along each episode), so when
# FILE is missing the copy in git history comes back first; STAGE makes it only where history lacks it (a shallow
# clone).
ensure_published() {
  [ -e "$1" ] && return
  if git cat-file -e "$2:$1" 2> /dev/null; then
    echo "+ git show $2:$1 > $1"
    [ "$dry_run" = 1 ] || { mkdir -p "$(dirname "$1")" && git show "$2:$1" > "$1.tmp-$$" && mv "$1.tmp-$$" "$1"; }
  else
    stage "$3"
  fi
}

run_stages() {
  local known=" $* all "
  for s in "${stages[@]}"; do
    [[ $known == *" $s "* ]] || { echo "$0: unknown stage '$s' (one of:$known)" >&2; exit 2; }
  done
  for s in "${stages[@]}"; do
    if [ "$s" = all ]; then
      for each in "$@"; do stage "$each"; done
    else
      stage "$s"
    fi
  done
}
