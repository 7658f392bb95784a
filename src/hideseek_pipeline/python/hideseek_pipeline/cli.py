"""hideseek_pipeline: the project's pipeline, one command with subcommands.

  hideseek_pipeline train VARIANT [...]    one run (--name RUN where the sweep's name is taken): trained,
                                           exported, recorded, evaluated
  hideseek_pipeline evaluate RUN WEIGHTS   a recorded run's evaluation (seeds 0-99) and trajectories
  hideseek_pipeline analyze RUN WEIGHTS    a recorded run's probes, t-SNE and behaviour
  hideseek_pipeline evaluate-seeker SEEKER  a learned seeker's captures, beside the scripted seeker's
  hideseek_pipeline selfplay OUT           hider-seeker self-play in generations; --crossplay: the table;
                                           --record RUN: the table and the records (docs/runs/RUN/)
  hideseek_pipeline test                   make test: every test, ending "N passed, M failed"; the sweep held
  hideseek_pipeline bench                  make bench: this machine's throughput, the sweep held meanwhile
  hideseek_pipeline report                 make reproduce: Table 2, the claims and the figures in docs/report
  hideseek_pipeline sweep status           the sweep's phases and every run's state
  hideseek_pipeline sweep start            the queue in the background (make sweep)
  hideseek_pipeline sweep hours            machine-hours per phase, from the registry
  hideseek_pipeline sweep hold CMD ...     CMD with the queue paused, resumed after

Each subcommand answers --help.
"""
import argparse
import os
import subprocess
import sys

from hideseek_pipeline import analyze, control, evaluate, runner, seeker, selfplay, sweep_config, tests, train
from hideseek_pipeline.measure import MeasureError
from hideseek_pipeline.queue import Sweep, SweepError
from hideseek_pipeline.records import Records
from hideseek_pipeline.workspace import Interrupted, ToolError, Workspace

SWEEP_COMMANDS = {
    "start": "start the queue in the background and return (it builds the first phase's worktree first, a later "
             "phase's when its first run could start); a queue already running is left alone",
    "run": "the queue in the foreground (what start runs)",
    "build": "create and build each phase's worktree at its commit, and nothing else",
    "status": "every phase, and every run in queue order: done (its evaluations, whether it is analysed and "
              "whether its weights are here), training, partial (a checkpoint) or missing",
    "hours": "machine time per phase (a Markdown table): the done runs' training time as run-hours, and as "
             "machine-hours (run-hours / the runs the phase trains at once); retrains apart; the runs left "
             "(retrains queued among them), "
             "estimated at the machine time per step of the phase's done runs or of an earlier phase of its kind",
    "partial": "record every unfinished run's training so far (log and curve, no weights) into docs/runs/<run>/"
               "partial/ of the records, before a machine goes; a done run's partial records are removed",
    "analyze": "the per-run analysis of every done run that lacks it and whose weights are here",
    "ship": "ship every variant's median sweep run into policies/, where its weights are here",
    "retrain": "train again, after every other run, done runs whose weights are lost (RUN ...), each as "
               "<run>_retrain beside its first draw",
    "pause": "SIGSTOP every training run (the paused time is kept apart from the run's wall time)",
    "resume": "SIGCONT them",
    "stop": "stop the queue and its runs (each resumes from its last checkpoint at the next start)",
    "hold": "pause a running queue, run CMD ..., resume it whatever CMD's exit (with no queue: just CMD)",
}


def share(text):
    """A probability, for argparse: a number from 0 to 1, or an error naming it."""
    value = sweep_config.probability(text)
    if value is None:
        raise argparse.ArgumentTypeError("'%s' is not a number from 0 to 1" % text)
    return value


def repository_root():
    """The checkout this package belongs to (src/hideseek_pipeline/python/hideseek_pipeline/..)."""
    env = os.environ.get("HIDESEEK_ROOT")
    if env:
        return os.path.realpath(env)
    here = os.path.dirname(os.path.realpath(__file__))
    root = os.path.realpath(os.path.join(here, "..", "..", "..", ".."))
    if not os.path.isfile(os.path.join(root, "config", "sweep.yaml")):
        raise SweepError("cannot find the checkout (config/sweep.yaml) above %s: set HIDESEEK_ROOT" % here)
    return root


def parser():
    p = argparse.ArgumentParser(prog="hideseek_pipeline", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--record-root", help="the checkout whose registry names the run and whose docs/runs/ "
                        "receives its files (default: this checkout; a folder of one's own needs a "
                        "policies/policies.yaml, which may be empty)")
    common.add_argument("--workspace", help="the catkin workspace whose launch files and tools run (default: this "
                        "checkout; the sweep passes a phase's pinned worktree)")
    _train_parser(sub, common)
    _evaluate_and_analyze_parsers(sub, common)
    _seeker_parsers(sub, common)
    sub.add_parser("test", help="every test of the workspace (make test), with a running sweep held",
                   description=tests.__doc__)
    sub.add_parser("bench", help="this machine's throughput figures, with a running sweep held",
                   description=bench_doc(), formatter_class=argparse.RawDescriptionHelpFormatter)
    _report_parser(sub)
    _sweep_parser(sub)
    return p


def _train_parser(sub, common):
    t = sub.add_parser("train", parents=[common], help="train, export, record and evaluate one run",
                       description=train.__doc__)
    t.add_argument("variant", help="a variant of config/variants, or with --variant-config the variant that file names")
    t.add_argument("--variant-config", help="a variant file of one's own (its variant field VARIANT, a name no variant "
                   "of the project takes): recorded with its map and their sha256, played again by the run's "
                   "evaluation and analysis; the run does not ship")
    t.add_argument("--seed", type=int, default=0, help="the training seed (default 0)")
    t.add_argument("--steps", type=int, default=2_000_000, help="environment steps (default 2000000)")
    t.add_argument("--runs-dir", default="~/hideseek_runs",
                   help="where <run>/ holds weights and checkpoints (default ~/hideseek_runs)")
    t.add_argument("--network", choices=["ff", "gru"], default="ff")
    t.add_argument("--name", help="the run's name (default: as the sweep names it, <variant>[_seeker][_<game> unless v2]"
                   "[_gru][_<budget> unless 2M]_seed<S>, e.g. basic_v3_8m_seed0)")
    t.add_argument("--game", help="default: config/games.yaml's")
    t.add_argument("--precision", choices=["auto", "fp32", "bf16"], default="auto")
    t.add_argument("--num-arenas", type=int, help="default: train.launch's")
    t.add_argument("--hider-threads", type=int, help="the learner's intra-op threads (default: train.launch's)")
    t.add_argument("--ppo-config", help="default: config/ppo.yaml")
    t.add_argument("--port", type=int, help="ROS master port (default 14000 + seed, + 50 for the GRU, + 25 for a seeker)")
    t.add_argument("--eval-port", type=int, help="the evaluation's master port (default: the run's + 1000)")
    t.add_argument("--eval-modes", nargs="+", choices=list(evaluate.MODES), default=["greedy"])
    t.add_argument("--paused-file", help="a file holding the seconds the run was held paused (the sweep's)")
    t.add_argument("--ship", action="store_true", help="ship the run as its variant's policy (a hider's run)")
    t.add_argument("--role", choices=list(train.ROLES), default="hider",
                   help="who learns: hider (the default) or seeker (against --opponent; evaluated as a seeker)")
    t.add_argument("--opponent", help="the fixed other side. Role seeker: shipped (the records' shipped hider of the "
                   "variant and game; the default), random, scripted/EVADER or a hider's checkpoint. Role hider: "
                   "scripted (the default), random or a seeker's checkpoint")


def _evaluate_and_analyze_parsers(sub, common):
    e = sub.add_parser("evaluate", parents=[common], help="a recorded run's evaluation and trajectories",
                       description=evaluate.__doc__)
    e.add_argument("run")
    e.add_argument("weights")
    e.add_argument("--modes", nargs="+", choices=list(evaluate.MODES), default=["greedy"])
    e.add_argument("--port", type=int, default=11479, help="ROS master port; sampled uses the next (default 11479)")
    a = sub.add_parser("analyze", parents=[common], help="a recorded run's (or a baseline's) per-run analysis",
                       description=analyze.__doc__)
    a.add_argument("run", nargs="?", help="a run of the registry (with WEIGHTS)")
    a.add_argument("weights", nargs="?")
    a.add_argument("--part", choices=list(analyze.PARTS), default="all",
                   help="one part alone: tsne, memoryless (a GRU's) or behaviour (default: all)")
    a.add_argument("--baseline", nargs=2, metavar=("VARIANT", "POLICY"),
                   help="random or scripted/EVADER on VARIANT: behaviour only")
    a.add_argument("--game", help="--baseline's game (default: config/games.yaml's)")
    a.add_argument("--episodes", type=int, default=100, help="rollouts (default 100)")
    a.add_argument("--first-seed", type=int, default=10000, help="the rollouts' first seed (default 10000)")


def _seeker_parsers(sub, common):
    e = sub.add_parser("evaluate-seeker", parents=[common], help="a learned seeker against hiders, beside the "
                       "scripted seeker", description=seeker.__doc__)
    e.add_argument("seeker", help="a seeker's checkpoint or exported policy")
    e.add_argument("--variant", help="default: the --variant-config file's own name, else basic")
    e.add_argument("--variant-config", help="a variant file of one's own (its variant field names it)")
    e.add_argument("--game", help="default: config/games.yaml's")
    e.add_argument("--hiders", nargs="+", default=["shipped"],
                   help="the hiders to play against: shipped, random, scripted/EVADER or a hider's checkpoint "
                   "(default: shipped)")
    e.add_argument("--output", required=True, help="the folder of seeker_evaluation.md/.csv")
    e.add_argument("--episodes", type=int, default=100)
    e.add_argument("--first-seed", type=int, default=0)
    e.add_argument("--port", type=int, default=11489)
    p = sub.add_parser("selfplay", parents=[common], help="hider-seeker self-play: generations, then cross-play",
                       description=selfplay.__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("output", help="the self-play's folder (resumes what it holds)")
    p.add_argument("--variant", help="default: the --variant-config file's own name, else basic")
    p.add_argument("--variant-config", help="a variant file of one's own (its variant field names it)")
    p.add_argument("--game", help="default: config/games.yaml's")
    p.add_argument("--generations", type=int, default=4)
    p.add_argument("--steps", type=int, default=250_000, help="steps per side and generation (default 250000)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--latest-share", type=share, default=0.5,
                   help="the chance that a generation's opponent is the other side's latest generation; otherwise "
                   "uniform over its pool, the random policy included (0: uniform alone; default 0.5)")
    p.add_argument("--num-arenas", type=int, help="default: train.launch's")
    p.add_argument("--hider-threads", type=int, help="the learners' intra-op threads (default: train.launch's)")
    p.add_argument("--precision", choices=["auto", "fp32", "bf16"], default="auto")
    p.add_argument("--ppo-config", help="default: config/ppo.yaml (its annealing turned off)")
    p.add_argument("--port", type=int, default=14900, help="ROS master ports: this, +1 and +2 (default 14900)")
    p.add_argument("--crossplay", action="store_true",
                   help="then the cross-play table of every generation (a pair played to the end before, with as "
                   "many episodes, is kept: remove OUT/crossplay to play every pair again)")
    p.add_argument("--episodes", type=int, default=100, help="cross-play: episodes per pair (default 100)")
    p.add_argument("--record", metavar="RUN",
                   help="instead of training: the cross-play (keeping the pairs played to the end before) and the "
                   "records, docs/runs/RUN/ of --record-root, once every generation is saved (the sweep's self-play "
                   "phase)")


def bench_doc():
    return ("One `name value` line per figure; timing goals live here, never in tests. A running sweep is paused "
            "meanwhile and resumed after. ARENAS (16), SECONDS_PER_RUN (10), ROS_UPDATES (20) and FLOOR_UPDATES (4) "
            "in the environment change the runs (hideseek_pipeline/bench.py says what each group measures).")


def _report_parser(sub):
    r = sub.add_parser("report", help="Table 2, the claims and the figures into docs/report (make reproduce)",
                       description="From the committed evaluations and analyses (under a minute), or with "
                       "--from-scratch from the weights: re-evaluates and re-analyses the shipped policies "
                       "(hideseek_pipeline/report.py says each step).")
    r.add_argument("report_dir", nargs="?", help="default docs/report")
    r.add_argument("--from-scratch", action="store_true", help="evaluate and analyse the shipped policies again")
    r.add_argument("--work-dir", help="--from-scratch's bags and feature arrays (default ~/.ros/hideseek_reproduce; "
                   "large, not part of the report)")
    r.add_argument("--steps", type=int, help="--from-scratch's recorded steps per policy (default 50000; 5000 for a "
                   "quick look)")
    r.add_argument("--game", help="--from-scratch's game: its shipped policies, into REPORT_DIR/<game>/ (default: "
                   "config/games.yaml's)")
    r.add_argument("--variants", nargs="+", metavar="VARIANT", help="--from-scratch: these variants only (with "
                   "their GRU hiders), keeping what the report holds for the others (give REPORT_DIR before it)")
    r.add_argument("--port", type=int, default=11478, help="ROS master port (default 11478)")


def _sweep_parser(sub):
    s = sub.add_parser("sweep", help="the sweep's queue of training runs (config/sweep.yaml's phases)",
                       description=sweep_config.__doc__ + "\nSWEEP_DIR (default ~/hideseek_sweep) is the sweep's "
                       "folder; SWEEP_RECORD_ROOT (default the checkout) receives the records.",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    s.add_argument("--config", help="the sweep's configuration (default: config/sweep.yaml of the checkout)")
    ss = s.add_subparsers(dest="sweep_command", required=True, metavar="COMMAND")
    for name, text in SWEEP_COMMANDS.items():
        c = ss.add_parser(name, help=text, description=text)
        if name == "retrain":
            c.add_argument("runs", nargs="*", metavar="RUN")
        if name == "hold":
            c.add_argument("hold_command", nargs=argparse.REMAINDER, metavar="CMD")


def make_sweep(root, config_path=None):
    records_root = os.path.realpath(os.environ.get("SWEEP_RECORD_ROOT", root))
    records = Records(records_root, root)
    reg = records.registry
    config = sweep_config.load(config_path or os.path.join(root, "config", "sweep.yaml"), reg.variants(), reg.paper_order(),
                               reg.default_game())
    return Sweep(root, records, config, os.path.expanduser(os.environ.get("SWEEP_DIR", "~/hideseek_sweep")))


def sweep_command(args):
    root = repository_root()
    if args.sweep_command == "hold":
        if not args.hold_command:
            raise SweepError("hold: name the command to run while the sweep is paused")
        return held(root, args.hold_command, args.config)
    sweep = make_sweep(root, args.config)
    c = args.sweep_command
    if c == "run":
        return runner.run(sweep) or 0
    if c == "build":
        sweep.make_dirs()
        for phase in sweep.config.phases:
            runner.prepare_tree(sweep, phase)
        return 0
    if c == "retrain":
        return control.retrain(sweep, args.runs)
    return {"start": runner.start, "analyze": runner.analyze_all, "ship": runner.ship_all, "status": control.status,
            "hours": control.hours, "partial": control.partial,
            "pause": control.pause, "resume": control.resume, "stop": control.stop}[c](sweep)


def _variant(args):
    """--variant, else the --variant-config file's own name (the nodes refuse a file named otherwise), else basic."""
    if args.variant:
        return args.variant
    if args.variant_config:
        import yaml  # python3-yaml: install_deps.sh installs it
        with open(args.variant_config) as f:
            return (yaml.safe_load(f) or {}).get("variant") or "basic"
    return "basic"


def run_command(args):
    root = repository_root()
    ws = Workspace(args.workspace or root)
    records = Records(os.path.realpath(args.record_root or root), root, "--record-root")
    if args.command == "train":
        o = train.TrainOptions(
            variant=args.variant, seed=args.seed, steps=args.steps, runs_dir=args.runs_dir, network=args.network,
            name=args.name, game=args.game, precision=args.precision, num_arenas=args.num_arenas,
            ppo_config=args.ppo_config and os.path.realpath(args.ppo_config), hider_threads=args.hider_threads,
            port=args.port, eval_port=args.eval_port, eval_modes=tuple(args.eval_modes),
            paused_file=args.paused_file, ship=args.ship, role=args.role, opponent=args.opponent,
            variant_config=args.variant_config and os.path.realpath(args.variant_config))
        train.train(ws, records, o)
    elif args.command == "evaluate":
        evaluate.evaluate(ws, records, args.run, args.weights, tuple(args.modes), args.port)
    elif args.command == "evaluate-seeker":
        seeker.evaluate_seeker(ws, _variant(args), args.game, args.seeker, args.hiders, os.path.realpath(args.output),
                               args.episodes, args.first_seed, args.port,
                               variant_config=args.variant_config and os.path.realpath(args.variant_config))
    elif args.command == "selfplay":
        o = selfplay.SelfPlayOptions(
            out=args.output, variant=_variant(args), game=args.game, generations=args.generations, steps=args.steps,
            seed=args.seed, latest_share=args.latest_share, num_arenas=args.num_arenas,
            hider_threads=args.hider_threads, precision=args.precision,
            ppo_config=args.ppo_config and os.path.realpath(args.ppo_config),
            variant_config=args.variant_config and os.path.realpath(args.variant_config), port=args.port)
        if args.record:
            selfplay.require_generations(o)  # the records train nothing
        else:
            selfplay.selfplay(ws, o)
        if args.crossplay or args.record:
            selfplay.crossplay(ws, o, args.episodes)
        if args.record:
            selfplay.record(ws, records, o, args.record, args.episodes)
    elif args.baseline:
        if args.run or args.part != "all":
            raise ToolError("analyze: --baseline takes no RUN, WEIGHTS or --part")
        analyze.analyze_baseline(ws, records.root, args.baseline[0], args.baseline[1], args.game, args.episodes,
                                 args.first_seed)
    else:
        if not (args.run and args.weights):
            raise ToolError("analyze: name a RUN and its WEIGHTS, or --baseline VARIANT POLICY")
        analyze.analyze_run(ws, records, args.run, args.weights, args.part, args.episodes, args.first_seed)
    return 0


HELD = "HIDESEEK_PIPELINE_HELD"  # set in the environment of a command that runs with the sweep held


def workspace_command(args):
    """test, bench and report: each on this checkout, test and bench with a running sweep held
    (the pipeline runs itself again under `sweep hold`, marked so that it does not hold twice)."""
    root = repository_root()
    if args.command in ("test", "bench") and not os.environ.get(HELD):
        here = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
        os.environ[HELD] = "1"
        os.environ["PYTHONPATH"] = os.pathsep.join(x for x in (here, os.environ.get("PYTHONPATH")) if x)
        return held(root, [sys.executable, "-m", "hideseek_pipeline", args.command])
    if args.command == "test":
        return tests.run_tests(root)
    if args.command == "bench":
        from hideseek_pipeline import bench  # its progress bars need python3-tqdm, which install_deps.sh installs
        return bench.bench(Workspace(root))
    given = [name for name, value in (("--work-dir", args.work_dir), ("--steps", args.steps),
                                      ("--variants", args.variants), ("--game", args.game)) if value is not None]
    if given and not args.from_scratch:
        raise ToolError("report: %s only with --from-scratch (without it the report is made from the committed "
                        "records alone)" % ", ".join(given))
    from hideseek_pipeline import report
    return report.report(Workspace(root), args.report_dir, args.from_scratch, args.work_dir, args.steps or 50000,
                         args.variants, args.port, lambda: runner.analyze_all(make_sweep(root)), args.game)


def held(root, command, config=None):
    """`command`, with a running sweep paused meanwhile and resumed after, whatever its exit. With
    no sweep folder there is no queue to pause: just the command (no folder is created)."""
    if not os.path.isdir(os.path.expanduser(os.environ.get("SWEEP_DIR", "~/hideseek_sweep"))):
        rc = subprocess.run(command).returncode
        return 128 - rc if rc < 0 else rc  # killed by a signal: 128 + its number, as a shell says
    return control.hold(make_sweep(root, config), command)


def main(argv=None):
    # Started as a node (selfplay.launch), roslaunch appends its own arguments (__name:=, __log:=).
    argv = [a for a in (sys.argv[1:] if argv is None else argv) if not (a.startswith("__") and ":=" in a)]
    args = parser().parse_args(argv)
    # No process the pipeline starts may leave __pycache__ in a pinned worktree (the trainers there
    # import the registry module): the tree would look modified and no further run would start.
    os.environ["PYTHONDONTWRITEBYTECODE"] = "1"
    sys.dont_write_bytecode = True
    if args.command in ("test", "bench", "report"):
        try:
            return workspace_command(args)
        except (ToolError, MeasureError, SweepError, FileNotFoundError) as e:
            print("hideseek_pipeline: %s" % e, file=sys.stderr)
            return 1
    try:
        return sweep_command(args) if args.command == "sweep" else run_command(args)
    except (SweepError, sweep_config.ConfigError, FileNotFoundError) as e:
        print("%s: %s" % ("sweep" if args.command == "sweep" else "hideseek_pipeline " + args.command, e),
              file=sys.stderr)
        return 2
    except Interrupted as e:
        print("hideseek_pipeline: %s" % e, file=sys.stderr)
        return 130
    except ToolError as e:
        print("hideseek_pipeline: %s" % e, file=sys.stderr)
        return 1
