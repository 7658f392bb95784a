#!/usr/bin/env bash
# Measures training throughput for each choice of thread counts, on this machine: the learner's
# intra-op threads (hider_threads), OpenBLAS's threads and the world's render threads, through
# the ROS graph (16 arenas, 84x84), and the in-process floor for the learner's choices.
# Usage: experiments/throughput/measure_threads.sh [PRECISION]   (default fp32). Prints a Markdown table.
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/env.sh
source experiments/throughput/measure.sh
precision=${1:-fp32}
echo "| precision | hider_threads | OPENBLAS_NUM_THREADS | render_threads | train_ros_samples_per_s | train_floor_samples_per_s |"
echo "| --- | --- | --- | --- | --- | --- |"
for ht in 1 2; do
  for blas in 1 2; do
    floor=$(OPENBLAS_NUM_THREADS=$blas devel/lib/hideseek_hider/train_floor_bench config/ppo.yaml 16 3 "$ht" "$precision" |
      awk '/samples_per_s/ { print $2 }')
    for rt in 1 2; do
      run=$(mktemp -d)
      train_through_graph "$run" 11488 16 5 precision:="$precision" hider_threads:="$ht" blas_threads:="$blas" \
        render_threads:="$rt" > /dev/null 2>&1
      ros=$(samples_per_s "$run/training_log.csv")
      rm -rf "$run"
      echo "| $precision | $ht | $blas | $rt | $ros | $floor |"
    done
  done
done
