#!/usr/bin/env bash
# Every relative link of the project's Markdown (README.md, docs/, the stages' READMEs) points at a file
# that exists, and a link with #anchor at a heading of that file. ctest runs this as `docs_links`.
# Usage: scripts/check_links.sh [REPO_ROOT]
set -uo pipefail
cd "${1:-$(dirname "$0")/..}" || exit 2
failures=0 links=0

# GitHub's heading anchor: lower case, punctuation dropped, spaces to hyphens.
slug() { tr '[:upper:]' '[:lower:]' <<< "$1" | sed -E 's/[^[:alnum:] _-]//g; s/ /-/g'; }

anchors_of() {
  grep -E '^#{1,6} ' "$1" | sed -E 's/^#+ +//' | while read -r heading; do slug "$heading"; done
}

while read -r md; do
  dir=$(dirname "$md")
  # ](target) of links and images, outside code spans' backticks as far as a line-based look allows
  while read -r target; do
    case $target in http://*|https://*|mailto:*) continue ;; esac
    links=$((links + 1))
    file=${target%%#*} anchor=""
    [[ $target == *#* ]] && anchor=${target#*#}
    path=$dir/$file
    [ -z "$file" ] && path=$md
    if [ ! -e "$path" ]; then
      echo "FAIL: $md: link to $target: no such file"; failures=$((failures + 1))
    elif [ -n "$anchor" ] && ! grep -qxF -- "$anchor" <<< "$(anchors_of "$path")"; then
      echo "FAIL: $md: link to $target: no such heading in $path"; failures=$((failures + 1))
    fi
  done < <(grep -oE '\]\([^) ]+\)' "$md" | sed -E 's/^\]\(//; s/\)$//')
done < <(ls README.md docs/*.md docs/*/*.md src/*/README.md 2> /dev/null)

echo "$links relative links checked; $failures broken"
[ "$failures" -eq 0 ]
