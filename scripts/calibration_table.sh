#!/usr/bin/env bash
# The calibration table: the uniformly random hider on all seven variants over seeds 0..99, beside
# the paper's random-hider living steps, with the median and the share of episodes in which the
# seeker sees the hider at step 0. Writes docs/calibration.md and docs/calibration.csv (or the
# folder given) and prints the table. The in-process game is the one the ROS graph plays
# (evaluate_test.sh checks that episode by episode); it takes about 2 seconds.
set -euo pipefail
out=$(realpath -m "${1:-$(dirname "$0")/../docs}")
cd "$(dirname "$0")/.."
source scripts/env.sh
mkdir -p "$out"
devel/lib/hideseek_seeker/random_hider_table --csv "$out/calibration.csv" | tee "$out/calibration.md"
