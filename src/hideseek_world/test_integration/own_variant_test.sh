#!/usr/bin/env bash
# A variant file of one's own through the pipeline: `hideseek_pipeline train --variant-config` trains
# tiny_basic (one PPO update on two arenas, one learner thread, fp32) into a records folder of its own,
# which records the file and its map with their sha256; the run's evaluation (evaluate.launch, seeds
# 0-99) and its trajectories play that file, whose short episodes show in every episode's length; its
# behaviour is analysed on it. Once the file changes, the run's evaluation is refused, naming it.
# usage: own_variant_test.sh XUNIT_OUTPUT
set -uo pipefail
source "$(dirname "$0")/xunit.sh"
out=$1
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
dir=$(mktemp -d /tmp/hideseek_own_variant_test.XXXXXX)
port=$((13300 + RANDOM % 20 * 5))
failures=()
pipeline() {
  PYTHONPATH="$root/src/hideseek_pipeline/python" /usr/bin/python3 -m hideseek_pipeline "$@" \
    --record-root "$dir/records"
}
mkdir -p "$dir/records/policies"
: > "$dir/records/policies/policies.yaml"
# The file lives outside the project, as a user's would; its episodes last at most 200 steps.
cp "$here/data/tiny_basic.yaml" "$dir/tiny_basic.yaml"
pipeline train tiny_basic --variant-config "$dir/tiny_basic.yaml" --steps 128 --num-arenas 2 --hider-threads 1 \
  --precision fp32 --runs-dir "$dir/runs" --port "$port" --eval-port $((port + 1)) > "$dir/train.log" 2>&1 ||
  failures+=("train failed: $(tail -n 3 "$dir/train.log" | tr '\n' ' ')")
run=tiny_basic_v3_128_seed0
pipeline analyze "$run" "$dir/runs/$run/policy.pt" --part behaviour --episodes 4 > "$dir/analyze.log" 2>&1 ||
  failures+=("analyze failed: $(tail -n 3 "$dir/analyze.log" | tr '\n' ' ')")
/usr/bin/python3 - "$dir" "$run" > "$dir/check.log" 2>&1 <<'PY' || failures+=("$(cat "$dir/check.log")")
import csv, hashlib, os, sys, yaml
d, run = sys.argv[1], sys.argv[2]
e = yaml.safe_load(open(d + "/records/policies/policies.yaml"))[run]
sha = lambda p: hashlib.sha256(open(p, "rb").read()).hexdigest()
assert (e["variant"], e["game"], e["steps"]) == ("tiny_basic", "v3", 128), e
assert e["variant_config"] == d + "/tiny_basic.yaml" and e["variant_sha256"] == sha(e["variant_config"]), e
assert e["map_file"].endswith("/maps/v3/deterministic.yaml") and e["map_sha256"] == sha(e["map_file"]), e
docs = d + "/records/docs/runs/" + run
episodes = list(csv.DictReader(open(docs + "/episodes.csv")))
assert len(episodes) == 100, "%d episodes evaluated" % len(episodes)
longest = max(int(r["living_steps"]) for r in episodes)
assert longest <= 200, "an episode lasted %d steps: the evaluation did not play the file (200 at most)" % longest
last = list(csv.reader(open(docs + "/evaluation.csv")))[-1]
assert last[0] == "tiny_basic", last
for f in ("trajectories.png", "learning_curve.png", "analysis/behaviour.csv"):
    assert os.path.getsize(docs + "/" + f) > 0, "no " + f
PY
echo "# edited after training" >> "$dir/tiny_basic.yaml"
if pipeline evaluate "$run" "$dir/runs/$run/policy.pt" --port $((port + 1)) > "$dir/changed.log" 2>&1; then
  failures+=("the run was evaluated on a changed variant file")
elif ! grep -q "trained on $dir/tiny_basic.yaml with sha256 .* it has changed since" "$dir/changed.log"; then
  failures+=("a changed variant file was refused without naming it: $(tail -n 2 "$dir/changed.log" | tr '\n' ' ')")
fi
write_xunit "$out" own_variant TrainsEvaluatesAndAnalysesTheFileItRecords "${failures[@]}"
printf 'failure: %s\n' "${failures[@]}"
rm -rf "$dir"
[ ${#failures[@]} -eq 0 ]
