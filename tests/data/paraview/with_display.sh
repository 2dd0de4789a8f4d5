#!/usr/bin/env bash
# Runs a command on a private Xvfb display whose number Xvfb picks itself (-displayfd), which
# concurrent tests cannot race for as they can with `xvfb-run -a`'s scan of lock files; -noreset
# keeps the server up between clients (ParaView connects more than once).
# Usage: with_display.sh COMMAND [ARGS...]
set -u
fifo=$(mktemp -u)
mkfifo "$fifo"
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp -noreset 3>"$fifo" 2>/dev/null &
xvfb_pid=$!
trap 'kill "$xvfb_pid" 2>/dev/null; wait "$xvfb_pid" 2>/dev/null' EXIT
number=""
read -r number <"$fifo"
rm -f "$fifo"
if [ -z "$number" ]; then
  echo "with_display.sh: Xvfb did not start" >&2
  exit 1
fi
DISPLAY=":$number" "$@"
