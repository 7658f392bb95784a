"""Tables across training seeds, and the formatting every table here shares: Table 3 (what the
features say about S and H) and the behaviour table, from every run's per-run analysis."""
import csv
import os

import numpy as np

from . import stats as st
from .runs import read_csv
from .states import transition_factors


def write_rows(path, rows, fields=None):
    """Rows (dicts) as a CSV file, with `fields` (default: the first row's keys) as its header."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields or list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in (fields or list(rows[0]))})


def write_table(out, name, rows, title, intro, columns, md_rows, fields=None):
    """OUT/NAME.csv (rows, with `fields` as its header: default the first row's keys) and OUT/NAME.md
    (title, intro, a markdown table); nothing without rows."""
    if not rows:
        return
    write_rows(os.path.join(out, name + ".csv"), rows, fields)
    text = ["# " + title, "", intro, "", "| " + " | ".join(columns) + " |", "|" + " --- |" * len(columns)] + md_rows
    with open(os.path.join(out, name + ".md"), "w") as f:
        f.write("\n".join(text + [""]))


def fmt_ci(point, ci, digits=1, scale=1.0):
    """point [low, high], each scaled and with `digits` decimals."""
    f = "%%.%df" % digits
    return (f + " [" + f + ", " + f + "]") % (point * scale, ci[0] * scale, ci[1] * scale)


def interval_text(lo, hi, runs, fmt):
    """ [lo, hi] for a bootstrap interval over 3 or more runs; (range of 2 runs: lo to hi) for two,
    where the bootstrap over runs can only return their range."""
    if runs == 2:
        return (" (range of 2 runs: " + fmt + " to " + fmt + ")") % (lo, hi)
    return (" [" + fmt + ", " + fmt + "]") % (lo, hi)


def rounded(x, digits=4):
    """A number for a CSV cell: empty where it is not a number (no interval over one run)."""
    return "" if np.isnan(x) else round(x, digits)


def ci_over_runs(values, seed, reps, *key):
    """Mean over runs and its bootstrap interval, drawn from the generator of `key` (stats.keyed_rng)."""
    return st.mean_over_runs(values, st.keyed_rng(seed, *key), reps)


TABLE3_INTRO = (
    "Balanced accuracy (%) of a linear probe on the shared probe set's held-out episodes "
    "([docs/analysis.md](ANALYSIS_MD)): the trained network of each run, mean over the variant's runs "
    "with a 95 % bootstrap interval over runs (none with one run; with two runs the bootstrap returns their "
    "range, and the table says so); the mean of five random-init networks "
    "and the raw pixels, the same images for every variant; the gain, trained minus random init, per run "
    "and then over runs. S: the hider sees the seeker; H: the seeker sees the hider; H|S=1 and H|S=0: H "
    "among the images where S is 1 or 0. The paper's figures are accuracies on each policy's own "
    "rollouts, whose label priors differ from variant to variant: they stand beside ours, not as the "
    "same measurement.")
TABLE3_COLUMNS = ["variant", "target", "runs", "trained [95 % CI]", "random init: mean (range of 5) / pixels",
                  "gain [95 % CI]", "paper: trained / random"]
TARGETS = ("S", "H", "H|S=1", "H|S=0")


def probe_value(rows, target, key="gain_over_random_init"):
    """A probe's figure for one target from a run's probes.csv (nan where the target is absent)."""
    for r in rows:
        if r["target"] == target:
            return float(r[key])
    return np.nan


def _table3_row(v, target, analysed, paper_row, random_range, seed, reps):
    trained = [probe_value(r, target, "balanced_accuracy") for _, r in analysed]
    m, ci = ci_over_runs(trained, seed, reps, "table3", v, target, "trained")
    g, gci = ci_over_runs([probe_value(r, target) for _, r in analysed], seed, reps, "table3", v, target, "gain")
    first = analysed[0][1]
    key = {"S": "S", "H": "H"}.get(target)
    row = {"variant": v, "target": target, "runs": len(trained), "trained": round(m, 4),
           "trained_ci_low": rounded(ci[0]), "trained_ci_high": rounded(ci[1]),
           "random_init_mean": round(probe_value(first, target, "random_init_mean"), 4),
           "random_init_min": random_range[0], "random_init_max": random_range[1],
           "pixels": round(probe_value(first, target, "pixels"), 4), "gain": round(g, 4),
           "gain_ci_low": rounded(gci[0]), "gain_ci_high": rounded(gci[1]),
           "paper_trained": paper_row.get("probe_%s_trained" % key, "") if key else "",
           "paper_random": paper_row.get("probe_%s_random" % key, "") if key else ""}
    return row, _table3_line(row, g)


def _table3_line(row, gain):
    """The row's markdown line; `gain`, unrounded, as the CSV's is rounded."""
    n = row["runs"]

    def pct(x, lo, hi):
        return "%.1f" % (100 * x) + ("" if lo == "" else interval_text(lo * 100, hi * 100, n, "%.1f"))
    spread = "" if row["random_init_min"] == "" else " (%.1f to %.1f)" % (
        100 * row["random_init_min"], 100 * row["random_init_max"])
    gain = ("%+.1f" % (100 * gain)) + ("" if row["gain_ci_low"] == "" else interval_text(
        100 * row["gain_ci_low"], 100 * row["gain_ci_high"], n, "%+.1f"))
    paper = "%s / %s" % (row["paper_trained"] or "-", row["paper_random"] or "-") if row["paper_trained"] != "" else "-"
    return "| %s | %s | %d | %s | %.1f%s / %.1f | %s | %s |" % (
        row["variant"], row["target"].replace("|", "\\|"), n,
        pct(row["trained"], row["trained_ci_low"], row["trained_ci_high"]), 100 * row["random_init_mean"], spread,
        100 * row["pixels"], gain, paper)


def table3(root, out, R, variants, paper, seed, reps):
    """Table 3 across training seeds (table3_seeds.md/.csv), from every run's probes.csv, beside the
    random-init networks (docs/probe_set/baselines.csv) and `paper`'s accuracies."""
    base = read_csv(os.path.join(root, "docs", "probe_set", "baselines.csv")) or []

    def random_range(target):
        vals = [float(b["balanced_accuracy"]) for b in base
                if b["target"] == target and b["representation"].startswith("random_init_")]
        return (round(min(vals), 4), round(max(vals), 4)) if vals else ("", "")

    made = [_table3_row(v, target, analysed, paper.get(v, {}), random_range(target), seed, reps)
            for v in variants for analysed in [R.analysed(v, "probes")] if analysed for target in TARGETS]
    analysis_md = os.path.relpath(os.path.join(root, "docs", "analysis.md"), out)
    write_table(out, "table3_seeds", [r for r, _ in made], "Table 3 across training seeds: what the features say "
                "about S and H", TABLE3_INTRO.replace("ANALYSIS_MD", analysis_md), TABLE3_COLUMNS,
                [line for _, line in made])


BEHAVIOUR = (("backward_share", "walks backward (share of steps)"),
             ("sees_seeker_share", "sees the seeker (share of steps)"),
             ("seen_share", "is seen (share of steps)"),
             ("line_of_sight_breaks_per_100", "breaks the line of sight (per 100 steps)"),
             ("seeker_lost_per_100", "loses the seeker from view (per 100 steps)"),
             ("distance_turns_per_100", "turns the distance round (per 100 steps)"))
BEHAVIOUR_INTRO = (
    "Each run's 100 greedy rollouts on seeds 10000-10099 (`hideseek_pipeline analyze`); per variant the mean over "
    "its runs with a 95 % bootstrap interval over runs (none with one run; with two runs the bootstrap returns "
    "their range, and the table says so), and below it the random "
    "hider of the same variant (1000 episodes). Walking backward: the hider's action moves it backward; "
    "breaking the line of sight: H goes from 1 to 0; losing the seeker: S goes from 1 to 0; turns of the "
    "distance: sign changes of its 5-step average's slope.")


def _behaviour_variant(v, analysed, base, seed, reps):
    """The variant's rows and its two markdown lines (its runs, then its random hider)."""
    rows, cells, random_cells = [], [], []
    for key, _ in BEHAVIOUR:
        m, ci = ci_over_runs([float(r[0][key]) for _, r in analysed], seed, reps, "behaviour", v, key)
        rnd = float(base[0][key]) if base else np.nan
        rows.append({"variant": v, "measure": key, "runs": len(analysed), "trained": round(m, 4),
                     "ci_low": rounded(ci[0]), "ci_high": rounded(ci[1]), "random": rounded(rnd)})
        f = "%%.%df" % (2 if m < 10 else 1)
        cells.append((f % m) + ("" if np.isnan(ci[0]) else interval_text(ci[0], ci[1], len(analysed), f)))
        random_cells.append("-" if np.isnan(rnd) else f % rnd)
    return rows, ["| %s | %d | %s |" % (v, len(analysed), " | ".join(cells)),
                  "| %s, random hider | | %s |" % (v, " | ".join(random_cells))]


def behaviour_table(out, R, variants, seed, reps):
    """behaviour_seeds.md/.csv: each behaviour measure per variant, mean [95 % CI over runs], and
    the random hider's."""
    rows, md = [], []
    for v in variants:
        analysed = R.analysed(v, "behaviour")
        if analysed:
            r, lines = _behaviour_variant(v, analysed, R.baseline(v, "behaviour"), seed, reps)
            rows += r
            md += lines
    write_table(out, "behaviour_seeds", rows, "Behaviour across training seeds", BEHAVIOUR_INTRO,
                ["variant", "runs"] + [label for _, label in BEHAVIOUR], md)


# The paper's two highlighted transitions (Figure 5, this project's reading): (from, to, name).
TRANSITIONS = (((1, 1), (0, 1), "turns away: S1H1 -> S0H1"), ((0, 1), (0, 0), "leaves the view: S0H1 -> S0H0"))
FACTORS = (("time_in", "time in the from-state (share of steps)", "%.3f"),
           ("leave_rate", "leaves it (per 100 steps there)", "%.1f"),
           ("given", "to the to-state (P, given it leaves)", "%.3f"),
           ("rate", "the transition (per 100 steps)", "%.2f"))
FACTORS_INTRO = (
    "Each transition's rate per 100 steps, on which the claims decide it, is the product of three factors: the "
    "share of steps the hider spends in the from-state, how often it leaves that state (changes of S or H per "
    "100 steps spent there) and where it goes when it leaves (the conditional form: P(to-state | it leaves)). "
    "Each run's row multiplies out to its rate (where the hider never leaves the from-state, the rate is 0 and "
    "where it goes is undefined: -), so a run that misses the random hider's rate shows which factor does it. "
    "The factors are given per run, not averaged: two runs can miss on opposite factors, and a product of means "
    "is not a mean of products. Below a variant's runs, the mean of their rates with a 95 % bootstrap interval "
    "over runs (with two runs, their range), as the claim takes it, and the random hider of the same variant. "
    "Greedy rollouts on seeds 10000-10099 (`hideseek_pipeline analyze`).")
FACTORS_COLUMNS = ["transition", "variant", "run"] + [label for _, label, _ in FACTORS]


def _factor_cells(f):
    return ["-" if not np.isfinite(f[key]) else fmt % f[key] for key, _, fmt in FACTORS]


def transition_factors_table(out, R, variants, seed, reps):
    """transitions_factors_seeds.md/.csv: each highlighted transition's rate split into its three
    factors (states.transition_factors), run by run, with the variant's mean rate over runs and its
    random hider."""
    rows, md = [], []
    for src, dst, name in TRANSITIONS:
        for v in variants:
            runs = [(n, transition_factors(t, s, src, dst)) for n in R.names(v)
                    for t, s in [(R.analysis(n, "transitions"), R.analysis(n, "states"))] if t and s]
            if not runs:
                continue
            for n, f in runs:
                rows.append(dict(transition=name, variant=v, run=n, **{k: rounded(f[k]) for k, _, _ in FACTORS}))
                md.append("| %s | %s | %s | %s |" % (name, v, n, " | ".join(_factor_cells(f))))
            m, ci = ci_over_runs([f["rate"] for _, f in runs], seed, reps, "factors", name, v)
            rows.append({"transition": name, "variant": v, "run": "mean of %d runs" % len(runs), "rate": rounded(m),
                         "rate_ci_low": rounded(ci[0]), "rate_ci_high": rounded(ci[1])})
            md.append("| %s | %s | mean of %d runs | | | | %s |" % (
                name, v, len(runs), ("%.2f" % m) + ("" if np.isnan(ci[0]) else interval_text(ci[0], ci[1], len(runs),
                                                                                            "%.2f"))))
            base_t, base_s = R.baseline(v, "transitions"), R.baseline(v, "states")
            if base_t and base_s:
                f = transition_factors(base_t, base_s, src, dst)
                rows.append(dict(transition=name, variant=v, run="random hider",
                                 **{k: rounded(f[k]) for k, _, _ in FACTORS}))
                md.append("| %s | %s | random hider | %s |" % (name, v, " | ".join(_factor_cells(f))))
    write_table(out, "transitions_factors_seeds", rows, "The highlighted transitions, factor by factor",
                FACTORS_INTRO, FACTORS_COLUMNS, md,
                ["transition", "variant", "run"] + [k for k, _, _ in FACTORS] + ["rate_ci_low", "rate_ci_high"])
    return rows
