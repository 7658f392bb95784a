#!/usr/bin/env bash
# Evaluates one recorded run into its folder, docs/runs/<run>/: evaluation.md/.csv and episodes.csv
# (evaluate.launch, seeds 0-99, greedy, fp32, through the ROS graph) and trajectories.png/.md (six
# seeded episodes played in process and drawn from above, seeds 0-5).
# usage: scripts/evaluate_run.sh RUN WEIGHTS      (RUN as in policies/policies.yaml)
#   EVAL_MODES (default "greedy"): the evaluations to run, among greedy and sampled; the sampled
#   one (the policy samples its action) goes to docs/runs/<run>/sampled/.
#   RECORD_ROOT (default this checkout): the checkout whose registry names the run and whose
#   docs/runs/<run>/ receives the files (the sweep evaluates from its worktree into the main checkout).
#   HIDESEEK_PORT (default 11479): the ROS master port; the sampled evaluation uses the next one.
set -euo pipefail
name=$1
weights=$(realpath "$2")
[ -z "${RECORD_ROOT:-}" ] || RECORD_ROOT=$(realpath "$RECORD_ROOT")
cd "$(dirname "$0")/.."
source scripts/env.sh
records=${RECORD_ROOT:-$PWD}
modes=${EVAL_MODES:-greedy}
for mode in $modes; do
  case "$mode" in greedy|sampled) ;; *) echo "evaluate_run: EVAL_MODES: '$mode' is not greedy or sampled" >&2; exit 2 ;; esac
done
read -r variant game < <(/usr/bin/python3 -c 'import sys; sys.path.insert(0, "scripts"); import hideseek_registry as r
e = r.runs(sys.argv[2])[sys.argv[1]]; print(e["variant"], e["game"])' "$name" "$records/policies/policies.yaml")
docs="$records/docs/runs/$name"
mkdir -p "$docs"
port=${HIDESEEK_PORT:-11479}
# A failed attempt must not leave an older evaluation behind that passes for this one.
rm -f "$docs/evaluation.csv" "$docs/sampled/evaluation.csv"
for mode in $modes; do
  out=$docs
  greedy=true
  if [ "$mode" = sampled ]; then out=$docs/sampled; greedy=false; port=$((port + 1)); fi
  mkdir -p "$out"
  export ROS_MASTER_URI=http://localhost:$port
  start=$(date +%s)
  log="/tmp/hideseek_evaluate_run_${name}_$mode.log"
  # roslaunch exits 0 even when a required node dies: the evaluator's files are the verdict.
  roslaunch -p "$port" hideseek_world evaluate.launch variant:="$variant" game:="$game" policy:="$weights" \
    greedy:="$greedy" output_dir:="$out" > "$log" 2>&1 || true
  [ -s "$out/evaluation.csv" ] || { echo "evaluate_run: $name ($mode) failed, see $log" >&2; exit 1; }
  # The table names the run, not the path of its weights on this machine.
  sed -i "s#$weights#$name#" "$out/evaluation.md" "$out/evaluation.csv"
  echo "evaluate_run: $name ($mode): $(tail -n 1 "$out/evaluation.csv" | cut -d, -f4,5 | tr , ' ') (living steps, success; $(($(date +%s) - start)) s)"
done
map=$(devel/lib/hideseek_game/resolve --game "$game" "$variant" map_file)
devel/lib/hideseek_play/play_episodes --game "$game" "$variant" "$weights" 0 6 "/tmp/hideseek_traj_$name.csv" greedy > /dev/null
/usr/bin/python3 src/hideseek_analysis/scripts/plot_trajectories.py "/tmp/hideseek_traj_$name.csv" "$map" "$docs/trajectories.png" \
  "$name ($variant, game $game), greedy, seeds 0-5"
echo "evaluate_run: $name: $docs/trajectories.png"
