"""Table 2, the one generator: per variant and hider, the mean and the interquartile mean (IQM) of
living steps and of success over the pooled evaluation episodes of its runs, each with its 95 %
interval from the two-level bootstrap (stats.py), beside the paper's figures and the baselines.

It reads one of two sources:
- the sweep (default): every sweep run of the game (runs.py selects them), greedy and sampled,
  from docs/runs/<run>/episodes.csv and sampled/episodes.csv, beside the random hider and the
  scripted evaders (the game's calibration table); into ROOT/docs/report/<game>/table2_seeds;
- --evaluations DIR: the shipped policies as `hideseek_pipeline report --from-scratch` evaluated them, one run per
  variant and network, DIR/<label>_trained/episodes.csv (and, for a GRU hider, <variant>_gru_trained
  and <variant>_gru_memoryless), beside the random hider evaluated with them (DIR/<variant>_random).

Writes into OUT:
- table2.md / table2.csv: the table;
- orderings.md / orderings.csv: the probability of improvement for each ordering the paper reports
  (config/paper_reference.yaml), at the level of runs and of episodes, and Spearman's rank
  correlation with the paper's ordering;
- readings.md / readings.csv: the two readings of the paper's stochastic seeker side by side (its
  `readings`): the difference of their means with its interval, the probability of improvement,
  and which is closer to the paper's figure. Not one of the paper's orderings, not in the rank
  correlation;
- performance_profile.png: the fraction of episodes living longer than tau, per variant, with bands.
"""
import csv
import os
import sys

import numpy as np

from . import stats as st
from .config import Config
from .figures import performance_profile
from .runs import calibration, load_episodes, outputs, parse_selection, read_csv, sweep_runs
from .tables import fmt_ci, write_rows


class SweepSource:
    """The sweep's runs of a game, greedy and sampled, beside docs/calibration_table.csv."""
    modes = (("greedy", ""), ("sampled", "sampled"))
    scope = "per run; greedy is the headline, sampled beside it"
    nothing = "No sweep run evaluated yet"

    def __init__(self, root, found, game="v2"):
        self.root, self.found, self.calib = root, found, calibration(root, game)
        self.title = "Table 2 across training seeds, game %s" % game

    def runs_of(self, variant):
        return [n for n, _ in self.found.get(variant, [])]

    def episodes_path(self, name, sub):
        return os.path.join(self.root, "docs", "runs", name, sub, "episodes.csv")

    def baselines(self, variant):
        """(who, living steps, success rate, median living steps) of each baseline of the variant."""
        return [("random hider" if c["evader"] == "random" else "scripted %s (reads the true state)" % c["evader"],
                 float(c["avg_living_steps"]), float(c["success_rate"]), "median %s" % c["median_living_steps"])
                for c in self.calib.get(variant, [])]

    def run_count(self):
        return sum(len(x) for x in self.found.values())


class EvaluationsSource:
    """The shipped policies of one evaluation (hideseek_pipeline report --from-scratch's REPORT/evaluations)."""
    modes = (("greedy", "trained"), ("GRU, greedy", "gru_trained"), ("GRU memoryless, greedy", "gru_memoryless"))
    scope = ("of each shipped policy (one run per variant and network: its interval covers only the spread between "
             "its evaluation episodes), and of a shipped GRU hider with its state zeroed at every step (memoryless)")
    title = "Table 2: the shipped policies"
    nothing = "No shipped policy evaluated"

    def __init__(self, folder):
        self.folder = folder

    def runs_of(self, variant):
        return [variant]

    def episodes_path(self, name, sub):
        return os.path.join(self.folder, "%s_%s" % (name, sub), "episodes.csv")

    def baselines(self, variant):
        rows = read_csv(os.path.join(self.folder, variant + "_random", "evaluation.csv"))
        return [("random hider", float(rows[-1]["avg_living_steps"]), float(rows[-1]["success_rate"]), "")] if rows else []

    def run_count(self):
        return len([n for n in os.listdir(self.folder) if not n.endswith("_random")])

    def check(self, variants):
        """Refuses a folder that holds no evaluation this table reads (its folders are named
        <variant>_trained, <variant>_gru_trained, <variant>_gru_memoryless and <variant>_random)."""
        if not os.path.isdir(self.folder):
            raise ValueError("--evaluations %s: no such folder" % self.folder)
        known = {"%s_%s" % (v, sub) for v in variants for sub in [m[1] for m in self.modes] + ["random"]}
        found = sorted(os.listdir(self.folder))
        if not any(n in known for n in found):
            raise ValueError("--evaluations %s holds no evaluation named VARIANT_trained (or VARIANT_gru_trained, "
                             "VARIANT_gru_memoryless, VARIANT_random, VARIANT one of %s), as hideseek_pipeline report "
                             "--from-scratch writes them; it holds: %s. To compare evaluations of your own, use the "
                             "library (docs/analysis.md, The analysis as a library)"
                             % (self.folder, ", ".join(variants), ", ".join(found) or "nothing"))


MEASURES = (("living_mean", 0, st.mean), ("living_iqm", 0, st.iqm), ("success_mean", 1, st.mean),
            ("success_iqm", 1, st.iqm))
FIELDS = ["variant", "mode", "runs", "episodes", "living_mean", "living_mean_lo", "living_mean_hi", "living_iqm",
          "living_iqm_lo", "living_iqm_hi", "success_mean", "success_mean_lo", "success_mean_hi", "success_iqm",
          "success_iqm_lo", "success_iqm_hi", "per_run_living", "per_run_success", "run_names"]


def summary_row(v, mode, runs, seed, reps):
    """One row of the table: runs [(name, (living, success))] of a variant and mode."""
    living = [r[1][0] for r in runs]
    success = [r[1][1] for r in runs]
    row = {"variant": v, "mode": mode, "runs": len(runs), "run_names": " ".join(r[0] for r in runs),
           "episodes": sum(len(x) for x in living),
           "per_run_living": " ".join("%.1f" % x.mean() for x in living),
           "per_run_success": " ".join("%.0f" % (100 * x.mean()) for x in success)}
    for key, which, stat in MEASURES:
        point, ci = st.pooled_statistic((living, success)[which], stat, st.keyed_rng(seed, v, mode, key), reps)
        row[key], row[key + "_lo"], row[key + "_hi"] = point, ci[0], ci[1]
    return row


def collect(source, order, seed, reps):
    """(rows, living, success): the table's rows, and per (variant, mode) each run's living steps and
    success arrays."""
    rows, data, succ = [], {}, {}
    for v in order:
        for mode, sub in source.modes:
            runs = [(name, load_episodes(path)) for name in source.runs_of(v)
                    for path in [source.episodes_path(name, sub)] if os.path.exists(path)]
            if runs:
                data[(v, mode)] = [r[1][0] for r in runs]
                succ[(v, mode)] = [r[1][1] for r in runs]
                rows.append(summary_row(v, mode, runs, seed, reps))
    return rows, data, succ


def _rounded_rows(path, rows, fields):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for r in rows:
            w.writerow({k: (round(r[k], 4) if isinstance(r[k], float) else r[k]) for k in fields})


INTRO = (
    "Evaluation seeds 0-99, at most 1000 steps, %s. "
    "Mean and interquartile mean (IQM) over the pooled episodes of a variant's runs, each with its 95 %% "
    "interval from a two-level bootstrap (%d resamples: the runs, then the episodes within each run). "
    "The interval covers the spread between training seeds and between evaluation episodes; with three "
    "training seeds it is wide, and it cannot cover a behaviour none of the runs showed; with two runs "
    "its run level can only draw one run twice or both, so it is about their range widened by the episodes' "
    "spread, and its coverage is below 95 %%; for a "
    "variant with one run so far it covers only the spread between that run's evaluation episodes. "
    "The IQM of success, a 0/1 outcome, is clip((p - 0.25) / 0.5, 0, 1) of the success rate p: it is "
    "given because the protocol asks for it, and the mean is the figure to read.")


def _variant_lines(v, rows, paper, baselines):
    md = []
    for r in (x for x in rows if x["variant"] == v):
        md.append("| %s | PPO, %s | %d | %s | %s | %s | %s | %s / %s |" % (
            v, r["mode"], r["runs"], fmt_ci(r["living_mean"], (r["living_mean_lo"], r["living_mean_hi"])),
            fmt_ci(r["living_iqm"], (r["living_iqm_lo"], r["living_iqm_hi"])),
            fmt_ci(r["success_mean"], (r["success_mean_lo"], r["success_mean_hi"]), 0, 100),
            fmt_ci(r["success_iqm"], (r["success_iqm_lo"], r["success_iqm_hi"]), 0, 100),
            r["per_run_living"], r["per_run_success"]))
    if v in paper:
        md.append("| %s | paper, trained (8M steps) | 1 | %s | | %.0f | | |" % (v, paper[v]["living_trained"],
                                                                           paper[v]["success_trained"]))
    for who, living, success, median in baselines:
        md.append("| %s | %s | | %.1f | | %.0f | | %s |" % (v, who, living, 100 * success, median))
    if v in paper:
        md.append("| %s | paper, random | | %s | | %.0f | | |" % (v, paper[v]["living_random"], paper[v]["success_random"]))
    return md


def table_markdown(source, rows, order, paper, data, reps):
    """table2.md's table: per variant its hiders' rows, the paper's and the baselines'."""
    md = ["# " + source.title, "", INTRO % (source.scope, reps), "",
          "| variant | hider | runs | living steps: mean [95 % CI] | IQM [95 % CI] | success %: mean [95 % CI] | "
          "IQM [95 % CI] | per run (living steps / success %) |",
          "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for v in order:
        md += _variant_lines(v, rows, paper, source.baselines(v))
    md.append("")
    missing = [v for v in order if (v, "greedy") not in data]
    if missing:
        md += ["%s: %s." % (source.nothing, ", ".join(missing)), ""]
    return md


def orderings(data, order, cfg, seed, reps):
    """(rows, rho, variants): the probability of improvement of each of the paper's orderings whose
    two variants were evaluated, and the rank correlation over the paper's evaluated variants (None
    with fewer than three)."""
    rows = []
    present = [v for v in order if (v, "greedy") in data]
    for better, worse in cfg.orderings(present):
        if (better, "greedy") in data and (worse, "greedy") in data:
            x, y = data[(better, "greedy")], data[(worse, "greedy")]
            poi = st.probability_of_improvement(x, y, st.keyed_rng(seed, "improvement", better, worse), reps)
            rows.append({"better": better, "worse": worse, "runs": "%d vs %d" % (len(x), len(y)),
                         "poi_runs": poi["runs"][0], "poi_runs_lo": poi["runs"][1][0], "poi_runs_hi": poi["runs"][1][1],
                         "poi_episodes": poi["episodes"][0], "poi_episodes_lo": poi["episodes"][1][0],
                         "poi_episodes_hi": poi["episodes"][1][1]})
    in_paper = [v for v in present if v in cfg.paper]
    rho = None
    if len(in_paper) >= 3:
        rho = st.rank_correlation([data[(v, "greedy")] for v in in_paper],
                                  [cfg.paper[v]["living_trained"] for v in in_paper], st.keyed_rng(seed, "rho"), reps)
    return rows, rho, in_paper


ORDER_FIELDS = ["better", "worse", "runs", "poi_runs", "poi_runs_lo", "poi_runs_hi", "poi_episodes", "poi_episodes_lo",
                "poi_episodes_hi"]
ORDER_INTRO = (
    "Greedy evaluations. The probability of improvement P(X > Y) (ties count half) at two levels: "
    "**runs**, a run of X against a run of Y by mean living steps (rliable's definition: what training X "
    "rather than Y gives), its interval from the two-level bootstrap; **episodes**, an episode of X against "
    "one of Y. 0.5 is no difference; an interval that holds 0.5 does not decide the ordering.")


def write_orderings(out, rows, rho, in_paper):
    """orderings.csv; returns orderings.md's lines."""
    _rounded_rows(os.path.join(out, "orderings.csv"), rows, ORDER_FIELDS)
    if rho:
        with open(os.path.join(out, "orderings.csv"), "a") as f:
            f.write("# spearman_rho_with_paper,%d variants,%.4f,%.4f,%.4f\n" % (len(in_paper), rho[0], *rho[1]))
    md = ["# The paper's orderings", "", ORDER_INTRO, "",
          "| ordering (paper) | runs | P(X > Y), runs [95 % CI] | P(X > Y), episodes [95 % CI] |", "| --- | --- | --- | --- |"]
    for r in rows:
        md.append("| %s > %s | %s | %s | %s |" % (r["better"], r["worse"], r["runs"],
                                                  fmt_ci(r["poi_runs"], (r["poi_runs_lo"], r["poi_runs_hi"]), 2),
                                                  fmt_ci(r["poi_episodes"], (r["poi_episodes_lo"], r["poi_episodes_hi"]), 2)))
    md.append("")
    if rho:
        md.append("Spearman's rank correlation between the variants' mean living steps and the paper's (%d variants: "
                  "%s): **%s** (95 %% two-level bootstrap interval)." % (len(in_paper), ", ".join(in_paper),
                                                                         fmt_ci(rho[0], rho[1], 2)))
    else:
        md.append("Rank correlation with the paper: needs at least three of the paper's variants evaluated "
                  "(%d so far)." % len(in_paper))
    return md + [""]


READINGS_INTRO = (
    "Greedy evaluations, seeds 0-99. Differences are the first reading minus the second, "
    "pooled means with their 95 % two-level bootstrap interval (each variant's runs, then "
    "episodes within them, resampled on their own); the probability of improvement as in "
    "the orderings. This comparison is not one of the paper's orderings, and the second "
    "reading stays out of the rank correlation.")


def _closer(a, b, va, vb, sa, sb, ref, d_living, d_success):
    """Which reading is closer to the paper's figure, and whether the difference tells them apart."""
    closer = []
    for what, x, y, target, scale, unit in (("living steps", va, vb, float(ref["living_trained"]), 1.0, ""),
                                            ("success", sa, sb, float(ref["success_trained"]) / 100.0, 100.0, " points")):
        da, db = abs(x - target), abs(y - target)
        closer.append("in %s, %s (%.1f%s from the paper's %.0f, against %.1f)" % (
            what, a if da < db else b, scale * min(da, db), unit, scale * target, scale * max(da, db)))
    told = ["in %s the interval of the difference %s" % (
        what, "holds 0: the two readings are not told apart" if d[1][0] <= 0 <= d[1][1] else "excludes 0")
        for what, d in (("living steps", d_living), ("success", d_success))]
    return ["", "Closer to the paper's figure: %s. %s." % ("; ".join(closer), "; ".join(told).capitalize())]


def _reading(reading, data, succ, paper, seed, reps):
    """One reading's rows for readings.csv and its lines for readings.md."""
    a, a_says, b, b_says = reading
    ref = paper.get(a, {})
    key = ("reading", a, b)
    x, y = data[(a, "greedy")], data[(b, "greedy")]
    d_living = st.mean_difference(x, y, st.keyed_rng(seed, *key, "living"), reps)
    d_success = st.mean_difference(succ[(a, "greedy")], succ[(b, "greedy")], st.keyed_rng(seed, *key, "success"), reps)
    poi = st.probability_of_improvement(x, y, st.keyed_rng(seed, *key, "improvement"), reps)
    va, vb = (float(np.mean(np.concatenate(data[(v, "greedy")]))) for v in (a, b))
    sa, sb = (float(np.mean(np.concatenate(succ[(v, "greedy")]))) for v in (a, b))
    rows = [{"first": a, "second": b, "measure": measure, "first_value": p, "second_value": q, "paper": paper_value,
             "estimate": est[0], "lo": est[1][0], "hi": est[1][1]} for measure, p, q, paper_value, est in (
        ("living_mean", va, vb, ref.get("living_trained"), d_living),
        ("success_mean", sa, sb, None if "success_trained" not in ref else ref["success_trained"] / 100.0, d_success),
        ("poi_runs", None, None, None, poi["runs"]), ("poi_episodes", None, None, None, poi["episodes"]))]
    md = ["- **%s** (%d runs): %s." % (a, len(x), a_says), "- **%s** (%d runs): %s." % (b, len(y), b_says), "",
          "| measure | %s | %s | paper (%s) | %s minus %s [95 %% CI] |" % (a, b, a, a, b), "| --- | --- | --- | --- | --- |",
          "| living steps | %.1f | %.1f | %s | %s |" % (va, vb, ref.get("living_trained", "-"), fmt_ci(*d_living)),
          "| success %% | %.0f | %.0f | %s | %s |" % (100 * sa, 100 * sb, "%.0f" % ref["success_trained"]
                                                    if "success_trained" in ref else "-", fmt_ci(*d_success, 0, 100)), "",
          "P(%s > %s): runs %s, episodes %s." % (a, b, fmt_ci(*poi["runs"], 2), fmt_ci(*poi["episodes"], 2))]
    if "living_trained" in ref:
        md += _closer(a, b, va, vb, sa, sb, ref, d_living, d_success)
    return rows, md + [""]


def write_readings(out, readings, data, succ, paper, seed, reps):
    """readings.md, and readings.csv where both readings of a pair were evaluated."""
    rows, md = [], ["# Two readings of the paper's stochastic seeker", "", READINGS_INTRO, ""]
    for a, a_says, b, b_says in readings:
        if (a, "greedy") not in data or (b, "greedy") not in data:
            missing = [v for v in (a, b) if (v, "greedy") not in data]
            md.append("%s against %s: needs a run of each (%s %s none)." % (
                a, b, " and ".join(missing), "has" if len(missing) == 1 else "have"))
            continue
        r, lines = _reading((a, a_says, b, b_says), data, succ, paper, seed, reps)
        rows += r
        md += lines
    if rows:
        write_rows(os.path.join(out, "readings.csv"),
                   [{k: (round(v, 4) if isinstance(v, float) else ("" if v is None else v)) for k, v in r.items()}
                    for r in rows])
    with open(os.path.join(out, "readings.md"), "w") as f:
        f.write("\n".join(md))


def write_all(out, source, cfg, order, seed, reps):
    """Every output of the module's docstring into `out`; returns the number of table rows."""
    os.makedirs(out, exist_ok=True)
    rows, data, succ = collect(source, order, seed, reps)
    _rounded_rows(os.path.join(out, "table2.csv"), rows, FIELDS)
    md = table_markdown(source, rows, order, cfg.paper, data, reps)
    order_rows, rho, in_paper = orderings(data, order, cfg, seed, reps)
    omd = write_orderings(out, order_rows, rho, in_paper)
    readings = cfg.readings()
    if any((x, "greedy") in data for r in readings for x in (r[0], r[2])):
        omd += ["The two readings of the paper's stochastic seeker, side by side: [readings.md](readings.md).", ""]
    with open(os.path.join(out, "table2.md"), "w") as f:
        f.write("\n".join(md + omd))
    with open(os.path.join(out, "orderings.md"), "w") as f:
        f.write("\n".join(omd))
    write_readings(out, readings, data, succ, cfg.paper, seed, reps)
    present = [v for v in order if (v, "greedy") in data]
    if present:
        performance_profile(out, data, present, seed, reps)
    return len(rows)


def main(argv=None):
    """table2.py: Table 2 of the sweep's runs (default) or of one evaluation of the shipped policies."""
    args = parse_selection("Table 2 with 95 % intervals, the paper's orderings and the two readings of its stochastic "
                           "seeker: of each game's sweep runs, or (--evaluations) of the shipped policies.", argv,
                           lambda p: p.add_argument("--evaluations", help="the shipped policies' evaluations "
                                                    "(hideseek_pipeline report --from-scratch's REPORT/evaluations) "
                                                    "instead of the sweep's runs"), game=None)
    cfg = Config(args.root)
    if args.evaluations:
        source = EvaluationsSource(os.path.abspath(args.evaluations))
        try:
            source.check(cfg.table_order())
        except ValueError as e:
            print("table2: %s" % e, file=sys.stderr)
            return 2
        made = [(source, args.out or os.path.join(os.path.dirname(source.folder), "table2_shipped"))]
    else:
        made = [(SweepSource(args.root, sweep_runs(args.root, args.steps, set(args.extra), game=game), game), out)
                for game, out in outputs(args, cfg.sweep_games(), "table2_seeds")]
    for source, out in made:
        try:
            n = write_all(out, source, cfg, cfg.table_order(), args.seed, args.reps)
        except ValueError as e:  # an evaluation without episodes
            print("table2: %s" % e, file=sys.stderr)
            return 2
        print("table2: %d variant rows from %d runs into %s" % (n, source.run_count(), out))
    return 0
