#!/bin/sh
# expect-exit.sh CODE PATTERN COMMAND ARGS...: runs the command and passes when
# it exits with CODE and its output (stdout and stderr) matches PATTERN (grep -E).
code=$1 pattern=$2
shift 2
out=$("$@" 2>&1)
rc=$?
printf '%s\n' "$out"
if [ "$rc" -ne "$code" ]; then echo "expect-exit: exit code $rc, expected $code"; exit 1; fi
if ! printf '%s\n' "$out" | grep -Eq -- "$pattern"; then echo "expect-exit: output does not match '$pattern'"; exit 1; fi
