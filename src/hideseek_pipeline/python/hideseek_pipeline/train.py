"""One run: trained through train.launch (resuming when <runs>/<run> holds a checkpoint), its
weights exported to <runs>/<run>/policy.pt (outside the repository), its training log and learning
curve copied to docs/runs/<run>/, an entry in the run registry (variant, network, game, training
seed, steps, wall time, precision and the commit it trained with), then its evaluation.

A seeker's run (--role seeker) trains the seeker against a fixed hider (--opponent: the variant's
shipped hider of the game, as the records' registry ships it, by default), is recorded with its
role, and is evaluated as a seeker: its capture rate and mean time to capture against that hider
and the scripted evaders, beside the scripted seeker's against the same hiders (seeds 0-99,
docs/runs/<run>/seeker_evaluation.md).

A variant file of one's own (--variant-config FILE, its variant field VARIANT, a name the project's
variants do not take) trains, evaluates and analyses like a variant of the project. Its registry
entry records the file and its map with their sha256; the run's evaluation and analysis play that
file, refused once either has changed, and a checkpoint is resumed only on the files it trained on.
Such a run does not ship (play its weights with policy:=PATH)."""
import os
import re
import shutil
import subprocess
from dataclasses import dataclass
from typing import Optional

from hideseek_pipeline import own_variant
from hideseek_pipeline import seeker as seeker_evaluation
from hideseek_pipeline import sweep_config
from hideseek_pipeline.evaluate import evaluate
from hideseek_pipeline.workspace import Interrupted, ToolError

ROLES = ("hider", "seeker")
# The hiders a seeker's run is evaluated against besides its opponent: the scripted evaders.
EVADERS = ("scripted/backpedal", "scripted/flee", "scripted/hide", "scripted/lap")


@dataclass
class TrainOptions:
    variant: str
    seed: int = 0
    steps: int = 2_000_000
    runs_dir: str = "~/hideseek_runs"
    network: str = "ff"
    name: Optional[str] = None
    game: Optional[str] = None        # None: the default game (config/games.yaml)
    precision: str = "auto"
    num_arenas: Optional[int] = None  # None: train.launch's
    ppo_config: Optional[str] = None
    hider_threads: Optional[int] = None
    port: Optional[int] = None        # None: default_port(seed, network, role); the evaluation uses port + 1000
    eval_port: Optional[int] = None
    eval_modes: tuple = ("greedy",)
    paused_file: Optional[str] = None  # the seconds the sweep held the run paused, left out of wall_s
    ship: bool = False
    role: str = "hider"               # who learns: hider or seeker
    opponent: Optional[str] = None    # the fixed other side (None: train.launch's; a seeker's: the shipped hider)
    variant_config: Optional[str] = None  # a variant file of one's own, named `variant`

    def run_name(self, game):
        """--name, or the name the sweep gives the same run (sweep_config.run_name): the role, the
        game, the network and the budget, each where it is not the default (basic_v3_seed0,
        basic_v3_8m_seed0), so that no run takes the name of a run that differs from it."""
        return self.name or sweep_config.run_name(self.variant, self.seed, game, self.network, self.steps, self.role)


def default_port(seed, network="ff", role="hider"):
    """A run's ROS master port when --port is not given; its evaluation takes this + 1000 and + 1001.
    Outside every test's range (docs/testing.md, "Ports"), so a run started by hand never meets a test."""
    return 14000 + seed + (50 if network == "gru" else 0) + (25 if role == "seeker" else 0)


def _commit(ws):
    r = subprocess.run(["git", "describe", "--always", "--dirty", "--abbrev=12"], cwd=ws.root, capture_output=True,
                       text=True)
    return r.stdout.strip() if r.returncode == 0 else "unknown"


def _last_row(path):
    with open(path) as f:
        return f.read().strip().splitlines()[-1].split(",")


def command_line(o, name, root):
    """What reproduces the run, from the checkout `root`: the options that are not the defaults."""
    parts = ["hideseek_pipeline", "train", o.variant, "--seed", str(o.seed), "--steps", str(o.steps),
             "--network", o.network, "--name", name]
    for flag, value in (("--role", None if o.role == "hider" else o.role), ("--opponent", o.opponent),
                        ("--game", o.game), ("--precision", None if o.precision == "auto" else o.precision),
                        ("--num-arenas", o.num_arenas), ("--hider-threads", o.hider_threads),
                        ("--ppo-config", o.ppo_config and os.path.relpath(o.ppo_config, root)),
                        ("--variant-config", o.variant_config)):
        if value is not None:
            parts += [flag, str(value)]
    return " ".join(parts)


def train(ws, records, o, say=print):
    """`ws`: the Workspace that trains (its launch files, binaries and commit); `records`: the
    Records of the checkout that receives the run's files and registry entry."""
    variant_config = o.variant_config and own_variant.check_file(o.variant_config, o.variant,
                                                                 records.registry.variants(), "train")
    if not variant_config and o.variant not in records.registry.variants():
        raise ToolError("train: no variant '%s' in config/variants (a variant file of one's own: --variant-config "
                        "FILE)" % o.variant)
    if variant_config and o.ship:
        raise ToolError("train: --ship makes a run the shipped policy of a variant of the project; a run on a variant "
                        "file of one's own is played from its weights (roslaunch hideseek_world variant.launch.xml "
                        "variant:=%s variant_config:=FILE policy:=PATH)" % o.variant)
    game = o.game or ws.resolve(o.variant, "game", None, variant_config)
    fields = variant_config and own_variant.fingerprint(ws, o.variant, game, variant_config)
    if fields and not set(fields) <= set(getattr(records.registry, "RUN_KEYS", ())):
        raise ToolError("train: the registry reader of %s predates variant files of one's own (it would record the "
                        "run without its file): record into a checkout of today, or a folder without one "
                        "(--record-root)" % records.root)
    name = o.run_name(game)
    if not name or "/" in name or name.startswith("."):
        raise ToolError("train: the run's name '%s' must be a plain file name (no '/', not starting with '.')" % name)
    if o.ppo_config and not os.path.isfile(o.ppo_config):
        raise ToolError("train: --ppo-config: no file %s" % o.ppo_config)
    if o.role not in ROLES:
        raise ToolError("train: --role: '%s' is not one of %s" % (o.role, ", ".join(ROLES)))
    if o.ship and o.role != "hider":
        raise ToolError("train: --ship ships a hider's run as its variant's policy; a seeker's run is not shipped")
    opponent = _opponent(records, o, game)
    _refuse_another_run(records, name, o, game, fields)
    run = os.path.join(os.path.realpath(os.path.expanduser(o.runs_dir)), name)
    os.makedirs(run, exist_ok=True)
    own_variant.check_resume(run, fields, name, "train")
    port = o.port or default_port(o.seed, o.network, o.role)
    commit, commit_file = _commit(ws), os.path.join(run, "commit")
    lines = open(commit_file).read().splitlines() if os.path.isfile(commit_file) else []
    if not lines:
        open(commit_file, "w").write(commit + "\n")
    elif lines[0] != commit and "resumed at " + commit not in lines:
        open(commit_file, "a").write("resumed at %s\n" % commit)
        say("train: %s started at commit %s, resumes at %s" % (name, lines[0], commit))
    args = ["roslaunch", "-p", port, "hideseek_world", "train.launch", "variant:=" + o.variant, "game:=" + game,
            "seed:=%d" % o.seed, "steps:=%d" % o.steps, "network:=" + o.network, "precision:=" + o.precision,
            "output_dir:=" + run] + (["role:=" + o.role] if o.role != "hider" else []) + \
        (["opponent:=" + opponent] if opponent else []) + (["variant_config:=" + variant_config] if fields else [])
    for key, value in (("num_arenas", o.num_arenas), ("hider_threads", o.hider_threads),
                       ("ppo_config", o.ppo_config and os.path.realpath(o.ppo_config))):
        if value is not None:
            args.append("%s:=%s" % (key, value))
    say("train: %s (%svariant %s, network %s, game %s, training seed %d), %d steps, into %s (log: %s/launch.log)"
        % (name, "a seeker against %s, " % opponent if o.role == "seeker" else "", o.variant, o.network, game, o.seed,
           o.steps, run, run))
    launch_log = os.path.join(run, "launch.log")
    ws.command(args, env={"ROS_MASTER_URI": "http://localhost:%d" % port}, log=launch_log, check=False,
               through_interrupt=True)
    # roslaunch exits 0 even when the hider dies: record only a run that trained all its steps.
    log_csv = os.path.join(run, "training_log.csv")
    row = _last_row(log_csv) if os.path.isfile(log_csv) and os.path.getsize(log_csv) else []
    trained = int(row[1]) if len(row) > 2 and row[1].isdigit() else 0
    if trained < o.steps:
        again = "; the same command resumes it from its checkpoint" if os.path.isfile(
            os.path.join(run, "checkpoint.pt")) else ""
        raise (Interrupted if ws.interrupted else ToolError)(
            "train: %s stopped at %d of %d steps (see %s); nothing recorded%s" % (name, trained, o.steps, launch_log,
                                                                                 again))
    ws.command([ws.tool("hideseek_hider", "export_policy"), os.path.join(run, "checkpoint.pt"),
                os.path.join(run, "policy.pt")])
    docs = records.docs(name)
    os.makedirs(docs, exist_ok=True)
    shutil.copyfile(log_csv, os.path.join(docs, "training_log.csv"))
    ws.python("plot_learning_curve.py", os.path.join(docs, "training_log.csv"), os.path.join(docs, "learning_curve.png"),
              "%s%s, network %s, game %s, training seed %d, %d steps" % (
                  o.variant, ", the seeker" if o.role == "seeker" else "", o.network, game, o.seed, trained))
    record(records, name, o, game, trained, row, run, launch_log, ws.root, fields)
    say("train: %s recorded in %s; weights in %s" % (name, records.registry_path, os.path.join(run, "policy.pt")))
    if o.role == "seeker":
        seeker_evaluation.evaluate_seeker(ws, o.variant, game, os.path.join(run, "policy.pt"),
                                          [opponent] + [e for e in EVADERS if e != opponent], docs,
                                          port=o.eval_port or port + 1000, say=say, name=name,
                                          variant_config=variant_config)
        return name
    evaluate(ws, records, name, os.path.join(run, "policy.pt"), o.eval_modes, o.eval_port or port + 1000, say)
    if o.ship:
        records.registry.ship(name, os.path.join(run, "policy.pt"), records.registry_path)
        say("train: %s shipped as the %s policy" % (name, o.variant))
    return name


def _sweep_runs(records):
    """The names of the runs that config/sweep.yaml of the records' checkout trains (done or not);
    none where it has no such file or cannot read it (the sweep itself says what is wrong)."""
    path = os.path.join(records.root, "config", "sweep.yaml")
    if not os.path.isfile(path):
        return set()
    reg = records.registry
    environ = {k: v for k, v in os.environ.items() if k != "SWEEP_PHASES"}  # every phase, not a chosen few
    try:
        return {r.name for r in sweep_config.load(path, reg.variants(), reg.paper_order(), reg.default_game(),
                                                  environ).runs()}
    except (sweep_config.ConfigError, OSError):
        return set()


def _refuse_another_run(records, name, o, game, fields=None):
    """A run keeps what it was recorded with: a name that the registry holds for another game,
    variant (or version of its variant file), role, network, training seed or budget is not trained
    (or resumed, or overwritten) as this run; and an unnamed run does not take the name of one of the
    sweep's runs (recorded or still to train), whose records Table 2 and the claims count."""
    entry = records.entry(name) or {}
    if not o.name and (str(entry.get("note", "")).startswith(records.registry.SWEEP_NOTE)
                       or name in _sweep_runs(records)):
        raise ToolError("train: %s is a run of the sweep (config/sweep.yaml), which trains and records it: give "
                        "yours a name of its own with --name" % name)
    if not entry:
        return
    for field, recorded, here in (("game", entry.get("game"), game), ("variant", entry.get("variant"), o.variant),
                                  ("role", entry.get("role", "hider"), o.role),
                                  ("network", records.registry.run_network(name, entry), o.network),
                                  ("training seed", entry.get("training_seed"), o.seed),
                                  ("variant file sha256", entry.get("variant_sha256"),
                                   (fields or {}).get("variant_sha256")),
                                  ("map sha256", entry.get("map_sha256"), (fields or {}).get("map_sha256"))):
        if recorded is not None and str(recorded) != str(here):
            raise ToolError("train: %s is recorded as a run of %s %s (policies/policies.yaml); this is %s %s: name "
                            "the run otherwise" % (name, field, recorded, field, here))
    if entry.get("steps") and not records.registry.of_budget(entry["steps"], o.steps):
        raise ToolError("train: %s is recorded with %s steps trained (policies/policies.yaml); this run's budget is "
                        "%d steps: name the run otherwise (a recorded run is not extended or cut under its name)"
                        % (name, entry["steps"], o.steps))


def _opponent(records, o, game):
    """What train.launch's `opponent` gets: for a seeker, the hider it trains against, with `shipped`
    (the default) taken from the records' registry, so that a run trained in a pinned worktree meets
    the hider shipped now; a checkpoint as an absolute path. None: train.launch's default."""
    opponent = o.opponent or ("shipped" if o.role == "seeker" else None)
    if opponent == "shipped" and o.role == "seeker":
        name, weights = records.registry.shipped(o.variant, "ff", game, records.registry_path)
        if not weights or not os.path.isfile(weights):
            raise ToolError("train: no hider of %s on game %s ships in %s (or its weights are missing): name the "
                            "seeker's --opponent (random, scripted/EVADER or a hider's checkpoint)"
                            % (o.variant, game, records.registry_path))
        return weights
    if not opponent:
        return None
    named = ("random",) + (EVADERS if o.role == "seeker" else ("scripted",))
    if opponent in named:
        return opponent
    if os.path.isfile(opponent):
        return os.path.realpath(opponent)
    if opponent.endswith(".pt"):
        raise ToolError("train: --opponent: no file %s" % opponent)
    raise ToolError("train: --opponent %s: a %s's opponent is one of %s, or a checkpoint (.pt)"
                    % (opponent, o.role, ", ".join(("shipped",) + named if o.role == "seeker" else named)))


def record(records, name, o, game, trained, row, run, launch_log, root, fields=None):
    # The precision the hider chose, from its last start-up line ("... on cpu in auto: bf16, ...").
    chosen = re.findall(r"PPO, network [a-z]+, on \S+ in [^,]*", open(launch_log).read())
    precision = (re.findall(r"bf16|fp32", chosen[-1]) or ["unknown"])[0] if chosen else "unknown"
    paused = 0
    if o.paused_file and os.path.isfile(o.paused_file) and os.path.getsize(o.paused_file):
        text = open(o.paused_file).read().split()[0].split(".")[0]
        if not text.isdigit():
            raise ToolError("train: %s must hold a number of seconds >= 0, holds '%s'" % (o.paused_file, text))
        paused = int(text)
    commits = "; ".join(line for line in open(os.path.join(run, "commit")).read().splitlines() if line)
    records.registry.record(name, {
        "variant": o.variant, "network": o.network, "game": game, "training_seed": o.seed, "steps": trained,
        "wall_s": int(float(row[2])) - paused, "paused_s": paused or None, "precision": precision, "commit": commits,
        "log": "docs/runs/%s/training_log.csv" % name, "curve": "docs/runs/%s/learning_curve.png" % name,
        "command": command_line(o, name, root), "role": None if o.role == "hider" else o.role, **(fields or {})},
        records.registry_path)
