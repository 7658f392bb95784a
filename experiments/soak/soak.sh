#!/usr/bin/env bash
# A soak (issue #49; not in CI): a game left running for hours while every node's memory is sampled.
# usage: experiments/soak/soak.sh realtime SECONDS OUT      basic.launch in realtime with the shipped policy, on
#                                                  its own master, rviz's topics subscribed all along
#        experiments/soak/soak.sh attach PORT SECONDS OUT [--continue]
#                                                  a graph already running on master port PORT (a sweep
#                                                  run: 12100 + 10 x its slot), subscribing to nothing;
#                                                  --continue goes on with a watch cut short
# OUT gets rss.csv, world.csv and summary.md (experiments/soak/soak_monitor.py).
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/env.sh
mode=${1:-}
kill_tree() {  # roslaunch starts each node in its own session: kill the tree by PID
  local child
  for child in $(pgrep -P "$1" || true); do kill_tree "$child"; done
  kill -INT "$1" 2>/dev/null || true
}
case "$mode" in
  realtime)
    [ $# -eq 3 ] || { sed -n 3,10p "$0"; exit 2; }
    seconds=$2 out=$3 port=14950
    mkdir -p "$out"
    export ROS_MASTER_URI=http://localhost:$port
    roslaunch -p "$port" hideseek_world basic.launch > "$out/launch.log" 2>&1 &
    launch=$!
    trap 'kill_tree $launch; wait $launch 2>/dev/null || true' EXIT
    for _ in $(seq 1 150); do rostopic list 2>/dev/null | grep -q /world/episodes && break; sleep 0.2; done
    /usr/bin/python3 experiments/soak/soak_monitor.py --duration "$seconds" --out "$out" --rviz
    ;;
  attach)
    [ $# -eq 4 ] || [ $# -eq 5 ] || { sed -n 3,10p "$0"; exit 2; }
    export ROS_MASTER_URI=http://localhost:$2
    mkdir -p "$4"
    /usr/bin/python3 experiments/soak/soak_monitor.py --duration "$3" --out "$4" --interval 60 ${5:+"$5"}
    ;;
  *) sed -n 3,10p "$0"; exit 2 ;;
esac
