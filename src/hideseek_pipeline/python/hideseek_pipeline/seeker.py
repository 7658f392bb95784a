"""A learned seeker's evaluation: against each hider given, on seeds 0-99 through the ROS graph
(evaluate.launch, fp32, greedy), its capture rate and mean time to capture, beside the scripted
seeker's against the same hider. Written to OUT/seeker_evaluation.md and .csv; each game's
episodes.csv under OUT/<hider>/<seeker>/."""
import csv
import os
import re
import time

from hideseek_pipeline.workspace import ToolError

SCRIPTED = "scripted"


def capture_summary(episodes_csv):
    """Episodes, captures, capture rate and the mean time to capture (decision steps, over the
    captures) of an evaluation's episodes.csv (seed,living_steps,outcome)."""
    with open(episodes_csv) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise ToolError("seeker evaluation: %s holds no episode" % episodes_csv)
    caught = [int(r["living_steps"]) for r in rows if r["outcome"] == "captured"]
    living = [int(r["living_steps"]) for r in rows]
    return {"episodes": len(rows), "captures": len(caught), "capture_rate": len(caught) / len(rows),
            "mean_time_to_capture": sum(caught) / len(caught) if caught else float("nan"),
            "mean_living_steps": sum(living) / len(living)}


def play(ws, variant, game, hider, seeker, out, episodes, first_seed, port, greedy=True, variant_config=None):
    """One evaluation through evaluate.launch: `hider` (random, shipped, scripted/EVADER or a hider's
    checkpoint) against `seeker` (scripted, random or a seeker's checkpoint), into `out`. Returns its
    capture summary."""
    os.makedirs(out, exist_ok=True)
    table = os.path.join(out, "episodes.csv")
    if os.path.exists(table):
        os.remove(table)  # a failed attempt must not leave an older table that passes for this one
    seeker_args = ["seeker_mode:=" + seeker] if seeker in (SCRIPTED, "random") else ["seeker_policy:=" + seeker]
    log = os.path.join(out, "launch.log")
    ws.command(["roslaunch", "-p", port, "hideseek_world", "evaluate.launch", "variant:=" + variant, "game:=" + game,
                "policy:=" + hider, "episodes:=%d" % episodes, "first_seed:=%d" % first_seed,
                "greedy:=%s" % str(greedy).lower(), "output_dir:=" + out] + seeker_args +
               (["variant_config:=" + variant_config] if variant_config else []),
               env={"ROS_MASTER_URI": "http://localhost:%d" % port}, log=log, check=False)
    if not os.path.isfile(table) or os.path.getsize(table) == 0:
        raise ToolError("seeker evaluation: %s against %s failed, see %s" % (seeker, hider, log))
    return capture_summary(table)


def label(policy):
    """A short, file-safe name of a policy for folders and tables."""
    if policy in (SCRIPTED, "random", "shipped") or policy.startswith("scripted/"):
        return policy.replace("/", "_")
    return re.sub(r"[^A-Za-z0-9_.-]", "_", os.path.splitext(os.path.basename(policy))[0])


def evaluate_seeker(ws, variant, game, seeker, hiders, out, episodes=100, first_seed=0, port=11489, say=print,
                    variant_config=None, name=None):
    """The learned `seeker` and the scripted seeker against every hider of `hiders`; the table is
    titled `name` (a run's), or the seeker's file name."""
    game = game or ws.resolve(variant, "game", None, variant_config)
    rows = []
    # The launch files take a relative path from the workspace's root, where the tools run: absolute here.
    hiders = [h if h in ("random", "shipped") or h.startswith("scripted/") else os.path.realpath(h) for h in hiders]
    for hider in hiders:
        for who, policy in (("learned", os.path.realpath(seeker)), (SCRIPTED, SCRIPTED)):
            start = time.time()
            s = play(ws, variant, game, hider, policy, os.path.join(out, label(hider), who), episodes, first_seed,
                     port, variant_config=variant_config)
            # A checkpoint by its file's name: no path of this machine in the table.
            rows.append(dict(s, hider=label(hider) if os.path.isabs(hider) else hider, seeker=who))
            say("evaluate-seeker: %s seeker against %s: %d of %d captured, mean time to capture %.1f steps (%d s)"
                % (who, hider, s["captures"], s["episodes"], s["mean_time_to_capture"], time.time() - start))
    write_table(rows, out, "%s (variant %s, game %s), seeds %d-%d, greedy" % (
        name or label(seeker), variant, game, first_seed, first_seed + episodes - 1))
    return rows


def write_table(rows, out, title):
    keys = ["hider", "seeker", "episodes", "captures", "capture_rate", "mean_time_to_capture"]
    with open(os.path.join(out, "seeker_evaluation.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, keys, extrasaction="ignore", lineterminator="\n")
        w.writeheader()
        for r in rows:
            w.writerow(dict(r, capture_rate="%.3f" % r["capture_rate"],
                            mean_time_to_capture="%.1f" % r["mean_time_to_capture"]))
    lines = ["# Seeker evaluation: %s" % title, "",
             "Capture rate over the episodes, and the mean time to capture in decision steps (0.12 s each) over "
             "the captures (- without one); the learned seeker beside the scripted one, against the same hider.", "",
             "| hider | seeker | episodes | captures | capture rate | mean time to capture |",
             "| --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        mean = r["mean_time_to_capture"]
        lines.append("| %s | %s | %d | %d | %.1f %% | %s |" % (r["hider"], r["seeker"], r["episodes"], r["captures"],
                                                            100 * r["capture_rate"],
                                                            "-" if mean != mean else "%.1f" % mean))
    with open(os.path.join(out, "seeker_evaluation.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
