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
# catkin_test_results adds suite totals to case counts; count the test cases themselves.
read -r passed failed < <(/usr/bin/python3 - build/test_results <<'PY'
import glob, os, sys
import xml.etree.ElementTree as ET
passed = failed = 0
for path in glob.glob(os.path.join(sys.argv[1], "**", "*.xml"), recursive=True):
    try:
        cases = ET.parse(path).getroot().iter("testcase")
    except ET.ParseError:
        failed += 1
        continue
    for case in cases:
        if case.find("failure") is not None or case.find("error") is not None:
            failed += 1
        elif case.find("skipped") is None:
            passed += 1
print(passed, failed)
PY
)
if [ "$((passed + failed))" -eq 0 ]; then
  echo "0 passed, 1 failed"
  exit 1
fi
[ "$status" -ne 0 ] && [ "$failed" -eq 0 ] && failed=1
echo "${passed} passed, ${failed} failed"
[ "$status" -eq 0 ] && [ "$failed" -eq 0 ]
