#!/usr/bin/env python3
"""Table 2 across training seeds, with 95 % intervals (the rliable method; see sweep_stats.py).

usage: sweep_table2.py [--root DIR] [--out DIR] [--steps N] [--extra RUN ...] [--reps N]

Reads the run registry (ROOT/policies/policies.yaml): the sweep's runs are its feed-forward game-v2
entries named <variant>_seed<S> whose variant is <variant>, whose note says the sweep's queue
trained them, trained for at least --steps steps, each seed's first draw (a retrain, <run>_retrain,
never counts: docs/sweep.md) (--extra adds other runs by name, each to its own variant). Each run's episodes come from
ROOT/docs/runs/<run>/episodes.csv (greedy) and sampled/episodes.csv (sampled). Beside them: the
paper's figures (config/paper_reference.yaml) and the random hider and scripted evaders
(docs/calibration_table.csv).

Writes into OUT (default ROOT/docs/report/table2_seeds; make reproduce writes it there):
- table2.md / table2.csv: per variant and mode (greedy, sampled), the runs, the mean and the IQM of
  living steps and of success over the pooled episodes, each with its interval;
- orderings.md / orderings.csv: the probability of improvement for each ordering the paper reports,
  at the level of runs and of episodes, and Spearman's rank correlation with the paper's ordering;
- readings.md / readings.csv: the two readings of the paper's stochastic seeker side by side
  (stochasticseeker, whose seeker starts knowing the spawn point, and stochasticseeker_explore, whose
  seeker explores until it sees the hider): the difference of their means with its interval, the
  probability of improvement, and which is closer to the paper's figure. Not one of the paper's
  orderings, and not in the rank correlation;
- performance_profile.png: the fraction of episodes living longer than tau, per variant, with bands.
"""
import argparse
import csv
import os
import re
import sys

import numpy as np
import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sweep_stats as st  # noqa: E402

MODES = (("greedy", ""), ("sampled", "sampled"))
NAME = re.compile(r"^(?P<variant>.+)_seed(?P<seed>\d+)$")
# Two readings of one variant of the paper: (the paper's variant, what its seeker does, the other
# reading's variant, what its seeker does). The paper's figure is the first's.
READINGS = [("stochasticseeker", "its seeker starts knowing the hider's spawn point",
             "stochasticseeker_explore", "its seeker explores until it sees the hider (the paper's text, literally)")]
SWEEP_NOTE = "sweep run"  # the sweep's queue notes each run it trained (a same-named run from elsewhere is not one)


def paper_orderings(variants, paper):
    """The orderings the paper reports, among its variants present: (better, worse) pairs."""
    pairs = [("basic", "stochasticseeker"), ("basic", "visibilityreward"), ("fasterhider", "visibilityreward_faster")]
    pairs += [(v, "slowerhider") for v in variants if v != "slowerhider" and v in paper]
    return pairs


def load_episodes(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise ValueError("%s: no episodes" % path)
    living = np.array([float(r["living_steps"]) for r in rows])
    success = np.array([1.0 if r["outcome"] != "captured" else 0.0 for r in rows])
    return living, success


def sweep_runs(root, steps, extra, network="ff", warn=True):
    """variant -> [(run, entry)], in training-seed order: the sweep's runs of `network` (ff:
    <variant>_seed<S>; gru: <variant>_gru_seed<S>), plus the runs named in `extra` of that network
    (`warn`: say on stderr which of `extra` are of another network and so left out)."""
    with open(os.path.join(root, "policies", "policies.yaml")) as f:
        entries = yaml.safe_load(f) or {}
    suffix = "" if network == "ff" else "_" + network
    retrains = sorted(n for n in extra if n in entries and entries[n].get("draw", "first") == "retrain")
    if retrains:
        raise SystemExit("sweep_table2: --extra %s: a retrain never enters Table 2 or a claim (its first draw, %s, "
                         "does)" % (", ".join(retrains), ", ".join(entries[n]["retrain_of"] for n in retrains)))
    found = {}
    for name, e in entries.items():
        if e.get("draw", "first") != "first":
            continue  # a retrain: shown beside its first draw in the run's records, never counted
        m = NAME.match(name)
        chosen = (name in extra and e.get("network", "ff") == network) or (
            m and m.group("variant") == str(e.get("variant")) + suffix and e.get("network") == network
            and e.get("game") == "v2" and int(e.get("steps", 0)) >= steps
            and str(e.get("note", "")).startswith(SWEEP_NOTE))
        if chosen:
            found.setdefault(e["variant"], []).append((name, e))
    for v in found:
        found[v].sort(key=lambda ne: (int(ne[1].get("training_seed", 0)), ne[0]))
    other = sorted(n for n in extra if n in entries and entries[n].get("network", "ff") != network)
    if other and warn:
        print("sweep_table2: --extra %s: not %s runs, left out here" % (", ".join(other), network), file=sys.stderr)
    missing = [n for n in extra if n not in entries]
    if missing:
        raise SystemExit("sweep_table2: --extra: no run %s in the registry" % ", ".join(missing))
    return found


def fmt_ci(point, ci, digits=1, scale=1.0):
    f = "%%.%df" % digits
    return (f + " [" + f + ", " + f + "]") % (point * scale, ci[0] * scale, ci[1] * scale)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    st.add_selection_args(p, os.path.dirname(os.path.abspath(__file__)))
    args = p.parse_args(argv)
    root = os.path.abspath(args.root)
    out = args.out or os.path.join(root, "docs", "report", "table2_seeds")
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(root, "config", "paper_reference.yaml")) as f:
        paper = (yaml.safe_load(f) or {}).get("variants") or {}
    calib = {}
    calib_path = os.path.join(root, "docs", "calibration_table.csv")
    if os.path.exists(calib_path):
        with open(calib_path) as f:
            for r in csv.DictReader(f):
                calib.setdefault(r["variant"], []).append(r)
    found = sweep_runs(root, args.steps, set(args.extra))
    variant_files = sorted(n[:-5] for n in os.listdir(os.path.join(root, "config", "variants")) if n.endswith(".yaml"))
    order = [v for v in paper if v in variant_files] + [v for v in variant_files if v not in paper]

    rows, data, succ = [], {}, {}
    for v in order:
        for mode, sub in MODES:
            runs = []
            for name, _ in found.get(v, []):
                path = os.path.join(root, "docs", "runs", name, sub, "episodes.csv")
                if os.path.exists(path):
                    runs.append((name, load_episodes(path)))
            if not runs:
                continue
            living = [r[1][0] for r in runs]
            success = [r[1][1] for r in runs]
            data[(v, mode)] = living
            succ[(v, mode)] = success
            row = {"variant": v, "mode": mode, "runs": len(runs), "run_names": " ".join(r[0] for r in runs),
                   "episodes": sum(len(x) for x in living),
                   "per_run_living": " ".join("%.1f" % x.mean() for x in living),
                   "per_run_success": " ".join("%.0f" % (100 * x.mean()) for x in success)}
            for key, values, stat in (("living_mean", living, st.mean), ("living_iqm", living, st.iqm),
                                      ("success_mean", success, st.mean), ("success_iqm", success, st.iqm)):
                point, ci = st.pooled_statistic(values, stat, st.keyed_rng(args.seed, v, mode, key), args.reps)
                row[key], row[key + "_lo"], row[key + "_hi"] = point, ci[0], ci[1]
            rows.append(row)

    fields = ["variant", "mode", "runs", "episodes", "living_mean", "living_mean_lo", "living_mean_hi", "living_iqm",
              "living_iqm_lo", "living_iqm_hi", "success_mean", "success_mean_lo", "success_mean_hi", "success_iqm",
              "success_iqm_lo", "success_iqm_hi", "per_run_living", "per_run_success", "run_names"]
    with open(os.path.join(out, "table2.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for r in rows:
            w.writerow({k: (round(r[k], 4) if isinstance(r[k], float) else r[k]) for k in fields})

    md = ["# Table 2 across training seeds", "",
          "Evaluation seeds 0-99, at most 1000 steps, per run; greedy is the headline, sampled beside it. "
          "Mean and interquartile mean (IQM) over the pooled episodes of a variant's runs, each with its 95 %% "
          "interval from a two-level bootstrap (%d resamples: the runs, then the episodes within each run). "
          "The interval covers the spread between training seeds and between evaluation episodes; with three "
          "training seeds it is wide, and it cannot cover a behaviour none of the runs showed; with two runs "
          "its run level can only draw one run twice or both, so it is about their range widened by the episodes' "
          "spread, and its coverage is below 95 %%; for a "
          "variant with one run so far it covers only the spread between that run's evaluation episodes. "
          "The IQM of success, a 0/1 outcome, is clip((p - 0.25) / 0.5, 0, 1) of the success rate p: it is "
          "given because the protocol asks for it, and the mean is the figure to read." % args.reps, "",
          "| variant | hider | runs | living steps: mean [95 % CI] | IQM [95 % CI] | success %: mean [95 % CI] | "
          "IQM [95 % CI] | per run (living steps / success %) |",
          "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for v in order:
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
        for c in calib.get(v, []):
            who = "random hider" if c["evader"] == "random" else "scripted %s (reads the true state)" % c["evader"]
            md.append("| %s | %s | | %.1f | | %.0f | | median %s |" % (
                v, who, float(c["avg_living_steps"]), 100 * float(c["success_rate"]), c["median_living_steps"]))
        if v in paper:
            md.append("| %s | paper, random | | %s | | %.0f | | |" % (v, paper[v]["living_random"], paper[v]["success_random"]))
    md.append("")
    missing = [v for v in order if (v, "greedy") not in data]
    if missing:
        md.append("No sweep run evaluated yet: %s." % ", ".join(missing))
        md.append("")

    # Orderings and rank correlation, greedy.
    orow = []
    present = [v for v in order if (v, "greedy") in data]
    for better, worse in paper_orderings(present, paper):
        if (better, "greedy") in data and (worse, "greedy") in data:
            poi = st.probability_of_improvement(data[(better, "greedy")], data[(worse, "greedy")],
                                                st.keyed_rng(args.seed, "improvement", better, worse), args.reps)
            orow.append({"better": better, "worse": worse,
                         "runs": "%d vs %d" % (len(data[(better, "greedy")]), len(data[(worse, "greedy")])),
                         "poi_runs": poi["runs"][0], "poi_runs_lo": poi["runs"][1][0], "poi_runs_hi": poi["runs"][1][1],
                         "poi_episodes": poi["episodes"][0], "poi_episodes_lo": poi["episodes"][1][0],
                         "poi_episodes_hi": poi["episodes"][1][1]})
    in_paper = [v for v in present if v in paper]
    rho = None
    if len(in_paper) >= 3:
        rho = st.rank_correlation([data[(v, "greedy")] for v in in_paper],
                                  [paper[v]["living_trained"] for v in in_paper],
                                  st.keyed_rng(args.seed, "rho"), args.reps)
    ofields = ["better", "worse", "runs", "poi_runs", "poi_runs_lo", "poi_runs_hi", "poi_episodes", "poi_episodes_lo",
               "poi_episodes_hi"]
    with open(os.path.join(out, "orderings.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=ofields)
        w.writeheader()
        for r in orow:
            w.writerow({k: (round(r[k], 4) if isinstance(r[k], float) else r[k]) for k in ofields})
        if rho:
            f.write("# spearman_rho_with_paper,%d variants,%.4f,%.4f,%.4f\n" % (len(in_paper), rho[0], *rho[1]))
    omd = ["# The paper's orderings", "",
           "Greedy evaluations. The probability of improvement P(X > Y) (ties count half) at two levels: "
           "**runs**, a run of X against a run of Y by mean living steps (rliable's definition: what training X "
           "rather than Y gives), its interval from the two-level bootstrap; **episodes**, an episode of X against "
           "one of Y. 0.5 is no difference; an interval that holds 0.5 does not decide the ordering.", "",
           "| ordering (paper) | runs | P(X > Y), runs [95 % CI] | P(X > Y), episodes [95 % CI] |",
           "| --- | --- | --- | --- |"]
    for r in orow:
        omd.append("| %s > %s | %s | %s | %s |" % (r["better"], r["worse"], r["runs"],
                                                   fmt_ci(r["poi_runs"], (r["poi_runs_lo"], r["poi_runs_hi"]), 2),
                                                   fmt_ci(r["poi_episodes"], (r["poi_episodes_lo"], r["poi_episodes_hi"]), 2)))
    omd.append("")
    if rho:
        omd.append("Spearman's rank correlation between the variants' mean living steps and the paper's (%d variants: "
                   "%s): **%s** (95 %% two-level bootstrap interval)." % (len(in_paper), ", ".join(in_paper),
                                                                          fmt_ci(rho[0], rho[1], 2)))
    else:
        omd.append("Rank correlation with the paper: needs at least three of the paper's variants evaluated "
                   "(%d so far)." % len(in_paper))
    omd.append("")
    if any((x, "greedy") in data for r in READINGS for x in (r[0], r[2])):
        omd += ["The two readings of the paper's stochastic seeker, side by side: [readings.md](readings.md).", ""]
    with open(os.path.join(out, "table2.md"), "w") as f:
        f.write("\n".join(md + omd))
    with open(os.path.join(out, "orderings.md"), "w") as f:
        f.write("\n".join(omd))

    readings_rows, rmd = [], ["# Two readings of the paper's stochastic seeker", "",
                              "Greedy evaluations, seeds 0-99. Differences are the first reading minus the second, "
                              "pooled means with their 95 % two-level bootstrap interval (each variant's runs, then "
                              "episodes within them, resampled on their own); the probability of improvement as in "
                              "the orderings. This comparison is not one of the paper's orderings, and the second "
                              "reading stays out of the rank correlation.", ""]
    for a, a_says, b, b_says in READINGS:
        if (a, "greedy") not in data or (b, "greedy") not in data:
            missing = [v for v in (a, b) if (v, "greedy") not in data]
            rmd.append("%s against %s: needs a run of each (%s %s none)." % (
                a, b, " and ".join(missing), "has" if len(missing) == 1 else "have"))
            continue
        ref = paper.get(a, {})
        rng_key = ("reading", a, b)
        d_living = st.mean_difference(data[(a, "greedy")], data[(b, "greedy")], st.keyed_rng(args.seed, *rng_key, "living"),
                                      args.reps)
        d_success = st.mean_difference(succ[(a, "greedy")], succ[(b, "greedy")],
                                       st.keyed_rng(args.seed, *rng_key, "success"), args.reps)
        poi = st.probability_of_improvement(data[(a, "greedy")], data[(b, "greedy")],
                                            st.keyed_rng(args.seed, *rng_key, "improvement"), args.reps)
        va, vb = (float(np.mean(np.concatenate(data[(v, "greedy")]))) for v in (a, b))
        sa, sb = (float(np.mean(np.concatenate(succ[(v, "greedy")]))) for v in (a, b))
        for measure, x, y, paper_value, est in (
                ("living_mean", va, vb, ref.get("living_trained"), d_living),
                ("success_mean", sa, sb, None if "success_trained" not in ref else ref["success_trained"] / 100.0,
                 d_success),
                ("poi_runs", None, None, None, poi["runs"]), ("poi_episodes", None, None, None, poi["episodes"])):
            readings_rows.append({"first": a, "second": b, "measure": measure, "first_value": x, "second_value": y,
                                  "paper": paper_value, "estimate": est[0], "lo": est[1][0], "hi": est[1][1]})
        na, nb = len(data[(a, "greedy")]), len(data[(b, "greedy")])
        rmd += ["- **%s** (%d runs): %s." % (a, na, a_says), "- **%s** (%d runs): %s." % (b, nb, b_says), "",
                "| measure | %s | %s | paper (%s) | %s minus %s [95 %% CI] |" % (a, b, a, a, b),
                "| --- | --- | --- | --- | --- |",
                "| living steps | %.1f | %.1f | %s | %s |" % (va, vb, ref.get("living_trained", "-"),
                                                           fmt_ci(d_living[0], d_living[1])),
                "| success %% | %.0f | %.0f | %s | %s |" % (100 * sa, 100 * sb, "%.0f" % ref["success_trained"]
                                                          if "success_trained" in ref else "-",
                                                          fmt_ci(d_success[0], d_success[1], 0, 100)), "",
                "P(%s > %s): runs %s, episodes %s." % (a, b, fmt_ci(poi["runs"][0], poi["runs"][1], 2),
                                                       fmt_ci(poi["episodes"][0], poi["episodes"][1], 2))]
        if "living_trained" in ref:
            closer = []
            for what, x, y, target, scale, unit in (
                    ("living steps", va, vb, float(ref["living_trained"]), 1.0, ""),
                    ("success", sa, sb, float(ref["success_trained"]) / 100.0, 100.0, " points")):
                da, db = abs(x - target), abs(y - target)
                closer.append("in %s, %s (%.1f%s from the paper's %.0f, against %.1f)" % (
                    what, a if da < db else b, scale * min(da, db), unit, scale * target, scale * max(da, db)))
            told = ["in %s the interval of the difference %s" % (
                what, "holds 0: the two readings are not told apart" if d[1][0] <= 0 <= d[1][1] else "excludes 0")
                for what, d in (("living steps", d_living), ("success", d_success))]
            rmd += ["", "Closer to the paper's figure: %s. %s." % ("; ".join(closer), "; ".join(told).capitalize())]
        rmd.append("")
    if readings_rows:
        st.write_rows(os.path.join(out, "readings.csv"),
                      [{k: (round(v, 4) if isinstance(v, float) else ("" if v is None else v)) for k, v in r.items()}
                       for r in readings_rows])
    with open(os.path.join(out, "readings.md"), "w") as f:
        f.write("\n".join(rmd))

    if present:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        taus = np.arange(0, 1001, 10)
        fig, ax = plt.subplots(figsize=(8, 5))
        for v in present:
            prof, lo, hi = st.performance_profile(data[(v, "greedy")], taus, st.keyed_rng(args.seed, "profile", v),
                                                  max(200, args.reps // 4))
            n = len(data[(v, "greedy")])
            line, = ax.plot(taus, prof, label="%s (%d run%s)" % (v, n, "" if n == 1 else "s"))
            ax.fill_between(taus, lo, hi, color=line.get_color(), alpha=0.15)
        ax.set_xlabel("living steps tau")
        ax.set_ylabel("fraction of episodes living more than tau")
        ax.set_title("Performance profiles, greedy, evaluation seeds 0-99 (bands: 95 % two-level bootstrap)")
        ax.set_xlim(0, 1000)
        ax.set_ylim(0, 1)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "performance_profile.png"), dpi=110)
        plt.close(fig)
    print("sweep_table2: %d variant rows from %d runs into %s" % (
        len(rows), sum(len(x) for x in found.values()), out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
