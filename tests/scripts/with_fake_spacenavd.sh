#!/bin/sh
# with_fake_spacenavd.sh DAEMON SHIM SCRIPT.csv COMMAND ARGS...: runs COMMAND
# against MillSim's fake spacenavd (tests/emulators/spacenav) playing
# SCRIPT.csv on a socket of its own, the real libspnav redirected to it by the
# SHIM (LD_PRELOAD; libspnav's socket path is fixed at /var/run/spnav.sock).
# SCRIPT.csv may be "none": no daemon listens. Exits with COMMAND's status.
daemon=$1 shim=$2 script=$3
shift 3
dir=$(mktemp -d)
sock="$dir/spnav.sock"
pid=''
if [ "$script" != none ]; then
  "$daemon" "$sock" "$script" &
  pid=$!
  i=0
  while [ ! -S "$sock" ] && [ $i -lt 100 ]; do sleep 0.05; i=$((i + 1)); done
  [ -S "$sock" ] || { echo "with_fake_spacenavd: the fake daemon did not listen on $sock" >&2; exit 3; }
fi
LD_PRELOAD="$shim${LD_PRELOAD:+:$LD_PRELOAD}" MILLSIM_SPNAV_SOCKET="$sock" "$@"
code=$?
[ -n "$pid" ] && kill "$pid" 2>/dev/null && wait "$pid" 2>/dev/null
rm -rf "$dir"
exit $code
