# The throughput studies' helpers (sourced by measure_loop.sh, measure_threads.sh and
# sweep_throughput.sh): the measurement itself is make bench's, hideseek_pipeline.measure (one way
# to time a run: samples/s after the warm-up's MEASURE_WARMUP updates, the loop's shares over the
# same updates); this file adds the training run through the graph that the studies time.
MEASURE_WARMUP=${MEASURE_WARMUP:-2}
export MEASURE_WARMUP
_measure_root=$(realpath "$(dirname "${BASH_SOURCE[0]}")/../..")
_measure() { PYTHONPATH="$_measure_root/src/hideseek_pipeline/python" /usr/bin/python3 -m hideseek_pipeline.measure "$@"; }

rollout_steps() { _measure rollout-steps "$1"; }  # PPO_CONFIG: its steps per arena per update
samples_per_s() { _measure samples-per-s "$@"; }  # TRAINING_LOG [FIRST [LAST]] (default: the warm-up's last, the log's last)
loop_shares() { _measure loop-shares "$@"; }      # LOOP_PROFILE [FIRST [LAST]]: "update inference wait other" shares

# A training run through train.launch on its own master, with no checkpoint in the timed updates:
# OUTPUT_DIR PORT ARENAS UPDATES [roslaunch args...]; it trains MEASURE_WARMUP + UPDATES updates of
# config/ppo.yaml's rollout unless a ppo_config argument says otherwise (then ROLLOUT must be set).
train_through_graph() {
  local out=$1 port=$2 arenas=$3 updates=$4
  shift 4
  local rollout=${ROLLOUT:-$(rollout_steps "$_measure_root/config/ppo.yaml")}
  ROS_MASTER_URI=http://localhost:$port roslaunch -p "$port" hideseek_world train.launch num_arenas:="$arenas" \
    steps:=$((arenas * rollout * (MEASURE_WARMUP + updates))) output_dir:="$out" checkpoint_interval:=100000 "$@"
}
