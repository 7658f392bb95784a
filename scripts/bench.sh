#!/usr/bin/env bash
# `make bench`: throughput figures of this machine, one `name value` line each.
# Timing goals live here, never in tests. ROS_UPDATES (default 20) is the number of PPO updates
# each training run through the graph is timed over, after 2 it is allowed to warm up on.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh
source scripts/measure.sh
ARENAS=${ARENAS:-16}
SECONDS_PER_RUN=${SECONDS_PER_RUN:-10}
ROS_UPDATES=${ROS_UPDATES:-20}
FLOOR_UPDATES=${FLOOR_UPDATES:-4}
ROLLOUT=$(rollout_steps config/ppo.yaml)  # config/ppo.yaml's steps per arena per update
echo "# world core: physics, labels and rendering of $ARENAS arenas at 84x84 in one process"
devel/lib/hideseek_game/world_core_bench config/game.yaml config/variants/basic.yaml "$ARENAS" "$SECONDS_PER_RUN"
echo "# the same from Python (hideseek.make_vec, random hider actions, the scripted seeker planning), $ARENAS environments"
/usr/bin/python3 src/hideseek_python/bench/python_env_bench.py "$ARENAS" "$SECONDS_PER_RUN"
echo "# world node in lockstep with two minimal agents as separate processes, $ARENAS arenas"
export ROS_MASTER_URI=http://localhost:11433
roslaunch -p 11433 hideseek_world bench_world.launch num_arenas:="$ARENAS" duration:="$SECONDS_PER_RUN" 2>/dev/null | \
  grep -E "^world_ros_steps_per_s"
echo "# full game graph in lockstep: world, seeker node, random hider node, $ARENAS arenas"
roslaunch -p 11433 hideseek_world bench_game.launch num_arenas:="$ARENAS" duration:="$SECONDS_PER_RUN" 2>/dev/null | \
  grep -E "^game_ros_steps_per_s"

floor_bench() {  # PRECISION NETWORK [MEMORY_FORMAT]: the floor's output
  devel/lib/hideseek_hider/train_floor_bench config/ppo.yaml "$ARENAS" "$FLOOR_UPDATES" 2 "$1" "$2" "${3:-auto}"
}
field() { awk -v k="$1" '$1 ~ k { print $2 }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
ratio_to_mean() { awk -v a="$1" -v b="$2" -v c="$3" 'BEGIN { printf "%.2f", 2 * a / (b + c) }'; }  # A / mean(B, C)
echo "# training floor: the network and PPO update in one process (2 intra-op threads, as the hider"
echo "# node trains), on observations drawn before timing; in fp32 and in the default precision (auto)"
floor_fp32=$(floor_bench fp32 ff | field '_samples_per_s$')
echo "train_floor_fp32_samples_per_s $floor_fp32"
default=$(floor_bench auto ff)
echo "$default" | grep '^#'
floor=$(echo "$default" | field '_samples_per_s$')
echo "train_floor_samples_per_s $floor"
echo "train_speedup $(ratio "$floor" "$floor_fp32")"
echo "# the floor's arithmetic: FLOPs per sample counted from the network's layers and PPO's passes,"
echo "# achieved GFLOP/s, and their fraction of the peak of the unit the precision's kernels run on: FMA, or"
echo "# AMX-BF16 tiles in bf16 where the CPU has them (the '# peak' line above names it)"
echo "train_flops_per_sample $(echo "$default" | field '^flops_per_sample')"
echo "train_gflops $(echo "$default" | field '^gflops')"
echo "train_peak_fraction $(echo "$default" | field '^peak_fraction')"
echo "# recurrent training floor: the GRU network (network gru) and recurrent PPO over sequences, in process,"
echo "# default precision, and its ratio to the feed-forward floor"
gru_out=$(floor_bench auto gru)
gru=$(echo "$gru_out" | field '_samples_per_s$')
echo "train_gru_samples_per_s $gru"
echo "train_gru_ratio $(ratio "$gru" "$floor")"
echo "train_gru_gflops $(echo "$gru_out" | field '^gflops')"
# The NCHW lines are there for one release (#64): until a CPU with native bf16 has measured them too.
echo "# memory format: the floors again with the images copied into NCHW order (memory_format nchw), against"
echo "# the channels-last layout the hider trains in (the '# memory format' line above); their ratios"
floor_nchw=$(floor_bench auto ff nchw | field '_samples_per_s$')
echo "train_floor_nchw_samples_per_s $floor_nchw"
echo "train_channels_last_speedup $(ratio "$floor" "$floor_nchw")"
gru_nchw=$(floor_bench auto gru nchw | field '_samples_per_s$')
echo "train_gru_nchw_samples_per_s $gru_nchw"
echo "train_gru_channels_last_speedup $(ratio "$gru" "$gru_nchw")"

# PPO through the ROS graph (world, seeker, hider in train mode), timed after the warm-up
# (scripts/measure.sh) over ROS_UPDATES updates; prints samples/s and where the hider's time went
# (its loop_profile.csv over the same updates).
ros_train() {  # NETWORK [MEMORY_FORMAT]: "samples_per_s update inference wait other" (shares of the loop's time)
  local run
  run=$(mktemp -d)
  train_through_graph "$run" 11433 "$ARENAS" "$ROS_UPDATES" network:="$1" memory_format:="${2:-auto}" > /dev/null 2>&1
  echo "$(samples_per_s "$run/training_log.csv") $(loop_shares "$run/loop_profile.csv")"
  rm -rf "$run"
}
echo "# training through the ROS graph: world, seeker, hider in train mode, $ARENAS arenas, 84x84, default"
echo "# precision, $ROS_UPDATES updates; the loop's time in the update, in inference, waiting for the world, other"
read -r ros update inference wait other <<< "$(ros_train ff)"
echo "train_ros_samples_per_s $ros"
# This machine's speed drifts by 10 % and more over minutes: the floor is timed again right after
# the graph, and the efficiency divides by the mean of the floors on either side of it.
after=$(floor_bench auto ff)
floor_after=$(echo "$after" | field '_samples_per_s$')
echo "train_floor_after_samples_per_s $floor_after"
echo "train_efficiency $(ratio_to_mean "$ros" "$floor" "$floor_after")"
# The same ratio at the graph's own speed: the PPO update is the same computation in the floor and
# the graph, so the graph's update share times the floor's loop-to-update ratio (the mean of both
# floors') is what the floor would have reached in the graph's seconds; the host's drift between
# the floor runs and the graph does not move it; it leans high where the other processes slow the
# graph's update (see docs/performance.md).
ratio_before=$(echo "$default" | field '^loop_over_update') ratio_after=$(echo "$after" | field '^loop_over_update')
[ -n "$ratio_before" ] && [ -n "$ratio_after" ] || { echo "bench: train_floor_bench printed no loop_over_update" >&2; exit 1; }
loop_ratio=$(awk -v a="$ratio_before" -v b="$ratio_after" 'BEGIN { print (a + b) / 2 }')
echo "train_efficiency_own_speed $(awk -v u="$update" -v r="$loop_ratio" 'BEGIN { printf "%.2f", u * r }')"
echo "train_ros_update_share $update"
echo "train_ros_inference_share $inference"
echo "train_ros_wait_share $wait"
echo "train_ros_other_share $other"
read -r ros_nchw _ <<< "$(ros_train ff nchw)"
echo "train_ros_nchw_samples_per_s $ros_nchw"
echo "train_ros_channels_last_speedup $(ratio "$ros" "$ros_nchw")"
read -r gru_ros update inference wait other <<< "$(ros_train gru)"
echo "train_gru_ros_samples_per_s $gru_ros"
gru_after=$(floor_bench auto gru | field '_samples_per_s$')
echo "train_gru_efficiency $(ratio_to_mean "$gru_ros" "$gru" "$gru_after")"
echo "train_gru_ros_wait_share $wait"
# Training across machines (DD-PPO), both ranks on this machine: 2 ranks of 1 learner thread, each
# its own graph on its own master with ARENAS arenas, against 1 rank of 2 threads (train_ros above);
# rank 0's log counts both ranks' samples. Then one gradient all-reduce of the feed-forward network
# between 2 ranks over loopback (docs/distributed.md models other networks from it).
dd_train() {  # "samples_per_s"
  local run0 run1 port
  run0=$(mktemp -d) run1=$(mktemp -d)
  port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
  for r in 0 1; do
    roslaunch -p $((11435 + r)) hideseek_world train.launch num_arenas:="$ARENAS" hider_threads:=1 \
      world_size:=2 rank:=$r rendezvous:=127.0.0.1:"$port" steps:=$((2 * ARENAS * ROLLOUT * (MEASURE_WARMUP + ROS_UPDATES))) \
      output_dir:="$([ $r = 0 ] && echo "$run0" || echo "$run1")" checkpoint_interval:=100000 >/dev/null 2>&1 &
  done
  wait
  samples_per_s "$run0/training_log.csv"
  rm -rf "$run0" "$run1"
}
echo "# training across machines, both ranks here: 2 ranks x 1 learner thread, $ARENAS arenas each, against"
echo "# train_ros_samples_per_s (1 rank x 2 threads); one gradient all-reduce between 2 ranks on loopback"
dd=$(dd_train)
echo "train_ddppo_2ranks_samples_per_s $dd"
echo "train_ddppo_2ranks_ratio $(ratio "$dd" "$ros")"
devel/lib/hideseek_hider/allreduce_bench 20 | sed 's/^/ddppo_/'
