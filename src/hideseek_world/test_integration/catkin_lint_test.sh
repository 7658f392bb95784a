#!/usr/bin/env bash
# catkin_lint over every package of the workspace: no error and no warning (-W1).
# usage: catkin_lint_test.sh SOURCE_DIR XUNIT_OUTPUT [PACKAGE_DIR ...]   (more packages: the examples)
# Each problem becomes a failure message naming its package, file, line and text. catkin_lint's
# note that it cannot load a rosdep database (Debian ships none offline) is not a problem of ours.
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
src=$1
out=$2
failures=()
report=$(PATH=/usr/bin:$PATH catkin_lint -W1 "$src" "${@:3}" 2>&1)
status=$?
echo "$report"
while IFS= read -r line; do
  failures+=("$line")
done < <(echo "$report" | grep -E ": (error|warning): ")
summary=$(echo "$report" | grep -E "^catkin_lint: checked [0-9]+ packages")
if [ -z "$summary" ]; then
  failures+=("catkin_lint did not run to its summary (exit $status)")
fi
write_xunit "$out" catkin_lint NoErrorOrWarningAtW1 "${failures[@]}"
