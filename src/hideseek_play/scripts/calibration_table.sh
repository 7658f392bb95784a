#!/usr/bin/env bash
# The calibration table: the random hider and the scripted evaders (backpedal, flee, hide, lap) on every
# variant over seeds 0..99, beside the paper's random-hider living steps, with the median and the
# share of episodes in which the seeker sees the hider at step 0. Writes docs/calibration_table.md and
# docs/calibration_table.csv (or the folder given) and prints the table. GAME (environment) names another
# game (v1) or a game file of one's own. The in-process game is the one the ROS graph plays
# (evaluate_test.sh checks that episode by episode); it takes about 3 minutes.
set -euo pipefail
out=$(realpath -m "${1:-$(dirname "$(realpath "$0")")/../../../docs}")
cd "$(dirname "$(realpath "$0")")/../../.."
source scripts/env.sh
mkdir -p "$out"
devel/lib/hideseek_play/calibration_table --game "${GAME:-}" --csv "$out/calibration_table.csv" | tee "$out/calibration_table.md"
