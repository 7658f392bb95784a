#!/usr/bin/env bash
# Trains one run through train.launch (resuming when RUNS_DIR/<run> holds a checkpoint) and records
# it: the exported weights go to RUNS_DIR/<run>/policy.pt (outside the repository), the training
# log, learning curve, evaluation and trajectories to docs/runs/<run>/, and an entry to the run registry
# (policies/policies.yaml: variant, network, game, training seed, steps, wall time, precision and
# the commit it trained with). SHIP=1 also ships it as the variant's policy
# (scripts/hideseek_registry.py ship); otherwise shipping is a separate, deliberate step.
# usage: scripts/train_variant.sh VARIANT [SEED=0] [STEPS=2000000] [RUNS_DIR=~/hideseek_runs] [NETWORK=ff] [NAME]
#   NAME defaults to <variant>_seed<S> (<variant>_gru_seed<S> for the GRU).
#   GAME (environment; default: config/games.yaml's) is the game (train.launch's game); PRECISION (default auto) its
#   precision; the one the hider chose is recorded. ROS_PORT (default 11700 + seed, + 50 for the
#   GRU) is the run's ROS master port: set it to train two runs of one seed at once; its
#   evaluation uses ROS_PORT + 1000 (HIDESEEK_PORT overrides). NUM_ARENAS and PPO_CONFIG (default:
#   train.launch's, 16 and config/ppo.yaml) set the rollout; when set they are part of the command
#   the registry records. HIDER_THREADS (default train.launch's, 2) is the learner's intra-op
#   threads (1 when two runs share two cores). RECORD_ROOT (default this checkout) is the checkout
#   that receives docs/runs/<run>/ and the registry entry: the sweep trains from its own pinned
#   worktree and records into the main checkout. PAUSED_FILE (default none) holds the seconds the
#   run was held paused (the sweep writes it), read when the run is recorded: they are recorded as
#   paused_s and left out of wall_s. EVAL_MODES (default greedy) is
#   passed to evaluate_run.sh.
set -euo pipefail
variant=$1
seed=${2:-0}
steps=${3:-2000000}
runs=$(realpath -m "${4:-$HOME/hideseek_runs}")
network=${5:-ff}
game=${GAME:-}  # none: the default game (config/games.yaml), resolved below
[ -z "${PPO_CONFIG:-}" ] || PPO_CONFIG=$(realpath -m "$PPO_CONFIG")  # as RUNS_DIR: from where it was called
[ -z "${RECORD_ROOT:-}" ] || RECORD_ROOT=$(realpath "$RECORD_ROOT")
cd "$(dirname "$0")/.."
source scripts/env.sh
records=${RECORD_ROOT:-$PWD}
[ -n "$game" ] || game=$(devel/lib/hideseek_game/resolve "$variant" game) || { echo "train_variant: cannot resolve the default game" >&2; exit 2; }
[ -f "$records/policies/policies.yaml" ] || { echo "train_variant: RECORD_ROOT: no policies/policies.yaml in $records" >&2; exit 2; }
registry=(/usr/bin/python3 scripts/hideseek_registry.py --registry "$records/policies/policies.yaml")
name=$variant
[ "$network" = ff ] || name=${name}_$network
name=${6:-${name}_seed$seed}
case "$name" in
  ''|*/*|.*) echo "train_variant: NAME '$name' must be a plain file name (no '/', not starting with '.')" >&2; exit 2 ;;
esac
# grep reads the whole list (no -q): a grep that stopped at the first match would break the
# writer's pipe, and pipefail would then report a known variant as unknown.
/usr/bin/python3 scripts/hideseek_registry.py variants | grep -x "$variant" > /dev/null \
  || { echo "train_variant: no variant '$variant' in config/variants" >&2; exit 2; }
# A run keeps its game: a name the registry records under another game is not trained (or
# resumed) under this one; the checkpoint refuses it too (training_run.cpp).
recorded_game=$(/usr/bin/python3 -c 'import sys; sys.path.insert(0, "scripts"); import hideseek_registry as r
e = r.runs(sys.argv[2]).get(sys.argv[1]); print(e["game"] if e else "")' "$name" "$records/policies/policies.yaml")
if [ -n "$recorded_game" ] && [ "$recorded_game" != "$game" ]; then
  echo "train_variant: $name is recorded as a run of game $recorded_game (policies/policies.yaml); this is game $game: name the run otherwise" >&2
  exit 2
fi
run="$runs/$name"
port=${ROS_PORT:-$((11700 + seed + $([ "$network" = gru ] && echo 50 || echo 0)))}
export ROS_MASTER_URI=http://localhost:$port
mkdir -p "$run"
# The commit the run trained with: the one it started at; a resume at another commit is noted.
commit=$(git describe --always --dirty --abbrev=12 2>/dev/null || echo unknown)
if [ ! -s "$run/commit" ]; then
  echo "$commit" > "$run/commit"
elif [ "$(head -n 1 "$run/commit")" != "$commit" ] && ! grep -qx "resumed at $commit" "$run/commit"; then
  echo "resumed at $commit" >> "$run/commit"
  echo "train_variant: $name started at commit $(head -n 1 "$run/commit"), resumes at $commit"
fi
rollout_args=()
if [ -n "${NUM_ARENAS:-}" ]; then
  [ "$NUM_ARENAS" -ge 1 ] 2> /dev/null || { echo "train_variant: NUM_ARENAS must be a whole number >= 1, got '$NUM_ARENAS'" >&2; exit 2; }
  rollout_args+=(num_arenas:="$NUM_ARENAS")
fi
if [ -n "${HIDER_THREADS:-}" ]; then
  [ "$HIDER_THREADS" -ge 1 ] 2> /dev/null || { echo "train_variant: HIDER_THREADS must be a whole number >= 1, got '$HIDER_THREADS'" >&2; exit 2; }
  rollout_args+=(hider_threads:="$HIDER_THREADS")
fi
if [ -n "${PPO_CONFIG:-}" ]; then
  [ -f "$PPO_CONFIG" ] || { echo "train_variant: PPO_CONFIG: no file $PPO_CONFIG" >&2; exit 2; }
  rollout_args+=(ppo_config:="$PPO_CONFIG")
fi
# What reproduces the run: the rollout's settings when they are not the defaults.
env_prefix=""
[ -z "${GAME:-}" ] || env_prefix+="GAME=$GAME "
[ -z "${PRECISION:-}" ] || env_prefix+="PRECISION=$PRECISION "
[ -z "${NUM_ARENAS:-}" ] || env_prefix+="NUM_ARENAS=$NUM_ARENAS "
[ -z "${HIDER_THREADS:-}" ] || env_prefix+="HIDER_THREADS=$HIDER_THREADS "
[ -z "${PPO_CONFIG:-}" ] || env_prefix+="PPO_CONFIG=$(realpath -m --relative-to=. "$PPO_CONFIG") "
echo "train_variant: $name (variant $variant, network $network, game $game, training seed $seed), $steps steps, into $run (log: $run/launch.log)"
roslaunch -p "$port" hideseek_world train.launch variant:="$variant" game:="$game" seed:="$seed" steps:="$steps" \
  "${rollout_args[@]}" network:="$network" precision:="${PRECISION:-auto}" output_dir:="$run" > "$run/launch.log" 2>&1
# roslaunch exits 0 even when the hider dies: record only a run that trained all its steps.
trained=$(tail -n 1 "$run/training_log.csv" | cut -d, -f2)
if [ "${trained:-0}" -lt "$steps" ]; then
  echo "train_variant: $name stopped at ${trained:-0} of $steps steps (see $run/launch.log); nothing recorded" >&2
  exit 1
fi
devel/lib/hideseek_hider/export_policy "$run/checkpoint.pt" "$run/policy.pt"
docs="$records/docs/runs/$name"
mkdir -p "$docs"
cp "$run/training_log.csv" "$docs/training_log.csv"
/usr/bin/python3 src/hideseek_analysis/scripts/plot_learning_curve.py "$docs/training_log.csv" "$docs/learning_curve.png" \
  "$variant, network $network, game $game, training seed $seed, $trained steps"
# The precision the hider chose, from its start-up line ("... on cpu in auto: bf16, ..."): the last
# start's, since each resume rewrites launch.log.
precision=$(grep -oE 'PPO, network [a-z]+, on [^ ]+ in [^,]*' "$run/launch.log" | tail -n 1 | grep -oE 'bf16|fp32' | head -n 1)
wall=$(tail -n 1 "$run/training_log.csv" | cut -d, -f3)
paused=0
[ -z "${PAUSED_FILE:-}" ] || [ ! -s "$PAUSED_FILE" ] || paused=$(head -n 1 "$PAUSED_FILE")
paused=${paused%.*}
[ "$paused" -ge 0 ] 2> /dev/null || { echo "train_variant: $PAUSED_FILE must hold a number of seconds >= 0, holds '$paused'" >&2; exit 2; }
# paused_s= (empty) removes a paused time left in the entry by an earlier training of this run.
paused_field=(paused_s=)
[ "$paused" = 0 ] || paused_field=(paused_s="$paused")
commits=$(paste -sd ';' "$run/commit" | sed 's/;/; /g')
"${registry[@]}" record "$name" variant="$variant" network="$network" game="$game" \
  training_seed="$seed" steps="$trained" wall_s="$((${wall%.*} - paused))" "${paused_field[@]}" precision="${precision:-unknown}" commit="$commits" \
  log="docs/runs/$name/training_log.csv" curve="docs/runs/$name/learning_curve.png" \
  command="${env_prefix}scripts/train_variant.sh $variant $seed $steps RUNS_DIR $network $name"
echo "train_variant: $name recorded in $records/policies/policies.yaml; weights in $run/policy.pt"
# What the run learned, beside its log: the evaluation (seeds 0-99, greedy, fp32) and six seeded
# episodes drawn from above (seeds 0-5).
# On its own port (the run's + 1000), so that two runs finishing together do not share a master.
HIDESEEK_PORT=${HIDESEEK_PORT:-$((port + 1000))} RECORD_ROOT=$records scripts/evaluate_run.sh "$name" "$run/policy.pt"
if [ "${SHIP:-0}" = 1 ]; then
  "${registry[@]}" ship "$name" "$run/policy.pt"
  echo "train_variant: $name shipped as the $variant policy"
fi
