"""make reproduce: the whole reproduction in one command, into one report folder (docs/report).

By default from the committed outputs alone, in about a minute: for each game the sweep trains,
Table 2 across training seeds (<game>/table2_seeds/), the game's claims table and Figures 4-7 across
seeds (<game>/), from every sweep run's evaluation and per-run analysis; and the claims on both
games side by side (claims.md) (hideseek_analysis: table2.py, seed_figures.py, claims.py).

--from-scratch, given the weights: first analyses every sweep run whose weights are on this
machine and lacks its analysis (hideseek_pipeline sweep analyze); then, on one game (--game,
default config/games.yaml's) and into <game>/, evaluates every policy shipped for that game and
the random hider on every variant through the ROS graph (evaluate.launch, seeds 0-99:
<game>/evaluations/ and Table 2 of the shipped policies, <game>/table2_shipped/); analyses every
variant that has a shipped policy (analyze.launch: --steps recorded steps, probes, t-SNE, state
statistics, distance over time, into <game>/<variant>/; the bags and feature arrays go to
--work-dir, large, not part of the report); gathers Table 3, the figures across variants and an
index.md (reproduce_report.py, into <game>/); and ends with the tables across seeds as above.
--variants V ... evaluates and analyses those variants only (with their GRU hiders) and keeps what
the report already holds for the others: for a newly trained policy; after a change to the game, run
it all.
"""
import os
import shutil
import time

from tqdm import tqdm

from hideseek_pipeline.records import load_registry_module
from hideseek_pipeline.workspace import ToolError


def across_seeds(ws, report, say):
    """Per game the sweep trains (the analysis reads them from config/sweep.yaml), Table 2 and the
    figures across training seeds into REPORT/<game>/, then the claims of every game, each into
    REPORT/<game>/ and side by side into REPORT/claims.md, from the committed records."""
    say("report: across training seeds, from the committed evaluations and analyses")
    for step in tqdm(("table2.py", "seed_figures.py", "claims.py"), desc="report: across seeds", unit="step"):
        for line in ws.python(step, "--out", report, show_stderr=True).splitlines():
            tqdm.write("  " + line)


def _evaluation(ws, variant, policy, folder, port, game, extra=()):
    """One evaluation through evaluate.launch into `folder`; its evaluation.csv is the verdict
    (roslaunch exits 0 even when a required node dies)."""
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    log = os.path.join(folder, "launch.log")
    ws.command(["roslaunch", "-p", port, "hideseek_world", "evaluate.launch", "variant:=" + variant,
                "game:=" + game, "policy:=" + policy, "output_dir:=" + folder] + list(extra),
               env={"ROS_MASTER_URI": "http://localhost:%d" % port}, log=log, check=False)
    table = os.path.join(folder, "evaluation.csv")
    if not os.path.isfile(table) or os.path.getsize(table) == 0:
        raise ToolError("report: the evaluation of %s (%s) failed, see %s" % (variant, policy, log))
    os.remove(log)
    with open(table) as f:
        last = f.read().strip().splitlines()[-1].split(",")
    return "%s %s" % (last[3], last[4])


def evaluations_of(reg, variants, game):
    """(variant, label, policy, extra launch arguments) of every evaluation on `game`: the random
    hider, the shipped feed-forward policy, the shipped GRU hider with and without its memory."""
    jobs = []
    for v in variants:
        jobs.append((v, "random", "random", ()))
        _, ff = reg.shipped(v, "ff", game)
        if ff:
            jobs.append((v, "trained", ff, ()))
        _, gru = reg.shipped(v, "gru", game)
        if gru:
            jobs += [(v, "gru_trained", gru, ()), (v, "gru_memoryless", gru, ("memoryless:=true",))]
    return jobs


def evaluate_shipped(ws, reg, report, variants, keep, port, game, say):
    """Every shipped policy and the random hider of `variants`, then Table 2 of the shipped policies
    (table2_shipped/). `keep`: leave the other variants' evaluations in place."""
    folder = os.path.join(report, "evaluations")
    if not keep:
        shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder, exist_ok=True)
    jobs = evaluations_of(reg, variants, game)
    for v in variants:
        if not reg.shipped(v, "ff", game)[1]:
            say("report: %s: no shipped policy on game %s" % (v, game))
    for v, label, policy, extra in tqdm(jobs, desc="report: evaluations", unit="evaluation"):
        start = time.time()
        result = _evaluation(ws, v, policy, os.path.join(folder, "%s_%s" % (v, label)), port, game, extra)
        tqdm.write("report: %s %s: %s (living steps, success; %d s)" % (v, label, result, time.time() - start))
    ws.python("table2.py", "--evaluations", folder, "--out", os.path.join(report, "table2_shipped"), show_stderr=True)


def analyse_shipped(ws, reg, report, work, variants, steps, port, game):
    """analyze.launch on every policy of `variants` shipped for `game` (its label's folder of the report)."""
    shipped = [(reg.label(v, n), v, path) for v in reg.paper_order() for n in reg.NETWORKS
               for _, path in [reg.shipped(v, n, game)] if path and v in variants]
    os.makedirs(work, exist_ok=True)
    for label, variant, weights in tqdm(shipped, desc="report: analyses", unit="policy"):
        shutil.rmtree(os.path.join(report, label), ignore_errors=True)
        log = os.path.join(work, label + ".log")
        # roslaunch exits 0 even when a required node dies: the report's files are the verdict.
        ws.command(["roslaunch", "-p", port, "hideseek_world", "analyze.launch", "variant:=" + variant,
                    "game:=" + game, "policy:=" + weights, "steps:=%d" % steps,
                    "output_dir:=" + os.path.join(work, label),
                    "report_dir:=" + os.path.join(report, label)],
                   env={"ROS_MASTER_URI": "http://localhost:%d" % port}, log=log, check=False)
        with open(log) as f:
            for line in f:
                if line.startswith("analysis:") or "report:" in line:
                    tqdm.write("  " + line.rstrip())
        if not os.path.isfile(os.path.join(report, label, "distance_time.png")):
            raise ToolError("report: the analysis of %s failed, see %s" % (label, log))


def report(ws, report_dir=None, from_scratch=False, work_dir=None, steps=50000, variants=None, port=11478,
           analyze_sweep=None, game=None, say=print):
    """The report into `report_dir` (default ws.root/docs/report), as the module's docstring says.
    `analyze_sweep`: a callable that analyses the sweep's runs lacking their analysis (--from-scratch)."""
    start = time.time()
    report_dir = os.path.abspath(report_dir or os.path.join(ws.root, "docs", "report"))
    os.makedirs(report_dir, exist_ok=True)
    if not from_scratch:
        across_seeds(ws, report_dir, say)
        say("report: done in %d s; open %s/claims.md (--from-scratch also re-evaluates and re-analyses)"
            % (time.time() - start, report_dir))
        return 0
    reg = load_registry_module(ws.root)
    known = reg.paper_order()
    unknown = [v for v in variants or [] if v not in known]
    if unknown:
        raise ToolError("report: --variants names %s, not among: %s" % (", ".join(unknown), " ".join(known)))
    game = game or reg.default_game()
    scratch = os.path.join(report_dir, game)
    if analyze_sweep:
        analyze_sweep()
    say("report: [1/3] Table 2 of game %s: every shipped policy and the random hider, seeds 0-99" % game)
    evaluate_shipped(ws, reg, scratch, variants or known, bool(variants), port, game, say)
    say("report: [2/3] the analysis of every shipped policy (%d steps each; %d s so far)" % (steps, time.time() - start))
    work = os.path.abspath(os.path.expanduser(work_dir or "~/.ros/hideseek_reproduce"))
    analyse_shipped(ws, reg, scratch, os.path.join(work, game), variants or known, steps, port, game)
    say("report: [3/3] tables and figures across variants")
    ws.python("reproduce_report.py", scratch, "--paper", os.path.join(ws.root, "config", "paper_reference.yaml"),
              show_stderr=True)
    across_seeds(ws, report_dir, say)
    say("report: done in %d s; open %s/index.md" % (time.time() - start, scratch))
    return 0
