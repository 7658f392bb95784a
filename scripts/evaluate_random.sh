#!/usr/bin/env bash
# The random hider on every variant, 100 episodes with seeds 0..99: one table in docs/.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh
export ROS_MASTER_URI=http://localhost:11477
out=${1:-docs/random_hider_evaluation.md}
tmp=$(mktemp -d)
{
  echo "| variant | policy | episodes | average living steps | success rate |"
  echo "| --- | --- | --- | --- | --- |"
} > "$out"
for v in basic fasterhider slowerhider stochasticseeker stochasticmaps visibilityreward visibilityreward_faster; do
  mkdir -p "$tmp/$v"
  roslaunch -p 11477 hideseek_world evaluate.launch variant:=$v policy:=random output_dir:="$tmp/$v" >/dev/null 2>&1 || true
  tail -n 1 "$tmp/$v/evaluation.md" >> "$out"
done
cat "$out"
