#!/usr/bin/env bash
# Training through the graph against the in-process floor, with where the loop's time and the
# processes' CPU time go: the floor (train_floor_bench), then a training run through train.launch
# whose updates 3 to UPDATES + 2 are timed (after 2 to warm up, as make bench does; one more
# update runs after them so that the processes are still there to be read), then the floor
# again. Prints the efficiency (graph over the mean of the two floors), the hider's loop split per
# update (its loop_profile.csv) and the CPU time this workspace's world, seeker and hider nodes
# used per update (/proc/PID/stat), all over the same UPDATES updates. It also prints the
# efficiency at the graph's own speed: the PPO update is the same computation in the floor and
# in the graph, so the graph's own update time, scaled by the floor's ratio of a whole update
# loop to its PPO update, estimates what the floor would have taken in the same seconds; that
# ratio does not depend on how fast the host runs at the moment, the floors' samples/s do. It
# leans high: where the world's and the seeker's threads slow the learner's update in the graph,
# that loss counts as the floor's. Run it with nothing else on the machine, and compare only
# figures taken alternating: this kind of virtual machine drifts by 10 to 40 % over minutes.
# usage: experiments/throughput/measure_loop.sh [ARENAS=16] [PPO_CONFIG=config/ppo.yaml] [UPDATES=20] [LABEL] [roslaunch args ...]
#   e.g. experiments/throughput/measure_loop.sh 32 /tmp/ppo_rollout32.yaml 20 32x32
#        experiments/throughput/measure_loop.sh 16 config/ppo.yaml 20 rt0 render_threads:=0
#   NETWORK (ff), PRECISION (auto) and ROS_PORT (11533) come from the environment.
set -euo pipefail
config=$(realpath -m "${2:-$(dirname "$0")/../../config/ppo.yaml}")
[ -f "$config" ] || { echo "measure_loop: PPO_CONFIG: no file ${2:-config/ppo.yaml}" >&2; exit 2; }
cd "$(dirname "$0")/../.."
arenas=${1:-16}
updates=${3:-20}
[ "$updates" -ge 1 ] 2> /dev/null || { echo "measure_loop: UPDATES must be a whole number >= 1, got '$updates'" >&2; exit 2; }
source experiments/throughput/measure.sh
rollout=$(rollout_steps "$config")
label=${4:-${arenas}x$rollout}
shift $(($# < 4 ? $# : 4))
network=${NETWORK:-ff}
precision=${PRECISION:-auto}
source scripts/env.sh
floor() {  # "samples/s loop_over_update" of the floor
  local out
  out=$(devel/lib/hideseek_hider/train_floor_bench "$config" "$arenas" 4 2 "$precision" "$network" |
    awk '$1 ~ /_samples_per_s$/ { s = $2 } $1 == "loop_over_update" { r = $2 } END { if (s && r) print s, r }')
  [ -n "$out" ] || { echo "measure_loop: train_floor_bench gave no samples/s or no loop_over_update" >&2; exit 1; }
  echo "$out"
}
ticks() {  # CPU time (user + system, clock ticks) of this workspace's nodes of one package
  local t=0 p
  for p in $(pgrep -f "$PWD/devel/lib/hideseek_$1/" || true); do
    t=$((t + $(awk '{ print $14 + $15 }' "/proc/$p/stat" 2>/dev/null || echo 0)))
  done
  echo "$t"
}
rows() { if [ -f "$run/training_log.csv" ]; then wc -l < "$run/training_log.csv"; else echo 0; fi; }
out=$(floor) && read -r floor_before ratio0 <<< "$out"
run=$(mktemp -d)
trap 'rm -rf "$run"' EXIT
port=${ROS_PORT:-11533}
export ROS_MASTER_URI=http://localhost:$port
roslaunch -p "$port" hideseek_world train.launch num_arenas:="$arenas" ppo_config:="$config" network:="$network" \
  precision:="$precision" steps:=$((arenas * rollout * (updates + 3))) output_dir:="$run" checkpoint_interval:=100000 \
  "$@" > "$run/launch.log" 2>&1 &
launch=$!
# The log has a header row: update k has ended when it has k + 1 rows.
died() { kill -0 $launch 2> /dev/null && return 1; cat "$run/launch.log" >&2; echo "measure_loop: the graph stopped early" >&2; exit 1; }
until [ "$(rows)" -ge 3 ]; do died || sleep 0.02; done
w0=$(ticks world) s0=$(ticks seeker) h0=$(ticks hider) r0=$(rows)
until [ "$(rows)" -ge $((updates + 3)) ]; do died || sleep 0.02; done
w1=$(ticks world) s1=$(ticks seeker) h1=$(ticks hider) r1=$(rows)
wait $launch || true
out=$(floor) && read -r floor_after ratio1 <<< "$out"
# Rows r0 and r1 as read above (the polling may have seen them a few ms late; the log's own times are exact).
graph=$(samples_per_s "$run/training_log.csv" $((r0 - 1)) $((r1 - 1)))  # row k + 1 ends update k
hz=$(getconf CLK_TCK)
awk -v l="$label" -v f0="$floor_before" -v f1="$floor_after" -v g="$graph" -v n=$((r1 - r0)) -v hz="$hz" \
  -v w=$((w1 - w0)) -v s=$((s1 - s0)) -v h=$((h1 - h0)) 'BEGIN {
  printf "%s: floor %s / %s, graph %s samples/s, efficiency %.3f\n", l, f0, f1, g, 2 * g / (f0 + f1)
  printf "%s: core-seconds per update: world %.3f, seeker %.3f, hider %.3f\n", l, w / hz / n, s / hz / n, h / hz / n }'
awk -F, -v l="$label" -v a="$r0" -v b="$r1" -v r0="$ratio0" -v r1="$ratio1" \
  'NR > a && NR <= b { w += $3; i += $4; u += $5; o += $6; n++ }
  END {
    printf "%s: seconds per update: wait %.3f, inference %.3f, update %.3f, other %.3f\n", l, w / n, i / n, u / n, o / n
    loop = (r0 + r1) / 2  # as make bench computes train_efficiency_own_speed
    printf "%s: floor loop / floor update %.3f, efficiency at the graph'"'"'s own speed %.3f\n", l, loop, loop * u / (w + i + u + o) }' \
  "$run/loop_profile.csv"
