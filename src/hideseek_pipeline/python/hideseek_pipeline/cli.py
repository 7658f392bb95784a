"""hideseek_pipeline: the project's pipeline, one command with subcommands.

  hideseek_pipeline sweep status        the sweep's phases and every run's state
  hideseek_pipeline sweep start         the queue in the background (make sweep)
  hideseek_pipeline sweep hold CMD ...  CMD with the queue paused (make test, make bench)

Each subcommand answers --help.
"""
import argparse
import os
import sys

from hideseek_pipeline import sweep_config
from hideseek_pipeline.queue import Sweep, SweepError
from hideseek_pipeline.records import Records

SWEEP_COMMANDS = {
    "start": "start the queue in the background (it builds each phase's worktree first) and return; a queue "
             "already running is left alone",
    "run": "the queue in the foreground (what start runs)",
    "build": "create and build each phase's worktree at its commit, and nothing else",
    "status": "every phase, and every run in queue order: done (its evaluations, whether it is analysed and "
              "whether its weights are here), training, partial (a checkpoint) or missing",
    "analyze": "the per-run analysis of every done run that lacks it and whose weights are here",
    "ship": "ship every variant's median sweep run into policies/, where its weights are here",
    "retrain": "train again, after every other run, done runs whose weights are lost (RUN ...), each as "
               "<run>_retrain beside its first draw",
    "pause": "SIGSTOP every training run (the paused time is kept apart from the run's wall time)",
    "resume": "SIGCONT them",
    "stop": "stop the queue and its runs (each resumes from its last checkpoint at the next start)",
    "hold": "pause a running queue, run CMD ..., resume it whatever CMD's exit (with no queue: just CMD)",
}


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
    return p


def make_sweep(root, config_path=None):
    records_root = os.path.realpath(os.environ.get("SWEEP_RECORD_ROOT", root))
    records = Records(records_root, root)
    reg = records.registry
    config = sweep_config.load(config_path or os.path.join(root, "config", "sweep.yaml"), reg.variants(), reg.paper_order(),
                               reg.default_game())
    return Sweep(root, records, config, os.path.expanduser(os.environ.get("SWEEP_DIR", "~/hideseek_sweep")))


def sweep_command(args):
    root = repository_root()
    if args.sweep_command == "hold" and not os.path.isdir(os.path.expanduser(
            os.environ.get("SWEEP_DIR", "~/hideseek_sweep"))):
        import subprocess
        if not args.hold_command:
            raise SweepError("hold: name the command to run while the sweep is paused")
        return subprocess.run(args.hold_command).returncode  # no sweep folder: no queue to pause
    sweep = make_sweep(root, args.config)
    c = args.sweep_command
    if c == "start":
        return sweep.start()
    if c == "run":
        return sweep.run() or 0
    if c == "build":
        sweep.make_dirs()
        for phase in sweep.config.phases:
            sweep.prepare_tree(phase)
        return 0
    if c == "retrain":
        return sweep.retrain(args.runs)
    if c == "hold":
        return sweep.hold(args.hold_command)
    return {"status": sweep.status, "analyze": sweep.analyze_all, "ship": sweep.ship_all, "pause": sweep.pause,
            "resume": sweep.resume, "stop": sweep.stop}[c]()


def main(argv=None):
    args = parser().parse_args(argv)
    # Python must not leave __pycache__ in a pinned worktree (it would look modified).
    sys.dont_write_bytecode = True
    try:
        return sweep_command(args)
    except (SweepError, sweep_config.ConfigError, FileNotFoundError) as e:
        print("sweep: %s" % e, file=sys.stderr)
        return 2
