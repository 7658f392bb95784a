#!/usr/bin/env bash
# Runs every test (core gtests and rostests) and ends with 'N passed, M failed'.
# catkin_make run_tests exits 0 even when tests fail, so the verdict comes from the results.
set -uo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh
rm -rf build/test_results
# Tests that start roscore need a free port of their own.
export ROS_MASTER_URI=http://localhost:11411
catkin_make run_tests -j1 -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 2>&1 | \
  grep -E "^\[ *(RUN|OK|FAILED|PASSED) *\]|^\[ROSTEST\]|^SUMMARY|^ \* RESULT|^  \* |Error|error:|Failure|FAIL" || true
echo
catkin_test_results build/test_results --all > build/test_summary.txt 2>&1
status=$?
grep -vE "^Skipping" build/test_summary.txt | tail -40
summary=$(tail -n 1 build/test_summary.txt)
# "Summary: 42 tests, 0 errors, 1 failures, 0 skipped"
tests=$(sed -n 's/^Summary: \([0-9]*\) tests.*/\1/p' <<<"$summary")
errors=$(sed -n 's/.* \([0-9]*\) errors.*/\1/p' <<<"$summary")
failures=$(sed -n 's/.* \([0-9]*\) failures.*/\1/p' <<<"$summary")
tests=${tests:-0}; errors=${errors:-0}; failures=${failures:-0}
failed=$((errors + failures))
if [ "$tests" -eq 0 ]; then
  echo "0 passed, 1 failed"
  exit 1
fi
echo "$((tests - failed)) passed, ${failed} failed"
[ "$status" -eq 0 ] && [ "$failed" -eq 0 ]
