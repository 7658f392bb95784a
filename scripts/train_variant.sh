#!/usr/bin/env bash
# Trains one variant through train.launch (resuming when RUNS_DIR/<run> holds a checkpoint), then
# ships what it produced: the exported policy, the training log and its learning curve.
# usage: scripts/train_variant.sh VARIANT [SEED=0] [STEPS=2000000] [RUNS_DIR=~/hideseek_runs] [NETWORK=ff] [NAME]
# Seed 0 ships as policies/<variant>.pt; other seeds as policies/<variant>_seed<S>.pt (the spread).
# NETWORK gru trains the recurrent hider and ships policies/<variant>_gru.pt (_gru_seed<S> likewise).
# NAME overrides the run's name (its folder in RUNS_DIR and its policy file).
# PRECISION (environment, default auto) is train.launch's precision; the one the hider chose is
# recorded in policies/policies.yaml.
set -euo pipefail
variant=$1
seed=${2:-0}
steps=${3:-2000000}
runs=$(realpath -m "${4:-$HOME/hideseek_runs}")
network=${5:-ff}
cd "$(dirname "$0")/.."
source scripts/env.sh
name=$variant
[ "$network" = ff ] || name=${name}_$network
[ "$seed" = 0 ] || name=${name}_seed$seed
name=${6:-$name}
case "$name" in
  ''|*/*|.*) echo "train_variant: NAME '$name' must be a plain file name (no '/', not starting with '.')" >&2; exit 2 ;;
esac
run="$runs/$name"
port=$((11700 + seed + $([ "$network" = gru ] && echo 50 || echo 0)))
export ROS_MASTER_URI=http://localhost:$port
mkdir -p "$run"
echo "train_variant: $name (network $network), $steps steps, into $run (log: $run/launch.log)"
roslaunch -p "$port" hideseek_world train.launch variant:="$variant" seed:="$seed" steps:="$steps" \
  network:="$network" precision:="${PRECISION:-auto}" output_dir:="$run" > "$run/launch.log" 2>&1
# roslaunch exits 0 even when the hider dies: ship only a run that trained all its steps.
trained=$(tail -n 1 "$run/training_log.csv" | cut -d, -f2)
if [ "${trained:-0}" -lt "$steps" ]; then
  echo "train_variant: $name stopped at ${trained:-0} of $steps steps (see $run/launch.log); nothing shipped" >&2
  exit 1
fi
devel/lib/hideseek_hider/export_policy "$run/checkpoint.pt" "policies/$name.pt"
# A partial export committed while the run was unfinished is superseded.
rm -f "policies/${name}_partial.pt" "docs/training_log_${name}_partial.csv" "docs/learning_curve_${name}_partial.png"
cp "$run/training_log.csv" "docs/training_log_$name.csv"
/usr/bin/python3 scripts/plot_learning_curve.py "docs/training_log_$name.csv" "docs/learning_curve_$name.png" \
  "$variant, network $network, training seed $seed, $(tail -n 1 "$run/training_log.csv" | cut -d, -f2) steps"
# The precision the hider chose, from its start-up line ("... on cpu in auto: bf16, ..."): the last
# start's, since each resume rewrites launch.log.
precision=$(grep -oE 'PPO, network [a-z]+, on [^ ]+ in [^,]*' "$run/launch.log" | tail -n 1 | grep -oE 'bf16|fp32' | head -n 1)
# Record what was shipped: steps and wall time of training up to the exported checkpoint.
/usr/bin/python3 - "$name" "$seed" "$run/training_log.csv" "docs/training_log_$name.csv" "$variant" "$network" "${precision:-unknown}" <<'PY'
import csv, sys
import yaml
name, seed, log, shipped_log, variant, network, precision = sys.argv[1:]
last = list(csv.DictReader(open(log)))[-1]
path = "policies/policies.yaml"
text = open(path).read()
header = "".join(l for l in text.splitlines(True) if l.startswith("#"))
entries = yaml.safe_load(text) or {}
entries[name] = {"variant": variant, "network": network, "training_seed": int(seed), "steps": int(last["steps"]), "wall_s": round(float(last["wall_s"])),
                 "precision": precision, "log": shipped_log}
with open(path, "w") as f:
    f.write(header + yaml.safe_dump(entries, sort_keys=False))
PY
