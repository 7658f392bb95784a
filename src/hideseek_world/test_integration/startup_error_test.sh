#!/usr/bin/env bash
# A node that cannot start says why, where roslaunch shows it: a missing checkpoint, a bad
# precision or memory format, an unknown game or variant name, a misspelt variant field, a misspelt scripted evader and the memoryless ablation
# asked of a hider without a GRU, a checkpoint of the other role, and a misspelt seeker mode each
# stop the game with a FATAL line naming the problem, as does a variant file of one's own named
# otherwise than variant:=. A variant's launch file given another variant
# refuses before any node starts, as train.launch does a misspelt role. A lockstep game refuses a
# master whose /clock is taken. A launch on a master that outlives it reads nothing an earlier
# launch left there.
# usage: startup_error_test.sh XUNIT_OUTPUT
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
dir=$(mktemp -d /tmp/hideseek_startup_test.XXXXXX)
port=$((13450 + RANDOM % 50))  # its own range: analyze_test.sh has 11900-11999
export ROS_MASTER_URI=http://localhost:$port
failures=()
expect_fatal() {  # name, expected text, launch arguments...
  local name=$1 expected=$2
  shift 2
  timeout 120 roslaunch -p "${launch_port:-$port}" hideseek_world "$@" > "$dir/$name.log" 2>&1
  grep -F "[FATAL]" "$dir/$name.log" | grep -F -- "$expected" > /dev/null ||
    failures+=("$name: no FATAL line with '$expected' (got: $(grep -F '[FATAL]' "$dir/$name.log" | head -c 200))")
}
expect_fatal missing_policy "checkpoint /nonexistent/policy.pt cannot be read" basic.launch policy:=/nonexistent/policy.pt
expect_fatal bad_precision "/hider/precision must be auto, fp32 or bf16, got 'fp16'" basic.launch precision:=fp16
expect_fatal bad_memory_format "/hider/memory_format must be auto, channels_last or nchw, got 'nhwc'" game.launch.xml \
  variant:=basic memory_format:=nhwc
expect_fatal unknown_game "game names no game: " basic.launch game:=v9
expect_fatal unknown_variant "'nosuch' is not a variant here (basic, " game.launch.xml variant:=nosuch
# train.launch names a role that is neither hider nor seeker before any node starts.
timeout 120 roslaunch -p "$port" hideseek_world train.launch role:=learner > "$dir/bad_role.log" 2>&1
if grep -q "^process\[" "$dir/bad_role.log" || ! grep -qF "role:=learner is neither hider nor seeker" "$dir/bad_role.log"; then
  failures+=("bad_role: train.launch role:=learner was not refused by name before any node started (got: $(tail -c 300 "$dir/bad_role.log"))")
fi
# A variant's launch file plays its own variant: variant:= naming another is refused before any node starts.
timeout 120 roslaunch -p "$port" hideseek_world slowerhider.launch variant:=basic > "$dir/other_variant.log" 2>&1
rc=$?
if [ $rc -eq 0 ] || grep -q "^process\[" "$dir/other_variant.log" ||
  ! grep -qF "variant:=basic: slowerhider.launch plays slowerhider only; start basic.launch" "$dir/other_variant.log"; then
  failures+=("other_variant: slowerhider.launch variant:=basic was not refused by name before any node started (exit $rc; got: $(tail -c 300 "$dir/other_variant.log"))")
fi
config="$(cd "$(dirname "$0")/../../hideseek_game/config" && pwd)"  # the game package holds the maps
printf 'variant: basic\nmap: %s/maps/deterministic.yaml\nhider:\n  sped: 3.0\n' "$config" > "$dir/typo.yaml"
expect_fatal bad_field "field 'hider.sped': unknown field" game.launch.xml variant:=basic variant_config:="$dir/typo.yaml"
# A variant file of one's own plays under its own name, which labels the results: another is refused.
printf 'variant: slowbasic\nmap: %s/maps/deterministic.yaml\nhider:\n  speed: 1.0\n' "$config" > "$dir/slowbasic.yaml"
expect_fatal variant_file_named_otherwise "variant_config is variant 'slowbasic' ($dir/slowbasic.yaml), but" \
  game.launch.xml variant:=basic variant_config:="$dir/slowbasic.yaml"
policies="$(cd "$(dirname "$0")/../policies" && pwd)"
expect_fatal memoryless_ff "memoryless applies to a GRU policy only, and this one is a feed-forward hider" evaluate.launch \
  policy:="$policies/basic.pt" memoryless:=true episodes:=1 output_dir:="$dir/eval_ff"
expect_fatal memoryless_random "is true, but the hider is in random mode: memoryless applies to a GRU policy only" \
  evaluate.launch policy:=random memoryless:=true episodes:=1 output_dir:="$dir/eval_random"
expect_fatal unknown_evader "/hider/policy: 'scripted/hid' names no scripted evader" evaluate.launch \
  policy:=scripted/hid episodes:=1 output_dir:="$dir/eval_evader"
# Each role refuses the other's checkpoint: a seeker given a hider's, a hider given a seeker's (one
# PPO update of a learning seeker, through train.launch), and a seeker mode misspelt.
expect_fatal seeker_given_hider "basic.pt is a hider's policy (role hider), not a seeker's" basic.launch \
  seeker_policy:="$policies/basic.pt"
timeout 120 roslaunch -p "$port" hideseek_world train.launch role:=seeker opponent:=random steps:=128 num_arenas:=2 \
  output_dir:="$dir/seeker" > "$dir/seeker_train.log" 2>&1
[ -f "$dir/seeker/checkpoint.pt" ] || failures+=("seeker_train: train.launch role:=seeker wrote no checkpoint")
expect_fatal hider_given_seeker "checkpoint.pt is a seeker's policy (role seeker), not a hider's" basic.launch \
  policy:="$dir/seeker/checkpoint.pt"
expect_fatal seeker_given_a_hider_name "/seeker/policy is 'shipped', a hider's policy: the seeker plays a seeker's checkpoint" \
  train.launch role:=hider opponent:=shipped steps:=128 num_arenas:=2 output_dir:="$dir/hider_vs_shipped"
expect_fatal hider_given_scripted "/hider/policy is 'scripted': name the evader, scripted/EVADER" \
  train.launch role:=seeker opponent:=scripted steps:=128 num_arenas:=2 output_dir:="$dir/seeker_vs_scripted"
expect_fatal bad_seeker_mode "/seeker/mode must be one of 'scripted', 'random', 'policy', 'train', got 'learn'" \
  basic.launch seeker_mode:=learn
# /clock belongs to the whole master: a lockstep game where something already publishes it (here
# rostopic, as a second lockstep game or `rosbag play --clock` would) stops before it publishes,
# naming the publisher; a realtime game beside it plays, and warns that tools read one clock.
clock_port=$((13200 + RANDOM % 100))
roscore -p "$clock_port" > "$dir/clock_master.log" 2>&1 &
master_pid=$!
export ROS_MASTER_URI=http://localhost:$clock_port
for _ in $(seq 100); do rostopic list > /dev/null 2>&1 && break; sleep 0.2; done
kill -0 "$master_pid" 2> /dev/null || failures+=("second_clock: roscore -p $clock_port did not start: $(tail -c 200 "$dir/clock_master.log")")
rostopic pub -r 10 /clock rosgraph_msgs/Clock "{clock: {secs: 5, nsecs: 0}}" __name:=clock_source > /dev/null 2>&1 &
clock_pid=$!
for _ in $(seq 100); do rostopic info /clock 2>/dev/null | grep -q clock_source && break; sleep 0.2; done
launch_port=$clock_port expect_fatal second_clock "/clock is already published on this master, by /clock_source" \
  basic.launch mode:=lockstep policy:=random
# This master outlives its launches, and roslaunch deletes no parameter: a launch that gave a bad
# precision and a misspelt variant file must leave nothing the next launch's nodes read.
launch_port=$clock_port expect_fatal stale_first "field 'hider.sped': unknown field" basic.launch policy:=random \
  precision:=fp16 variant_config:="$dir/typo.yaml"
roslaunch -p "$clock_port" hideseek_world basic.launch policy:=random > "$dir/realtime_beside_clock.log" 2>&1 &
beside=$!
for _ in $(seq 600); do grep -qF "starting realtime" "$dir/realtime_beside_clock.log" && break; sleep 0.2; done
for stale in /hider/precision /world/variant_config /seeker/variant_config /hider/variant_config; do
  if value=$(rosparam get "$stale" 2> /dev/null); then
    failures+=("stale_params: $stale is still '$value' from the launch before")
  fi
done
kill -INT "$beside" 2> /dev/null
wait "$beside" 2> /dev/null
grep -F "[ WARN]" "$dir/realtime_beside_clock.log" | grep -qF "/clock is published on this master, by /clock_source" ||
  failures+=("realtime_beside_clock: no warning that /clock is published (got: $(grep -F 'WARN' "$dir/realtime_beside_clock.log" | head -c 300))")
grep -qF "both agents connected, starting realtime" "$dir/realtime_beside_clock.log" ||
  failures+=("realtime_beside_clock: the realtime game beside /clock did not start")
kill "$clock_pid" 2> /dev/null
kill "$master_pid" 2> /dev/null
wait "$clock_pid" "$master_pid" 2> /dev/null
export ROS_MASTER_URI=http://localhost:$port
write_xunit "$out" startup StartupErrorsAreShownByRoslaunch "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
rm -rf "$dir"
[ ${#failures[@]} -eq 0 ]
