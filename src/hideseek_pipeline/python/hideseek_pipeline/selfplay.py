"""Hider-seeker self-play: the two learners alternate, generation after generation. In generation
k the seeker trains `steps` more steps against a hider drawn from the hider pool (every hider
generation before k, and the random hider), then the hider trains `steps` more against a seeker
drawn from the seeker pool (every seeker generation up to k, and the random seeker): a pool, as
fictitious self-play keeps one, so that the two do not chase each other in a cycle. The draw is
the other side's latest generation with probability `latest_share`, otherwise uniform over the
whole pool (0: uniform alone, as the sweep's first demonstration drew; with few generations a
uniform draw meets the random policy often: 6 of its 8 draws). Each side
resumes its own run (OUT/<role>/checkpoint.pt) with a constant learning rate (OUT/ppo.yaml: the
PPO file with its annealing off, so that no generation's schedule depends on how many follow).
The opponent samples its actions, as it did in training (a draw that depends only on the episode
seed and the step).

Every generation is saved (OUT/generations/<role>_gNNN.pt, exported weights) and registered in
OUT/generations.yaml like a run (role, variant, game, steps, wall time, its opponent, the commit).
The draws depend only on the seed and the generation, so a stopped self-play resumes where it
stopped: finished generations are kept, a generation cut off resumes from its checkpoint, and the
same seeds replay the same generations (one learner thread). Each generation's training plays
episodes of its own (seeds SEED + 100000 (k - 1) on), not the same openings again.

Each training is a train.launch of its own, on its own ROS master (port, port + 1), as the sweep
runs its runs."""
import csv
import os
import random
import shutil
import subprocess
from dataclasses import dataclass
from typing import Optional

import yaml

from hideseek_pipeline import seeker as seeker_evaluation
from hideseek_pipeline.queue import PAUSES_LOG, read_lines, write_atomically
from hideseek_pipeline.workspace import ToolError

ROLES = ("seeker", "hider")  # the order within a generation
GENERATION_SEEDS = 100_000  # episode seeds a generation's training may use before the next one's start


@dataclass
class SelfPlayOptions:
    out: str
    variant: str = "basic"
    game: Optional[str] = None
    generations: int = 4
    steps: int = 250_000      # per side and generation
    seed: int = 0
    latest_share: float = 0.5  # the draw's chance of the other side's latest generation (draw())
    num_arenas: Optional[int] = None
    hider_threads: Optional[int] = None
    precision: str = "auto"
    ppo_config: Optional[str] = None  # default: the workspace's config/ppo.yaml, annealing off
    variant_config: Optional[str] = None  # a variant file of one's own (tests)
    port: int = 14900


def world_seed(seed, generation):
    """The episode seeds of a generation's training start here: each generation plays new episodes
    (a resumed run restores its own random generator; the seed moves only the world's episodes)."""
    return seed + GENERATION_SEEDS * (generation - 1)


def draw(pool, seed, generation, role, latest_share=0.0):
    """The opponent of `role` in `generation`, a pure function of the seed, the generation and the
    role: the pool's last (latest) entry with probability `latest_share`, otherwise uniform over the
    pool (with 0, the draw is the uniform one alone, as it was before the share existed)."""
    rng = random.Random("%d/%d/%s" % (seed, generation, role))
    if latest_share > 0 and len(pool) > 1 and rng.random() < latest_share:
        return pool[-1]
    return pool[rng.randrange(len(pool))]


def pools(generations, role, upto):
    """What `role` may train against in generation `upto`: the random policy of the other side and
    every saved generation of it before this point (the seeker trains first, so the hider of
    generation k meets the seeker of k too)."""
    other = "hider" if role == "seeker" else "seeker"
    last = upto - 1 if role == "seeker" else upto
    return ["random"] + [g["checkpoint"] for g in generations if g["role"] == other and g["generation"] <= last]


def constant_rate_ppo(source, out):
    with open(source) as f:
        ppo = yaml.safe_load(f)
    ppo["anneal_learning_rate"] = False
    path = os.path.join(out, "ppo.yaml")
    with open(path, "w") as f:
        f.write("# %s with a constant learning rate: self-play's generations resume one run each\n" % source)
        yaml.safe_dump(ppo, f, sort_keys=False)
    return path


def train_generation(ws, o, game, role, generation, opponent, ppo):
    """`role` trains up to generation x steps (its run resumes), against `opponent`."""
    run = os.path.join(o.out, role)
    os.makedirs(run, exist_ok=True)
    port = o.port + (0 if role == "seeker" else 1)
    args = ["roslaunch", "-p", port, "hideseek_world", "train.launch", "role:=" + role, "variant:=" + o.variant,
            "game:=" + game, "seed:=%d" % world_seed(o.seed, generation), "steps:=%d" % (generation * o.steps),
            "precision:=" + o.precision,
            "output_dir:=" + run, "ppo_config:=" + ppo, "opponent_greedy:=false",
            "opponent:=" + (opponent if opponent == "random" else os.path.join(o.out, opponent))]
    for key, value in (("num_arenas", o.num_arenas), ("hider_threads", o.hider_threads),
                       ("variant_config", o.variant_config)):
        if value is not None:
            args.append("%s:=%s" % (key, value))
    log = os.path.join(run, "launch_g%03d.log" % generation)
    ws.command(args, env={"ROS_MASTER_URI": "http://localhost:%d" % port}, log=log, check=False)
    table = os.path.join(run, "training_log.csv")
    rows = open(table).read().strip().splitlines() if os.path.isfile(table) else []
    last = rows[-1].split(",") if len(rows) > 1 else []
    if not last or int(last[1]) < generation * o.steps:
        raise ToolError("selfplay: the %s of generation %d stopped before its %d steps (see %s)"
                        % (role, generation, generation * o.steps, log))
    return int(last[1]), float(last[2])


def save_generation(ws, o, game, role, generation, opponent, steps, wall_s):
    name = "generations/%s_g%03d.pt" % (role, generation)
    os.makedirs(os.path.join(o.out, "generations"), exist_ok=True)
    ws.command([ws.tool("hideseek_hider", "export_policy"), os.path.join(o.out, role, "checkpoint.pt"),
                os.path.join(o.out, name)])
    commit = subprocess.run(["git", "describe", "--always", "--dirty", "--abbrev=12"], cwd=ws.root,
                            capture_output=True, text=True).stdout.strip() or "unknown"
    return {"role": role, "generation": generation, "checkpoint": name, "variant": o.variant, "game": game,
            "training_seed": o.seed, "latest_share": o.latest_share, "steps": steps, "wall_s": round(wall_s), "opponent": opponent, "commit": commit,
            "log": "%s/training_log.csv" % role}


def generation_seconds(generations):
    """Each generation's own training seconds: a side resumes one run, whose wall_s counts every
    generation of that side so far, so a generation's time is the difference from its side's last."""
    last, out = {}, []
    for g in generations:
        total = float(g.get("wall_s") or 0)
        out.append(total - last.get(g["role"], 0.0))
        last[g["role"]] = total
    return out


def generation_pauses(out, generations):
    """The seconds the sweep held each generation paused: a pause its queue booked in
    OUT/paused.log belongs to the first generation saved after the pause ended, a generation's time
    of saving being its exported weights' (OUT/generations/...); no generation is saved during a
    pause, which stops the training. Zeros where the log or the weights are not on this machine."""
    held = [0] * len(generations)
    try:
        saved = [os.path.getmtime(os.path.join(out, g["checkpoint"])) for g in generations]
    except (OSError, KeyError, TypeError):
        return held
    order = sorted(range(len(generations)), key=lambda i: saved[i])
    for line in read_lines(os.path.join(out, PAUSES_LOG)):
        fields = line.split()
        try:
            ended, seconds = float(fields[0]), int(fields[1])
        except (IndexError, ValueError):
            continue  # a line cut short as it was written
        after = next((i for i in order if saved[i] >= ended), None)
        if after is not None:  # else: held after the last saved generation
            held[after] += seconds
    return held


def training_seconds(out, generations):
    """Each generation's own training seconds (generation_seconds), less the pauses that held it."""
    return [max(s - p, 0.0) for s, p in zip(generation_seconds(generations), generation_pauses(out, generations))]


def require_generations(o):
    """Every generation of both sides saved, or a ToolError naming what is missing (the records
    train nothing)."""
    saved = {(g["role"], g["generation"]) for g in load_generations(o.out)}
    missing = ["%s_g%03d" % (role, k) for k in range(1, o.generations + 1) for role in ROLES if (role, k) not in saved]
    if missing:
        raise ToolError("selfplay --record: %s has not saved %s: train them first (selfplay without --record)"
                        % (o.out, ", ".join(missing)))


def load_generations(out):
    path = os.path.join(out, "generations.yaml")
    if not os.path.isfile(path):
        return []
    with open(path) as f:
        return (yaml.safe_load(f) or {}).get("generations", [])


def write_generations(out, generations):
    write_atomically(os.path.join(out, "generations.yaml"),
                     "# hideseek_pipeline selfplay: every saved generation, like a run of the registry\n" +
                     yaml.safe_dump({"generations": generations}, sort_keys=False))


def selfplay(ws, o, say=print):
    """Trains the generations not yet saved; returns every generation's entry."""
    os.makedirs(o.out, exist_ok=True)
    o.out = os.path.realpath(o.out)
    game = o.game or ws.resolve(o.variant, "game", None, o.variant_config)
    generations = load_generations(o.out)
    drawn = {float(g.get("latest_share", 0.0)) for g in generations}  # saved before the share: uniform
    if drawn - {o.latest_share}:
        raise ToolError("selfplay: %s drew its generations with latest share %s: resume it with --latest-share "
                        "%s (latest_share:=%s), not %s" % (o.out, ", ".join(map(str, sorted(drawn))),
                                                           min(drawn), min(drawn), o.latest_share))
    done = {(g["role"], g["generation"]) for g in generations}
    ppo = None  # written once a generation is left to train
    for generation in range(1, o.generations + 1):
        for role in ROLES:
            if (role, generation) in done:
                continue
            ppo = ppo or constant_rate_ppo(o.ppo_config or os.path.join(ws.root, "config", "ppo.yaml"), o.out)
            opponent = draw(pools(generations, role, generation), o.seed, generation, role, o.latest_share)
            say("selfplay: generation %d: the %s trains to %d steps against %s" % (
                generation, role, generation * o.steps, opponent))
            steps, wall_s = train_generation(ws, o, game, role, generation, opponent, ppo)
            generations.append(save_generation(ws, o, game, role, generation, opponent, steps, wall_s))
            write_generations(o.out, generations)
    return generations


def copy_logs(o, dest):
    """The two learners' training logs beside the cross-play table (the learning curves)."""
    for role in ROLES:
        log = os.path.join(o.out, role, "training_log.csv")
        if os.path.isfile(log):
            shutil.copyfile(log, os.path.join(dest, "%s_training_log.csv" % role))


def crossplay(ws, o, episodes=100, first_seed=0, say=print):
    """Every saved hider generation (and the random hider) against every saved seeker generation
    (and the scripted and random seekers): capture rate and mean living steps, through
    evaluate.launch (greedy, fp32). Written to OUT/crossplay/crossplay.csv, .md and .png, with the
    two learners' training logs and their learning curves."""
    generations = load_generations(o.out)
    game = generations[0]["game"] if generations else (o.game or ws.resolve(o.variant, "game", None, o.variant_config))
    hiders = ["random"] + [g["checkpoint"] for g in generations if g["role"] == "hider"]
    seekers = ["scripted", "random"] + [g["checkpoint"] for g in generations if g["role"] == "seeker"]
    dest = os.path.join(o.out, "crossplay")
    rows = []
    for hider in hiders:
        for seeker in seekers:
            where = os.path.join(dest, seeker_evaluation.label(hider), seeker_evaluation.label(seeker))
            s = _played(os.path.join(where, "episodes.csv"), episodes, first_seed)  # a resumed one keeps its pairs
            if s is None:
                s = seeker_evaluation.play(ws, o.variant, game, _path(o, hider), _path(o, seeker), where, episodes,
                                           first_seed, o.port + 2, variant_config=o.variant_config)
            rows.append(dict(s, hider=seeker_evaluation.label(hider), seeker=seeker_evaluation.label(seeker)))
            say("crossplay: %s against %s: %d of %d captured, %.1f living steps" % (
                rows[-1]["seeker"], rows[-1]["hider"], s["captures"], s["episodes"], s["mean_living_steps"]))
    title = "%s (game %s), seeds %d-%d, greedy" % (o.variant, game, first_seed, first_seed + episodes - 1)
    write_crossplay(rows, dest, title)
    ws.python("plot_crossplay.py", os.path.join(dest, "crossplay.csv"), os.path.join(dest, "crossplay.png"),
              "cross-play: " + title)
    copy_logs(o, dest)
    plot_curves(ws, dest, generations, o.variant, game)
    say("crossplay: %s" % os.path.join(dest, "crossplay.md"))
    return rows


def plot_curves(ws, dest, generations, variant, game):
    """Both learners' curves (DEST/<role>_training_log.csv) into DEST/learning_curves.png, a dashed
    line where each generation but the last ends, and each side's opponents in the title."""
    curves = []
    for role in ROLES:
        curves += ["--run", role, os.path.join(dest, "%s_training_log.csv" % role)]
    hiders = [g for g in generations if g["role"] == "hider"]
    marks = []
    for g in hiders[:-1]:
        marks += ["--mark", str(g["steps"])]
    opponents = "; ".join("the %s's opponents: %s" % (role, ", ".join(
        seeker_evaluation.label(g["opponent"]) for g in generations if g["role"] == role and "opponent" in g))
        for role in ROLES)
    ws.python("plot_learning_curve.py", *curves, *marks, "--output", os.path.join(dest, "learning_curves.png"),
              "--title", "self-play, %s (game %s): both learners, %d generations (dashed: where one ends)\n%s"
              % (variant, game, len(hiders), opponents))


def _played(table, episodes, first_seed=0):
    """The capture summary of a pair played to the end before (every seed of first_seed ..
    first_seed + episodes - 1, each with its outcome), or None."""
    try:
        with open(table) as f:
            rows = list(csv.DictReader(f))
        whole = (sorted(int(r["seed"]) for r in rows) == list(range(first_seed, first_seed + episodes))
                 and all(r["outcome"] in ("captured", "survived") and r["living_steps"].isdigit() for r in rows))
        return seeker_evaluation.capture_summary(table) if whole else None
    except (OSError, ToolError, KeyError, ValueError, TypeError, AttributeError):  # none, or cut off mid-write
        return None


def _path(o, policy):
    return policy if policy in ("random", "scripted") else os.path.join(o.out, policy)


def write_crossplay(rows, dest, title):
    keys = ["hider", "seeker", "episodes", "captures", "capture_rate", "mean_living_steps"]
    with open(os.path.join(dest, "crossplay.csv"), "w") as f:
        f.write(",".join(keys) + "\n")
        for r in rows:
            f.write("%s,%s,%d,%d,%.3f,%.1f\n" % tuple(r[k] for k in keys))
    seekers = list(dict.fromkeys(r["seeker"] for r in rows))
    hiders = list(dict.fromkeys(r["hider"] for r in rows))
    cell = {(r["hider"], r["seeker"]): r for r in rows}
    lines = ["# Cross-play: %s" % title, "",
             "Each cell: the seeker's capture rate, and the hider's mean living steps, over the episodes.", "",
             "| hider \\ seeker | " + " | ".join(seekers) + " |", "| --- |" + " --- |" * len(seekers)]
    for h in hiders:
        lines.append("| %s | " % h + " | ".join("%.0f %%, %.0f" % (100 * cell[h, s]["capture_rate"],
                                                                   cell[h, s]["mean_living_steps"])
                                                 for s in seekers) + " |")
    with open(os.path.join(dest, "crossplay.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


# ---- the records of a self-play (the sweep's self-play phase) ------------------------------------

RECORDED = ("crossplay.csv", "crossplay.md", "crossplay.png", "learning_curves.png", "hider_training_log.csv",
            "seeker_training_log.csv")


def record(ws, records, o, name, episodes=100, say=print):
    """A finished self-play into the records' docs/runs/<name>/: its generations (generations.yaml,
    no weights), the cross-play table and figure, both learning curves, and its first and last
    hider against the scripted seeker (seeds 0-99, greedy, with trajectories; the last one also
    analysed as a run is: probes, states, t-SNE), then selfplay.md, which sets the last hider beside
    the variant's hiders trained only against the scripted seeker. selfplay.md comes last: it is
    what marks the self-play recorded."""
    from hideseek_pipeline.analyze import analyze_run
    from hideseek_pipeline.evaluate import evaluate, trajectories
    generations = load_generations(o.out)
    hiders = [g for g in generations if g["role"] == "hider"]
    if not hiders:
        raise ToolError("selfplay: %s holds no hider generation to record" % o.out)
    dest = records.docs(name)
    os.makedirs(dest, exist_ok=True)
    for f in RECORDED:
        shutil.copyfile(os.path.join(o.out, "crossplay", f), os.path.join(dest, f))
    shutil.copyfile(os.path.join(o.out, "generations.yaml"), os.path.join(dest, "generations.yaml"))
    game = generations[0]["game"]
    entry = {"variant": o.variant, "network": "ff", "game": game, "variant_config": o.variant_config}
    against_scripted = {}
    seekers = {g["generation"]: os.path.join(o.out, g["checkpoint"]) for g in generations if g["role"] == "seeker"}
    for g in (hiders[0], hiders[-1]) if len(hiders) > 1 else hiders[:1]:
        label = seeker_evaluation.label(g["checkpoint"])
        folder = os.path.join(dest, label)
        weights = os.path.join(o.out, g["checkpoint"])
        if g["generation"] not in seekers:
            raise ToolError("selfplay: %s lists no seeker of generation %d beside %s"
                            % (os.path.join(o.out, "generations.yaml"), g["generation"], g["checkpoint"]))
        # the self-play's own games: this generation's hider against its seeker
        trajectories(ws, "%s_g%03d" % (name, g["generation"]), entry, weights,
                     os.path.join(dest, "trajectories_g%03d.png" % g["generation"]), say,
                     seeker=seekers[g["generation"]],
                     title="%s, generation %d: the hider against the seeker (%s, game %s), greedy, seeds 0-5"
                     % (name, g["generation"], o.variant, game))
        evaluate(ws, records, "%s/%s" % (name, label), weights, ("greedy",), o.port + 2, say, entry=entry,
                 docs=folder)
        against_scripted[label] = records.registry.greedy_living_steps("%s/%s" % (name, label), records.root)
        if g is hiders[-1]:
            analyze_run(ws, records, "%s_%s" % (name, label), weights, say=say, entry=entry,
                        out=os.path.join(folder, "analysis"))
    scripted_only = _scripted_only(records, o.variant, game)
    last = seeker_evaluation.label(hiders[-1]["checkpoint"])
    beside = behaviour_beside(last, os.path.join(dest, last, "analysis"),
                              {run: records.docs(run, "analysis") for run in scripted_only})
    text = summary(name, o, game, generations, against_scripted, scripted_only, episodes) + beside
    with open(os.path.join(dest, "selfplay.md"), "w") as f:
        f.write(text)
    say("selfplay: recorded into %s" % dest)


def _scripted_only(records, variant, game):
    """The variant's hiders of this game trained only against the scripted seeker: the sweep's
    first draws of 2M steps, feed-forward, and their greedy living steps on seeds 0-99."""
    return dict(sorted(records.registry.first_draws(variant, "ff", game, records.registry_path, records.root,
                                                    records.note, 2_000_000).items()))


# The paper's analysis of a hider, as the per-run step writes it into analysis/: (label, file, how to
# read the value, format).
MEASURES = (
    ("mean living steps", "behaviour", "mean_living_steps", "%.1f"),
    ("success rate", "behaviour", "success_rate", "%.2f"),
    ("share of steps walking backward", "behaviour", "backward_share", "%.2f"),
    ("share of steps seeing the seeker (S = 1)", "behaviour", "sees_seeker_share", "%.2f"),
    ("share of steps seen by it (H = 1)", "behaviour", "seen_share", "%.2f"),
    ("share of steps in S1 H1 (each sees the other)", "states", (1, 1), "%.2f"),
    ("share of steps in S0 H0 (neither sees the other)", "states", (0, 0), "%.2f"),
    ("line-of-sight breaks per 100 steps", "behaviour", "line_of_sight_breaks_per_100", "%.2f"),
    ("distance swings of 1 m or more per 100 steps", "behaviour", "distance_swings_per_100", "%.2f"),
    ("probe S: balanced accuracy over random init", "probes", "S", "%+.3f"),
    ("probe H: balanced accuracy over random init", "probes", "H", "%+.3f"),
)


def analysis_measures(folder):
    """MEASURES' values from a hider's analysis folder (behaviour.csv, states.csv, probes.csv), None
    for each one whose file is missing or lacks it."""
    def rows(kind):
        try:
            with open(os.path.join(folder, kind + ".csv")) as f:
                return list(csv.DictReader(f))
        except OSError:
            return []
    tables = {kind: rows(kind) for kind in ("behaviour", "states", "probes")}
    values = {}
    for label, kind, key, _ in MEASURES:
        t = tables[kind]
        try:
            if kind == "behaviour":
                values[label] = float(t[0][key])
            elif kind == "states":
                values[label] = (sum(float(r["frequency"]) for r in t if (int(r["S"]), int(r["H"])) == key)
                                 if t else None)
            else:
                values[label] = float(next(r["gain_over_random_init"] for r in t
                                           if r["representation"] == "trained" and r["target"] == key))
        except (IndexError, KeyError, ValueError, StopIteration):
            values[label] = None
    return values


def behaviour_beside(last, last_folder, others):
    """The paper's analysis of the last self-play hider (label `last`, its analysis folder) beside
    that of each hider trained only against the scripted seeker (run -> analysis folder): a section
    of selfplay.md."""
    columns = [(last + " (self-play)", analysis_measures(last_folder))]
    columns += [(run, analysis_measures(folder)) for run, folder in others.items()]
    lines = ["", "## The paper's analysis of the last hider", "",
             "The per-run analysis (100 greedy rollouts against the scripted seeker on seeds 10000-10099, and the "
             "probes on the probe set; [%s/analysis/](%s/analysis/)) of the last self-play hider, beside the same "
             "analysis of the hiders trained only against the scripted seeker. A probe's figure is its balanced "
             "accuracy minus that of five randomly initialised networks; `-`: not in that run's analysis."
             % (last, last), "",
             "| measure | " + " | ".join(c for c, _ in columns) + " |", "| --- |" + " --- |" * len(columns)]
    for label, _, _, fmt in MEASURES:
        lines.append("| %s | " % label + " | ".join("-" if v[label] is None else fmt % v[label]
                                                    for _, v in columns) + " |")
    return "\n".join(lines) + "\n"


def summary(name, o, game, generations, against_scripted, scripted_only, episodes):
    hiders = [g for g in generations if g["role"] == "hider"]
    lines = ["# Self-play: %s (variant %s, game %s, seed %d)" % (name, o.variant, game, o.seed), "",
             "The seeker and the hider trained in turn, each against a draw from a pool of the other side's past "
             "generations and its random policy, %d steps a side and generation. Cross-play: every saved hider "
             "against every saved seeker, seeds 0-%d, greedy ([crossplay.md](crossplay.md), "
             "[crossplay.png](crossplay.png)); both learning curves: [learning_curves.png](learning_curves.png). "
             "The first and last generation's hider against the same generation's seeker, seeds 0-5, greedy: %s."
             % (o.steps, episodes - 1, ", ".join("[trajectories_g%03d.png](trajectories_g%03d.png)" % (k, k)
                                                   for k in sorted({hiders[0]["generation"],
                                                                    hiders[-1]["generation"]}))), "",
             "| generation | role | steps | trained against | training time (min), pauses left out |",
             "| --- | --- | --- | --- | --- |"]
    for g, seconds in zip(generations, training_seconds(o.out, generations)):
        lines.append("| %d | %s | %d | %s | %.0f |" % (g["generation"], g["role"], g["steps"],
                                                       seeker_evaluation.label(g["opponent"]), seconds / 60.0))
    lines += ["", "## Against the scripted seeker", "",
              "Each hider generation named here, against the variant's scripted seeker on seeds 0-99, greedy "
              "(its folder: evaluation.md, trajectories.png; the last one's analysis/), beside the hiders of this "
              "variant and game trained only against the scripted seeker (the sweep's first draws of 2M steps "
              "recorded when this was written).", "",
              "| hider | trained | mean living steps, seeds 0-99 |", "| --- | --- | --- |"]
    for label, living in against_scripted.items():
        lines.append("| [%s](%s/evaluation.md) | self-play | %.1f |" % (label, label, living))
    for run, living in scripted_only.items():
        lines.append("| %s | against the scripted seeker only | %.1f |" % (run, living))
    if scripted_only and against_scripted:
        last = list(against_scripted.values())[-1]
        lo, hi = min(scripted_only.values()), max(scripted_only.values())
        verdict = ("longer than every one" if last > hi else "shorter than every one" if last < lo
                   else "within their range")
        lines += ["", "The last self-play hider lives %.1f steps against the scripted seeker: %s of the %d hiders "
                  "trained only against it (%.1f to %.1f). One self-play seed: no interval." % (
                      last, verdict, len(scripted_only), lo, hi)]
    elif not scripted_only:
        lines += ["", "No hider of %s trained only against the scripted seeker on game %s is recorded yet: the "
                  "comparison waits for the sweep's first draws." % (o.variant, game)]
    return "\n".join(lines) + "\n"
