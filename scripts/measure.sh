# Training throughput measured one way (sourced by make bench's scripts/bench.sh and by
# measure_loop.sh, measure_threads.sh and sweep_throughput.sh; issue #52). A run through
# train.launch is timed from its log: samples/s between the end of update MEASURE_WARMUP and the
# end of a later update, and where the hider's loop went (loop_profile.csv) over the same updates.
# The first updates load the network, fault the buffers in and let the graph connect: they are
# warm-up, left out of every figure.
MEASURE_WARMUP=${MEASURE_WARMUP:-2}

rollout_steps() {  # PPO_CONFIG: its steps per arena per update
  local r
  r=$(awk '/^rollout_steps:/ { print $2 }' "$1")
  [ -n "$r" ] || { echo "measure: $1 has no rollout_steps" >&2; return 2; }
  echo "$r"
}

# Samples/s from the end of update FIRST (default: the warm-up's last) to the end of update LAST
# (default: the log's last), from the log's own step counts and wall times.
samples_per_s() {  # TRAINING_LOG [FIRST [LAST]]
  awk -F, -v a="${2:-$MEASURE_WARMUP}" -v b="${3:-0}" '
    NR > 1 && $1 == a { s0 = $2; t0 = $3 }
    NR > 1 && (b == 0 || $1 <= b) { s = $2; t = $3 }
    END { if (t > t0 && s0 != "") printf "%.0f\n", (s - s0) / (t - t0); else exit 1 }' "$1" ||
    { echo "measure: $1 holds no updates after update ${2:-$MEASURE_WARMUP}" >&2; return 1; }
}

# The hider's loop over updates FIRST + 1 to LAST of its loop_profile.csv (defaults as above):
# "update inference wait other", each a share of the loop's time.
loop_shares() {  # LOOP_PROFILE [FIRST [LAST]]
  awk -F, -v a="${2:-$MEASURE_WARMUP}" -v b="${3:-0}" '
    NR > 1 && $1 > a && (b == 0 || $1 <= b) { w += $3; i += $4; u += $5; o += $6 }
    END { t = w + i + u + o; if (t > 0) printf "%.3f %.3f %.3f %.3f\n", u / t, i / t, w / t, o / t; else exit 1 }' "$1"
}

# A training run through train.launch on its own master, with no checkpoint in the timed updates:
# OUTPUT_DIR PORT ARENAS UPDATES [roslaunch args...]; it trains MEASURE_WARMUP + UPDATES updates of
# config/ppo.yaml's rollout unless a ppo_config argument says otherwise (then ROLLOUT must be set).
train_through_graph() {
  local out=$1 port=$2 arenas=$3 updates=$4
  shift 4
  local rollout=${ROLLOUT:-$(rollout_steps config/ppo.yaml)}
  ROS_MASTER_URI=http://localhost:$port roslaunch -p "$port" hideseek_world train.launch num_arenas:="$arenas" \
    steps:=$((arenas * rollout * (MEASURE_WARMUP + updates))) output_dir:="$out" checkpoint_interval:=100000 "$@"
}
