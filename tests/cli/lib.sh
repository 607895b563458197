#!/usr/bin/env bash
# Shared by the command-line test scripts (sourced): pass/fail counters and
# the one-line error check. The sourcing script sets RAYTRACER and SCRATCH.
passed=0
failed=0

pass() { passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }

# expect_failure LEFTOVER NAME PATTERN ARGS...: `raytracer ARGS` exits
# non-zero, prints exactly one line on stderr (warnings aside) matching
# PATTERN, and leaves no file whose name starts with LEFTOVER in SCRATCH.
expect_failure() {
  local leftover=$1 name=$2 pattern=$3
  shift 3
  rm -f "$SCRATCH/$leftover"*
  "$RAYTRACER" "$@" >"$SCRATCH/stdout" 2>"$SCRATCH/stderr"
  local status=$?
  local lines
  lines=$(grep -vc '^warning: ' "$SCRATCH/stderr")
  if [[ $status -eq 0 ]]; then fail "$name: exit status 0"; return; fi
  if [[ $lines -ne 1 ]]; then fail "$name: expected one error line, got $lines: $(cat "$SCRATCH/stderr")"; return; fi
  if ! grep -Eq -- "$pattern" "$SCRATCH/stderr"; then fail "$name: '$(cat "$SCRATCH/stderr")' does not match '$pattern'"; return; fi
  if ls "$SCRATCH" | grep -q "^$leftover"; then fail "$name: an output file was left behind"; return; fi
  pass
}

# finish LABEL: prints the tally; the status is whether everything passed.
finish() {
  echo "$1: $passed passed, $failed failed"
  [[ $failed -eq 0 ]]
}
