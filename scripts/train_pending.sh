#!/usr/bin/env bash
# Trains, one after the other, every run of the paper's set that has no shipped policy yet: the
# feed-forward hider of each variant (training seed 0), basic with training seeds 1 and 2 (the
# spread), basic's seed-0 run carried on to the full 2M steps (basic_seed0_2m: the shipped basic
# policy is an earlier checkpoint of that run, and the GRU comparison needs the feed-forward hider
# at the GRU's seed and steps), and the GRU hider on basic, slowerhider and stochasticmaps. Each
# run goes through scripts/train_variant.sh, so a run stopped part way (a session ended, a machine
# rebooted) resumes from RUNS_DIR/<run>/checkpoint.pt when this script is started again, and a finished
# one ships its policy, log and learning curve. Runs whose policy exists are skipped. After the
# feed-forward hiders, the GRU runs alternate with basic's other seeds, basic's GRU run first: its
# feed-forward twin (basic_seed0_2m) exists, so it alone already answers the memory question once.
# usage: scripts/train_pending.sh [RUNS_DIR=~/hideseek_runs] [STEPS=2000000]
#   HIDESEEK_LIST=1 only prints what is pending.
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-$HOME/hideseek_runs}
steps=${2:-2000000}
# variant seed network policy-file
plan=(
  "fasterhider 0 ff fasterhider"
  "stochasticseeker 0 ff stochasticseeker"
  "stochasticmaps 0 ff stochasticmaps"
  "visibilityreward 0 ff visibilityreward"
  "basic 0 ff basic_seed0_2m"
  "visibilityreward_faster 0 ff visibilityreward_faster"
  "basic 0 gru basic_gru"
  "basic 1 ff basic_seed1"
  "slowerhider 0 gru slowerhider_gru"
  "basic 2 ff basic_seed2"
  "stochasticmaps 0 gru stochasticmaps_gru"
)
pending=()
for entry in "${plan[@]}"; do
  read -r variant seed network name <<< "$entry"
  [ -f "policies/$name.pt" ] || pending+=("$entry")
done
echo "train_pending: ${#pending[@]} of ${#plan[@]} runs pending:"
for entry in "${pending[@]}"; do
  read -r variant seed network name <<< "$entry"
  note=""
  if [ -f "$runs/$name/checkpoint.pt" ]; then
    # The checkpoint's own step count: the log may run past it (rows a resume drops).
    if info=$(devel/lib/hideseek_hider/export_policy --info "$runs/$name/checkpoint.pt" 2>/dev/null); then
      note=" (resumes from $runs/$name/checkpoint.pt, at $(cut -d' ' -f3 <<< "$info") steps)"
    else
      note=" (has $runs/$name/checkpoint.pt, which export_policy --info cannot read: is the workspace built?)"
    fi
  fi
  echo "  $name: $variant, training seed $seed, network $network$note"
done
[ -z "${HIDESEEK_LIST:-}" ] || exit 0
for entry in "${pending[@]}"; do
  read -r variant seed network name <<< "$entry"
  echo "train_pending: $name, started $(date '+%F %T')"
  scripts/train_variant.sh "$variant" "$seed" "$steps" "$runs" "$network" "$name"
done
echo "train_pending: nothing left to train"
