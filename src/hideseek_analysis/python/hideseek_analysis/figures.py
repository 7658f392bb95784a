"""The paper's Figures 4-7 and the t-SNE across training seeds, and Table 2's performance profile,
from the committed per-run analysis outputs (docs/runs/<run>/analysis/, hideseek_pipeline analyze)
and the random hider's (docs/analysis/baselines/<variant>/random/).

Into OUT (default ROOT/docs/report/<game>), with their numbers beside them as .csv:
- state_frequencies_seeds.png (Figure 4): each state's frequency, trained minus the random hider
  of the same variant, mean over runs with a 95 % bootstrap interval over runs;
- transitions_seeds.png (Figure 5): P(S1H1 -> S0H1 | leaving S1H1) (turning away) and
  P(S0H1 -> S0H0 | leaving S0H1) (leaving the seeker's view), per variant, trained and random;
  transitions_factors_seeds.md/.csv: each of the two as a rate per 100 steps split into its
  factors (time in the from-state, how often the hider leaves it, where it goes);
- distance_seeds.png (Figure 6): the mean distance between the agents over the episode, per
  variant, with the spread between its runs;
- survival_representation.png (Figure 7): probe gain (mean of S and H, over the 5 random-init
  networks) against living steps, one point per run, with the quadratic fit of the claims table
  (the runs of the paper's variants; a variant of our own is drawn hollow and not fitted);
- tsne_seeds.png: the t-SNE of the features on the probe set's test images of every run that has
  one (docs/runs/<run>/analysis/tsne.csv), panels variant by variant after random-init network 0,
  coloured by the (S, H) cell; and per variant how well the features' neighbourhoods separate S
  and H (11-nearest-neighbour balanced accuracy in 50 principal components, the image's own
  episode left out; mean over runs with its interval) against the random-init networks (mean and
  range) and the pixels.
An interval over one run is no interval: variants with one run are drawn without one. With two
runs a bootstrap over runs returns their range.
"""
import os
import textwrap
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import stats as st  # noqa: E402
from .config import Config  # noqa: E402
from .runs import Runs, load_episodes, outputs, parse_selection, read_csv, sweep_runs  # noqa: E402
from .states import STATE_NAMES, transition_prob  # noqa: E402
from .tables import (TRANSITIONS, behaviour_table, ci_over_runs, probe_value, rounded, table3,  # noqa: E402
                     transition_factors_table, write_rows)


def runs_label(n):
    return "1 run" if n == 1 else "%d runs" % n


def legend_outside(ax, fontsize=7):
    """The legend to the right of the axes, where it can hide no point or curve."""
    ax.legend(fontsize=fontsize, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)


def save(fig, out, name, rows=None, rect=(0, 0, 1, 1)):
    """A figure as OUT/NAME.png and, with rows, its numbers as OUT/NAME.csv; rect: the part of the
    figure the panels fill (room for a legend below them)."""
    fig.tight_layout(rect=rect)
    fig.savefig(os.path.join(out, name + ".png"), dpi=110)
    plt.close(fig)
    if rows:
        write_rows(os.path.join(out, name + ".csv"), rows)


def _state_bars(ax, k, v, variants, R, seed, reps, rows):
    base = R.baseline(v, "states")
    if not base:
        return
    b = np.array([float(r["frequency"]) for r in base])
    runs = [np.array([float(r["frequency"]) for r in rows_]) - b for _, rows_ in R.analysed(v, "states")]
    means, lo, hi = [], [], []
    for i in range(8):
        m, ci = ci_over_runs([r[i] for r in runs], seed, reps, "states", v, i)
        means.append(m)
        lo.append(ci[0])
        hi.append(ci[1])
        rows.append({"variant": v, "state": STATE_NAMES[i], "runs": len(runs), "relative_frequency": round(m, 5),
                     "ci_low": rounded(ci[0], 5), "ci_high": rounded(ci[1], 5)})
    width = 0.8 / len(variants)
    x = np.arange(8) + (k - (len(variants) - 1) / 2) * width
    err = None if np.isnan(lo).any() else [np.array(means) - lo, np.array(hi) - means]
    ax.bar(x, means, width, yerr=err, capsize=2, label="%s (%s)" % (v, runs_label(len(runs))))


def _any_two_runs(rows):
    """Whether some variant is drawn from exactly two runs (the figure's rows say from how many):
    their bootstrap interval is their range, which the figure's title then says."""
    return any(r["runs"] == 2 for r in rows)


def states_figure(out, R, variants, seed, reps):
    """Figure 4: each state's frequency relative to the random hider of the same variant."""
    rows = []
    fig, ax = plt.subplots(figsize=(13, 4.5))
    for k, v in enumerate(variants):
        _state_bars(ax, k, v, variants, R, seed, reps, rows)
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xticks(np.arange(8))
    ax.set_xticklabels(STATE_NAMES)
    ax.set_ylabel("frequency, trained minus random hider")
    ax.set_title("States (S: hider sees seeker, H: seeker sees hider, O: obstacle in view); bars: 95 % CI over runs"
                 + ("\n(with 2 runs of a variant, the bootstrap gives their range)"
                    if _any_two_runs(rows) else ""), fontsize=10)
    legend_outside(ax)
    save(fig, out, "state_frequencies_seeds", rows)


def _transition_panel(ax, src, dst, title, R, variants, seed, reps, rows):
    for k, v in enumerate(variants):
        vals = [transition_prob(r, src, dst) for _, r in R.analysed(v, "transitions")]
        vals = [x for x in vals if np.isfinite(x)]
        base = R.baseline(v, "transitions")
        rnd = transition_prob(base, src, dst) if base else np.nan
        if not vals:
            continue
        m, ci = ci_over_runs(vals, seed, reps, "transition", title, v)
        err = None if np.isnan(ci[0]) else [[m - ci[0]], [ci[1] - m]]
        ax.errorbar([k], [m], yerr=err, fmt="o", capsize=3, color="C0", label="trained" if k == 0 else None)
        ax.plot([k], [rnd], "x", color="C3", label="random hider" if k == 0 else None)
        rows.append({"transition": title, "variant": v, "runs": len(vals), "trained": round(m, 4),
                     "ci_low": rounded(ci[0]), "ci_high": rounded(ci[1]), "random": round(float(rnd), 4)})
    ax.set_xticks(range(len(variants)))
    ax.set_xticklabels(variants, rotation=30, ha="right", fontsize=8)
    ax.set_ylim(0, 1)
    ax.set_title(title)
    ax.set_ylabel("P(to | a change out of from)")
    ax.legend(fontsize=8)


def transitions_figure(out, R, variants, seed, reps):
    """Figure 5: the paper's two highlighted transitions, trained and random."""
    rows = []
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for ax, (src, dst, title) in zip(axes, TRANSITIONS):
        _transition_panel(ax, src, dst, title, R, variants, seed, reps, rows)
    fig.suptitle("Transitions, trained (95 %% CI over runs%s) and random hider"
                 % ("; with 2 runs of a variant, their range" if _any_two_runs(rows) else ""))
    save(fig, out, "transitions_seeds", rows)


def distance_figure(out, R, variants):
    """Figure 6: the mean distance between the agents over the episode, the runs' range as a band."""
    fig, ax = plt.subplots(figsize=(11, 4.5))
    for v in variants:
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
    legend_outside(ax)
    save(fig, out, "distance_seeds")


def survival_points(R, variants):
    """One point per analysed and evaluated run: its greedy living steps and its probe gain (mean of S, H)."""
    return [{"run": name, "variant": v, "living_steps": round(float(load_episodes(R.path(name, "episodes.csv"))[0].mean()), 2),
             "probe_gain": round((probe_value(rows_, "S") + probe_value(rows_, "H")) / 2, 4)}
            for v in variants for name, rows_ in R.analysed(v, "probes") if os.path.exists(R.path(name, "episodes.csv"))]


def survival_figure(out, R, variants, paper_variants):
    """Figure 7: representation against survival, one point per run, with the claim's quadratic fit
    over the runs of the paper's variants (a variant of our own is drawn hollow, not fitted)."""
    pts = survival_points(R, variants)
    if not pts:
        return
    fig, ax = plt.subplots(figsize=(9.5, 5))
    for k, v in enumerate(variants):
        xs = [q["living_steps"] for q in pts if q["variant"] == v]
        ys = [q["probe_gain"] for q in pts if q["variant"] == v]
        if xs:
            if v in paper_variants:
                ax.scatter(xs, ys, label=v, color="C%d" % k)
            else:
                ax.scatter(xs, ys, label=v + " (not fitted)", facecolors="none", edgecolors="C%d" % k)
    paper = [q for q in pts if q["variant"] in paper_variants]
    if len({q["living_steps"] for q in paper}) >= 3:
        x = np.array([q["living_steps"] for q in paper])
        coef = np.polyfit(x, [q["probe_gain"] for q in paper], 2)
        grid = np.linspace(x.min(), x.max(), 100)
        ax.plot(grid, np.polyval(coef, grid), "k--", lw=1, label="quadratic fit, the paper's variants (%d runs)" % len(paper))
    ax.set_xlabel("average living steps (evaluation seeds 0-99, greedy)")
    ax.set_ylabel("probe gain over random init (balanced accuracy, mean of S and H)")
    ax.set_title("Representation against survival, one point per run")
    legend_outside(ax)
    save(fig, out, "survival_representation", pts)


CELL_COLOURS = {(0, 0): ("#b0b0b0", "S0 H0: neither sees"), (1, 0): ("#1f77b4", "S1 H0: hider sees, unseen"),
                (0, 1): ("#ff7f0e", "S0 H1: seen, not seeing"), (1, 1): ("#d62728", "S1 H1: both see")}


class _TsneBaselines:
    """The probe set's t-SNE neighbourhood scores of the random-init networks and the pixels."""

    def __init__(self, rows):
        self.rows = rows

    def score(self, prefix, target, how=np.mean):
        vals = [float(b["neighbour_balanced_accuracy"]) for b in self.rows
                if b["target"] == target and b["representation"].startswith(prefix)]
        return round(float(how(vals)), 4) if vals else ""

    def of(self, representation):
        return tuple(float(b["neighbour_balanced_accuracy"]) for t in ("S", "H") for b in self.rows
                     if b["representation"] == representation and b["target"] == t)


def _tsne_table(R, variants, base, seed, reps):
    """Per variant and target, the runs' neighbourhood score with its interval over runs, beside
    the random-init networks' and the pixels'."""
    table = []
    for v in variants:
        scores = R.analysed(v, "tsne_neighbours")
        for target in ("S", "H"):
            vals = [float(r["neighbour_balanced_accuracy"]) for _, rows in scores for r in rows if r["target"] == target]
            m, ci = ci_over_runs(vals, seed, reps, "tsne", v, target)
            table.append({"variant": v, "target": target, "runs": len(vals), "neighbour_balanced_accuracy": round(m, 4),
                          "ci_low": rounded(ci[0]), "ci_high": rounded(ci[1]),
                          "random_init_mean": base.score("random_init_", target),
                          "random_init_min": base.score("random_init_", target, np.min),
                          "random_init_max": base.score("random_init_", target, np.max),
                          "pixels": base.score("pixels", target)})
    return table


def _tsne_panels(R, rows_of, base, random0):
    """(title, coordinates) of each panel: random-init network 0, then every run, variant by variant."""
    panels = []
    if random0:
        panels.append(("random-init network 0\nS %.2f, H %.2f" % base.of("random_init_0"), random0))
    for v, runs in rows_of.items():
        scores = dict((n, {r["target"]: float(r["neighbour_balanced_accuracy"]) for r in rows})
                      for n, rows in R.analysed(v, "tsne_neighbours"))
        panels += [("%s\nS %.2f, H %.2f" % (n, scores[n]["S"], scores[n]["H"]), coords) for n, coords in runs]
    return panels


def _tsne_axes(panels, labels):
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
    return fig, nrows


def _tsne_title(images, base, held, without):
    """The figure's title, naming the runs counted elsewhere that it cannot hold (analysed before the
    t-SNE existed, their weights lost since), so that it never passes for every run; and its lines
    past the first three."""
    title = ("t-SNE of the features on the probe set's %d test images. Under each name: how well the features'\n"
             "neighbourhoods separate S and H (11-NN balanced accuracy in 50 principal components, own episode left "
             "out;\n5 random-init networks: S %.2f to %.2f, H %.2f to %.2f; pixels: S %.2f, H %.2f)" % (
                 images, *(base.score("random_init_", t, how) or np.nan for t in ("S", "H") for how in (np.min, np.max)),
                 base.score("pixels", "S") or np.nan, base.score("pixels", "H") or np.nan))
    extra = []
    if without:
        extra = textwrap.wrap("Holds %d of %d runs; no t-SNE (analysed before it existed, weights lost): %s" % (
            len(held), len(held) + len(without), ", ".join(without)), 120)
        title += "\n" + "\n".join(extra)
    return title, len(extra)


def tsne_figure(root, out, R, variants, seed, reps):
    """The t-SNE across training seeds: the committed coordinates of every analysed run, one row per
    variant, and the neighbourhood scores with intervals over runs (tsne_seeds.csv)."""
    probe = os.path.join(root, "docs", "probe_set")
    rows_of = {v: [(n, read_csv(R.path(n, "analysis", "tsne.csv"))) for n, _ in R.analysed(v, "tsne_neighbours")]
               for v in variants}
    rows_of = {v: r for v, r in rows_of.items() if r}
    if not rows_of:
        print("seed_figures: no run has a t-SNE yet; tsne_seeds not drawn")
        return
    label_rows = read_csv(os.path.join(probe, "labels.csv"))
    if not label_rows:
        raise SystemExit("seed_figures: runs have a t-SNE but the probe set's labels are missing (%s): "
                         "the t-SNE is drawn on the probe set's images" % os.path.join(probe, "labels.csv"))
    labels = {int(r["image"]): (int(r["S"]), int(r["H"])) for r in label_rows}
    base = _TsneBaselines(read_csv(os.path.join(probe, "tsne_baselines.csv")))
    table = _tsne_table(R, rows_of, base, seed, reps)
    panels = _tsne_panels(R, rows_of, base, read_csv(os.path.join(probe, "tsne_random_init_0.csv")))
    fig, nrows = _tsne_axes(panels, labels)
    held = {n for runs in rows_of.values() for n, _ in runs}
    without = [n for v in variants for n in R.names(v) if n not in held]
    title, extra_lines = _tsne_title(len(panels[0][1]), base, held, without)
    fig.suptitle(title, fontsize=9)
    top = 0.6 + 0.2 * extra_lines  # room for the title's lines
    save(fig, out, "tsne_seeds", table, rect=(0, 0.9 / (2.5 * nrows + 1.5), 1, 1 - top / (2.5 * nrows + 1.5)))


def performance_profile(out, data, present, seed, reps,
                        title="Performance profiles, greedy, evaluation seeds 0-99 (bands: 95 % two-level bootstrap)"):
    """Table 2's performance profiles: the fraction of greedy episodes living longer than tau, per
    variant, with two-level bootstrap bands (performance_profile.png). data: {(label, "greedy"): runs},
    each runs a list of per-run arrays of living steps (or one array: one run); present: the labels
    to draw, in order; title: the figure's (say which episodes it holds)."""
    taus = np.arange(0, 1001, 10)
    fig, ax = plt.subplots(figsize=(8, 5))
    for v in present:
        prof, lo, hi = st.performance_profile(data[(v, "greedy")], taus, st.keyed_rng(seed, "profile", v),
                                              max(200, reps // 4))
        n = len(st.as_runs(data[(v, "greedy")]))
        line, = ax.plot(taus, prof, label="%s (%d run%s)" % (v, n, "" if n == 1 else "s"))
        ax.fill_between(taus, lo, hi, color=line.get_color(), alpha=0.15)
    ax.set_xlabel("living steps tau")
    ax.set_ylabel("fraction of episodes living more than tau")
    ax.set_title(title)
    ax.set_xlim(0, 1000)
    ax.set_ylim(0, 1)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "performance_profile.png"), dpi=110)
    plt.close(fig)


def draw_all(root, out, R, cfg, found, seed, reps):
    """Every figure and table across seeds of the runs `found`; returns how many variants were drawn."""
    variants = [v for v in cfg.order_of(found) if R.analysed(v, "states")]
    if not variants:
        print("seed_figures: no analysed run yet; nothing drawn")
        return 0
    states_figure(out, R, variants, seed, reps)
    transitions_figure(out, R, variants, seed, reps)
    transition_factors_table(out, R, variants, seed, reps)
    distance_figure(out, R, variants)
    survival_figure(out, R, variants, cfg.paper_variants)
    table3(root, out, R, cfg.order_of(found), cfg.paper, seed, reps)
    behaviour_table(out, R, cfg.order_of(found), seed, reps)
    tsne_figure(root, out, R, cfg.order_of(found), seed, reps)
    print("seed_figures: %d variants, %d analysed runs into %s" % (
        len(variants), sum(len(R.analysed(v, "states")) for v in variants), out))
    return len(variants)


def main(argv=None):
    """seed_figures.py: every figure and table across training seeds, per game (runs.outputs)."""
    args = parse_selection("The paper's Figures 4-7, Table 3, the behaviour table and the t-SNE across training "
                           "seeds of each game, from the committed per-run analyses.", argv, game=None)
    cfg = Config(args.root)
    for game, out in outputs(args, cfg.sweep_games()):
        os.makedirs(out, exist_ok=True)
        found = sweep_runs(args.root, args.steps, set(args.extra), game=game)
        draw_all(args.root, out, Runs(args.root, found, game), cfg, found, args.seed, args.reps)
    return 0
