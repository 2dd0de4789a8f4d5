#!/usr/bin/env bash
# Usage: doc_commands.sh THAW DOC.md WORKDIR TINY.toml
# Every documented command line runs (issue 27: docs that cannot drift): each line of DOC.md's
# ```sh blocks that starts with `thaw` or `build/thaw` is run in WORKDIR with THAW, on a tiny
# input: a scenario file named in it (my.toml, ...) becomes TINY.toml, and a `thaw run` renders
# one frame (--frames 0) at 32x24 unless the line sets --frames / --size itself. Lines of other
# programs (bash scripts/run-default: install and build) are left to scripts/test's fresh-Debian
# check. Fails on the first line that exits non-zero; prints each line as run.
set -eu
THAW=$1
DOC=$2
WORK=$3
TINY=$4
rm -rf "$WORK"
mkdir -p "$WORK"
cd "$WORK"
ran=0
while IFS= read -r line; do
  cmd=${line%%#*}                                   # no comment
  cmd=$(sed -E 's/[[:space:]]+$//' <<<"$cmd")
  case $cmd in build/thaw\ * | thaw\ *) ;; *) continue ;; esac
  read -r -a words <<<"$cmd"
  words[0]=$THAW
  for i in "${!words[@]}"; do
    [[ ${words[$i]} == *.toml ]] && words[$i]=$TINY
  done
  if [ "${words[1]}" = run ]; then
    [[ " ${words[*]} " == *" --frames "* ]] || words+=(--frames 0)
    [[ " ${words[*]} " == *" --size "* ]] || words+=(--size 32x24)
  fi
  echo "doc_commands: ${words[*]}"
  if ! "${words[@]}" >/dev/null 2>"$WORK/stderr"; then
    echo "doc_commands: FAILED: $line" >&2
    cat "$WORK/stderr" >&2
    exit 1
  fi
  ran=$((ran + 1))
done < <(awk '/^```sh/ {on = 1; next} /^```/ {on = 0} on' "$DOC")
echo "doc_commands: $ran command lines of $DOC ran"
[ "$ran" -gt 0 ]
