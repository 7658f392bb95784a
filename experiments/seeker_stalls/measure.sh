#!/usr/bin/env bash
# The scripted seeker's stalls (docs/calibration.md, "The scripted seeker's stalls"): every shipped
# variant of both games against the random hider and scripted/hide, the shipped policies of v3's
# wandering-seeker variants, and a serpentine maze (game v3, basic's rules, scripted/hide, 32 seeds).
# usage: measure.sh OUT_DIR [--no-backtrack] [--validation]   (after `source devel/setup.bash`;
# about 20 min on 2 cores)
#   --no-backtrack  every game plays with seeker.path_following: no_backtrack, through variant files
#                   of its own written to OUT_DIR/variants/
#   --validation    the validation seeds 1000-1099 (the maze: 1000-1031) instead of 0-99 (0-31)
#   GAMES="v3" VARIANTS="stochasticseeker ..." (environment) narrow the plays to those games and variants
#   (the maze plays whenever v3 does)
set -euo pipefail
shopt -s inherit_errexit
usage() {
  echo "usage: measure.sh OUT_DIR [--no-backtrack] [--validation]: $1" >&2
  exit 2
}
[[ $# -ge 1 ]] || usage "no output folder"
out=$1
shift
no_backtrack=false
first=0
for arg in "$@"; do
  case "$arg" in
    --no-backtrack) no_backtrack=true ;;
    --validation) first=1000 ;;
    *) usage "unknown argument '$arg'" ;;
  esac
done
here=$(cd "$(dirname "$0")" && pwd)
config="$here/../../config"
registry="$here/../../src/hideseek_analysis/scripts/hideseek_registry.py"
games=${GAMES:-v2 v3}
all_variants=${VARIANTS:-}
[[ -n "$all_variants" ]] || all_variants=$("$registry" variants)
variants=$(tr '\n' ' ' <<< "$all_variants")  # one line: the membership test below
[[ -n "${variants// /}" ]] || usage "no variants"
if [[ -d "$out" && -n "$(ls -A "$out")" ]]; then
  usage "$out is not empty (stalls.py would count what an earlier run left there)"
fi
mkdir -p "$out/variants"
# A variant file of its own: SOURCE plus, with --no-backtrack, the setting; MAP replaces its map.
own_variant() {  # SOURCE NAME [MAP]
  /usr/bin/python3 - "$1" "$out/variants/$2.yaml" "$no_backtrack" "${3:-}" <<'PY'
import sys
import yaml
variant = yaml.safe_load(open(sys.argv[1]))
variant["variant"] = sys.argv[2].rsplit("/", 1)[-1][:-len(".yaml")]  # a file's variant field names it
if sys.argv[3] == "true":
    variant.setdefault("seeker", {})["path_following"] = "no_backtrack"
if sys.argv[4]:
    variant["map"] = sys.argv[4]
yaml.safe_dump(variant, open(sys.argv[2], "w"), sort_keys=False)
PY
}
for variant in $variants; do own_variant "$config/variants/$variant.yaml" "$variant"; done
own_variant "$config/variants/basic.yaml" maze "$(cd "$here/../.." && pwd)/src/hideseek_play/test/data/serpentine_map.yaml"
play() {  # GAME VARIANT POLICY NAME [COUNT]: in two calls of at most 64 episodes
  local count=${5:-100}
  local args=(--game "$1" --variant "$2" --variant-config "$out/variants/$2.yaml" --policy "$3")
  rosrun hideseek_play play_episodes "${args[@]}" --first-seed "$first" --count $((count < 64 ? count : 64)) \
    --output "$out/$4_a.csv" > /dev/null
  if ((count > 64)); then
    rosrun hideseek_play play_episodes "${args[@]}" --first-seed $((first + 64)) --count $((count - 64)) \
      --output "$out/$4_b.csv" > /dev/null
  fi
}
for game in $games; do
  for variant in $variants; do
    play "$game" "$variant" random "${game}_${variant}_random"
    play "$game" "$variant" scripted/hide "${game}_${variant}_hide"
  done
done
if [[ " $games " == *" v3 "* ]]; then
  for variant in stochasticseeker stochasticseeker_explore stochasticmaps; do
    [[ " $variants " == *" $variant "* ]] || continue
    play v3 "$variant" "$("$registry" shipped "$variant")" "v3_${variant}_shipped"
  done
  play v3 maze scripted/hide v3_maze_hide 32
fi
/usr/bin/python3 "$here/stalls.py" "$out"/*_[ab].csv
