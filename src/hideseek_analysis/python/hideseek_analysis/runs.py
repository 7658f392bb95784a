"""The runs the analysis across training seeds counts, and what each left in the checkout.

A sweep run is a registry entry (policies/policies.yaml) named after its variant, game, network,
budget and training seed (<variant>[_<game> unless v2][_<network> unless ff][_<budget> unless
2M]_seed<S>), of that variant, network and game, trained for at least the sweep's steps by the
sweep's queue (its note says so), and the first draw of its seed: a retrain (<run>_retrain) never
counts. Its records lie in
docs/runs/<run>/: episodes.csv (greedy evaluation, seeds 0-99), sampled/episodes.csv, and analysis/
(probes, states, transitions, behaviour, distance, t-SNE: hideseek_pipeline analyze).
"""
import argparse
import csv
import os
import re
import sys

import numpy as np

from . import registry
from .stats import BOOTSTRAP

NAME = re.compile(r"^(?P<variant>.+)_seed(?P<seed>\d+)$")


def run_name(variant, seed, game="v2", network="ff", budget=""):
    """A sweep run's name: basic_seed0, basic_v3_gru_seed1, basic_v3_8m_seed0 (budget: the label of
    a budget other than the sweep's 2M steps)."""
    return "%s%s%s%s_seed%d" % (variant, "" if game == "v2" else "_" + game, "" if network == "ff" else "_" + network,
                                "_" + budget if budget else "", int(seed))


def parse_selection(description, argv=None, more=None, game="v2"):
    """The command line of a tool across training seeds: selection_arguments() (`game`: --game's
    default), then more(parser)'s own; --root made absolute."""
    parser = argparse.ArgumentParser(description=description)
    selection_arguments(parser, game)
    if more:
        more(parser)
    args = parser.parse_args(argv)
    args.root = os.path.abspath(args.root)
    return args


def outputs(args, games, *sub):
    """[(game, its output folder)]: --game's alone into --out (default ROOT/docs/report/<game>/SUB),
    or each of `games` (config/sweep.yaml's) into OUT/<game>/SUB (default OUT: ROOT/docs/report)."""
    report = os.path.join(args.root, "docs", "report")
    if args.game:
        return [(args.game, args.out or os.path.join(report, args.game, *sub))]
    return [(game, os.path.join(args.out or report, game, *sub)) for game in games]


def selection_arguments(parser, game="v2"):
    """The options every tool across training seeds takes: which checkout, where to write, which
    runs (the sweep's, by game and steps, plus --extra by name), and how many bootstrap resamples."""
    parser.add_argument("--root", default=registry.ROOT,
                        help="the checkout (registry, docs/runs, config; default: the one holding this code)")
    parser.add_argument("--out", help="output folder")
    parser.add_argument("--game", default=game, help="the game whose sweep runs count (default %s)" % (
        game or "each game config/sweep.yaml trains, side by side"))
    parser.add_argument("--steps", type=int, default=2000000, help="a sweep run's training steps (default 2000000)")
    parser.add_argument("--extra", nargs="*", default=[], help="other runs to count, by registry name")
    parser.add_argument("--reps", type=int, default=BOOTSTRAP, help="bootstrap resamples (default %d)" % BOOTSTRAP)
    parser.add_argument("--seed", type=int, default=0, help="the bootstrap's random seed")


def read_csv(path):
    """A CSV file's rows as dicts, or None where the file does not exist."""
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return list(csv.DictReader(f))


EPISODE_COLUMNS = ("seed", "living_steps", "outcome")
OUTCOMES = ("captured", "survived")


def episode_rows(path):
    """The rows of an evaluation's episodes.csv (evaluate.launch's: seed, living_steps, outcome per
    episode), checked: a missing file, a missing column, an outcome other than captured or survived
    or an empty file is refused, naming the file."""
    rows = read_csv(path)
    if rows is None:
        raise FileNotFoundError("%s: no such file (an evaluation's episodes.csv, as evaluate.launch writes it)" % path)
    if not rows:
        raise ValueError("%s: no episodes" % path)
    missing = [c for c in EPISODE_COLUMNS if c not in rows[0]]
    if missing:
        raise ValueError("%s: no column %s (an episodes.csv has %s)" % (path, ", ".join(missing), ", ".join(EPISODE_COLUMNS)))
    for line, r in enumerate(rows, start=2):
        if r["outcome"] not in OUTCOMES:
            raise ValueError("%s, line %d: outcome %r is neither %s" % (path, line, r["outcome"], " nor ".join(OUTCOMES)))
    return rows


def load_episodes(path):
    """(living steps, success) arrays of an evaluation's episodes.csv, one entry per episode (success:
    the hider survived)."""
    rows = episode_rows(path)
    living = np.array([float(r["living_steps"]) for r in rows])
    success = np.array([1.0 if r["outcome"] == "survived" else 0.0 for r in rows])
    return living, success


def evaluation_by_seed(path):
    """{evaluation seed: living steps} of an evaluation's episodes.csv."""
    return {int(r["seed"]): float(r["living_steps"]) for r in episode_rows(path)}


def calibration_file(game="v2"):
    """The game's calibration table under docs/: calibration_table.csv for v2, else calibration_table_<game>.csv."""
    return "calibration_table.csv" if game == "v2" else "calibration_table_%s.csv" % game


def calibration(root, game="v2"):
    """variant -> the rows of the game's calibration table (the random hider and the scripted evaders)."""
    found = {}
    for r in read_csv(os.path.join(root, "docs", calibration_file(game))) or []:
        found.setdefault(r["variant"], []).append(r)
    return found


def _is_sweep_run(name, e, steps, network, game, budget):
    m = NAME.match(name)
    return bool(m and m.group("variant") == run_name(e["variant"], 0, game, network, budget)[:-len("_seed0")]
                and e.get("network") == network and str(e.get("game")) == game and int(e.get("steps", 0)) >= steps
                and str(e.get("note", "")).startswith(registry.SWEEP_NOTE))


def _check_extra(entries, extra, network, warn):
    retrains = sorted(n for n in extra if n in entries and registry.draw(entries[n]) == "retrain")
    if retrains:
        raise SystemExit("hideseek_analysis: --extra %s: a retrain never enters Table 2 or a claim (its first draw, "
                         "%s, does)" % (", ".join(retrains), ", ".join(entries[n]["retrain_of"] for n in retrains)))
    missing = [n for n in extra if n not in entries]
    if missing:
        raise SystemExit("hideseek_analysis: --extra: no run %s in the registry" % ", ".join(missing))
    other = sorted(n for n in extra if entries[n].get("network", "ff") != network)
    if other and warn:
        print("hideseek_analysis: --extra %s: not %s runs, left out here" % (", ".join(other), network),
              file=sys.stderr)


def sweep_runs(root, steps, extra, network="ff", warn=True, game="v2", budget=""):
    """variant -> [(run, entry)], in training-seed order: the sweep's first draws of `network` on
    `game` trained for at least `steps` (see the module's docstring; `budget`: their names' budget
    label, 8m, where it is not the sweep's 2M), plus the runs named in `extra` of that network
    (`warn`: say on stderr which of `extra` are of another network and so left out)."""
    entries = registry.runs(os.path.join(root, "policies", "policies.yaml"))
    _check_extra(entries, extra, network, warn)
    found = {}
    for name, e in entries.items():
        if registry.draw(e) != "first" or registry.role(e) != "hider":
            continue  # a retrain (shown beside its first draw in the run's records) or a seeker: never counted
        if (name in extra and e.get("network", "ff") == network and str(e.get("game")) == game) or \
                _is_sweep_run(name, e, steps, network, game, budget):
            found.setdefault(e["variant"], []).append((name, e))
    for v in found:
        found[v].sort(key=lambda ne: (int(ne[1].get("training_seed", 0)), ne[0]))
    return found


class Runs:
    """The selected runs' evaluations and per-run analyses, read on demand from ROOT/docs."""

    def __init__(self, root, found, game="v2"):
        self.root = root
        self.found = found
        self.game = game

    def names(self, variant):
        return [n for n, _ in self.found.get(variant, [])]

    def path(self, name, *parts):
        return os.path.join(self.root, "docs", "runs", name, *parts)

    def analysis(self, name, table):
        return read_csv(self.path(name, "analysis", table + ".csv"))

    def analysed(self, variant, table):
        """[(run, its analysis table's rows)] of the variant's runs that have that table."""
        return [(n, rows) for n in self.names(variant) for rows in [self.analysis(n, table)] if rows]

    def episodes(self, variant):
        """The greedy living steps of each of the variant's evaluated runs."""
        return [load_episodes(self.path(n, "episodes.csv"))[0] for n in self.names(variant)
                if os.path.exists(self.path(n, "episodes.csv"))]

    def baseline(self, variant, table, policy="random"):
        """A table of the random hider's analysis on the runs' game
        (docs/analysis/baselines/[<game> unless v2/]<variant>/<policy>/)."""
        game = [] if self.game == "v2" else [self.game]
        return read_csv(os.path.join(self.root, "docs", "analysis", "baselines", *game, variant, policy, table + ".csv"))
