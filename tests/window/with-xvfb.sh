#!/usr/bin/env bash
# Runs a command with DISPLAY set to a private Xvfb server, which it starts on
# a free display number and stops afterwards: the `window` tests need a
# display, and must not use (or pop up on) the developer's own.
#   tests/window/with-xvfb.sh CMD ARGS...
set -uo pipefail
command -v Xvfb >/dev/null || { echo "with-xvfb: Xvfb is not installed (Debian package xvfb; scripts/setup installs it)" >&2; exit 1; }
fifo=$(mktemp -u)
mkfifo "$fifo"
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp 3>"$fifo" 2>/dev/null &
xvfb=$!
# -displayfd writes the display number once the server accepts clients.
read -r -t 20 number <"$fifo"
rm -f "$fifo"
if [ -z "${number:-}" ]; then
  echo "with-xvfb: Xvfb did not start within 20 s" >&2
  kill "$xvfb" 2>/dev/null
  exit 1
fi
export DISPLAY=":$number"
unset WAYLAND_DISPLAY
"$@"
status=$?
kill "$xvfb" 2>/dev/null
wait "$xvfb" 2>/dev/null
exit $status
