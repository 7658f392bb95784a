#!/usr/bin/env python3
"""Gathers the per-variant analysis reports into the reproduction report.

usage: reproduce_report.py REPORT_DIR --paper config/paper_reference.yaml

REPORT_DIR holds table2_shipped/ (hideseek_pipeline report --from-scratch: Table 2 of the shipped policies) and
one folder per analysed policy
(analyze.launch report_dir:=REPORT_DIR/<variant>, and REPORT_DIR/<variant>_gru for a GRU hider).
Writes into REPORT_DIR:
  table3.csv/.md                    probe accuracy, trained / random-init network, beside the paper's;
                                    a GRU hider has a second row, the probes of its GRU state
  state_frequencies_variants.png    trained minus random state frequencies, every variant
  transitions_variants.png          transition probabilities, every variant
  survival_vs_representation.png    self-visibility (H) probe balanced accuracy against average living
                                    steps, one point per variant, with a parabolic fit
  index.md                          links to everything, with the tables inline
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import yaml  # noqa: E402

STATE_NAMES = ["S%d H%d O%d" % ((i >> 2) & 1, (i >> 1) & 1, i & 1) for i in range(8)]


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def write_table(stem, header, table):
    with open(stem + ".csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(table)
    with open(stem + ".md", "w") as f:
        f.write(markdown(header, table))


def markdown(header, table):
    lines = ["| " + " | ".join(header) + " |", "| " + " | ".join("---" for _ in header) + " |"]
    lines += ["| " + " | ".join(str(c) for c in r) + " |" for r in table]
    return "\n".join(lines) + "\n"


def probe_accuracies(folder, representation="features"):
    """{(label, network): (accuracy %, balanced accuracy %, positive prior %, spread of the balanced
    accuracy over the splits %)} of one variant's probes.csv, for the features or (a GRU hider) the
    GRU state; {} when the folder has no such probes."""
    return {(r["label"], r["network"]): (100 * float(r["test_accuracy"]), 100 * float(r["balanced_accuracy"]),
                                         100 * float(r["positive_prior"]),
                                         # a report made before the splits has no spread: None, shown as "-"
                                         100 * float(r["balanced_accuracy_std"]) if r.get("balanced_accuracy_std")
                                         else None)
            for r in rows(os.path.join(folder, "probes.csv"))
            if r.get("representation", "features") == representation}


def paired_gains(folder, representation="features"):
    """{label: (mean, std, splits)} of trained minus random-init balanced accuracy (%), split by split:
    both probes are scored on the same splits, so the difference is free of the splits' own noise.
    {} when the folder has no probe_splits.csv."""
    path = os.path.join(folder, "probe_splits.csv")
    if not os.path.isfile(path):
        return {}
    score = {(r["label"], r["network"], int(r["split"])): 100 * float(r["balanced_accuracy"])
             for r in rows(path) if r["representation"] == representation}
    gains = {}
    for label in ("S", "H"):
        d = [score[label, "trained", k] - score[label, "random_init", k]
             for (l, n, k) in sorted(score) if l == label and n == "trained" and (label, "random_init", k) in score]
        if d:
            gains[label] = (float(np.mean(d)), float(np.std(d)), len(d))
    return gains


def pm(mean, std):
    return "%.1f" % mean if std is None else "%.1f ± %.1f" % (mean, std)


def base_variant(name):
    """The variant a policy folder plays: basic_gru plays basic."""
    return name[:-len("_gru")] if name.endswith("_gru") else name


# The paper's claim on representation (config/paper_reference.yaml): variants that give the hider a
# moderate weakness, and one that gives it an advantage. Set from the paper file in main().
WEAKER = []
STRONGER = []


def weakness_finding(probes, gains):
    """The paper's claim, on what was analysed: do moderate weaknesses give better self-visibility
    (H) features than an advantage? Balanced accuracy, trained features; then what training added
    (the paired gain over the random-init network), since how hard H is to read from an image
    depends on the games each policy plays, trained or not."""
    have = lambda vs: [(v, probes[v]["H", "trained"][1]) for v in vs if v in probes]  # noqa: E731
    weaker, stronger = have(WEAKER), have(STRONGER)
    text = ["The paper finds that moderate weaknesses (%s) give better self-visibility features than an "
            "advantage (%s). Here, balanced accuracy of the H probe on the trained features:" %
            (", ".join(WEAKER), ", ".join(STRONGER)), ""]
    for v, acc in weaker + stronger:
        text.append("- %s: %s %% (random-init network: %s %%)" %
                    (v, pm(acc, probes[v]["H", "trained"][3]), pm(*probes[v]["H", "random_init"][1:4:2])))
    missing = [v for v in WEAKER + STRONGER if v not in probes]
    if missing:
        text.append("")
        text.append("Not analysed yet (no shipped policy): %s." % ", ".join(missing))
    text.append("")
    if weaker and stronger:
        (wv, w), (sv, s) = max(weaker, key=lambda p: p[1]), max(stronger, key=lambda p: p[1])
        spread = max(probes[wv]["H", "trained"][3] or 0.0, probes[sv]["H", "trained"][3] or 0.0)
        verdict = "beats" if w > s else "does not beat"
        text.append("On these numbers the best weaker variant, %s, %s the advantaged one, %s (%.1f against %.1f %%)." %
                    (wv, verdict, sv, w, s))
        if spread > 0 and abs(w - s) <= spread:
            text.append("The gap (%.1f points) is within one standard deviation over the probe's splits (%.1f), "
                        "so these numbers do not decide the question." % (abs(w - s), spread))
        above = [v for v, a in weaker if a > s]
        text.append("%d of the %d weaker variants analysed %s above %s." %
                    (len(above), len(weaker), "scores" if len(weaker) == 1 else "score", sv))
        paired = [(v, gains[v]["H"]) for v, _ in weaker + stronger if "H" in gains.get(v, {})]
        if paired:
            text.append("")
            text.append("The random-init network reads H from the same images too, and how well depends on the "
                        "games the policy plays (where the seeker is when it looks). What training added, trained "
                        "minus random-init on the same splits:")
            text.append("")
            for v, (mean, std, n) in paired:
                text.append("- %s: %+.1f ± %.1f points (%d splits)" % (v, mean, std, n))
            wg = [g for v, g in paired if v in WEAKER]
            sg = [g for v, g in paired if v in STRONGER]
            if wg and sg:
                best_w, best_s = max(wg, key=lambda g: g[0]), max(sg, key=lambda g: g[0])
                text.append("")
                text.append("On the gain the best weaker variant %s the advantaged one (%+.1f against %+.1f)%s." %
                            ("beats" if best_w[0] > best_s[0] else "does not beat", best_w[0], best_s[0],
                             "; the gap is within one standard deviation" if abs(best_w[0] - best_s[0]) <=
                             max(best_w[1], best_s[1]) else ""))
    else:
        text.append("The comparison needs both sides analysed; it cannot be made yet.")
    return "\n".join(text)


TABLE3_HEADER = ["variant", "S: trained / random-init", "paper S", "H: trained / random-init", "paper H",
                 "balanced S: trained / random-init", "balanced H: trained / random-init",
                 "balanced gain S / H (paired)", "prior S=1 / H=1"]


def table3(report, analysed, ref, probes, memory_probes):
    """Table 3: probe accuracy beside the paper's; writes table3.md/.csv and returns its rows."""
    t3 = []
    for v in analysed:
        r = ref[base_variant(v)]
        for name, p, representation in ((v, probes[v], "features"), (v + ": GRU state", memory_probes[v], "gru_state")):
            if not p:
                continue
            g = paired_gains(os.path.join(report, v), representation)
            # The paper's network is feed-forward: its numbers stand beside ours for comparison only.
            t3.append([name,
                       "%.1f / %.1f" % (p["S", "trained"][0], p["S", "random_init"][0]),
                       "%.2f / %.2f" % (r["probe_S_trained"], r["probe_S_random"]),
                       "%.1f / %.1f" % (p["H", "trained"][0], p["H", "random_init"][0]),
                       "%.2f / %.2f" % (r["probe_H_trained"], r["probe_H_random"]),
                       "%s / %s" % (pm(*p["S", "trained"][1:4:2]), pm(*p["S", "random_init"][1:4:2])),
                       "%s / %s" % (pm(*p["H", "trained"][1:4:2]), pm(*p["H", "random_init"][1:4:2])),
                       " / ".join("%+.1f ± %.1f" % g[k][:2] if k in g else "-" for k in ("S", "H")),
                       "%.1f / %.1f" % (p["S", "trained"][2], p["H", "trained"][2])])
    write_table(os.path.join(report, "table3"), TABLE3_HEADER, t3)
    return t3


def plot_state_frequencies(report, analysed):
    """State frequencies, trained minus random, of every analysed variant side by side."""
    fig, ax = plt.subplots(figsize=(9, 4))
    width = 0.8 / len(analysed)
    for k, v in enumerate(analysed):
        diff = [float(r["trained_minus_random"]) for r in rows(os.path.join(report, v, "state_frequencies.csv"))]
        ax.bar(np.arange(8) + (k - (len(analysed) - 1) / 2) * width, diff, width, label=v)
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xticks(range(8))
    ax.set_xticklabels(STATE_NAMES, rotation=30, fontsize=8)
    ax.set_ylabel("relative frequency, trained - random policy")
    ax.set_title("State frequencies of every analysed variant (S: hider sees seeker, H: seeker sees hider, "
                 "O: obstacle in view)", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(report, "state_frequencies_variants.png"), dpi=90)
    plt.close(fig)


def plot_transitions(report, analysed):
    """Each variant's transition matrix; at most four panels a row, state names on the first column
    only, so none overlaps."""
    ncols = min(4, len(analysed))
    nrows = (len(analysed) + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(2.9 * ncols + 1.6, 3.3 * nrows), squeeze=False)
    for ax in axes.flat[len(analysed):]:
        ax.set_visible(False)
    for k, (ax, v) in enumerate(zip(axes.flat, analysed)):
        p = np.full((8, 8), np.nan)
        for r in rows(os.path.join(report, v, "transitions.csv")):
            if r["probability"] != "":
                p[STATE_NAMES.index(r["from"]), STATE_NAMES.index(r["to"])] = float(r["probability"])
        image = ax.imshow(p, cmap="viridis", vmin=0, vmax=1)
        ax.set_xticks(range(8))
        ax.set_yticks(range(8))
        ax.set_xticklabels(STATE_NAMES, rotation=90, fontsize=6)
        ax.set_yticklabels(STATE_NAMES if k % ncols == 0 else [], fontsize=6)
        ax.set_title(v, fontsize=9)
    fig.colorbar(image, ax=list(axes.flat), label="P(to | a change out of from)")
    fig.suptitle("Transitions between distinct states (rows: from, columns: to)", fontsize=10)
    fig.savefig(os.path.join(report, "transitions_variants.png"), dpi=80, bbox_inches="tight")
    plt.close(fig)


def plot_survival(report, analysed, table2, probes, memory_probes):
    """Survival against representation: one point per variant with a policy and an analysis. GRU
    hiders are drawn apart and left out of the fit, which is over the paper's network; a GRU
    hider's point reads the probe of its GRU state, what its heads act on."""
    points = [((memory_probes[v] or probes[v])["H", "trained"][1], table2[v], v,
               (memory_probes[v] or probes[v])["H", "trained"][3]) for v in analysed if v in table2]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for x, y, v, spread in points:
        gru = v.endswith("_gru")
        ax.errorbar(x, y, xerr=spread or 0.0, fmt="s" if gru else "o", color="tab:green" if gru else "tab:blue",
                    capsize=3, lw=0.8)
        ax.annotate(v, (x, y), textcoords="offset points", xytext=(4, 4), fontsize=8)
    if any(p[2].endswith("_gru") for p in points):
        ax.plot([], [], "s", color="tab:green", label="GRU hider: probe of its GRU state (not in the fit)")
        ax.legend(fontsize=8, loc="best")
    points = [p for p in points if not p[2].endswith("_gru")]
    fit_note = "fewer than 3 feed-forward variants: no parabolic fit"
    if len(points) >= 3:
        xs, ys = np.array([p[0] for p in points]), np.array([p[1] for p in points])
        coefficients = np.polyfit(xs, ys, 2)
        grid = np.linspace(xs.min() - 1, xs.max() + 1, 100)
        ax.plot(grid, np.polyval(coefficients, grid), color="tab:orange", lw=1)
        fit_note = "parabolic fit: %.3g x^2 + %.3g x + %.3g" % tuple(coefficients)
    ax.set_xlabel("self-visibility (H) probe, balanced accuracy of the trained features, %\n"
                  "(mean ± standard deviation over the probe's splits by episode)", fontsize=9)
    ax.set_ylabel("average living steps (seeds 0-99, greedy)")
    ax.set_title("Survival against representation\n" + fit_note, fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(report, "survival_vs_representation.png"), dpi=90)
    plt.close(fig)


def write_index(report, analysed, t3, probes, gains):
    """index.md: Table 2, the GRU comparison where there is one, Table 3, the figures, the folders."""
    with open(os.path.join(report, "table2_shipped", "table2.md")) as f:
        table2_md = f.read().split("\n", 1)[1]  # without its own title
    # Its sections (the paper's orderings) two levels down, under the index's heading.
    table2_md = "\n".join("##" + line if line.startswith("#") else line for line in table2_md.split("\n"))
    index = ["# Reproduction report", "",
             "Made by `make reproduce`: every shipped policy and the random hider evaluated on every variant, "
             "then every variant with a shipped policy analysed (`analyze.launch`).", "",
             "## Table 2: living steps and success", "", table2_md.strip(), "",
             "CSV: [table2_shipped/table2.csv](table2_shipped/table2.csv); the paper's orderings: "
             "[table2_shipped/orderings.md](table2_shipped/orderings.md); per evaluation: [evaluations/](evaluations/)",
             ""]
    index += ["## Table 3: linear probes of the 512 mid-level features", "",
              "Test accuracy in % on episodes held out from the probe's fit; the balanced accuracy (mean recall of "
              "both classes) is 50 % for any probe that ignores its input. Every probe is scored on several random "
              "splits by episode (analyze.launch probe_splits): the mean ± the standard deviation over the splits; "
              "the paired gain is trained minus random-init on the same splits, split by split. A GRU hider (`<variant>_gru`) has a "
              "second row, the probes of its 512-unit GRU state after the step; the paper's columns there are its "
              "feed-forward network's, for comparison.", "", markdown(TABLE3_HEADER, t3).strip(), "",
              "CSV: [table3.csv](table3.csv)", "",
              "### Weaknesses against advantages", "", weakness_finding(probes, gains), "",
              "## Across variants", "",
              "![state frequencies](state_frequencies_variants.png)", "",
              "![transitions](transitions_variants.png)", "",
              "![survival against representation](survival_vs_representation.png)", "",
              "## Per variant", ""]
    for v in analysed:
        files = sorted(f for f in os.listdir(os.path.join(report, v)))
        index.append("- **%s**: " % v + ", ".join("[%s](%s/%s)" % (f, v, f) for f in files))
    with open(os.path.join(report, "index.md"), "w") as f:
        f.write("\n".join(index) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("report")
    parser.add_argument("--paper", required=True)
    a = parser.parse_args()
    with open(a.paper) as f:
        paper = yaml.safe_load(f)
    ref = paper["variants"]
    WEAKER[:] = paper["moderate_weaknesses"]
    STRONGER[:] = paper["advantages"]
    # Each shipped policy's greedy mean living steps, by its label (basic, basic_gru).
    labels = {"greedy": "", "GRU, greedy": "_gru"}
    table2 = {r["variant"] + labels[r["mode"]]: float(r["living_mean"])
              for r in rows(os.path.join(a.report, "table2_shipped", "table2.csv")) if r["mode"] in labels}
    # The paper's Table 2 order; a variant the paper lacks has no reference numbers to print beside.
    analysed = [v for base in ref for v in (base, base + "_gru")
                if os.path.isfile(os.path.join(a.report, v, "probes.csv"))]
    if not analysed:
        raise SystemExit("reproduce_report: no variant folder with probes.csv in %s" % a.report)
    probes = {v: probe_accuracies(os.path.join(a.report, v)) for v in analysed}
    memory_probes = {v: probe_accuracies(os.path.join(a.report, v), "gru_state") for v in analysed}
    gains = {v: paired_gains(os.path.join(a.report, v)) for v in analysed}
    t3 = table3(a.report, analysed, ref, probes, memory_probes)
    plot_state_frequencies(a.report, analysed)
    plot_transitions(a.report, analysed)
    plot_survival(a.report, analysed, table2, probes, memory_probes)
    write_index(a.report, analysed, t3, probes, gains)
    print("reproduce_report: wrote %s/index.md (%d variants analysed: %s)" % (a.report, len(analysed),
                                                                          ", ".join(analysed)))


if __name__ == "__main__":
    main()
