#!/usr/bin/env bash
# The scripted seeker's stalls on every shipped variant of both games, evaluation seeds 0-99:
# the random hider and scripted/hide, and the shipped policies of v3's wandering-seeker variants.
# usage: measure.sh OUT_DIR [--forward]   (after `source devel/setup.bash`; about 20 min on 2 cores).
# With --forward every variant plays with seeker.path_following: forward (docs/calibration.md, "The
# scripted seeker's stalls"), through variant files of its own written to OUT_DIR/variants/.
set -euo pipefail
out=$1
forward=${2:-}
if [[ -n "$forward" && "$forward" != --forward ]]; then
  echo "measure.sh: the second argument is --forward or nothing, got '$forward'" >&2
  exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
config="$here/../../config"
registry="$here/../../src/hideseek_analysis/scripts/hideseek_registry.py"
mkdir -p "$out"
variant_args() {  # GAME VARIANT: the play_episodes arguments that choose the variant
  if [[ -z "$forward" ]]; then
    echo "--variant $2"
    return
  fi
  local file="$out/variants/$2.yaml"
  mkdir -p "$(dirname "$file")"
  /usr/bin/python3 - "$config/variants/$2.yaml" "$file" <<'PY'
import sys
import yaml
variant = yaml.safe_load(open(sys.argv[1]))
variant.setdefault("seeker", {})["path_following"] = "forward"
yaml.safe_dump(variant, open(sys.argv[2], "w"), sort_keys=False)
PY
  echo "--variant $2 --variant-config $file"
}
play() {  # GAME VARIANT POLICY NAME: seeds 0-99 in two calls (play_episodes takes 64 at most)
  local args
  args=$(variant_args "$1" "$2")
  # shellcheck disable=SC2086
  rosrun hideseek_play play_episodes --game "$1" $args --policy "$3" --first-seed 0 --count 64 \
    --output "$out/$4_a.csv" > /dev/null
  # shellcheck disable=SC2086
  rosrun hideseek_play play_episodes --game "$1" $args --policy "$3" --first-seed 64 --count 36 \
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
