#!/usr/bin/env bash
# Integration test of evaluate.launch (issue 4) on the shipped basic policy: both files appear,
# the CSV has the documented columns and 100 episodes. usage: evaluate_test.sh XUNIT_OUTPUT
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
policy="$(cd "$(dirname "$0")/.." && pwd)/policies/basic.pt"
dir=$(mktemp -d /tmp/hideseek_eval_test.XXXXXX)
port=$((11800 + RANDOM % 100))
failures=()
if [ ! -f "$policy" ]; then
  failures+=("no shipped policy at $policy")
else
  timeout 600 roslaunch -p "$port" hideseek_world evaluate.launch variant:=basic policy:="$policy" episodes:=100 \
    output_dir:="$dir" > "$dir/launch.log" 2>&1
  [ -f "$dir/evaluation.md" ] || failures+=("no evaluation.md")
  [ -f "$dir/evaluation.csv" ] || failures+=("no evaluation.csv")
  [ "$(head -n 1 "$dir/evaluation.csv" 2>/dev/null)" = "variant,policy,episodes,avg_living_steps,success_rate" ] ||
    failures+=("evaluation.csv header differs")
  [ "$(tail -n 1 "$dir/evaluation.csv" 2>/dev/null | cut -d, -f3)" = "100" ] || failures+=("not 100 episodes")
fi
write_xunit "$out" evaluate EvaluateLaunchWritesBothFilesFor100Episodes "${failures[@]}"
cat "$dir/evaluation.md" 2>/dev/null
printf 'failure: %s\n' "${failures[@]}"
rm -rf "$dir"
[ ${#failures[@]} -eq 0 ]
