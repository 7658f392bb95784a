#!/bin/bash
# #27's rollout experiment: trains basic, training seed 0, 2M steps, twice from one tree, 16 arenas
# x 64 steps (the default) and 32 arenas x 32 steps, in turns of SLICE s so that both see the same
# machine (its speed drifts by 10-40 % over minutes). A run's turn ends by stopping (SIGSTOP)
# every process under its train_variant.sh, the next turn continues them (SIGCONT).
# turns.log: "<name> <start> <end>" for each turn a run had the CPU alone, "finished <name> <time>"
# when its log reached its steps; a run's wall time is the sum of its turns up to then.
# touch $AB/hold: both stopped until it is removed.
# usage (from the repository root): AB=/work/exp/ab32 RUNS=/work/exp/runs32 docs/runs/basic_rollout32/alternate.sh
SLICE=${SLICE:-120}
AB=${AB:-/work/exp/ab32}; RUNS=${RUNS:-/work/exp/runs32}; STEPS=2000000
names=(basic_16x64_seed0 basic_32x32_seed0)
envs=("" "NUM_ARENAS=32 PPO_CONFIG=docs/runs/basic_rollout32/ppo_32x32.yaml")
ports=(11700 11760)
pids=("" ""); fin=(0 0)
mkdir -p "$AB" "$RUNS"
tree() {  # a process and all its descendants
  local p=$1 c
  echo "$p"
  for c in $(pgrep -P "$p"); do tree "$c"; done
}
signal() { local p; for p in $(tree "${pids[$2]}"); do kill -"$1" "$p" 2>/dev/null; done; }
start() {
  env ${envs[$1]} PATH=/usr/bin:$PATH ROS_PORT=${ports[$1]} nohup scripts/train_variant.sh basic 0 $STEPS "$RUNS" ff \
    ${names[$1]} >> "$AB/${names[$1]}.out" 2>&1 &
  pids[$1]=$!
}
alive() { [ -n "${pids[$1]}" ] && kill -0 "${pids[$1]}" 2>/dev/null; }
trained() { local s; s=$(tail -n 1 "$RUNS/${names[$1]}/training_log.csv" 2>/dev/null | cut -d, -f2); [ "${s:-0}" -ge $STEPS ] 2>/dev/null; }
note_finish() { if [ ${fin[$1]} = 0 ] && trained $1; then fin[$1]=1; echo "finished ${names[$1]} $(date +%s.%N)" >> "$AB/turns.log"; fi; }
for i in 0 1; do trained $i && fin[$i]=1; done
cur=0
while true; do
  if [ -f "$AB/hold" ]; then for i in 0 1; do alive $i && signal STOP $i; done; sleep 5; continue; fi
  left=0
  for i in 0 1; do { [ -z "${pids[$i]}" ] && [ ! -f "$AB/done_$i" ]; } || alive $i && left=1; done
  [ $left = 0 ] && { echo "both ended $(date +%s)" >> "$AB/turns.log"; exit 0; }
  if ! { [ -z "${pids[$cur]}" ] && [ ! -f "$AB/done_$cur" ]; } && ! alive $cur; then cur=$((1 - cur)); continue; fi
  t0=$(date +%s.%N)
  if [ -z "${pids[$cur]}" ]; then start $cur; else signal CONT $cur; fi
  end=$(( $(date +%s) + SLICE ))
  while [ $(date +%s) -lt $end ] && alive $cur && [ ! -f "$AB/hold" ]; do note_finish $cur; sleep 1; done
  note_finish $cur
  alive $cur && signal STOP $cur
  t1=$(date +%s.%N)
  echo "${names[$cur]} $t0 $t1" >> "$AB/turns.log"
  alive $cur || touch "$AB/done_$cur"
  cur=$((1 - cur))
done
