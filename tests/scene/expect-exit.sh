#!/bin/sh
# expect-exit.sh [OPTIONS] CODE PATTERN COMMAND ARGS...: runs the command and
# passes (exit 0) only when it exits with CODE and its output (stdout and
# stderr together) matches PATTERN (grep -E, any line). Any other outcome exits
# 1 and says why. ctest must run this WITHOUT PASS_REGULAR_EXPRESSION or
# FAIL_REGULAR_EXPRESSION: with either property ctest ignores the exit status.
#
# OPTIONS (before CODE, repeatable):
#   -e PATTERN      the output must match this pattern too (grep -E, any line)
#   -n PATTERN      the output must not match this pattern (grep -E, any line)
#   --rows FILE N   FILE (a CSV with one header line) is removed before the
#                   command runs and must then hold at least N data rows
#   --file FILE     FILE is removed before the command runs and must then exist
#                   and be non-empty
#   --max-memory MB the command runs with its address space capped at MB
#                   megabytes (ulimit -v): a runaway allocation fails inside it
#   --max-seconds S the command is stopped after S seconds (timeout) and the
#                   test fails, saying so
# Files are removed first so that a stale file from an earlier run cannot pass.
patterns=''
absent=''
maxmem=''
maxsecs=''
rows=''
files=''
nl='
'
while :; do
  case $1 in
    -e) patterns="$patterns$2$nl"; shift 2 ;;
    -n) absent="$absent$2$nl"; shift 2 ;;
    --rows) rows="$rows$2$nl$3$nl"; shift 3 ;;
    --file) files="$files$2$nl"; shift 2 ;;
    --max-memory) maxmem=$2; shift 2 ;;
    --max-seconds) maxsecs=$2; shift 2 ;;
    *) break ;;
  esac
done
if [ $# -lt 3 ]; then echo "usage: expect-exit.sh [-e PATTERN] [-n PATTERN] [--rows FILE N] [--file FILE] [--max-memory MB] [--max-seconds S] CODE PATTERN COMMAND..."; exit 1; fi
code=$1
patterns="$2$nl$patterns"
shift 2

printf '%s' "$files" | while IFS= read -r f; do rm -f -- "$f"; done
printf '%s' "$rows" | awk 'NR % 2 == 1' | while IFS= read -r f; do rm -f -- "$f"; done

if [ -n "$maxsecs" ]; then set -- timeout -k 2 "$maxsecs" "$@"; fi
if [ -n "$maxmem" ]; then
  out=$(ulimit -v $((maxmem * 1024)) && "$@" 2>&1)
else
  out=$("$@" 2>&1)
fi
rc=$?
printf '%s\n' "$out"
failed=0
if [ -n "$maxsecs" ] && { [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; }; then
  echo "expect-exit: still running after $maxsecs s (the limit); stopped"; failed=1
fi
if [ "$rc" -ne "$code" ]; then echo "expect-exit: exit code $rc, expected $code"; failed=1; fi
while IFS= read -r p; do
  [ -z "$p" ] && continue
  if ! printf '%s\n' "$out" | grep -Eq -- "$p"; then echo "expect-exit: output does not match '$p'"; failed=1; fi
done <<EOF
$patterns
EOF
while IFS= read -r p; do
  [ -z "$p" ] && continue
  if printf '%s\n' "$out" | grep -Eq -- "$p"; then echo "expect-exit: output matches '$p', which it must not"; failed=1; fi
done <<EOF
$absent
EOF
while IFS= read -r f && IFS= read -r n; do
  if [ ! -f "$f" ]; then echo "expect-exit: $f was not written"; failed=1; continue; fi
  have=$(($(wc -l < "$f") - 1))
  echo "expect-exit: $f has $have data rows (need $n)"
  if [ "$have" -lt "$n" ]; then echo "expect-exit: $f has $have data rows, expected at least $n"; failed=1; fi
done <<EOF
$rows
EOF
while IFS= read -r f; do
  [ -z "$f" ] && continue
  if [ ! -s "$f" ]; then echo "expect-exit: $f was not written (or is empty)"; failed=1; fi
done <<EOF
$files
EOF
exit $failed
