#!/usr/bin/env bash
# Evaluates one recorded run into its folder, docs/runs/<run>/: evaluation.md/.csv and episodes.csv
# (evaluate.launch, seeds 0-99, greedy, fp32, through the ROS graph) and trajectories.png/.md (six
# seeded episodes played in process and drawn from above, seeds 0-5).
# usage: scripts/evaluate_run.sh RUN WEIGHTS      (RUN as in policies/policies.yaml)
set -euo pipefail
name=$1
weights=$(realpath "$2")
cd "$(dirname "$0")/.."
source scripts/env.sh
read -r variant game < <(/usr/bin/python3 -c 'import sys; sys.path.insert(0, "scripts"); import hideseek_registry as r
e = r.runs()[sys.argv[1]]; print(e["variant"], e["game"])' "$name")
docs="docs/runs/$name"
mkdir -p "$docs"
port=${HIDESEEK_PORT:-11479}
export ROS_MASTER_URI=http://localhost:$port
start=$(date +%s)
# roslaunch exits 0 even when a required node dies: the evaluator's files are the verdict.
roslaunch -p "$port" hideseek_world evaluate.launch variant:="$variant" game:="$game" policy:="$weights" \
  output_dir:="$PWD/$docs" > "/tmp/hideseek_evaluate_run_$name.log" 2>&1 || true
[ -s "$docs/evaluation.csv" ] || { echo "evaluate_run: $name failed, see /tmp/hideseek_evaluate_run_$name.log" >&2; exit 1; }
# The table names the run, not the path of its weights on this machine.
sed -i "s#$weights#$name#" "$docs/evaluation.md" "$docs/evaluation.csv"
echo "evaluate_run: $name: $(tail -n 1 "$docs/evaluation.csv" | cut -d, -f4,5 | tr , ' ') (living steps, success; $(($(date +%s) - start)) s)"
if [ "$game" != v2 ]; then
  echo "evaluate_run: $name: no trajectories (play_episodes plays game v2 only)"
  exit 0
fi
map=$(sed -n 's/^map: *\([^ ]*\).*/\1/p' "config/variants/$variant.yaml")
devel/lib/hideseek_hider/play_episodes "$variant" "$weights" 0 6 "/tmp/hideseek_traj_$name.csv" greedy > /dev/null
/usr/bin/python3 src/hideseek_analysis/scripts/plot_trajectories.py "/tmp/hideseek_traj_$name.csv" "config/maps/$map" "$docs/trajectories.png" \
  "$name ($variant, game $game), greedy, seeds 0-5"
echo "evaluate_run: $name: $docs/trajectories.png"
