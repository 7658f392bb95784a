#!/usr/bin/env bash
# play_episodes and plot_trajectories.py (hideseek_analysis), as the README uses them to show a strategy.
# usage: trajectories_test.sh XUNIT_OUTPUT
# 1. stochasticmaps (new boxes every episode), random hider, seeds 0-2: every episode's rows end
#    with its outcome, the layouts file holds each episode's own boxes (not all the same), and
#    the figure's numbers (.md) give one row per episode whose steps match the CSV and whose
#    action shares add up to 100 %.
# 2. basic (fixed map): every episode's layout is the map file's obstacles.
# Both on game v3 and its maps (config/maps/v3/).
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
root="$(cd "$(dirname "$0")/.." && pwd)"
workspace="$(cd "$root/../.." && pwd)"
dir=$(mktemp -d /tmp/hideseek_trajectories_test.XXXXXX)
play=$(catkin_find hideseek_play play_episodes --first-only)
failures=()
if [ -z "$play" ]; then
  failures+=("play_episodes not built")
else
  "$play" --game v3 stochasticmaps random 0 3 "$dir/sm.csv" > "$dir/sm.log" 2>&1 || failures+=("play_episodes stochasticmaps failed: $(tail -n 1 "$dir/sm.log")")
  "$play" --game v3 basic random 0 2 "$dir/basic.csv" > "$dir/basic.log" 2>&1 || failures+=("play_episodes basic failed: $(tail -n 1 "$dir/basic.log")")
  /usr/bin/python3 "$workspace/src/hideseek_analysis/scripts/plot_trajectories.py" "$dir/sm.csv" "$root/../../config/maps/v3/stochastic.yaml" "$dir/sm.png" \
    "stochasticmaps, random" > "$dir/plot.log" 2>&1 || failures+=("plot_trajectories failed: $(tail -n 1 "$dir/plot.log")")
  [ -s "$dir/sm.png" ] || failures+=("no figure")
  /usr/bin/python3 - "$dir" "$root/../../config/maps/v3/deterministic.yaml" > "$dir/problems.txt" 2> "$dir/check.log" <<'PY'
import csv, sys, yaml
d, fixed_map = sys.argv[1:]
problems = []
rows = list(csv.DictReader(open(d + "/sm.csv")))
seeds = sorted({int(r["seed"]) for r in rows})
if seeds != [0, 1, 2]:
    problems.append("stochasticmaps CSV seeds %s, not 0-2" % seeds)
steps = {}
for s in seeds:
    ep = [r for r in rows if int(r["seed"]) == s]
    steps[s] = len(ep)
    if ep[-1]["outcome"] not in ("captured", "survived") or any(r["outcome"] for r in ep[:-1]):
        problems.append("seed %d: the outcome is not on its last row only" % s)
layouts = {e["seed"]: e for e in yaml.safe_load(open(d + "/sm_layouts.yaml"))["episodes"]}
if sorted(layouts) != [0, 1, 2]:
    problems.append("layouts file seeds %s, not 0-2" % sorted(layouts))
elif len({str(layouts[s]["obstacles"]) for s in layouts}) < 2:
    problems.append("stochasticmaps episodes all have the same layout")
table = [l for l in open(d + "/sm.md") if l.startswith("| ") and l[2].isdigit()]
if len(table) != 3:
    problems.append("sm.md has %d episode rows, not 3" % len(table))
for line in table:
    cells = [c.strip() for c in line.strip().strip("|").split("|")]
    if int(cells[2]) != steps.get(int(cells[0])):
        problems.append("sm.md seed %s: %s steps, the CSV has %s" % (cells[0], cells[2], steps.get(int(cells[0]))))
    if abs(sum(float(c) for c in cells[-5:]) - 100.0) > 0.3:
        problems.append("sm.md seed %s: action shares add up to %s" % (cells[0], sum(float(c) for c in cells[-5:])))
want = [(o["center"], o["size"]) for o in yaml.safe_load(open(fixed_map))["obstacles"]]
for e in yaml.safe_load(open(d + "/basic_layouts.yaml"))["episodes"]:
    got = [(o["center"], o["size"]) for o in e["obstacles"]]
    if len(got) != len(want) or any(abs(a - b) > 1e-6 for g, w in zip(got, want) for a, b in zip(g[0] + g[1], w[0] + w[1])):
        problems.append("basic seed %s: layout is not the map file's obstacles" % e["seed"])
for p in problems:
    print(p)
PY
  [ $? -eq 0 ] || failures+=("the check of the files failed: $(tail -n 1 "$dir/check.log")")
  while IFS= read -r line; do failures+=("$line"); done < "$dir/problems.txt"
fi
write_xunit "$out" trajectories PlayEpisodesAndPlotTrajectories "${failures[@]}"
[ ${#failures[@]} -eq 0 ] && echo "trajectories_test: ok" || printf 'trajectories_test: %s\n' "${failures[@]}"
rm -rf "$dir"
