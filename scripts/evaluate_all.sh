#!/usr/bin/env bash
# The paper's Table 2 side by side with this project's: every shipped policy (policies/<variant>.pt,
# greedy) and the uniformly random hider on all seven variants, seeds 0..99 through the ROS graph
# (evaluate.launch), beside the paper's figures (config/paper_reference.yaml).
# Usage: scripts/evaluate_all.sh [OUTPUT_DIR]   (default docs/). Writes table2.md, table2.csv
# and, per evaluation, OUTPUT_DIR/evaluations/<variant>_<policy>/{evaluation,episodes}.csv.
# A shipped GRU hider (policies/<variant>_gru.pt) is evaluated too, as <variant>_gru_trained, and so is
# every other run of the variant listed in policies/policies.yaml (another training seed, a longer run):
# policies/<run>.pt as <run>_trained.
# HIDESEEK_VARIANTS="v1 v2" evaluates those variants only and keeps the other evaluations already in
# OUTPUT_DIR/evaluations (made by the same code: use it after training a policy, not after changing the game).
set -euo pipefail
out=$(realpath -m "${1:-$(dirname "$0")/../docs}")
cd "$(dirname "$0")/.."
source scripts/env.sh
port=${HIDESEEK_PORT:-11477}
export ROS_MASTER_URI=http://localhost:$port
variants=(basic fasterhider visibilityreward_faster stochasticseeker stochasticmaps visibilityreward slowerhider)
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
# The variant's other runs in policies.yaml (not <variant> or <variant>_gru, evaluated above them).
other_runs() {
  /usr/bin/python3 - "$1" <<'PY'
import os, sys, yaml
v = sys.argv[1]
entries = yaml.safe_load(open("policies/policies.yaml")) or {}
for name, e in entries.items():
    if (e or {}).get("variant") == v and name not in (v, v + "_gru") and os.path.exists("policies/%s.pt" % name):
        print(name)
PY
}
for v in "${variants[@]}"; do
  policies_of_v=(random trained gru_trained)
  for run in $(other_runs "$v"); do policies_of_v+=("${run}_trained"); done
  for p in "${policies_of_v[@]}"; do
    policy=random
    if [ "$p" = trained ]; then
      policy="$PWD/policies/$v.pt"
      [ -f "$policy" ] || { echo "evaluate_all: $v: no shipped policy"; continue; }
    elif [ "$p" = gru_trained ]; then
      policy="$PWD/policies/${v}_gru.pt"
      [ -f "$policy" ] || continue
    elif [ "$p" != random ]; then
      policy="$PWD/policies/${p%_trained}.pt"
    fi
    dir="$out/evaluations/${v}_$p"
    [[ "$p" == random || "$p" == trained || "$p" == gru_trained ]] || dir="$out/evaluations/$p"
    rm -rf "$dir"
    mkdir -p "$dir"
    start=$(date +%s)
    # roslaunch exits 0 even when a required node dies: the evaluator's files are the verdict.
    roslaunch -p "$port" hideseek_world evaluate.launch variant:="$v" policy:="$policy" output_dir:="$dir" \
      > "$dir/launch.log" 2>&1 || true
    [ -s "$dir/evaluation.csv" ] || { echo "evaluate_all: $v $p failed, see $dir/launch.log"; exit 1; }
    rm -f "$dir/launch.log"
    echo "evaluate_all: $v $p: $(tail -n 1 "$dir/evaluation.csv" | cut -d, -f4,5 | tr , ' ') ($(($(date +%s) - start)) s)"
  done
done
/usr/bin/python3 scripts/table2.py config/paper_reference.yaml "$out/evaluations" "$out/table2" policies
cat "$out/table2.md"
