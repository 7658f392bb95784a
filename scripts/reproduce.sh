#!/usr/bin/env bash
# The whole reproduction in one command (`make reproduce`): evaluates every shipped policy and the
# random hider on all seven variants (Table 2), analyses every variant that has a shipped policy
# (analyze.launch: 50,000 recorded steps, probes, t-SNE, state statistics, distance over time),
# and gathers it all into one report folder with Table 3, the figures across variants, the
# survival-vs-representation plot and an index.md.
# By default it works from the committed outputs alone, in under a minute: Table 2 across training
# seeds (REPORT_DIR/table2_seeds/: table2.py), the claims table (claims.py) and Figures 4-7
# across seeds (seed_figures.py), from every sweep run's evaluation and per-run analysis. Given
# the weights, --from-scratch first analyses again every sweep run whose weights are on this machine
# and lacks its analysis (hideseek_pipeline sweep analyze), then re-evaluates and re-analyses the shipped
# policies through the ROS graph as described above.
# usage: scripts/reproduce.sh [--from-scratch] [REPORT_DIR=docs/report] [WORK_DIR=~/.ros/hideseek_reproduce]
#   WORK_DIR receives the bags and feature arrays (large; not part of the report).
#   HIDESEEK_ANALYSIS_STEPS overrides the 50,000 steps per variant (a quick look: 5000).
#   HIDESEEK_VARIANTS="v1 v2" evaluates and analyses those variants only (with their GRU hiders) and
#   keeps what REPORT_DIR already holds for the others, then remakes the tables and figures across
#   variants: for a newly trained policy. After a change to the game, run it all.
set -euo pipefail
cd "$(dirname "$0")/.."
scratch=0
if [ "${1:-}" = --from-scratch ]; then scratch=1; shift; fi
report=$(realpath -m "${1:-docs/report}")
work=$(realpath -m "${2:-$HOME/.ros/hideseek_reproduce}")
steps=${HIDESEEK_ANALYSIS_STEPS:-50000}
source scripts/env.sh
port=${HIDESEEK_PORT:-11478}
export ROS_MASTER_URI=http://localhost:$port
start=$(date +%s)
mkdir -p "$report" "$work"
across_seeds() {
  echo "reproduce: across training seeds, from the committed evaluations and analyses"
  /usr/bin/python3 src/hideseek_analysis/scripts/table2.py --out "$report/table2_seeds"
  /usr/bin/python3 src/hideseek_analysis/scripts/claims.py --out "$report"
  /usr/bin/python3 src/hideseek_analysis/scripts/seed_figures.py --out "$report"
}
if [ $scratch = 0 ]; then
  across_seeds
  echo "reproduce: done in $(($(date +%s) - start)) s; open $report/claims.md ($0 --from-scratch also re-evaluates and re-analyses)"
  exit 0
fi
PYTHONPATH=src/hideseek_pipeline/python /usr/bin/python3 -m hideseek_pipeline sweep analyze
echo "reproduce: [1/3] Table 2: every shipped policy and the random hider, seeds 0-99, all variants"
HIDESEEK_PORT=$port scripts/evaluate_all.sh "$report"
# Every shipped policy (policies/policies.yaml): its label (the report's folder), variant and weights.
shipped=$(/usr/bin/python3 scripts/hideseek_registry.py shipped --all)  # set -e stops on an unreadable registry
labels=() bases=() weights=()
while read -r label base _ path; do
  [ -n "$label" ] || continue
  [ -z "${HIDESEEK_VARIANTS:-}" ] || [[ " $HIDESEEK_VARIANTS " == *" $base "* ]] || continue
  labels+=("$label")
  bases+=("$base")
  weights+=("$path")
done <<< "$shipped"
variants=("${labels[@]}")
i=0
for v in "${variants[@]}"; do
  i=$((i + 1))
  echo "reproduce: [2/3] analysis $i of ${#variants[@]}: $v ($steps steps; $(($(date +%s) - start)) s so far)"
  rm -rf "${report:?}/$v"
  # roslaunch exits 0 even when a required node dies: the report's files are the verdict.
  roslaunch -p "$port" hideseek_world analyze.launch variant:="${bases[$((i - 1))]}" policy:="${weights[$((i - 1))]}" steps:="$steps" \
    output_dir:="$work/$v" report_dir:="$report/$v" > "$work/$v.log" 2>&1 || true
  grep -E "^analysis:|report:" "$work/$v.log" | sed 's/^/  /' || true
  [ -s "$report/$v/distance_time.png" ] || { echo "reproduce: the analysis of $v failed, see $work/$v.log" >&2; exit 1; }
done
echo "reproduce: [3/3] tables and figures across variants"
/usr/bin/python3 src/hideseek_analysis/scripts/reproduce_report.py "$report" --paper config/paper_reference.yaml
across_seeds
echo "reproduce: done in $(($(date +%s) - start)) s; open $report/index.md"
