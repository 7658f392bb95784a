"""The per-run analysis, small outputs committed so that a run's weights may go afterwards: its
probes on the shared probe set (the results, not the features), the t-SNE of its features on the
probe set's test images (coordinates and neighbourhood scores) and its behaviour on 100 rollouts
(play_episodes, seeds 10000-10099, greedy: states, transitions, distance over time, backward steps,
the seeker kept in view, line-of-sight breaks), into docs/runs/<run>/analysis/. A GRU run also gets
its memoryless ablation on the same rollout seeds (its state zeroed at every step: it acts on the
current image alone) into analysis/memoryless/, what the claims table compares its memory with.
A baseline (the random hider, or a scripted evader) gets the behaviour alone, into
docs/analysis/baselines/[<game>/]<variant>/<policy>/."""
import os
import shutil
import tempfile

from hideseek_pipeline import own_variant
from hideseek_pipeline.workspace import ToolError

PARTS = ("all", "tsne", "memoryless", "behaviour")
CHUNK = 50  # play_episodes plays at most 64 episodes at once


def rollouts(ws, game, variant, policy, first, episodes, memory, steps_csv, tmp, variant_config=None):
    """`episodes` greedy episodes from seed `first` into one per-step CSV, in chunks of 50; of a variant
    file of one's own where `variant_config` names one."""
    with open(steps_csv, "w") as out:
        for at in range(0, episodes, CHUNK):
            chunk = os.path.join(tmp, "chunk.csv")
            ws.command([ws.tool("hideseek_play", "play_episodes"), "--game", game, variant, policy, first + at,
                        min(CHUNK, episodes - at), chunk, "greedy", memory] +
                       (["--variant-config", variant_config] if variant_config else []))
            with open(chunk) as f:
                lines = f.readlines()
            out.writelines(lines if at == 0 else lines[1:])


def analyze_run(ws, records, name, policy, part="all", episodes=100, first=10000, say=print, entry=None, out=None):
    """A recorded run, on its own game (and variant file of its own, unchanged since it trained) as
    the registry records it; `part` one of PARTS. A policy
    that is not a run of the registry (a self-play generation) gives its `entry` (variant, network,
    game) and the folder `out` of its analysis instead."""
    if part not in PARTS:
        raise ToolError("analyze: part '%s' is not one of %s" % (part, ", ".join(PARTS)))
    entry = entry or records.entry(name)
    if not entry:
        raise ToolError("analyze: no run %s in %s" % (name, records.registry_path))
    variant, network, game = entry["variant"], entry.get("network", "ff"), entry["game"]
    if part == "memoryless" and network != "gru":
        raise ToolError("analyze: the memoryless ablation is a GRU's; %s is a %s run" % (name, network))
    variant_config = own_variant.check_unchanged(ws, name, entry, "analyze")
    policy = os.path.realpath(policy)
    out = out or records.docs(name, "analysis")
    os.makedirs(out, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix="hideseek_analyze_")
    try:
        steps = os.path.join(tmp, "steps.csv")

        def behaviour(memory, folder):
            rollouts(ws, game, variant, policy, first, episodes, memory, steps, tmp, variant_config)
            ws.python("behaviour.py", steps, folder, "--run", name)

        if part == "memoryless":
            behaviour("memoryless", os.path.join(out, "memoryless"))
        elif part == "behaviour":
            behaviour("memory", out)
        else:
            probe_set = ws.tool("hideseek_analysis", "probe_set")  # (probe_set.sh runs it too, to make the set)
            probe = ws.command([ws.analysis_script("probe_set.sh")]).strip().splitlines()[-1]
            features = os.path.join(tmp, "trained.npy")
            ws.command([probe_set, "features", probe, features, "--policy", policy])
            tsne = ["tsne", probe, features, out, "--run", name, "--baselines",
                    os.path.join(ws.root, "docs", "probe_set", "tsne_baselines.csv")]
            if part == "tsne":
                ws.python("probes.py", *tsne)
            else:
                ws.python("probes.py", "run", probe, features, os.path.join(ws.root, "docs", "probe_set", "baselines.csv"),
                          os.path.join(out, "probes.csv"), "--run", name)
                behaviour("memory", out)
                # The t-SNE and the memoryless ablation last: their failure must not cost the probes
                # and the behaviour above (sweep analyze redoes either alone).
                ws.python("probes.py", *tsne)
                if network == "gru":
                    behaviour("memoryless", os.path.join(out, "memoryless"))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    say("analyze: %s: %s into %s" % (name, part if part != "all" else "probes, behaviour, t-SNE", out))


def baseline_folder(records_root, variant, policy, game):
    """docs/analysis/baselines/[<game>/ unless v2]<variant>/<policy>/ of the records."""
    parts = [records_root, "docs", "analysis", "baselines"] + ([] if game == "v2" else [game])
    return os.path.join(*parts, variant, policy.replace("/", "_"))


def analyze_baseline(ws, records_root, variant, policy, game=None, episodes=100, first=10000, say=print):
    """The behaviour alone of the random hider (`random`) or a scripted evader (`scripted/EVADER`)."""
    game = game or ws.resolve(variant, "game")
    out = baseline_folder(records_root, variant, policy, game)
    label = policy.replace("/", "_")
    os.makedirs(out, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix="hideseek_analyze_")
    try:
        steps = os.path.join(tmp, "steps.csv")
        rollouts(ws, game, variant, policy, first, episodes, "memory", steps, tmp)
        ws.python("behaviour.py", steps, out, "--run", "%s_%s" % (variant, label))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    say("analyze: %s (%s, game %s): behaviour into %s" % (policy, variant, game, out))
