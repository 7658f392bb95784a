#!/usr/bin/env bash
# `make bench`: throughput figures of this machine, one `name value` line each.
# Timing goals live here, never in tests.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh
ARENAS=${ARENAS:-16}
SECONDS_PER_RUN=${SECONDS_PER_RUN:-10}
echo "# world core: physics, labels and rendering of $ARENAS arenas at 84x84 in one process"
devel/lib/hideseek_game/world_core_bench config/game.yaml config/variants/basic.yaml "$ARENAS" "$SECONDS_PER_RUN"
echo "# world node in lockstep with two minimal agents as separate processes, $ARENAS arenas"
export ROS_MASTER_URI=http://localhost:11433
roslaunch -p 11433 hideseek_world bench_world.launch num_arenas:="$ARENAS" duration:="$SECONDS_PER_RUN" 2>/dev/null | \
  grep -E "^world_ros_steps_per_s"
echo "# full game graph in lockstep: world, seeker node, random hider node, $ARENAS arenas"
roslaunch -p 11433 hideseek_world bench_game.launch num_arenas:="$ARENAS" duration:="$SECONDS_PER_RUN" 2>/dev/null | \
  grep -E "^game_ros_steps_per_s"
echo "# training floor: the network and PPO update in one process on synthetic data (2 intra-op threads,"
echo "# OPENBLAS_NUM_THREADS=1 as the hider node runs), in fp32 and in the default precision (auto)"
floor_fp32=$(OPENBLAS_NUM_THREADS=1 devel/lib/hideseek_hider/train_floor_bench config/ppo.yaml "$ARENAS" 3 2 fp32 |
  awk '/samples_per_s/ { print $2 }')
echo "train_floor_fp32_samples_per_s $floor_fp32"
default=$(OPENBLAS_NUM_THREADS=1 devel/lib/hideseek_hider/train_floor_bench config/ppo.yaml "$ARENAS" 3 2 auto)
echo "$default" | grep '^#'
floor=$(echo "$default" | awk '/samples_per_s/ { print $2 }')
echo "train_floor_samples_per_s $floor"
echo "train_speedup $(awk -v a="$floor" -v b="$floor_fp32" 'BEGIN { printf "%.2f", a / b }')"
echo "# recurrent training floor: the GRU network (network gru) and recurrent PPO over sequences, in process,"
echo "# default precision; compare with train_floor_samples_per_s"
gru=$(OPENBLAS_NUM_THREADS=1 devel/lib/hideseek_hider/train_floor_bench config/ppo.yaml "$ARENAS" 3 2 auto gru |
  awk '/samples_per_s/ { print $2 }')
echo "train_gru_samples_per_s $gru"
echo "# training: PPO through the ROS graph (world, seeker, hider in train mode), $ARENAS arenas, 84x84, default precision"
run=$(mktemp -d)
roslaunch -p 11433 hideseek_world train.launch num_arenas:="$ARENAS" steps:=$((ARENAS * 64 * 7)) \
  output_dir:="$run" checkpoint_interval:=100000 >/dev/null 2>&1
# Steady state: from the end of the first update to the end of the last (start-up excluded).
ros=$(awk -F, 'NR == 2 { s0 = $2; t0 = $3 } END { printf "%.0f", ($2 - s0) / ($3 - t0) }' "$run/training_log.csv")
rm -rf "$run"
echo "train_ros_samples_per_s $ros"
echo "train_efficiency $(awk -v a="$ros" -v b="$floor" 'BEGIN { printf "%.2f", a / b }')"
