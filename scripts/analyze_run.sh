#!/usr/bin/env bash
# The per-run analysis, small outputs committed so that a run's weights may go afterwards: its
# probes on the shared probe set (scripts/probe_set.sh; the results, not the features), the t-SNE
# of its features on the probe set's test images (coordinates and neighbourhood scores) and its
# behaviour on 100 rollouts (play_episodes, seeds 10000-10099, greedy: states, transitions,
# distance over time, how often it walks backward, keeps the seeker in view, breaks the line of
# sight), into docs/runs/<run>/analysis/. For a GRU run, also its memoryless ablation on the same
# rollout seeds (the same policy with its state zeroed at every step: it acts on the current image
# alone) into docs/runs/<run>/analysis/memoryless/: what the claims table compares its memory with.
# usage: scripts/analyze_run.sh RUN WEIGHTS          (RUN as in policies/policies.yaml)
#        scripts/analyze_run.sh --tsne-only RUN WEIGHTS   (the t-SNE alone: for a run analysed
#                                                           before the per-run t-SNE existed)
#        scripts/analyze_run.sh --memoryless-only RUN WEIGHTS   (a GRU run's memoryless ablation
#                                                           alone: for one analysed without it)
#        scripts/analyze_run.sh --behaviour-only RUN WEIGHTS   (the rollouts' behaviour tables alone:
#                                                           greedy, so they come out as before, plus
#                                                           what behaviour.py measures since)
#        scripts/analyze_run.sh --baseline VARIANT POLICY   (random or scripted/EVADER: behaviour
#                                                            only, into docs/analysis/baselines/<variant>/<policy>/;
#                                                            the random hider's: ROLLOUT_EPISODES=1000, about 43,000 steps;
#                                                            GAME=v3: into docs/analysis/baselines/v3/<variant>/<policy>/)
#   A run plays its own game, as the registry records it.
#   RECORD_ROOT (default this checkout): where the registry and docs/runs are (the sweep's checkout).
#   ROLLOUT_EPISODES (default 100), ROLLOUT_SEED (default 10000).
set -euo pipefail
[ -z "${RECORD_ROOT:-}" ] || RECORD_ROOT=$(realpath "$RECORD_ROOT")
only=
case "${1:-}" in --tsne-only | --memoryless-only | --behaviour-only) only=${1#--}; only=${only%-only}; shift ;; esac
case " $* " in *" --tsne-only "* | *" --memoryless-only "* | *" --behaviour-only "*) only=misplaced ;; esac
if [ "$only" = misplaced ] || { [ -n "$only" ] && [ "${1:-}" = --baseline ]; }; then
  echo "analyze_run.sh: --tsne-only, --memoryless-only and --behaviour-only come first and go with a run (RUN WEIGHTS), not with --baseline" >&2
  exit 2
fi
if [ "${1:-}" = --baseline ]; then
  baseline=1; variant=$2; policy=$3; name=${variant}_${policy//\//_}
else
  baseline=0; name=$1; policy=$(realpath "$2")
fi
cd "$(dirname "$0")/.."
source scripts/env.sh
records=${RECORD_ROOT:-$PWD}
episodes=${ROLLOUT_EPISODES:-100}
first=${ROLLOUT_SEED:-10000}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [ $baseline = 1 ]; then
  game=${GAME:-$(devel/lib/hideseek_game/resolve "$variant" game)}  # none: config/games.yaml's default
  out=$records/docs/analysis/baselines/$variant/${policy//\//_}
  [ "$game" = v2 ] || out=$records/docs/analysis/baselines/$game/$variant/${policy//\//_}
else
  # A run is analysed on its own game, as the registry records it.
  entry=$(/usr/bin/python3 -c 'import sys; sys.path.insert(0, "scripts"); import hideseek_registry as r
e = r.runs(sys.argv[2])[sys.argv[1]]
print(e["variant"], e.get("network", "ff"), e["game"])' "$name" "$records/policies/policies.yaml")
  read -r variant network game <<< "$entry"
  out=$records/docs/runs/$name/analysis
fi
# play_episodes plays at most 64 episodes at once: chunks of 50, one CSV. $1: memory or memoryless.
rollouts() {
  local at n
  for ((at = 0; at < episodes; at += 50)); do
    n=$((episodes - at < 50 ? episodes - at : 50))
    devel/lib/hideseek_play/play_episodes --game "$game" "$variant" "$policy" $((first + at)) "$n" "$tmp/chunk.csv" greedy "$1" > /dev/null
    if [ $at = 0 ]; then cp "$tmp/chunk.csv" "$tmp/steps.csv"; else tail -n +2 "$tmp/chunk.csv" >> "$tmp/steps.csv"; fi
  done
}
memoryless() {
  rollouts memoryless
  /usr/bin/python3 src/hideseek_analysis/scripts/behaviour.py "$tmp/steps.csv" "$out/memoryless" --run "$name"
}
if [ "$only" = memoryless ]; then
  [ "$network" = gru ] || { echo "analyze_run.sh: --memoryless-only: $name is a $network run; the ablation is a GRU's" >&2; exit 2; }
  memoryless
  echo "analyze_run: $name: memoryless ablation into $out/memoryless"
  exit 0
fi
if [ "$only" = behaviour ]; then
  mkdir -p "$out"
  rollouts memory
  /usr/bin/python3 src/hideseek_analysis/scripts/behaviour.py "$tmp/steps.csv" "$out" --run "$name"
  echo "analyze_run: $name: behaviour into $out"
  exit 0
fi
if [ $baseline = 0 ]; then
  probe=$(scripts/probe_set.sh)
  devel/lib/hideseek_analysis/probe_set features "$probe" "$tmp/trained.npy" --policy "$policy" > /dev/null
  mkdir -p "$out"
  tsne() {
    /usr/bin/python3 src/hideseek_analysis/scripts/probes.py tsne "$probe" "$tmp/trained.npy" "$out" --run "$name" \
      --baselines docs/probe_set/tsne_baselines.csv
  }
  if [ "$only" = tsne ]; then tsne; echo "analyze_run: $name: t-SNE into $out"; exit 0; fi
  /usr/bin/python3 src/hideseek_analysis/scripts/probes.py run "$probe" "$tmp/trained.npy" docs/probe_set/baselines.csv \
    "$out/probes.csv" --run "$name"
fi
mkdir -p "$out"
rollouts memory
/usr/bin/python3 src/hideseek_analysis/scripts/behaviour.py "$tmp/steps.csv" "$out" --run "$name"
# The t-SNE and the memoryless ablation last: their failure must not cost the probes and the
# behaviour above (hideseek_pipeline sweep analyze redoes either alone).
[ $baseline = 1 ] || tsne
[ $baseline = 1 ] || [ "$network" != gru ] || memoryless
echo "analyze_run: $name: $out"
