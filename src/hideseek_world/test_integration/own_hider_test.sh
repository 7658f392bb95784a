#!/usr/bin/env bash
# A hider of your own: examples/hider_node.py, a rospy node, plays the hider that
# evaluate.launch policy:=external leaves out, and is evaluated as a policy is: seeds 0.. in
# lockstep, the table naming it "external". In lockstep the world advances only on an answer it
# accepts, so six finished episodes are six episodes of the example's own actions.
# usage: own_hider_test.sh XUNIT_OUTPUT
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
dir=$(mktemp -d /tmp/hideseek_own_hider_test.XXXXXX)
port=$((13100 + RANDOM % 100))
export ROS_MASTER_URI=http://localhost:$port
failures=()
example="$(cd "$(dirname "$(readlink -f "$0")")/../../.." && pwd)/examples/hider_node.py"
roslaunch -p "$port" hideseek_world evaluate.launch policy:=external episodes:=6 num_arenas:=3 \
  output_dir:="$dir" > "$dir/launch.log" 2>&1 &
launch=$!
for _ in $(seq 1 300); do rostopic list 2>/dev/null | grep -q /hider/observations && break; sleep 0.2; done  # the world is up
/usr/bin/python3 "$example" > "$dir/hider.log" 2>&1 &
hider=$!
for _ in $(seq 1 900); do kill -0 "$launch" 2>/dev/null || break; sleep 0.2; done  # the evaluator ends it
kill "$launch" "$hider" 2>/dev/null
wait "$launch" "$hider" 2>/dev/null
[ "$(tail -n 1 "$dir/evaluation.csv" 2>/dev/null | cut -d, -f1-3)" = "basic,external,6" ] ||
  failures+=("no evaluation of 6 episodes of the external hider: $(tr '\n' ' ' < "$dir/evaluation.csv" 2>/dev/null)")
[ "$(tail -n +2 "$dir/episodes.csv" 2>/dev/null | cut -d, -f1 | sort -n | tr '\n' ' ')" = "0 1 2 3 4 5 " ] ||
  failures+=("the external hider's episodes are not seeds 0-5: $(tr '\n' ' ' < "$dir/episodes.csv" 2>/dev/null)")
grep -q "Traceback" "$dir/hider.log" && failures+=("the example hider failed: $(tail -c 300 "$dir/hider.log")")
write_xunit "$out" own_hider ExampleHiderNodeIsEvaluatedLikeAPolicy "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
[ ${#failures[@]} -eq 0 ] && rm -rf "$dir"
[ ${#failures[@]} -eq 0 ]
