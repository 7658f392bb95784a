#!/usr/bin/env bash
# The paper's Table 2 side by side with this project's: every shipped policy (policies/<variant>.pt,
# greedy) and the uniformly random hider on every variant (config/variants), seeds 0..99 through the ROS graph
# (evaluate.launch), beside the paper's figures (config/paper_reference.yaml).
# Usage: scripts/evaluate_all.sh [OUTPUT_DIR]   (default docs/report, as make reproduce). Writes, per evaluation,
# OUTPUT_DIR/evaluations/<variant>_<policy>/{evaluation,episodes}.csv, and Table 2 of them with 95 % intervals
# over their episodes into OUTPUT_DIR/table2_shipped/ (table2.py --evaluations: the generator of Table 2 across seeds).
# A shipped GRU hider (policies/<variant>_gru.pt) is evaluated too, as <variant>_gru_trained, and once more
# with its state zeroed at every step (memoryless:=true, what its memory does) as <variant>_gru_memoryless;
# the GRU hiders against their feed-forward twins across training seeds are the memory claim's (claims.py).
# A run that is not shipped is evaluated into its own folder by hideseek_pipeline evaluate.
# HIDESEEK_VARIANTS="v1 v2" evaluates those variants only and keeps the other evaluations already in
# OUTPUT_DIR/evaluations (made by the same code: use it after training a policy, not after changing the game).
set -euo pipefail
out=$(realpath -m "${1:-$(dirname "$0")/../docs/report}")
cd "$(dirname "$0")/.."
source scripts/env.sh
port=${HIDESEEK_PORT:-11477}
export ROS_MASTER_URI=http://localhost:$port
registered=$(/usr/bin/python3 scripts/hideseek_registry.py variants --paper-order)  # set -e stops on a bad variant file
mapfile -t variants <<< "$registered"
if [ -n "${HIDESEEK_VARIANTS:-}" ]; then
  for v in $HIDESEEK_VARIANTS; do
    [[ " ${variants[*]} " == *" $v "* ]] || { echo "evaluate_all: HIDESEEK_VARIANTS names '$v', which is not one of: ${variants[*]}" >&2; exit 2; }
  done
  read -r -a variants <<< "$HIDESEEK_VARIANTS"
  echo "evaluate_all: evaluating ${variants[*]} only; keeping the other evaluations in $out/evaluations"
else
  rm -rf "$out/evaluations"
fi
mkdir -p "$out/evaluations"
# evaluate VARIANT LABEL POLICY DIR [ARG:=VALUE ...]: one evaluation through evaluate.launch into DIR.
evaluate() {
  local v=$1 label=$2 policy=$3 dir=$4 start
  shift 4
  rm -rf "$dir"
  mkdir -p "$dir"
  start=$(date +%s)
  # roslaunch exits 0 even when a required node dies: the evaluator's files are the verdict.
  roslaunch -p "$port" hideseek_world evaluate.launch variant:="$v" policy:="$policy" output_dir:="$dir" "$@" \
    > "$dir/launch.log" 2>&1 || true
  [ -s "$dir/evaluation.csv" ] || { echo "evaluate_all: $v $label failed, see $dir/launch.log"; exit 1; }
  rm -f "$dir/launch.log"
  echo "evaluate_all: $v $label: $(tail -n 1 "$dir/evaluation.csv" | cut -d, -f4,5 | tr , ' ') ($(($(date +%s) - start)) s)"
}
# The registry ships at most one policy per variant and network (policies/policies.yaml); read once,
# so that set -e stops on a registry that cannot be read.
shipped=$(/usr/bin/python3 scripts/hideseek_registry.py shipped --all)
weights_of() { awk -v v="$1" -v n="$2" '$2 == v && $3 == n { print $4 }' <<< "$shipped"; }
for v in "${variants[@]}"; do
  evaluate "$v" random random "$out/evaluations/${v}_random"
  ff=$(weights_of "$v" ff)
  if [ -n "$ff" ]; then
    evaluate "$v" trained "$ff" "$out/evaluations/${v}_trained"
  else
    echo "evaluate_all: $v: no shipped policy"
  fi
  gru=$(weights_of "$v" gru)
  if [ -n "$gru" ]; then
    evaluate "$v" gru_trained "$gru" "$out/evaluations/${v}_gru_trained"
    evaluate "$v" gru_memoryless "$gru" "$out/evaluations/${v}_gru_memoryless" memoryless:=true
  fi
done
/usr/bin/python3 src/hideseek_analysis/scripts/table2.py --evaluations "$out/evaluations" --out "$out/table2_shipped"
cat "$out/table2_shipped/table2.md"
