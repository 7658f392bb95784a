#!/usr/bin/env bash
# Integration test of the recurrent hider (network gru) through the ROS graph: a short
# train.launch network:=gru run finishes and writes a GRU checkpoint (export_policy says so);
# relaunched on that folder with network:=ff it is refused with a message naming both networks,
# with network:=gru it resumes from the checkpoint's step, and with network:=auto (the default)
# it resumes as gru too. analyze.launch then analyses the GRU policy: every recorded image matches
# its re-rendering from the recorded poses, and the probes read the GRU state as well as the features;
# with precision:=bf16 (its state could not be replayed) it is refused before recording.
# Writes an xunit result. usage: train_gru_test.sh XUNIT_OUTPUT
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
here=$(cd "$(dirname "$0")" && pwd)
run=$(mktemp -d /tmp/hideseek_gru_test.XXXXXX)
port=$((13400 + RANDOM % 50))  # its own range: evaluate_test.sh has 11800-11899
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
# --info (what a checkpoint holds): variant, network, the checkpoint's steps, wall s, episodes.
info_variant="" info_network="" info_steps="" info_wall="" info_episodes=""
read -r info_variant info_network info_steps info_wall info_episodes < <(rosrun hideseek_hider export_policy --info "$run/checkpoint.pt")
[ "$info_variant $info_network $info_steps" = "tiny_basic gru $steps" ] && [ "${info_episodes:-0}" -gt 0 ] ||
  failures+=("export_policy --info says '$info_variant $info_network $info_steps $info_wall $info_episodes', wanted tiny_basic gru $steps with episodes")

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
  variant_config:="$here/data/tiny_basic.yaml" policy:="$run/policy.pt" steps:=160 num_arenas:=1 precision:=bf16 \
  output_dir:="$run/analysis_bf16" > "$run/analyze_bf16.log" 2>&1
grep -F "[FATAL]" "$run/analyze_bf16.log" | grep "a GRU policy is analysed in fp32 only" > /dev/null ||
  failures+=("analyze.launch precision:=bf16 did not refuse the GRU policy with a clear message")
[ ! -e "$run/analysis_bf16/rollout.bag" ] || failures+=("analyze.launch recorded a bf16 GRU rollout it cannot replay")
timeout -s INT 300 roslaunch -p "$port" hideseek_world analyze.launch variant:=tiny_basic \
  variant_config:="$here/data/tiny_basic.yaml" policy:="$run/policy.pt" steps:=1600 num_arenas:=4 image_every:=2 \
  tsne_samples:=200 output_dir:="$run/analysis" > "$run/analyze.log" 2>&1
grep -q "GRU states replayed; 800 recorded images match their re-rendering" "$run/analyze.log" ||
  failures+=("the analysis did not replay the GRU states of 800 images: $(grep -m3 -E 'analysis:|FATAL|ERROR' "$run/analyze.log" | tr '\n' ' ')")
for f in probes.csv distance_time.png tsne_H.png; do
  [ -s "$run/analysis/report/$f" ] || failures+=("no $f in the GRU policy's report")
done
for label in S H; do
  for network in trained random_init; do
    tr -d '\r' < "$run/analysis/report/probes.csv" 2>/dev/null | grep -q "^$label,$network,.*,gru_state," ||
      failures+=("probes.csv has no $label probe of the $network network's GRU state")
  done
done
write_xunit "$out" train_gru GruTrainsResumesRefusesTheOtherNetworkAndIsAnalysed "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
[ ${#failures[@]} -eq 0 ] && rm -rf "$run"  # kept for a look when something failed
[ ${#failures[@]} -eq 0 ]
