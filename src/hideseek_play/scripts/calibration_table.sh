#!/usr/bin/env bash
# The calibration table: the random hider and the scripted evaders (backpedal, flee, hide, lap) on every
# variant over seeds 0..99, beside the paper's random-hider living steps, with the median and the
# share of episodes in which the seeker sees the hider at step 0. GAME (environment; default: the
# default game, config/games.yaml's) names the game (v3, v2, v1) or a game file of one's own. Writes
# docs/calibration_table.md and .csv for game v2, docs/calibration_table_<game>.md and .csv for another
# game (the names the analysis reads; into the folder given instead of docs/) and prints the table.
# The in-process game is the one the ROS graph plays (evaluate_test.sh checks that episode by
# episode); it takes about 3 minutes.
set -euo pipefail
out=$(realpath -m "${1:-$(dirname "$(realpath "$0")")/../../../docs}")
cd "$(dirname "$(realpath "$0")")/../../.."
source scripts/env.sh
mkdir -p "$out"
game=${GAME:-$(devel/lib/hideseek_game/resolve basic game)}  # the default game's name
case "$game" in
  v2) name=calibration_table ;;
  */* | *.yaml) name=calibration_table_$(basename "$game" .yaml) ;;
  *) name=calibration_table_$game ;;
esac
devel/lib/hideseek_play/calibration_table --game "$game" --csv "$out/$name.csv" | tee "$out/$name.md"
