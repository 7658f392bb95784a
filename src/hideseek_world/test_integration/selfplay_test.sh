#!/usr/bin/env bash
# Self-play replays bit-identically, and a seeker's checkpoint plays through the graph: two
# generations of tiny_basic self-play (one PPO update a side and generation, one learner thread,
# fp32), trained twice into two folders with the same seed, save the same weights (every tensor of
# every generation's exported policy), the same training logs (timing columns aside) and the same
# opponents; every generation is registered with its role. Then the cross-play table of the first
# folder (one episode a pair), the same episodes played in process (play_episodes --seeker-policy)
# and a seeker evaluation beside the scripted seeker.
# usage: selfplay_test.sh XUNIT_OUTPUT
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
dir=$(mktemp -d /tmp/hideseek_selfplay_test.XXXXXX)
port=$((12500 + RANDOM % 80 * 5))  # the sweep uses 12100-12112, the fault campaign 12400-12499
failures=()
pipeline() { PYTHONPATH="$root/src/hideseek_pipeline/python" /usr/bin/python3 -m hideseek_pipeline "$@"; }
for copy in a b; do
  pipeline selfplay "$dir/$copy" --variant tiny_basic --variant-config "$here/data/tiny_basic.yaml" --generations 2 \
    --steps 128 --num-arenas 2 --hider-threads 1 --precision fp32 --seed 3 --port "$port" > "$dir/$copy.log" 2>&1 ||
    failures+=("selfplay into $copy failed: $(tail -n 3 "$dir/$copy.log" | tr '\n' ' ')")
  port=$((port + 3))
done
/usr/bin/python3 - "$dir/a" "$dir/b" > "$dir/compare.log" 2>&1 <<'PY' || failures+=("$(cat "$dir/compare.log")")
import csv, sys, yaml, zipfile
a, b = sys.argv[1], sys.argv[2]
ga = yaml.safe_load(open(a + "/generations.yaml"))["generations"]
gb = yaml.safe_load(open(b + "/generations.yaml"))["generations"]
order = [(g["role"], g["generation"]) for g in ga]
assert order == [("seeker", 1), ("hider", 1), ("seeker", 2), ("hider", 2)], "generations saved: %s" % order
assert [g["opponent"] for g in ga] == [g["opponent"] for g in gb], "the opponents drawn differ"
assert all(g["steps"] == 128 * g["generation"] for g in ga), "steps: %s" % [g["steps"] for g in ga]
def tensors(path):
    z = zipfile.ZipFile(path)
    return {n.split("/", 1)[1]: z.read(n) for n in z.namelist() if "/data/" in n}
for g in ga:
    ta, tb = tensors(a + "/" + g["checkpoint"]), tensors(b + "/" + g["checkpoint"])
    assert ta and ta == tb, "%s: the weights differ between the two self-plays" % g["checkpoint"]
for role in ("seeker", "hider"):
    rows = [list(csv.DictReader(open("%s/%s/training_log.csv" % (d, role)))) for d in (a, b)]
    for r in rows[0] + rows[1]:
        r.pop("wall_s"); r.pop("steps_per_s")
    assert rows[0] == rows[1], "the %s's training logs differ" % role
    assert len(rows[0]) == 2, "the %s's log has %d updates, not 2" % (role, len(rows[0]))
print("ok")
PY
pipeline selfplay "$dir/a" --variant tiny_basic --variant-config "$here/data/tiny_basic.yaml" --generations 2 \
  --steps 128 --num-arenas 2 --hider-threads 1 --precision fp32 --seed 3 --port "$port" --crossplay --episodes 1 \
  > "$dir/crossplay.log" 2>&1 || failures+=("crossplay failed: $(tail -n 3 "$dir/crossplay.log" | tr '\n' ' ')")
grep -q "the seeker trains" "$dir/crossplay.log" && failures+=("a resumed self-play trained a saved generation again")
pairs=$(($(grep -c . "$dir/a/crossplay/crossplay.csv" 2>/dev/null || echo 1) - 1))
[ "$pairs" -eq 12 ] || failures+=("crossplay.csv holds $pairs pairs, not 3 hiders x 4 seekers")
for f in crossplay.md crossplay.png learning_curves.png; do
  [ -s "$dir/a/crossplay/$f" ] || failures+=("no crossplay/$f")
done
pipeline evaluate-seeker "$dir/a/generations/seeker_g002.pt" --variant tiny_basic \
  --variant-config "$here/data/tiny_basic.yaml" --hiders random --output "$dir/eval" --episodes 4 --port "$port" \
  > "$dir/evaluate_seeker.log" 2>&1 || failures+=("evaluate-seeker failed: $(tail -n 3 "$dir/evaluate_seeker.log")")
rows=$(cut -d, -f1,2 "$dir/eval/seeker_evaluation.csv" 2>/dev/null | tr '\n' ' ')
[ "$rows" = "hider,seeker random,learned random,scripted " ] || failures+=("seeker_evaluation.csv rows: '$rows'")
# In process, play_episodes plays a learned seeker as the graph does: the episodes of the seeker
# evaluation (the random hider, seeds 0-3) and of the cross-play's last pair (seed 0), each
# episode's steps and outcome; and the learned seeker is not the scripted one (its path differs).
play=$(catkin_find hideseek_play play_episodes --first-only)
tiny=(--variant-config "$here/data/tiny_basic.yaml")
seeker=(--seeker-policy "$dir/a/generations/seeker_g002.pt")
"$play" tiny_basic random 0 4 "$dir/random.csv" greedy "${tiny[@]}" "${seeker[@]}" > "$dir/random.log" 2>&1 &&
  "$play" tiny_basic "$dir/a/generations/hider_g002.pt" 0 1 "$dir/g002.csv" greedy "${tiny[@]}" "${seeker[@]}" \
    > "$dir/g002.log" 2>&1 &&
  "$play" tiny_basic random 0 1 "$dir/scripted.csv" greedy "${tiny[@]}" > "$dir/scripted.log" 2>&1 ||
  failures+=("play_episodes failed: $(tail -q -n 1 "$dir"/random.log "$dir"/g002.log "$dir"/scripted.log 2>/dev/null)")
/usr/bin/python3 - "$dir" > "$dir/in_process.log" 2>&1 <<'PY' || failures+=("$(cat "$dir/in_process.log")")
import csv, sys
d = sys.argv[1]
def played(path):  # seed -> (living steps, outcome), from play_episodes' last row of each episode
    rows = list(csv.DictReader(open(path)))
    return {int(r["seed"]): (int(r["step"]) + 1, r["outcome"]) for r in rows if r["outcome"]}
def graph(path):
    return {int(r["seed"]): (int(r["living_steps"]), r["outcome"]) for r in csv.DictReader(open(path))}
for name, ours, theirs in (("random", "random.csv", "eval/random/learned/episodes.csv"),
                           ("hider_g002", "g002.csv", "a/crossplay/hider_g002/seeker_g002/episodes.csv")):
    a, b = played(d + "/" + ours), graph(d + "/" + theirs)
    assert a and a == b, "%s against seeker_g002: in process %s, the graph %s (seed: steps, outcome)" % (name, a, b)
path = lambda f: [(r["seeker_x"], r["seeker_y"]) for r in csv.DictReader(open(d + "/" + f)) if r["seed"] == "0"]
assert path("random.csv") != path("scripted.csv"), "the learned seeker moved as the scripted seeker does"
PY
write_xunit "$out" selfplay ReplaysBitIdenticallyAndCrossPlays "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
rm -rf "$dir"
[ ${#failures[@]} -eq 0 ]
