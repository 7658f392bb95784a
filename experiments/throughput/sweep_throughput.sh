#!/usr/bin/env bash
# The sweep's arrangement, measured on this machine: total training samples/s over 20 updates of
# (A) one run with two learner threads, against (B) two concurrent runs with one learner thread
# each, each on its own ROS master. Both through train.launch (basic, bf16 where native, 16 arenas
# x 64 steps), updates 3 to 22 of each run's log (the first two warm up). Alternates A B B A so that
# the host's drift falls on both. Prints a Markdown table and the arrangement that trains more
# samples per hour. Take it with the sweep paused (hideseek_pipeline sweep pause).
# usage: experiments/throughput/sweep_throughput.sh [ROUNDS=2]
#   WORKSPACE (default this checkout): the built workspace to train with (the sweep's worktree:
#   WORKSPACE=~/hideseek_sweep/tree). PORT (default 14960): masters on PORT and PORT + 1.
set -euo pipefail
rounds=${1:-2}
ws=$(realpath "${WORKSPACE:-$(dirname "$0")/../..}")
port=${PORT:-14960}
here=$(dirname "$(realpath "$0")")/../../scripts
source "$here/env.sh"
source "$here/../experiments/throughput/measure.sh"
set +u
source "$ws/devel/setup.bash"
set -u
ROLLOUT=$(rollout_steps "$ws/config/ppo.yaml")
updates=$((MEASURE_WARMUP + 20))
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# One training of `updates` updates into $1 on port $2 with $3 learner threads, in the background.
train() { train_through_graph "$1" "$2" 16 20 variant:=basic hider_threads:="$3" > "$1.log" 2>&1; }
# samples/s over updates 3..22 of a training log
rate() { samples_per_s "$1/training_log.csv" "$MEASURE_WARMUP" "$updates"; }
one() {
  local d=$tmp/a$1
  train "$d" "$port" 2
  rate "$d"
}
two() {
  local d1=$tmp/b$1_1 d2=$tmp/b$1_2
  train "$d1" "$port" 1 &
  local p1=$!
  train "$d2" $((port + 1)) 1 &
  local p2=$!
  wait $p1 $p2
  echo "$(rate "$d1") $(rate "$d2")"
}
echo "| round | arrangement | samples/s per run | total samples/s |"
echo "| --- | --- | --- | --- |"
sum_a=0
sum_b=0
for ((r = 1; r <= rounds; r++)); do
  for arr in $([ $((r % 2)) = 1 ] && echo "A B" || echo "B A"); do
    if [ "$arr" = A ]; then
      a=$(one "$r")
      echo "| $r | A: 1 run x 2 threads | $a | $a |"
      sum_a=$(awk "BEGIN { print $sum_a + $a }")
    else
      read -r b1 b2 < <(two "$r")
      echo "| $r | B: 2 runs x 1 thread | $b1, $b2 | $(awk "BEGIN { print $b1 + $b2 }") |"
      sum_b=$(awk "BEGIN { print $sum_b + $b1 + $b2 }")
    fi
  done
done
a=$(awk "BEGIN { print $sum_a / $rounds }")
b=$(awk "BEGIN { print $sum_b / $rounds }")
printf '\nmean total samples/s: A (1 run x 2 threads) %.0f, B (2 runs x 1 thread) %.0f; B / A = %.2f\n' "$a" "$b" "$(awk "BEGIN { print $b / $a }")"
if awk "BEGIN { exit !($b > $a) }"; then echo "more samples per hour: B, two runs at once (sweep jobs: 2, hider_threads: 1)"; else echo "more samples per hour: A, one run at a time (sweep jobs: 1, hider_threads: 2)"; fi
