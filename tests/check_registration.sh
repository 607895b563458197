#!/usr/bin/env bash
# Usage: check_registration.sh RT_TESTS FILTER...
# Fails unless the source-file filters of the ctest entries (one per test
# source) select every doctest case of RT_TESTS exactly once: each case is
# defined in one file, so the filters' counts must add up to the total.
set -euo pipefail
rt_tests=$1
shift

# count [FILTER]: the number of test cases (skipped ones too) a filter selects.
count() {
  local output
  output=$("$rt_tests" --count --no-skip "$@" 2>/dev/null)
  sed -n 's/.*unskipped test cases passing the current filters: \([0-9]*\).*/\1/p' <<<"$output"
}

total=$(count)
if [[ -z "$total" || "$total" -eq 0 ]]; then
  echo "FAIL: could not count the test cases of $rt_tests" >&2
  exit 1
fi
sum=0
for filter in "$@"; do
  n=$(count "--source-file=$filter")
  if [[ -z "$n" || "$n" -eq 0 ]]; then
    echo "FAIL: the entry for $filter selects no test case" >&2
    exit 1
  fi
  printf '%5d  %s\n' "$n" "$filter"
  sum=$((sum + n))
done
printf '%5d  in all; rt_tests --count: %d\n' "$sum" "$total"
if ((sum != total)); then
  echo "FAIL: the ctest entries run $sum test cases, rt_tests has $total" >&2
  exit 1
fi
