#!/usr/bin/env bash
# The scripted seeker's stalls on every shipped variant of both games, evaluation seeds 0-99:
# the random hider and scripted/hide, and the shipped policies of v3's wandering-seeker variants.
# usage: measure.sh OUT_DIR   (after `source devel/setup.bash`; about 20 min on 2 cores)
set -euo pipefail
out=$1
here=$(cd "$(dirname "$0")" && pwd)
registry="$here/../../src/hideseek_analysis/scripts/hideseek_registry.py"
mkdir -p "$out"
play() {  # GAME VARIANT POLICY NAME: seeds 0-99 in two calls (play_episodes takes 64 at most)
  rosrun hideseek_play play_episodes --game "$1" --variant "$2" --policy "$3" --first-seed 0 --count 64 \
    --output "$out/$4_a.csv" > /dev/null
  rosrun hideseek_play play_episodes --game "$1" --variant "$2" --policy "$3" --first-seed 64 --count 36 \
    --output "$out/$4_b.csv" > /dev/null
}
for game in v2 v3; do
  for variant in $("$registry" variants); do
    play "$game" "$variant" random "${game}_${variant}_random"
    play "$game" "$variant" scripted/hide "${game}_${variant}_hide"
  done
done
for variant in stochasticseeker stochasticseeker_explore stochasticmaps; do
  play v3 "$variant" "$("$registry" shipped "$variant")" "v3_${variant}_shipped"
done
/usr/bin/python3 "$here/stalls.py" "$out"/*_[ab].csv
