#!/usr/bin/env bash
# Integration test of training (issue 4): a short train.launch run with small images writes a
# checkpoint and a log; the whole graph is then killed with SIGKILL and started again with the
# same output folder, and training resumes from the checkpoint's step instead of starting over.
# Then Ctrl-C: a run without a periodic checkpoint yet, stopped by SIGINT to roslaunch, writes the
# checkpoint of its last update as it stops, and the next start resumes there, dropping no log row.
# Writes an xunit result. usage: train_resume_test.sh XUNIT_OUTPUT
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
here=$(cd "$(dirname "$0")" && pwd)
run=$(mktemp -d /tmp/hideseek_train_test.XXXXXX)
port=$((11600 + RANDOM % 200))
export ROS_MASTER_URI=http://localhost:$port
failures=()
launch() {  # launch STEPS [OUTPUT_DIR [CHECKPOINT_INTERVAL]]
  local dir=${2:-$run}
  setsid roslaunch -p "$port" hideseek_world train.launch variant:=tiny_basic num_arenas:=4 \
    variant_config:="$here/data/tiny_basic.yaml" output_dir:="$dir" checkpoint_interval:="${3:-0.01}" steps:="$1" \
    > "$dir/launch_$1.log" 2>&1 &
  echo $!
}
wait_for() {  # wait_for SECONDS COMMAND...
  local end=$((SECONDS + $1)); shift
  until "$@"; do [ $SECONDS -ge $end ] && return 1; sleep 0.5; done
}
log_lines() { grep -c . "$run/training_log.csv" 2>/dev/null || echo 0; }
has_rows() { local n; n=$(grep -c . "$1" 2>/dev/null); [ "${n:-0}" -ge "$2" ]; }  # has_rows FILE LINES
# roslaunch starts every node in a session of its own, so killing roslaunch's process group
# leaves the nodes running: collect the whole tree first, then SIGKILL all of it at once.
tree() { local p; for p in $(pgrep -P "$1"); do tree "$p"; done; echo "$1"; }
kill_graph() {
  local pids
  pids=$(tree "$1")
  kill -KILL $pids 2>/dev/null
  wait_for 10 bash -c "! kill -0 $(echo $pids) 2>/dev/null"
}

pid=$(launch 100000)
if ! wait_for 120 test -s "$run/checkpoint.pt"; then failures+=("no checkpoint after the first updates"); fi
wait_for 60 has_rows "$run/training_log.csv" 4
kill_graph "$pid"
rows_before=$(($(log_lines) - 1))
steps_before=$(tail -n 1 "$run/training_log.csv" | cut -d, -f2)
[ "$rows_before" -ge 1 ] || failures+=("no training log rows before the kill")

target=$((steps_before + 512))
pid=$(launch "$target")
wait_for 180 bash -c "! kill -0 $pid 2>/dev/null" || { kill_graph "$pid"; failures+=("the resumed run did not finish"); }
grep -q "resumed at step" "$run/launch_$target.log" || failures+=("the second run did not resume")
resumed_at=$(sed -n 's/.*resumed at step \([0-9]*\).*/\1/p' "$run/launch_$target.log" | head -n 1)
[ -n "$resumed_at" ] && [ "$resumed_at" -ge "$((steps_before - 4 * 64))" ] && [ "$resumed_at" -le "$steps_before" ] ||
  failures+=("resumed at step '${resumed_at}', the killed run had logged ${steps_before}")
# The resumed log continues the killed one: update numbers 1, 2, 3, ... once each, and steps,
# wall time and episodes never go back.
bad_rows=$(awk -F, 'NR > 1 && ($1 != NR - 1 || (NR > 2 && ($2 <= s || $3 < w || $5 < e))) { print NR } { s = $2; w = $3; e = $5 }' \
  "$run/training_log.csv" | head -n 3 | tr '\n' ' ')
[ -z "$bad_rows" ] || failures+=("training_log.csv repeats or goes back at rows: $bad_rows")
final_steps=$(tail -n 1 "$run/training_log.csv" | cut -d, -f2)
[ "$final_steps" -ge "$target" ] || failures+=("final log row at ${final_steps} steps, wanted ${target}")

echo "steps before kill: $steps_before, resumed at: ${resumed_at:-none}, final: $final_steps"

# Ctrl-C: no periodic checkpoint in the hour (checkpoint_interval 3600 s), so only the stop writes one.
stopped=$run/interrupted
mkdir -p "$stopped"
pid=$(launch 100000 "$stopped" 3600)
wait_for 120 has_rows "$stopped/training_log.csv" 4 ||
  failures+=("interrupted run: fewer than 3 updates logged")
[ -e "$stopped/checkpoint.pt" ] && failures+=("interrupted run: a checkpoint before the stop, with checkpoint_interval 3600")
kill -INT "$pid"  # what Ctrl-C sends roslaunch, which passes it to every node
wait_for 60 bash -c "! kill -0 $pid 2>/dev/null" || { kill_graph "$pid"; failures+=("roslaunch did not stop on SIGINT"); }
logged=$(tail -n 1 "$stopped/training_log.csv" | cut -d, -f2)
test -s "$stopped/checkpoint.pt" || failures+=("Ctrl-C at ${logged} steps wrote no checkpoint")
grep -q "stopped at $logged of [0-9]* steps" "$stopped/launch_100000.log" ||
  failures+=("the stopped run does not say it kept step ${logged}: $(grep -o 'stopped at.*' "$stopped/launch_100000.log")")
target=$((logged + 512))
pid=$(launch "$target" "$stopped" 3600)
wait_for 180 bash -c "! kill -0 $pid 2>/dev/null" || { kill_graph "$pid"; failures+=("the run resumed after Ctrl-C did not finish"); }
grep -q "resumed at step $logged of" "$stopped/launch_$target.log" ||
  failures+=("after Ctrl-C at ${logged} steps: $(grep -o '\(resumed\|started\) at step [0-9]*' "$stopped/launch_$target.log")")
grep -q "dropped .* log rows" "$stopped/launch_$target.log" && failures+=("after Ctrl-C, log rows were dropped")
echo "interrupted at: $logged, then: $(grep -o 'resumed at step [0-9]*' "$stopped/launch_$target.log")"

write_xunit "$out" train_resume KilledTrainingResumesFromItsCheckpoint "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
rm -rf "$run"
[ ${#failures[@]} -eq 0 ]
