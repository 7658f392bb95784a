#!/usr/bin/env bash
# Integration tests of evaluate.launch. usage: evaluate_test.sh XUNIT_OUTPUT
# 1. On the shipped basic policy (policy:=shipped): evaluation.md, evaluation.csv and episodes.csv
#    appear, with the documented columns and 100 episodes, and name the registry's file; the
#    shipped basic policies of games v3 (ff and GRU) and v2 replay their runs' recorded episodes.
# 2. The random hider through the ROS graph (4 arenas) plays exactly the episodes that the
#    in-process calibration table plays (calibration_table): the calibration is the real game,
#    and an episode's draws do not depend on the number of arenas.
# 3. The same for a scripted evader on game v2 (scripted/hide), for game v1's random hider (game:=v1), and for
#    policy:=shipped on a variant that ships none (the random hider, with a warning).
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
root="$(cd "$(dirname "$0")/.." && pwd)"
policy=$(/usr/bin/python3 "$root/../hideseek_analysis/scripts/hideseek_registry.py" shipped basic)
dir=$(mktemp -d /tmp/hideseek_eval_test.XXXXXX)
port=$((11800 + RANDOM % 100))
failures=()
if [ ! -f "$policy" ]; then
  failures+=("no basic policy is shipped (policies/policies.yaml)")
else
  timeout 600 roslaunch -p "$port" hideseek_world evaluate.launch variant:=basic policy:=shipped episodes:=100 \
    output_dir:="$dir" > "$dir/launch.log" 2>&1
  # The table names the file policy:=shipped resolved to, the one the registry ships.
  named=$(tail -n 1 "$dir/evaluation.csv" 2>/dev/null | cut -d, -f2)
  [ "$(readlink -f "${named% (greedy)}")" = "$(readlink -f "$policy")" ] && [ "${named% (greedy)}" != "$named" ] ||
    failures+=("evaluation.csv names '$named', not the shipped $policy (greedy)")
  [ -f "$dir/evaluation.md" ] || failures+=("no evaluation.md")
  [ -f "$dir/evaluation.csv" ] || failures+=("no evaluation.csv")
  [ "$(head -n 1 "$dir/evaluation.csv" 2>/dev/null)" = "variant,policy,episodes,avg_living_steps,success_rate,game" ] ||
    failures+=("evaluation.csv header differs")
  # game:= left unset plays config/games.yaml's default game, which the table names
  default_game=$(sed -n 's/^default: *\([a-z0-9]*\).*/\1/p' "$(rospack find hideseek_game)/config/games.yaml")
  [ -n "$default_game" ] && [ "$(tail -n 1 "$dir/evaluation.csv" 2>/dev/null | cut -d, -f6)" = "$default_game" ] ||
    failures+=("evaluation.csv does not name the default game '$default_game'")
  [ "$(tail -n 1 "$dir/evaluation.csv" 2>/dev/null | cut -d, -f3)" = "100" ] || failures+=("not 100 episodes")
  [ "$(head -n 1 "$dir/episodes.csv" 2>/dev/null)" = "seed,living_steps,outcome" ] || failures+=("episodes.csv header differs")
  [ "$(tail -n +2 "$dir/episodes.csv" 2>/dev/null | wc -l)" = "100" ] || failures+=("episodes.csv has not 100 rows")
fi
write_xunit "$out" evaluate EvaluateLaunchWritesItsFilesFor100Episodes "${failures[@]}"
cat "$dir/evaluation.md" 2>/dev/null
printf 'failure: %s\n' "${failures[@]}"
shipped_failed=${#failures[@]}

# 1b. What a user reproduces: a shipped policy, evaluated here (fp32, greedy, seeds 0-99), plays the
#     episodes its run recorded when it was trained (another commit, often another kind of CPU) seed
#     for seed: game v3's basic (part 1's evaluation) and its GRU, and game v2's basic, which the
#     later games must leave as it was. A change to the game, the renderer or the network that moves
#     one episode fails here; one meant to change a game must be a new game.
failures=()
replays() {  # NETWORK GAME [EVALUATION_DIR]: evaluates the shipped basic policy into a folder of its own
  # (or reads part 1's EVALUATION_DIR) and compares its episodes.csv with its run's recorded one
  local run policy evaluation=${3:-$dir/$1_$2}
  read -r run policy < <(/usr/bin/python3 -c "import sys; sys.path.insert(0, '$root/../hideseek_analysis/python')
from hideseek_analysis import registry; print(*registry.shipped('basic', network='$1', game='$2'))")
  local recorded="$root/../../docs/runs/$run/episodes.csv"
  if [ "$run" = None ] || [ ! -s "$recorded" ]; then
    failures+=("basic ($1, $2): no shipped run with recorded episodes ('$run', $recorded)")
    return
  fi
  if [ -z "${3:-}" ]; then
    mkdir -p "$evaluation"
    timeout 600 roslaunch -p "$port" hideseek_world evaluate.launch variant:=basic game:="$2" policy:="$policy" \
      output_dir:="$evaluation" > "$evaluation/launch.log" 2>&1
  fi
  if [ ! -s "$evaluation/episodes.csv" ]; then
    failures+=("$run: the evaluation wrote no $evaluation/episodes.csv")
  elif ! diff "$recorded" "$evaluation/episodes.csv" > "$evaluation/replay.diff"; then
    failures+=("$run: $(grep -c '^<' "$evaluation/replay.diff") of its 100 recorded episodes differ: \
$(head -c 300 "$evaluation/replay.diff" | tr '\n' ' ')")
  fi
}
replays ff v3 "$dir"
replays gru v3
replays ff v2
write_xunit "${out%.xml}-replay.xml" evaluate ShippedPoliciesReplayTheirRecordedEpisodes "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
replay_failed=${#failures[@]}

failures=()
mkdir -p "$dir/random"
timeout 300 roslaunch -p "$port" hideseek_world evaluate.launch variant:=stochasticseeker policy:=random episodes:=40 \
  num_arenas:=4 output_dir:="$dir/random" > "$dir/random/launch.log" 2>&1
"$(catkin_find hideseek_play calibration_table --first-only 2>/dev/null || echo calibration_table)" \
  --episodes 40 --evaders random --episodes-csv "$dir/in_process.csv" stochasticseeker > /dev/null
if [ ! -s "$dir/random/episodes.csv" ]; then
  failures+=("the graph's evaluation wrote no episodes.csv")
elif ! diff "$dir/random/episodes.csv" "$dir/in_process.csv" > "$dir/diff.txt"; then
  failures+=("graph and in-process random hider differ: $(head -c 300 "$dir/diff.txt" | tr '\n' ' ')")
fi
write_xunit "${out%.xml}-random_hider.xml" evaluate RandomHiderThroughTheGraphPlaysTheCalibratedEpisodes "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
random_failed=${#failures[@]}

# 3. A scripted evader through the graph (policy:=scripted/hide, 4 arenas, stochastic maps whose
#    layouts the hider draws again from each seed; game v2) plays the calibration table's episodes, and so
#    does the random hider of game v1 (game:=v1).
failures=()
compare() {  # NAME VARIANT POLICY EVADER GAME_FILE [LAUNCH ARGS...]
  local name=$1 variant=$2 policy=$3 evader=$4 game=$5
  shift 5
  mkdir -p "$dir/$name"
  timeout 300 roslaunch -p "$port" hideseek_world evaluate.launch variant:="$variant" policy:="$policy" episodes:=20 \
    num_arenas:=4 output_dir:="$dir/$name" "$@" > "$dir/$name/launch.log" 2>&1
  "$(catkin_find hideseek_play calibration_table --first-only 2>/dev/null || echo calibration_table)" \
    --game "$game" --episodes 20 --evaders "$evader" --episodes-csv "$dir/$name/in_process.csv" "$variant" > /dev/null
  if [ ! -s "$dir/$name/episodes.csv" ]; then
    failures+=("$name: the graph's evaluation wrote no episodes.csv")
  elif ! diff "$dir/$name/episodes.csv" "$dir/$name/in_process.csv" > "$dir/$name/diff.txt"; then
    failures+=("$name: graph and in-process differ: $(head -c 300 "$dir/$name/diff.txt" | tr '\n' ' ')")
  fi
}
compare hide stochasticmaps scripted/hide hide "$root/../../config/game.yaml" game:=v2  # (part 2 played the default game, v3)
compare v1 basic random random "$root/../../config/game_v1.yaml" game:=v1
# A variant without a shipped policy of its game plays the random hider by default, and says so.
# Game v1 ships none (its weights left the tree with game v2), while the sweep ships game v2's.
compare unshipped basic shipped random "$root/../../config/game_v1.yaml" game:=v1
grep -q "no policy is shipped for variant 'basic' on game v1" "$dir/unshipped/launch.log" ||
  failures+=("unshipped: no warning that basic has no shipped policy on game v1")
write_xunit "${out%.xml}-scripted.xml" evaluate ScriptedEvaderAndGameV1ThroughTheGraphPlayTheCalibratedEpisodes "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
rm -rf "$dir"
[ "$shipped_failed" -eq 0 ] && [ "$replay_failed" -eq 0 ] && [ "$random_failed" -eq 0 ] && [ ${#failures[@]} -eq 0 ]
