#!/usr/bin/env bash
# Integration test: the ROS master dies under a running game and a new one starts on its port.
# usage: master_restart_test.sh XUNIT_OUTPUT
# The game goes on over the nodes' connections; each of world, seeker and hider says, once, that
# the master does not answer, and then that the new master does not know it and what to do.
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
dir=$(mktemp -d /tmp/hideseek_master_test.XXXXXX)
port=$((12300 + RANDOM % 100))
export ROS_MASTER_URI=http://localhost:$port
failures=()
roscore -p "$port" > "$dir/core1.log" 2>&1 &
core=$!
# Each wait ends as soon as what it waits for happens; its bound, in seconds of wall time (2 min,
# 5 min for the first episode), only catches a hang, however slow the CPU.
wait_until() {
  local end=$((SECONDS + $1))
  shift
  until "$@"; do [ $SECONDS -ge $end ] && return 1; sleep 0.2; done
}
wait_until 120 eval 'rostopic list > /dev/null 2>&1'
roslaunch -p "$port" hideseek_world basic.launch mode:=lockstep num_arenas:=2 policy:=random > "$dir/game.log" 2>&1 &
launch=$!
wait_until 300 grep -a -q "episode .* (seed" "$dir/game.log"
episodes() { grep -a -c "episode .* (seed" "$dir/game.log"; }
# The master and its rosout die as a crash would: roscore's children only (rosmaster and rosout),
# never another graph's rosout on this machine (a held sweep's, a second checkout's tests).
kill -KILL $(pgrep -P "$core") "$core" 2> /dev/null
said() { grep -a "$1" "$dir/game.log" | grep -a -o "/[a-z]*: $2" | sort -u | tr '\n' ' '; }  # (the log holds NULs)
wait_until 120 eval '[ "$(said "does not answer" "the ROS")" = "/hider: the ROS /seeker: the ROS /world: the ROS " ]'
gone=$(said "does not answer" "the ROS")
before=$(episodes)
roscore -p "$port" > "$dir/core2.log" 2>&1 &
core=$!
wait_until 120 eval '[ "$(said "a new ROS master answers" "a new")" = "/hider: a new /seeker: a new /world: a new " ]'
unknown=$(said "a new ROS master answers" "a new")
after=$(episodes)
[ "$gone" = "/hider: the ROS /seeker: the ROS /world: the ROS " ] ||
  failures+=("the nodes that said the master does not answer: '$gone'")
[ "$unknown" = "/hider: a new /seeker: a new /world: a new " ] ||
  failures+=("the nodes that said the new master does not know them: '$unknown'")
grep -a -q "stop the launch and run the same command" "$dir/game.log" || failures+=("no node said what to do")
[ "$after" -gt "$before" ] || failures+=("the game stopped with the master: $before episodes, then $after")
kill -INT "$launch" 2> /dev/null
timeout 30 tail --pid="$launch" -f /dev/null || failures+=("the launch did not stop within 30 s of SIGINT")
kill -INT "$core" 2> /dev/null
wait "$core" 2> /dev/null
write_xunit "$out" master MasterRestartedUnderARunningGame "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
[ ${#failures[@]} -eq 0 ] && rm -rf "$dir"
[ ${#failures[@]} -eq 0 ]
