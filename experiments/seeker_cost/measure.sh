#!/usr/bin/env bash
# The cost of a learning seeker's PPO update beside the hider's (issue #68): the same train.launch,
# the same network, arenas and PPO file, once with role hider (against the scripted seeker) and once
# with role seeker (against the random hider, or OPPONENT), each UPDATES updates from scratch.
# Prints samples per second after two warm-up updates and where the loop's time went.
# usage: experiments/seeker_cost/measure.sh [UPDATES] [OPPONENT]   (defaults: 8, random)
set -euo pipefail
updates=${1:-8}
opponent=${2:-random}
root=$(cd "$(dirname "$0")/../.." && pwd)
source "$root/scripts/env.sh"
out=$(mktemp -d /tmp/hideseek_seeker_cost.XXXXXX)
port=$((14970 + RANDOM % 10))  # outside the tests' ranges (docs/testing.md, Ports)
measure() { PYTHONPATH="$root/src/hideseek_pipeline/python" /usr/bin/python3 -m hideseek_pipeline.measure "$@"; }
for role in hider seeker; do
  ROS_MASTER_URI=http://localhost:$port roslaunch -p "$port" hideseek_world train.launch role:="$role" \
    opponent:="$([ "$role" = seeker ] && echo "$opponent" || echo scripted)" steps:=$((updates * 1024)) \
    output_dir:="$out/$role" checkpoint_interval:=100000 > "$out/$role.log" 2>&1
  port=$((port + 1))
  printf '%-6s %s samples/s; update, inference, waiting for the world, other: %s\n' "$role" \
    "$(measure samples-per-s "$out/$role/training_log.csv")" "$(measure loop-shares "$out/$role/loop_profile.csv")"
done
grep -h "training basic PPO" "$out"/*.log | sed 's/\x1b\[[0-9;]*m//g' | cut -c1-200
rm -rf "$out"
