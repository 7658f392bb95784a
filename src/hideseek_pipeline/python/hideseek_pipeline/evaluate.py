"""One recorded run's evaluation into its folder, docs/runs/<run>/: evaluation.md/.csv and
episodes.csv (evaluate.launch, seeds 0-99, fp32, through the ROS graph), greedy and optionally
sampled (into sampled/), and trajectories.png/.md (six seeded episodes played in process and drawn
from above, seeds 0-5). A run trained on a variant file of its own plays that file, once it and its
map hash as the registry recorded."""
import os
import time

from hideseek_pipeline import own_variant
from hideseek_pipeline.workspace import ToolError

MODES = ("greedy", "sampled")


def evaluate(ws, records, name, weights, modes=("greedy",), port=11479, say=print, entry=None, docs=None):
    """`ws`: the Workspace whose launch files and tools run; `records`: the Records of the checkout
    that names the run and receives its files. A policy that is not a run of the registry (a
    self-play generation) gives its `entry` (variant, game) and its folder `docs` instead."""
    for mode in modes:
        if mode not in MODES:
            raise ToolError("evaluate: mode '%s' is not greedy or sampled" % mode)
    entry = entry or records.entry(name)
    if not entry:
        raise ToolError("evaluate: no run %s in %s" % (name, records.registry_path))
    variant_config = own_variant.check_unchanged(ws, name, entry, "evaluate")
    weights = os.path.realpath(weights)
    docs = docs or records.docs(name)
    os.makedirs(docs, exist_ok=True)
    # A failed attempt must not leave an older evaluation behind that passes for this one.
    for old in (os.path.join(docs, "evaluation.csv"), os.path.join(docs, "sampled", "evaluation.csv")):
        if os.path.exists(old):
            os.remove(old)
    for i, mode in enumerate(modes):
        out = docs if mode == "greedy" else os.path.join(docs, "sampled")
        os.makedirs(out, exist_ok=True)
        mode_port = port + (1 if mode == "sampled" else 0)
        start = time.time()
        log = "/tmp/hideseek_evaluate_%s_%s.log" % (name.replace("/", "_"), mode)
        # roslaunch exits 0 even when a required node dies: the evaluator's files are the verdict.
        ws.command(["roslaunch", "-p", mode_port, "hideseek_world", "evaluate.launch", "variant:=" + entry["variant"],
                    "game:=" + entry["game"], "policy:=" + weights, "greedy:=%s" % str(mode == "greedy").lower(),
                    "output_dir:=" + out] + (["variant_config:=" + variant_config] if variant_config else []),
                   env={"ROS_MASTER_URI": "http://localhost:%d" % mode_port}, log=log, check=False)
        table = os.path.join(out, "evaluation.csv")
        if not os.path.isfile(table) or os.path.getsize(table) == 0:
            raise ToolError("evaluate: %s (%s) failed, see %s" % (name, mode, log))
        # The table names the run, not the path of its weights on this machine.
        for f in (os.path.join(out, "evaluation.md"), table):
            with open(f) as fh:
                text = fh.read()
            with open(f, "w") as fh:
                fh.write(text.replace(weights, name))
        last = text.strip().splitlines()[-1].split(",")
        say("evaluate: %s (%s): %s %s (living steps, success; %d s)" % (name, mode, last[3], last[4],
                                                                         time.time() - start))
    trajectories(ws, name, entry, weights, os.path.join(docs, "trajectories.png"), say)


def trajectories(ws, name, entry, weights, png, say=print, seeker=None, title=None):
    """Six seeded episodes (seeds 0-5, greedy) drawn from above, against the variant's scripted
    seeker or the learned `seeker` (a seeker's checkpoint); the entry's `variant_config`, a variant file of one's
    own, where it names one."""
    variant, game, variant_config = entry["variant"], entry["game"], entry.get("variant_config")
    steps = "/tmp/hideseek_traj_%s.csv" % name.replace("/", "_")
    ws.command([ws.tool("hideseek_play", "play_episodes"), "--game", game, variant, weights, 0, 6, steps, "greedy"] +
               (["--seeker-policy", seeker] if seeker else []) +
               (["--variant-config", variant_config] if variant_config else []))
    ws.python("plot_trajectories.py", steps, ws.resolve(variant, "map_file", game, variant_config), png,
              title or "%s (%s, game %s), greedy, seeds 0-5" % (name, variant, game))
    say("evaluate: %s: %s" % (name, png))
