#!/usr/bin/env bash
# Integration tests of analyze.launch and analyze_bag. usage: analyze_test.sh XUNIT_OUTPUT
# 1. A small analysis of the shipped basic policy (the default, policy:=shipped; 4 arenas, 800 decisions, an image every 4th)
#    records every decision into its bag and writes every file of the report.
# 2. The same bag with one decision filtered out is reported as missing that step, and nothing
#    is analysed; analysed as another variant than its policy's, it is warned about first; a
#    variant file of one's own is analysed under its name, and refused under another.
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
root="$(cd "$(dirname "$0")/.." && pwd)"
dir=$(mktemp -d /tmp/hideseek_analyze_test.XXXXXX)
port=$((11900 + RANDOM % 100))
failures=()
timeout 600 roslaunch -p "$port" hideseek_world analyze.launch variant:=basic \
  steps:=3200 num_arenas:=4 image_every:=4 tsne_samples:=200 output_dir:="$dir/work" report_dir:="$dir/report" \
  > "$dir/launch.log" 2>&1
grep -q "800 decisions of 4 arenas (3200 steps), 800 images, no step missing" "$dir/launch.log" ||
  failures+=("the analysis did not read 800 complete decisions: $(grep -m3 -E 'analysis|ERROR|FATAL' "$dir/launch.log" | tr '\n' ' ')")
messages=$(rosbag info "$dir/work/rollout.bag" 2>/dev/null | grep -E "^ *topics:.*/world/steps" | awk '{print $3}')
[ "$messages" = "800" ] || failures+=("the bag holds '$messages' world/steps messages, not 800")
for f in probes.csv probes.md tsne_S.png tsne_H.png state_frequencies.csv state_frequencies.md state_frequencies.png \
         transitions.csv transitions.md transitions.png distance_time.png; do
  [ -s "$dir/report/$f" ] || failures+=("no $f in the report")
done
[ "$(head -n 1 "$dir/report/probes.csv" 2>/dev/null | cut -d, -f1-3)" = "label,network,test_accuracy" ] ||
  failures+=("probes.csv header differs")
write_xunit "$out" analyze AnalyzeLaunchRecordsEveryStepAndWritesEveryFile "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
first_failed=${#failures[@]}

failures=()
if [ -s "$dir/work/rollout.bag" ]; then
  rosbag filter "$dir/work/rollout.bag" "$dir/gap.bag" "topic != '/world/steps' or m.decision != 100" > /dev/null 2>&1
  "$(catkin_find hideseek_analysis analyze_bag --first-only)" basic "$(/usr/bin/python3 "$root/../hideseek_analysis/scripts/hideseek_registry.py" shipped basic)" "$dir/gap.bag" \
    "$dir/gap" > "$dir/gap.log" 2>&1
  status=$?
  [ "$status" -eq 1 ] || failures+=("analyze_bag exited $status on a bag with a missing step")
  grep -q "decisions 100 to 100 are missing (1 decision steps of 4 arenas); nothing was analysed" "$dir/gap.log" ||
    failures+=("the missing step was not reported: $(head -c 300 "$dir/gap.log")")
  [ ! -e "$dir/gap/report/probes.csv" ] || failures+=("a report was written past the missing step")
  # A policy of another variant than the one analysed: named before the bag is read.
  "$(catkin_find hideseek_analysis analyze_bag --first-only)" fasterhider "$(/usr/bin/python3 "$root/../hideseek_analysis/scripts/hideseek_registry.py" shipped basic)" "$dir/gap.bag" \
    "$dir/other" > "$dir/other.log" 2>&1
  grep -q "was trained on variant 'basic', game v3; this analysis is of variant 'fasterhider', game v3" "$dir/other.log" ||
    failures+=("no warning for a basic policy analysed as fasterhider: $(head -c 300 "$dir/other.log")")
  # A variant file of one's own (basic's, renamed): selected under its own name; a misnamed one is refused.
  sed 's/^variant: basic$/variant: mine/' "$root/../../config/variants/basic.yaml" > "$dir/mine.yaml"
  "$(catkin_find hideseek_analysis analyze_bag --first-only)" --variant-config "$dir/mine.yaml" mine \
    "$(/usr/bin/python3 "$root/../hideseek_analysis/scripts/hideseek_registry.py" shipped basic)" "$dir/gap.bag" \
    "$dir/mine" > "$dir/mine.log" 2>&1
  { grep -q "this analysis is of variant 'mine', game v3" "$dir/mine.log" &&
    grep -q "decisions 100 to 100 are missing" "$dir/mine.log"; } ||
    failures+=("--variant-config was not read as variant 'mine' to the missing step: $(head -c 300 "$dir/mine.log")")
  "$(catkin_find hideseek_analysis analyze_bag --first-only)" --variant-config "$dir/mine.yaml" yours \
    "$(/usr/bin/python3 "$root/../hideseek_analysis/scripts/hideseek_registry.py" shipped basic)" "$dir/gap.bag" \
    "$dir/yours" > "$dir/yours.log" 2>&1
  status=$?
  { [ "$status" -eq 1 ] && grep -q "is 'mine', but the file was given as variant 'yours'" "$dir/yours.log"; } ||
    failures+=("a variant file given under another name was not refused (exit $status): $(head -c 300 "$dir/yours.log")")
else
  failures+=("no bag to cut a step out of")
fi
write_xunit "${out%.xml}-missing_step.xml" analyze ABagWithAMissingStepIsReportedNotAnalysed "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
[ "$first_failed" -eq 0 ] && [ ${#failures[@]} -eq 0 ] && rm -rf "$dir"
[ "$first_failed" -eq 0 ] && [ ${#failures[@]} -eq 0 ]
