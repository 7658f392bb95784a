#!/usr/bin/env bash
# `make bench`: throughput figures of this machine, one `name value` line each.
# Timing goals live here, never in tests.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh
ARENAS=${ARENAS:-16}
SECONDS_PER_RUN=${SECONDS_PER_RUN:-10}
echo "# world core: physics, labels and rendering of $ARENAS arenas at 84x84 in one process"
devel/lib/hideseek_world/world_core_bench config/game.yaml config/variants/basic.yaml "$ARENAS" "$SECONDS_PER_RUN"
echo "# world node in lockstep with two minimal agents as separate processes, $ARENAS arenas"
export ROS_MASTER_URI=http://localhost:11433
roslaunch -p 11433 hideseek_world bench_world.launch num_arenas:="$ARENAS" duration:="$SECONDS_PER_RUN" 2>/dev/null | \
  grep -E "^world_ros_steps_per_s"
echo "# full game graph in lockstep: world, seeker node, random hider node, $ARENAS arenas"
roslaunch -p 11433 hideseek_world bench_game.launch num_arenas:="$ARENAS" duration:="$SECONDS_PER_RUN" 2>/dev/null | \
  grep -E "^game_ros_steps_per_s"
