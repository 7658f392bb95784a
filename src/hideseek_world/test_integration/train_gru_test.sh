#!/usr/bin/env bash
# Integration test of the recurrent hider (network gru) through the ROS graph: a short
# train.launch network:=gru run finishes and writes a GRU checkpoint (export_policy says so);
# relaunched on that folder with network:=ff it is refused with a message naming both networks,
# with network:=gru it resumes from the checkpoint's step, and with network:=auto (the default)
# it resumes as gru too; analyze.launch refuses the GRU policy before it records anything.
# Writes an xunit result. usage: train_gru_test.sh XUNIT_OUTPUT
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
here=$(cd "$(dirname "$0")" && pwd)
run=$(mktemp -d /tmp/hideseek_gru_test.XXXXXX)
port=$((11800 + RANDOM % 100))
export ROS_MASTER_URI=http://localhost:$port
failures=()
train() {  # train NETWORK STEPS: runs to the end (the hider is required) with a time limit
  timeout -s INT 240 roslaunch -p "$port" hideseek_world train.launch variant:=tiny_basic num_arenas:=4 \
    variant_config:="$here/data/tiny_basic.yaml" output_dir:="$run" checkpoint_interval:=0.01 \
    network:="$1" steps:="$2" > "$run/launch_$1_$2.log" 2>&1
}

train gru 512
grep -q "network gru" "$run/launch_gru_512.log" || failures+=("the hider did not say it trains network gru")
[ -s "$run/checkpoint.pt" ] || failures+=("no checkpoint after a 512-step GRU run")
steps=$(tail -n 1 "$run/training_log.csv" 2>/dev/null | cut -d, -f2)
[ "${steps:-0}" -ge 512 ] || failures+=("the GRU run logged ${steps:-no} steps, wanted 512")
exported=$(rosrun hideseek_hider export_policy "$run/checkpoint.pt" "$run/policy.pt" 2>&1)
[[ "$exported" == *"network gru"* ]] || failures+=("export_policy does not see a GRU checkpoint: $exported")

train ff 1024
grep -q "holds a recurrent (GRU) hider (network gru), but network ff was asked" "$run/launch_ff_1024.log" ||
  failures+=("network:=ff on a GRU checkpoint was not refused with a clear message")

train gru 1024
grep -q "resumed at step 512" "$run/launch_gru_1024.log" || failures+=("network:=gru did not resume the GRU run at step 512")
final=$(tail -n 1 "$run/training_log.csv" | cut -d, -f2)
[ "${final:-0}" -ge 1024 ] || failures+=("the resumed GRU run ended at ${final:-no} steps, wanted 1024")

train auto 1536
grep -q "network gru" "$run/launch_auto_1536.log" && grep -q "resumed at step 1024" "$run/launch_auto_1536.log" ||
  failures+=("network:=auto did not resume the GRU run as gru at step 1024")

timeout -s INT 120 roslaunch -p "$port" hideseek_world analyze.launch variant:=tiny_basic \
  variant_config:="$here/data/tiny_basic.yaml" policy:="$run/policy.pt" steps:=160 num_arenas:=1 \
  output_dir:="$run/analysis" > "$run/analyze.log" 2>&1
grep -F "[FATAL]" "$run/analyze.log" | grep -q "holds a recurrent (GRU) hider" ||
  failures+=("analyze.launch did not refuse the GRU policy with a clear message")
[ ! -e "$run/analysis/rollout.bag" ] || failures+=("analyze.launch recorded a bag for a GRU policy it cannot analyse")

write_xunit "$out" train_gru GruTrainsResumesAndRefusesTheOtherNetwork "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
rm -rf "$run"
[ ${#failures[@]} -eq 0 ]
