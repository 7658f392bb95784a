#!/usr/bin/env python3
"""The paper's Figures 4-7 across training seeds, from the committed per-run analysis outputs
(docs/runs/<run>/analysis/, hideseek_pipeline analyze) and the random hider's
(docs/analysis/baselines/<variant>/random/).

usage: seed_figures.py [--root DIR] [--out DIR] [--steps N] [--extra RUN ...] [--reps N]

Writes into OUT (default ROOT/docs/report):
- state_frequencies_seeds.png/.csv (Figure 4): each state's frequency, trained minus the random
  hider of the same variant, mean over runs with a 95 % bootstrap interval over runs;
- transitions_seeds.png/.csv (Figure 5): P(S1H1 -> S0H1 | leaving S1H1) (turning away) and
  P(S0H1 -> S0H0 | leaving S0H1) (leaving the seeker's view), per variant, trained and random;
- distance_seeds.png (Figure 6): the mean distance between the agents over the episode, per
  variant, with the spread between its runs;
- survival_representation.png/.csv (Figure 7): probe gain (mean of S and H, over the 5 random-init
  networks) against living steps, one point per run, with the quadratic fit of the claims table
  (the runs of the paper's seven variants; a variant of our own is drawn hollow and not fitted).
- table3_seeds.md/.csv (Table 3): each variant's probe balanced accuracy on the shared probe set
  for S, H, H where S = 1 and H where S = 0, trained (mean over runs, 95 % interval over runs),
  the random-init networks' mean and the pixels, and the gain with its interval, beside the
  paper's accuracies (on its own rollouts, so beside ours, not comparable one to one);
- behaviour_seeds.md/.csv: how often each variant's hider walks backward, sees the seeker, is
  seen, breaks the line of sight, loses the seeker from view and turns the distance round (mean
  over runs with a 95 % interval over runs), beside the random hider of the same variant;
- tsne_seeds.png/.csv: the t-SNE of the features on the probe set's test images of every run
  that has one (docs/runs/<run>/analysis/tsne.csv: the runs whose weights were at hand when the
  per-run t-SNE was added, and every run after), panels variant by variant after random-init
  network 0, coloured by the (S, H) cell; and per variant how well the features' neighbourhoods
  separate S and H (11-nearest-neighbour balanced accuracy in 50 principal components, the image's
  own episode left out; mean over runs with its interval) against the random-init networks (mean
  and range) and the pixels.
An interval over one run is no interval: variants with one run are drawn without one. With two
runs a bootstrap over runs returns their range: the tables say "range of 2 runs" there.
"""
import argparse
import os
import sys
import textwrap
import warnings

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sweep_stats as st  # noqa: E402
from claims import PAPER_VARIANTS, Runs, probe_value, read_csv, transition_prob  # noqa: E402
from hideseek_analysis import STATE_NAMES  # noqa: E402
from sweep_table2 import load_episodes, sweep_runs  # noqa: E402



def runs_label(n):
    return "1 run" if n == 1 else "%d runs" % n


def order(root, found):
    import yaml
    with open(os.path.join(root, "config", "paper_reference.yaml")) as f:
        paper = list((yaml.safe_load(f) or {}).get("variants") or {})
    return [v for v in paper if v in found] + sorted(v for v in found if v not in paper)


def write_table(out, name, rows, title, intro, columns, md_rows):
    """OUT/NAME.csv (rows) and OUT/NAME.md (title, intro, a markdown table); nothing without rows."""
    if not rows:
        return
    st.write_rows(os.path.join(out, name + ".csv"), rows)
    text = ["# " + title, "", intro, "", "| " + " | ".join(columns) + " |", "|" + " --- |" * len(columns)] + md_rows
    with open(os.path.join(out, name + ".md"), "w") as f:
        f.write("\n".join(text + [""]))


def interval_text(lo, hi, runs, fmt):
    """ [lo, hi] for a bootstrap interval over 3 or more runs; (range of 2 runs: lo to hi) for two,
    where the bootstrap over runs can only return their range."""
    if runs == 2:
        return (" (range of 2 runs: " + fmt + " to " + fmt + ")") % (lo, hi)
    return (" [" + fmt + ", " + fmt + "]") % (lo, hi)


def ci_over_runs(values, seed, reps, *key):
    """Mean over runs and its bootstrap interval, drawn from the generator of `key` (sweep_stats.keyed_rng)."""
    rng = st.keyed_rng(seed, *key)
    values = np.asarray(values, dtype=float)
    if len(values) < 2:
        return float(values.mean()), (np.nan, np.nan)
    boot = [values[rng.integers(0, len(values), len(values))].mean() for _ in range(reps)]
    return float(values.mean()), st.interval(boot)


def save(fig, out, name, rows=None, rect=(0, 0, 1, 1)):
    """A figure as OUT/NAME.png and, with rows, its numbers as OUT/NAME.csv; rect: the part of the
    figure the panels fill (room for a legend below them)."""
    import matplotlib.pyplot as plt
    fig.tight_layout(rect=rect)
    fig.savefig(os.path.join(out, name + ".png"), dpi=110)
    plt.close(fig)
    if rows:
        st.write_rows(os.path.join(out, name + ".csv"), rows)


def table3(root, out, R, variants, seed, reps):
    """Table 3 across training seeds (table3_seeds.md/.csv), from every run's probes.csv."""
    import yaml
    with open(os.path.join(root, "config", "paper_reference.yaml")) as f:
        paper = (yaml.safe_load(f) or {}).get("variants") or {}
    base = read_csv(os.path.join(root, "docs", "probe_set", "baselines.csv")) or []

    def random_range(target):
        vals = [float(b["balanced_accuracy"]) for b in base
                if b["target"] == target and b["representation"].startswith("random_init_")]
        return (round(min(vals), 4), round(max(vals), 4)) if vals else ("", "")

    rows, md = [], []
    for v in variants:
        analysed = R.analysed(v, "probes")
        if not analysed:
            continue
        for target in ("S", "H", "H|S=1", "H|S=0"):
            trained = [probe_value(r, target, "balanced_accuracy") for _, r in analysed]
            gains = [probe_value(r, target) for _, r in analysed]
            m, ci = ci_over_runs(trained, seed, reps, "table3", v, target, "trained")
            g, gci = ci_over_runs(gains, seed, reps, "table3", v, target, "gain")
            first = analysed[0][1]
            ref = paper.get(v, {})
            key = {"S": "S", "H": "H"}.get(target)
            row = {"variant": v, "target": target, "runs": len(trained), "trained": round(m, 4),
                   "trained_ci_low": "" if np.isnan(ci[0]) else round(ci[0], 4),
                   "trained_ci_high": "" if np.isnan(ci[1]) else round(ci[1], 4),
                   "random_init_mean": round(probe_value(first, target, "random_init_mean"), 4),
                   "random_init_min": random_range(target)[0], "random_init_max": random_range(target)[1],
                   "pixels": round(probe_value(first, target, "pixels"), 4), "gain": round(g, 4),
                   "gain_ci_low": "" if np.isnan(gci[0]) else round(gci[0], 4),
                   "gain_ci_high": "" if np.isnan(gci[1]) else round(gci[1], 4),
                   "paper_trained": ref.get("probe_%s_trained" % key, "") if key else "",
                   "paper_random": ref.get("probe_%s_random" % key, "") if key else ""}
            rows.append(row)

            def pct(x, lo, hi):
                return "%.1f" % (100 * x) + ("" if lo == "" else interval_text(lo * 100, hi * 100, len(trained), "%.1f"))
            spread = "" if row["random_init_min"] == "" else " (%.1f to %.1f)" % (
                100 * row["random_init_min"], 100 * row["random_init_max"])
            md.append("| %s | %s | %d | %s | %.1f%s / %.1f | %s | %s |" % (
                v, target.replace("|", "\\|"), len(trained), pct(row["trained"], row["trained_ci_low"], row["trained_ci_high"]),
                100 * row["random_init_mean"], spread, 100 * row["pixels"],
                ("%+.1f" % (100 * g)) + ("" if row["gain_ci_low"] == "" else interval_text(
                    100 * row["gain_ci_low"], 100 * row["gain_ci_high"], len(trained), "%+.1f")),
                "%s / %s" % (row["paper_trained"] or "-", row["paper_random"] or "-") if row["paper_trained"] != "" else "-"))
    write_table(out, "table3_seeds", rows, "Table 3 across training seeds: what the features say about S and H",
                ("Balanced accuracy (%) of a linear probe on the shared probe set's held-out episodes "
                 "([docs/analysis.md](../analysis.md)): the trained network of each run, mean over the variant's runs "
                 "with a 95 % bootstrap interval over runs (none with one run; with two runs the bootstrap returns their "
                 "range, and the table says so); the mean of five random-init networks "
                 "and the raw pixels, the same images for every variant; the gain, trained minus random init, per run "
                 "and then over runs. S: the hider sees the seeker; H: the seeker sees the hider; H|S=1 and H|S=0: H "
                 "among the images where S is 1 or 0. The paper's figures are accuracies on each policy's own "
                 "rollouts, whose label priors differ from variant to variant: they stand beside ours, not as the "
                 "same measurement."),
                ["variant", "target", "runs", "trained [95 % CI]", "random init: mean (range of 5) / pixels",
                 "gain [95 % CI]", "paper: trained / random"], md)


BEHAVIOUR = (("backward_share", "walks backward (share of steps)"),
             ("sees_seeker_share", "sees the seeker (share of steps)"),
             ("seen_share", "is seen (share of steps)"),
             ("line_of_sight_breaks_per_100", "breaks the line of sight (per 100 steps)"),
             ("seeker_lost_per_100", "loses the seeker from view (per 100 steps)"),
             ("distance_turns_per_100", "turns the distance round (per 100 steps)"))


def behaviour_table(out, R, variants, seed, reps):
    """behaviour_seeds.md/.csv: each behaviour measure per variant, mean [95 % CI over runs], and
    the random hider's."""
    rows, md = [], []
    for v in variants:
        analysed = R.analysed(v, "behaviour")
        if not analysed:
            continue
        base = R.baseline(v, "behaviour")
        cells, random_cells = [], []
        for key, _ in BEHAVIOUR:
            m, ci = ci_over_runs([float(r[0][key]) for _, r in analysed], seed, reps, "behaviour", v, key)
            rnd = float(base[0][key]) if base else np.nan
            rows.append({"variant": v, "measure": key, "runs": len(analysed), "trained": round(m, 4),
                         "ci_low": "" if np.isnan(ci[0]) else round(ci[0], 4),
                         "ci_high": "" if np.isnan(ci[1]) else round(ci[1], 4),
                         "random": "" if np.isnan(rnd) else round(rnd, 4)})
            digits = 2 if m < 10 else 1
            f = "%%.%df" % digits
            cells.append((f % m) + ("" if np.isnan(ci[0]) else interval_text(ci[0], ci[1], len(analysed), f)))
            random_cells.append("-" if np.isnan(rnd) else f % rnd)
        md.append("| %s | %d | %s |" % (v, len(analysed), " | ".join(cells)))
        md.append("| %s, random hider | | %s |" % (v, " | ".join(random_cells)))
    write_table(out, "behaviour_seeds", rows, "Behaviour across training seeds",
                ("Each run's 100 greedy rollouts on seeds 10000-10099 (`hideseek_pipeline analyze`); per variant the mean over "
                 "its runs with a 95 % bootstrap interval over runs (none with one run; with two runs the bootstrap returns "
                 "their range, and the table says so), and below it the random "
                 "hider of the same variant (1000 episodes). Walking backward: the hider's action moves it backward; "
                 "breaking the line of sight: H goes from 1 to 0; losing the seeker: S goes from 1 to 0; turns of the "
                 "distance: sign changes of its 5-step average's slope."),
                ["variant", "runs"] + [label for _, label in BEHAVIOUR], md)


CELL_COLOURS = {(0, 0): ("#b0b0b0", "S0 H0: neither sees"), (1, 0): ("#1f77b4", "S1 H0: hider sees, unseen"),
                (0, 1): ("#ff7f0e", "S0 H1: seen, not seeing"), (1, 1): ("#d62728", "S1 H1: both see")}


def tsne_figure(root, out, R, variants, seed, reps):
    """The t-SNE across training seeds: the committed coordinates of every analysed run, one row per
    variant, and the neighbourhood scores with intervals over runs (tsne_seeds.csv)."""
    import matplotlib.pyplot as plt
    probe = os.path.join(root, "docs", "probe_set")
    labels = {int(r["image"]): (int(r["S"]), int(r["H"])) for r in read_csv(os.path.join(probe, "labels.csv"))}
    rows_of = {v: [(n, read_csv(os.path.join(root, "docs", "runs", n, "analysis", "tsne.csv")))
                   for n, _ in R.analysed(v, "tsne_neighbours")] for v in variants}
    rows_of = {v: r for v, r in rows_of.items() if r}
    if not rows_of:
        print("seed_figures: no run has a t-SNE yet; tsne_seeds not drawn")
        return
    base = read_csv(os.path.join(probe, "tsne_baselines.csv"))

    def base_mean(prefix, target, how=np.mean):
        vals = [float(b["neighbour_balanced_accuracy"]) for b in base
                if b["target"] == target and b["representation"].startswith(prefix)]
        return round(float(how(vals)), 4) if vals else ""

    table = []
    for v in rows_of:
        scores = R.analysed(v, "tsne_neighbours")
        for target in ("S", "H"):
            vals = [float(r["neighbour_balanced_accuracy"]) for _, rows in scores for r in rows if r["target"] == target]
            m, ci = ci_over_runs(vals, seed, reps, "tsne", v, target)
            table.append({"variant": v, "target": target, "runs": len(vals), "neighbour_balanced_accuracy": round(m, 4),
                          "ci_low": "" if np.isnan(ci[0]) else round(ci[0], 4),
                          "ci_high": "" if np.isnan(ci[1]) else round(ci[1], 4),
                          "random_init_mean": base_mean("random_init_", target),
                          "random_init_min": base_mean("random_init_", target, np.min),
                          "random_init_max": base_mean("random_init_", target, np.max),
                          "pixels": base_mean("pixels", target)})
    random0 = read_csv(os.path.join(probe, "tsne_random_init_0.csv"))
    panels = []  # (title, coordinates): random-init network 0, then every run, variant by variant
    if random0:
        panels.append(("random-init network 0\nS %.2f, H %.2f" % tuple(
            float(b["neighbour_balanced_accuracy"]) for t in ("S", "H") for b in base
            if b["representation"] == "random_init_0" and b["target"] == t), random0))
    for v, runs in rows_of.items():
        scores = dict((n, {r["target"]: float(r["neighbour_balanced_accuracy"]) for r in rows})
                      for n, rows in R.analysed(v, "tsne_neighbours"))
        panels += [("%s\nS %.2f, H %.2f" % (n, scores[n]["S"], scores[n]["H"]), coords) for n, coords in runs]
    cols = min(4, len(panels))
    nrows = -(-len(panels) // cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(2.6 * cols, 2.5 * nrows + 1.5), squeeze=False)
    for k, ax in enumerate(axes.flat):
        if k >= len(panels):
            ax.axis("off")
            continue
        title, coords = panels[k]
        pts = np.array([[float(r["x"]), float(r["y"])] for r in coords])
        cells = [labels[int(r["image"])] for r in coords]
        for cell, (colour, _) in CELL_COLOURS.items():
            pick = np.array([c == cell for c in cells])
            if pick.any():
                ax.scatter(pts[pick, 0], pts[pick, 1], s=2, color=colour, rasterized=True)
        ax.set_title(title, fontsize=8)
        ax.set_xticks([])
        ax.set_yticks([])
    handles = [plt.Line2D([], [], marker="o", ls="", color=c, label=l) for c, l in CELL_COLOURS.values()]
    fig.legend(handles=handles, loc="lower center", ncol=2, fontsize=8, frameon=False)
    # The runs counted elsewhere that this figure cannot hold: analysed before the t-SNE existed, with
    # their weights lost since (the figure names them, so that it never passes for every run).
    held = {n for runs in rows_of.values() for n, _ in runs}
    without = [n for v in variants for n in R.names(v) if n not in held]
    title = ("t-SNE of the features on the probe set's %d test images. Under each name: how well the features'\n"
             "neighbourhoods separate S and H (11-NN balanced accuracy in 50 principal components, own episode left "
             "out;\n5 random-init networks: S %.2f to %.2f, H %.2f to %.2f; pixels: S %.2f, H %.2f)" % (
                 len(panels[0][1]), *(base_mean("random_init_", t, how) or np.nan for t in ("S", "H")
                                      for how in (np.min, np.max)),
                 base_mean("pixels", "S") or np.nan, base_mean("pixels", "H") or np.nan))
    extra = []
    if without:
        extra = textwrap.wrap("Holds %d of %d runs; no t-SNE (analysed before it existed, weights lost): %s" % (
            len(held), len(held) + len(without), ", ".join(without)), 120)
        title += "\n" + "\n".join(extra)
    fig.suptitle(title, fontsize=9)
    top = 0.6 + 0.2 * len(extra)  # room for the title's lines
    save(fig, out, "tsne_seeds", table, rect=(0, 0.9 / (2.5 * nrows + 1.5), 1, 1 - top / (2.5 * nrows + 1.5)))


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    st.add_selection_args(p, os.path.dirname(os.path.abspath(__file__)))
    args = p.parse_args(argv)
    root = os.path.abspath(args.root)
    out = args.out or os.path.join(root, "docs", "report")
    os.makedirs(out, exist_ok=True)
    found = sweep_runs(root, args.steps, set(args.extra))
    R = Runs(root, found)
    variants = [v for v in order(root, found) if R.analysed(v, "states")]
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    if not variants:
        print("seed_figures: no analysed run yet; nothing drawn")
        return 0

    # Figure 4: states relative to random.
    rows = []
    fig, ax = plt.subplots(figsize=(11, 4.5))
    width = 0.8 / len(variants)
    for k, v in enumerate(variants):
        base = R.baseline(v, "states")
        if not base:
            continue
        b = np.array([float(r["frequency"]) for r in base])
        runs = [np.array([float(r["frequency"]) for r in rows_]) - b for _, rows_ in R.analysed(v, "states")]
        means, lo, hi = [], [], []
        for i in range(8):
            m, ci = ci_over_runs([r[i] for r in runs], args.seed, args.reps, "states", v, i)
            means.append(m)
            lo.append(ci[0])
            hi.append(ci[1])
            rows.append({"variant": v, "state": STATE_NAMES[i], "runs": len(runs), "relative_frequency": round(m, 5),
                         "ci_low": "" if np.isnan(ci[0]) else round(ci[0], 5),
                         "ci_high": "" if np.isnan(ci[1]) else round(ci[1], 5)})
        x = np.arange(8) + (k - (len(variants) - 1) / 2) * width
        err = None if np.isnan(lo).any() else [np.array(means) - lo, np.array(hi) - means]
        ax.bar(x, means, width, yerr=err, capsize=2, label="%s (%s)" % (v, runs_label(len(runs))))
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xticks(np.arange(8))
    ax.set_xticklabels(STATE_NAMES)
    ax.set_ylabel("frequency, trained minus random hider")
    ax.set_title("States (S: hider sees seeker, H: seeker sees hider, O: obstacle in view); bars: 95 % CI over runs\n"
                 "(with 2 runs of a variant, the bootstrap gives their range)", fontsize=10)
    ax.legend(fontsize=7, ncol=2)
    save(fig, out, "state_frequencies_seeds", rows)

    # Figure 5: the two highlighted transitions.
    trows = []
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for ax, (src, dst, title) in zip(axes, (((1, 1), (0, 1), "turns away: S1H1 -> S0H1"),
                                            ((0, 1), (0, 0), "leaves the view: S0H1 -> S0H0"))):
        for k, v in enumerate(variants):
            vals = [transition_prob(r, src, dst) for _, r in R.analysed(v, "transitions")]
            vals = [x for x in vals if np.isfinite(x)]
            base = R.baseline(v, "transitions")
            rnd = transition_prob(base, src, dst) if base else np.nan
            if not vals:
                continue
            m, ci = ci_over_runs(vals, args.seed, args.reps, "transition", title, v)
            err = None if np.isnan(ci[0]) else [[m - ci[0]], [ci[1] - m]]
            ax.errorbar([k], [m], yerr=err, fmt="o", capsize=3, color="C0", label="trained" if k == 0 else None)
            ax.plot([k], [rnd], "x", color="C3", label="random hider" if k == 0 else None)
            trows.append({"transition": title, "variant": v, "runs": len(vals), "trained": round(m, 4),
                          "ci_low": "" if np.isnan(ci[0]) else round(ci[0], 4),
                          "ci_high": "" if np.isnan(ci[1]) else round(ci[1], 4), "random": round(float(rnd), 4)})
        ax.set_xticks(range(len(variants)))
        ax.set_xticklabels(variants, rotation=30, ha="right", fontsize=8)
        ax.set_ylim(0, 1)
        ax.set_title(title)
        ax.set_ylabel("P(to | a change out of from)")
        ax.legend(fontsize=8)
    fig.suptitle("Transitions, trained (95 % CI over runs; with 2 runs of a variant, their range) and random hider")
    save(fig, out, "transitions_seeds", trows)

    # Figure 6: distance over the episode.
    fig, ax = plt.subplots(figsize=(9, 4.5))
    for k, v in enumerate(variants):
        analysed = R.analysed(v, "distance")
        if not analysed:
            continue
        curves = [[float(r["mean_distance"]) if r["mean_distance"] else np.nan for r in rows_] for _, rows_ in analysed]
        bins = [int(r["step_bin_start"]) for r in analysed[0][1]]
        c = np.array(curves)
        with warnings.catch_warnings():  # bins no episode reached are empty: NaN, not drawn
            warnings.simplefilter("ignore", RuntimeWarning)
            mean = np.nanmean(c, axis=0)
            lo, hi = np.nanmin(c, axis=0), np.nanmax(c, axis=0)
        line, = ax.plot(bins, mean, label="%s (%s)" % (v, runs_label(len(curves))))
        if len(curves) > 1:
            ax.fill_between(bins, lo, hi, color=line.get_color(), alpha=0.15)
    ax.set_xlabel("step of the episode")
    ax.set_ylabel("mean distance between the agents (m)")
    ax.set_title("Distance over the episode (seeds 10000-10099, greedy); band: the runs' range")
    ax.legend(fontsize=7)
    save(fig, out, "distance_seeds")

    # Figure 7: survival against representation.
    pts = []
    for v in variants:
        for name, rows_ in R.analysed(v, "probes"):
            ep = os.path.join(root, "docs", "runs", name, "episodes.csv")
            if os.path.exists(ep):
                pts.append({"run": name, "variant": v, "living_steps": round(float(load_episodes(ep)[0].mean()), 2),
                            "probe_gain": round((probe_value(rows_, "S") + probe_value(rows_, "H")) / 2, 4)})
    if pts:
        fig, ax = plt.subplots(figsize=(7, 5))
        for k, v in enumerate(variants):
            xs = [q["living_steps"] for q in pts if q["variant"] == v]
            ys = [q["probe_gain"] for q in pts if q["variant"] == v]
            if xs:
                if v in PAPER_VARIANTS:
                    ax.scatter(xs, ys, label=v, color="C%d" % k)
                else:
                    ax.scatter(xs, ys, label=v + " (not fitted)", facecolors="none", edgecolors="C%d" % k)
        # The fit is the claim's (claims.py): the runs of the paper's seven variants only; a variant of
        # our own (stochasticseeker_explore) is drawn, hollow, but not fitted.
        paper = [q for q in pts if q["variant"] in PAPER_VARIANTS]
        if len({q["living_steps"] for q in paper}) >= 3:
            x = np.array([q["living_steps"] for q in paper])
            coef = np.polyfit(x, [q["probe_gain"] for q in paper], 2)
            grid = np.linspace(x.min(), x.max(), 100)
            ax.plot(grid, np.polyval(coef, grid), "k--", lw=1,
                    label="quadratic fit, the paper's variants (%d runs)" % len(paper))
        ax.set_xlabel("average living steps (evaluation seeds 0-99, greedy)")
        ax.set_ylabel("probe gain over random init (balanced accuracy, mean of S and H)")
        ax.set_title("Representation against survival, one point per run")
        ax.legend(fontsize=7)
        save(fig, out, "survival_representation", pts)
    table3(root, out, R, order(root, found), args.seed, args.reps)
    behaviour_table(out, R, order(root, found), args.seed, args.reps)
    tsne_figure(root, out, R, order(root, found), args.seed, args.reps)
    print("seed_figures: %d variants, %d analysed runs into %s" % (len(variants), sum(len(R.analysed(v, "states"))
                                                                                      for v in variants), out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
