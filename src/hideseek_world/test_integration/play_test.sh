#!/usr/bin/env bash
# Integration test of play.launch with the keyboard hider. usage: play_test.sh XUNIT_OUTPUT
# The keyboard hider runs in a pseudo-terminal (script) fed with held 'w' keys; the human's two
# episodes are evaluated like a policy's (evaluation.csv names the policy "human"), and the
# world applied the human's FORWARD.
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
dir=$(mktemp -d /tmp/hideseek_play_test.XXXXXX)
port=$((12000 + RANDOM % 100))
export ROS_MASTER_URI=http://localhost:$port
failures=()
roslaunch -p "$port" hideseek_world play.launch teleop:=false episodes:=2 output_dir:="$dir" > "$dir/launch.log" 2>&1 &
launch=$!
for _ in $(seq 1 100); do rostopic list 2>/dev/null | grep -q /world/episodes && break; sleep 0.2; done
timeout 60 rostopic echo -p /game_state/hider_action > "$dir/actions.csv" 2>/dev/null &
echo_pid=$!
teleop="$(catkin_find hideseek_hider teleop_node --first-only)"
# Hold 'w' (terminal auto-repeat sends it about ten times a second) until both episodes ended.
(for _ in $(seq 1 600); do [ -s "$dir/evaluation.csv" ] && break; printf 'w'; sleep 0.1; done; printf 'q') |
  timeout 90 script -qfc "$teleop" /dev/null > /dev/null 2>&1
kill "$echo_pid" 2>/dev/null
kill "$launch" 2>/dev/null
wait "$launch" 2>/dev/null
[ "$(tail -n 1 "$dir/evaluation.csv" 2>/dev/null | cut -d, -f2,3)" = "human,2" ] ||
  failures+=("no evaluation of 2 human episodes: $(cat "$dir/evaluation.csv" 2>/dev/null | tr '\n' ' ')")
[ "$(tail -n +2 "$dir/episodes.csv" 2>/dev/null | cut -d, -f1 | tr '\n' ' ')" = "0 1 " ] ||
  failures+=("the human's episodes are not seeds 0 and 1")
grep -q ",1$" "$dir/actions.csv" || failures+=("the world never applied the human's FORWARD")
write_xunit "$out" play KeyboardHiderPlaysAndIsEvaluatedLikeAPolicy "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
[ ${#failures[@]} -eq 0 ] && rm -rf "$dir"
[ ${#failures[@]} -eq 0 ]
