#!/bin/bash
# Trains the before (2fc186d) and after runs of #27 in turns of SLICE s, so that both see the same
# machine (its speed drifts by 40 % over hours). A run whose tree is not built yet (no devel/) waits;
# the other trains meanwhile. turns.log: "<name> <start> <end>" of each turn a
# run had the CPU alone, and "finished <name> <time>" when its log reached its steps; a run's wall
# time is the sum of its turns up to then. touch hold: both stopped until it is removed.
SLICE=${SLICE:-120}
AB=/work/exp/ab; RUNS=/work/exp/runs27; STEPS=2000000
names=(basic_before27_seed0 basic_after27_seed0)
trees=(/work/before27 /work/after27)
ports=(11700 11760)
pids=("" ""); fin=(0 0)
procs() { echo "${trees[$1]}/devel/lib/hideseek_(world|seeker|hider)/"; }
start() {
  cd "${trees[$1]}" && PATH=/usr/bin:$PATH ROS_PORT=${ports[$1]} nohup scripts/train_variant.sh basic 0 $STEPS $RUNS ff ${names[$1]} >> $AB/${names[$1]}.out 2>&1 &
  pids[$1]=$!
}
alive() { [ -n "${pids[$1]}" ] && kill -0 "${pids[$1]}" 2>/dev/null; }
trained() { local s; s=$(tail -n 1 "$RUNS/${names[$1]}/training_log.csv" 2>/dev/null | cut -d, -f2); [ "${s:-0}" -ge $STEPS ] 2>/dev/null; }
note_finish() { if [ ${fin[$1]} = 0 ] && trained $1; then fin[$1]=1; echo "finished ${names[$1]} $(date +%s.%N)" >> $AB/turns.log; fi; }
for i in 0 1; do trained $i && fin[$i]=1; done
cur=0
while true; do
  if [ -f $AB/hold ]; then for i in 0 1; do pkill -STOP -f "$(procs $i)"; done; sleep 5; continue; fi
  # a run that is not started yet and not done is started in its turn; one whose wrapper ended is done
  left=0
  for i in 0 1; do { [ -z "${pids[$i]}" ] && [ ! -f $AB/done_$i ]; } || alive $i && left=1; done
  [ $left = 0 ] && { echo "both ended $(date +%s)" >> $AB/turns.log; exit 0; }
  if ! { [ -z "${pids[$cur]}" ] && [ ! -f $AB/done_$cur ]; } && ! alive $cur; then cur=$((1 - cur)); continue; fi
  if [ -z "${pids[$cur]}" ] && [ ! -x "${trees[$cur]}/devel/lib/hideseek_hider/hider_node" ]; then cur=$((1 - cur)); sleep 1; continue; fi
  t0=$(date +%s.%N)
  if [ -z "${pids[$cur]}" ]; then start $cur; else pkill -CONT -f "$(procs $cur)"; fi
  end=$(( $(date +%s) + SLICE ))
  while [ $(date +%s) -lt $end ] && alive $cur && [ ! -f $AB/hold ]; do note_finish $cur; sleep 1; done
  note_finish $cur
  pkill -STOP -f "$(procs $cur)"
  t1=$(date +%s.%N)
  echo "${names[$cur]} $t0 $t1" >> $AB/turns.log
  alive $cur || touch $AB/done_$cur
  cur=$((1 - cur))
done
