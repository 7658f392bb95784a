#!/usr/bin/env bash
# A hider of your own: examples/hider_node.py, a rospy node, plays the hider that
# evaluate.launch policy:=external leaves out, and is evaluated as a policy is: seeds 0.. in
# lockstep, the table naming it "external". In lockstep the world advances only on an answer it
# accepts, so six finished episodes are six episodes of the example's own actions. Then a seeker
# of your own, examples/seeker_node.py, with seeker_mode:=external, both ways it may decide.
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

# A seeker of your own: examples/seeker_node.py plays the seeker that seeker_mode:=external leaves
# out, against the random hider, deciding when the scripted seeker would (every frame) and then
# once a step. The table names it; every episode it ends is its own catch or the hider's survival.
for decides in game step; do
  eval_dir="$dir/seeker_$decides"
  roslaunch -p "$port" hideseek_world evaluate.launch policy:=random seeker_mode:=external seeker_decides:=$decides \
    episodes:=4 num_arenas:=2 output_dir:="$eval_dir" > "$dir/seeker_$decides.launch.log" 2>&1 &
  launch=$!
  for _ in $(seq 1 300); do rostopic list 2>/dev/null | grep -q /seeker/observations && break; sleep 0.2; done
  /usr/bin/python3 "$(dirname "$example")/seeker_node.py" > "$dir/seeker_$decides.log" 2>&1 &
  seeker=$!
  for _ in $(seq 1 1500); do kill -0 "$launch" 2>/dev/null || break; sleep 0.2; done
  kill "$launch" "$seeker" 2>/dev/null
  wait "$launch" "$seeker" 2>/dev/null
  row=$(tail -n 1 "$eval_dir/evaluation.csv" 2>/dev/null)
  want="against the seeker external"
  [ "$decides" = step ] && want="against the seeker external (deciding once a step)"
  case "$row" in
    "basic,random $want,4,"*)  # and as many columns as the header has (no comma in the seeker's name)
      [ "$(echo "$row" | tr -cd , | wc -c)" = "$(head -n 1 "$eval_dir/evaluation.csv" | tr -cd , | wc -c)" ] ||
        failures+=("seeker_decides:=$decides: the row has other columns than the header: '$row'") ;;
    *) failures+=("seeker_decides:=$decides: no evaluation of 4 episodes against the external seeker: '$row'") ;;
  esac
  grep -q "Traceback" "$dir/seeker_$decides.log" &&
    failures+=("the example seeker failed: $(tail -c 300 "$dir/seeker_$decides.log")")
  echo "seeker_decides:=$decides: $row"
done
write_xunit "$out" own_hider ExampleHiderAndSeekerNodesAreEvaluatedLikePolicies "${failures[@]}"
[ ${#failures[@]} -eq 0 ] || printf 'failure: %s\n' "${failures[@]}"
[ ${#failures[@]} -eq 0 ] && rm -rf "$dir"
[ ${#failures[@]} -eq 0 ]
