#!/usr/bin/env bash
# Training across machines, shown on this machine (docs/distributed.md): variant basic, training
# seed 0, STEPS environment steps, trained twice from the same seed: by 1 rank of 2 learner threads
# (train.launch as always) and by 2 ranks of 1 learner thread each, each rank its own graph on its
# own master, as two machines would run it. Midway through the 2-rank run rank 1's hider is killed
# (SIGKILL): rank 0 must stop, naming rank 1; the same two commands then resume both ranks from
# rank 0's last checkpoint. Writes OUT (default docs/runs/ddppo_basic_seed0): both training logs,
# the ranks' console lines, and curves.png with both learning curves.
#   experiments/ddppo/ddppo_demo.sh [OUT]      (STEPS=200000 KILL_AFTER_S=150 by default)
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/env.sh
STEPS=${STEPS:-200000}
KILL_AFTER_S=${KILL_AFTER_S:-150}
out=$(realpath -m "${1:-docs/runs/ddppo_basic_seed0}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
say() { echo "ddppo_demo $(date +%H:%M:%S): $*"; }

say "1 rank, 2 learner threads, $STEPS steps"
start=$(date +%s)
roslaunch -p 11471 hideseek_world train.launch variant:=basic seed:=0 steps:="$STEPS" hider_threads:=2 \
  output_dir:="$work/one" > "$work/one.log" 2>&1
say "1 rank: done in $(($(date +%s) - start)) s"

# Rank r of 2: its own master (11472 + r), rank 0 hosting the rendezvous.
ranks() {
  for r in 0 1; do
    roslaunch -p $((11472 + r)) hideseek_world train.launch variant:=basic seed:=0 steps:="$STEPS" hider_threads:=1 \
      world_size:=2 rank:=$r rendezvous:=127.0.0.1:"$port" rendezvous_timeout:=60 checkpoint_interval:=30 \
      output_dir:="$work/rank$r" >> "$work/rank$r.log" 2>&1 &
  done
}
# The hider of rank r: the hider_node whose master is rank r's.
hider_of() {
  local pid
  for pid in $(pgrep -f "hideseek_hider/hider_node"); do
    if tr '\0' '\n' < "/proc/$pid/environ" 2> /dev/null | grep -q "^ROS_MASTER_URI=http://[^:]*:$((11472 + $1))/\?$"; then
      echo "$pid"
    fi
  done
}
say "2 ranks, 1 learner thread each, $STEPS steps; rank 1's hider is killed after $KILL_AFTER_S s"
start=$(date +%s)
ranks
sleep "$KILL_AFTER_S"
victim=$(hider_of 1)
[ -n "$victim" ] || { echo "ddppo_demo: rank 1's hider is not running" >&2; exit 1; }
kill -KILL "$victim"
say "killed rank 1's hider (pid $victim)"
wait || true
killed_at=$(date +%s)
say "both ranks stopped $((killed_at - start - KILL_AFTER_S)) s after the kill; rank 0 said:"
grep -h "training stopped" "$work/rank0.log" | sed 's/\x1b\[[0-9;]*m//g' | tee "$work/stop.txt"
grep -q "rank 1 stopped" "$work/stop.txt" || { echo "ddppo_demo: rank 0 did not name rank 1" >&2; exit 1; }
say "the same commands again: both ranks resume from rank 0's checkpoint"
ranks
wait
say "2 ranks: done in $(($(date +%s) - start)) s, the stop and restart included"
grep -h "resumed at step" "$work/rank0.log" "$work/rank1.log" | sed 's/\x1b\[[0-9;]*m//g' || true

cp "$work/one/training_log.csv" "$out/one_rank_training_log.csv"
cp "$work/rank0/training_log.csv" "$out/two_ranks_training_log.csv"
for f in one rank0 rank1; do
  grep -hE "hider: |train: done|training stopped|DD-PPO" "$work/$f.log" | sed 's/\x1b\[[0-9;]*m//g' > "$out/$f.console.txt" || true
done
/usr/bin/python3 src/hideseek_analysis/scripts/plot_learning_curve.py --run "1 rank (2 threads)" "$out/one_rank_training_log.csv" \
  --run "2 ranks (1 thread each; rank 1 killed and resumed)" "$out/two_ranks_training_log.csv" \
  --title "basic, seed 0: DD-PPO with 2 ranks beside 1 rank" --output "$out/curves.png"
say "wrote $out"
