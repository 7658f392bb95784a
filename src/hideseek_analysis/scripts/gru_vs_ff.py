#!/usr/bin/env python3
"""The GRU hider against its feed-forward twin, seed by seed.

usage: gru_vs_ff.py EVALUATIONS_DIR POLICIES_DIR OUTPUT_STEM [--variants V ...] [--resamples N]

For each variant (default: basic, slowerhider, stochasticmaps, the ones where the paper blames the
hider's lack of memory) the GRU hider <variant>_gru is set beside its feed-forward twin: the
feed-forward run of policies.yaml with the same variant, training seed and training steps
(basic's twin is basic_seed0_2m, since the shipped basic.pt is an earlier checkpoint). Both were
evaluated on the same evaluation seeds (EVALUATIONS_DIR/<run>_trained/episodes.csv), so the
comparison is paired: per evaluation seed, GRU living steps minus feed-forward living steps, with a
bootstrap 95 % interval of the mean difference (over evaluation seeds, a fixed generator) and a
Wilcoxon signed-rank test. Both only measure the evaluation noise of two given policies: with one
training seed per network, the training-seed spread is not in them, so the feed-forward runs of the
variant at other training seeds (same steps) are listed beside as that spread.

What the GRU's memory itself does: where EVALUATIONS_DIR/<variant>_gru_memoryless/episodes.csv exists
(evaluate.launch memoryless:=true, the same policy with its state zeroed at every step, so that it acts
on the current image alone), the same paired comparison is made between the GRU with and without its
memory, in a second table and in the memory_* columns of the CSV.

Writes OUTPUT_STEM.md and OUTPUT_STEM.csv. A variant whose GRU hider is not shipped or not
evaluated gets a row saying so, and the goal (the GRU lives longer on at least two of the three
variants) is reported as undecided until all are in.
"""
import argparse
import csv
import os
import sys

import numpy as np
import yaml
from scipy.stats import wilcoxon

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hideseek_registry as registry  # noqa: E402

# The variants where the paper blames the hider's lack of memory (its GRU study's subjects).
DEFAULT_VARIANTS = ["basic", "slowerhider", "stochasticmaps"]
KNOWN = registry.variants()


def run_variant(name, entry):
    return registry.run_variant(name, entry, KNOWN)


def run_network(name, entry):
    return registry.run_network(name, entry)


def episodes(evaluations, run, folder_suffix="_trained"):
    """{evaluation seed: (living steps, outcome)} of EVALUATIONS_DIR/<run><folder_suffix>, or None."""
    path = os.path.join(evaluations, run + folder_suffix, "episodes.csv")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    missing = {"seed", "living_steps", "outcome"} - set(rows[0].keys() if rows else [])
    if missing:
        sys.exit("gru_vs_ff: %s lacks the column(s) %s" % (path, ", ".join(sorted(missing))))
    return {int(r["seed"]): (int(r["living_steps"]), r["outcome"]) for r in rows}


def twin_of(variant, gru, shipped):
    """The feed-forward run with the GRU's variant, training seed and steps; the variant's own name first."""
    candidates = [n for n, e in shipped.items()
                  if run_variant(n, e) == variant and run_network(n, e) == "ff"
                  and e.get("training_seed") == gru.get("training_seed") and e.get("steps") == gru.get("steps")]
    candidates.sort(key=lambda n: (n != variant, n))
    return candidates[0] if candidates else None


def compare(variant, shipped, evaluations, resamples):
    row = {"variant": variant, "gru_run": variant + "_gru", "ff_twin": "", "training_seed": "", "training_steps": "",
           "status": "", "episodes": "", "gru_living": "", "ff_living": "", "difference": "", "ci_low": "",
           "ci_high": "", "wilcoxon_p": "", "gru_longer": "", "gru_shorter": "", "equal": "", "gru_success": "",
           "ff_success": "", "ff_other_seeds": "", "gru_lives_longer": "", "memoryless_living": "",
           "memory_gain": "", "memory_gain_ci_low": "", "memory_gain_ci_high": "", "memory_gain_p": "",
           "memory_longer": "", "memory_shorter": "", "memory_equal": "", "memoryless_success": ""}
    gru_name = variant + "_gru"
    gru = shipped.get(gru_name)
    if gru is None:
        row["status"] = "not trained (no %s in policies.yaml)" % gru_name
        return row, []
    row["training_seed"], row["training_steps"] = gru.get("training_seed", ""), gru.get("steps", "")
    twin = twin_of(variant, gru, shipped)
    if twin is None:
        row["status"] = "no feed-forward run of %s at training seed %s and %s steps" % (
            variant, gru.get("training_seed"), gru.get("steps"))
        return row, []
    row["ff_twin"] = twin
    g, f = episodes(evaluations, gru_name), episodes(evaluations, twin)
    if g is None or f is None:
        row["status"] = "not evaluated (%s)" % ", ".join(
            "%s_trained" % n for n, e in ((gru_name, g), (twin, f)) if e is None)
        return row, []
    if set(g) != set(f):
        sys.exit("gru_vs_ff: %s_trained and %s_trained were evaluated on different seeds; evaluate both with "
                 "the same evaluation seeds" % (gru_name, twin))
    seeds = sorted(g)
    gl = np.array([g[s][0] for s in seeds], dtype=float)
    fl = np.array([f[s][0] for s in seeds], dtype=float)
    d, ci, p = paired(gl, fl, resamples)
    others = []
    for n, e in sorted(shipped.items()):
        if (n != twin and run_variant(n, e) == variant and run_network(n, e) == "ff" and e.get("steps") == gru.get("steps")
                and e.get("training_seed") != gru.get("training_seed")):
            ep = episodes(evaluations, n)
            if ep is not None:
                others.append("%s %.1f" % (n, np.mean([v[0] for v in ep.values()])))
    row.update({
        "status": "compared", "episodes": len(seeds), "gru_living": round(gl.mean(), 2), "ff_living": round(fl.mean(), 2),
        "difference": round(d.mean(), 2), "ci_low": ci[0], "ci_high": ci[1], "wilcoxon_p": float("%.3g" % p),
        "gru_longer": int((d > 0).sum()), "gru_shorter": int((d < 0).sum()), "equal": int((d == 0).sum()),
        "gru_success": round(100.0 * np.mean([g[s][1] == "survived" for s in seeds]), 1),
        "ff_success": round(100.0 * np.mean([f[s][1] == "survived" for s in seeds]), 1),
        "ff_other_seeds": "; ".join(others), "gru_lives_longer": "yes" if d.mean() > 0 else "no"})
    m = episodes(evaluations, gru_name, "_memoryless")
    if m is not None:
        if set(m) != set(g):
            sys.exit("gru_vs_ff: %s_memoryless and %s_trained were evaluated on different seeds" % (gru_name, gru_name))
        ml = np.array([m[s][0] for s in seeds], dtype=float)
        dm, cim, pm = paired(gl, ml, resamples)
        row.update({"memoryless_living": round(ml.mean(), 2), "memory_gain": round(dm.mean(), 2),
                    "memory_gain_ci_low": cim[0], "memory_gain_ci_high": cim[1], "memory_gain_p": float("%.3g" % pm),
                    "memory_longer": int((dm > 0).sum()), "memory_shorter": int((dm < 0).sum()),
                    "memory_equal": int((dm == 0).sum()),
                    "memoryless_success": round(100.0 * np.mean([m[s][1] == "survived" for s in seeds]), 1)})
    worst = sorted(((d[i], seeds[i], int(gl[i]), int(fl[i])) for i in range(len(seeds)) if d[i] < 0))[:5]
    return row, worst


def paired(a, b, resamples):
    """Per-seed differences a - b, the bootstrap 95 % interval of their mean and the Wilcoxon p-value."""
    d = a - b
    rng = np.random.default_rng(0)
    boot = d[rng.integers(0, len(d), size=(resamples, len(d)))].mean(axis=1)
    p = 1.0 if not np.any(d) else float(wilcoxon(d).pvalue)
    return d, (round(float(np.percentile(boot, 2.5)), 2), round(float(np.percentile(boot, 97.5)), 2)), p


def fmt_p(p):
    """A p-value as people read it: three significant digits, and below 0.001 only its order."""
    return "< 0.001" if p < 0.001 else "%.3g" % p


def markdown(rows, worst, variants):
    out = ["# The GRU hider against its feed-forward twin", "",
           "Same variant, training seed and training steps; both greedy on the same evaluation seeds, so each "
           "seed gives a paired difference (GRU minus feed-forward living steps). The 95 % interval is a bootstrap "
           "over evaluation seeds and the p-value a Wilcoxon signed-rank test: both measure evaluation noise only. "
           "With one training seed per network they do not include the training-seed spread; the feed-forward "
           "runs at other training seeds are listed beside for that.", "",
           "| variant | GRU / feed-forward twin | living steps, GRU / FF | difference [95 % CI] | Wilcoxon p | "
           "seeds GRU longer / shorter / equal | success %, GRU / FF | FF at other training seeds |",
           "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        if r["status"] != "compared":
            out.append("| %s | %s | %s | | | | | |" % (r["variant"], r["gru_run"], r["status"]))
            continue
        out.append("| %s | %s / %s | %.1f / %.1f | %+.1f [%+.1f, %+.1f] | %s | %d / %d / %d | %.0f / %.0f | %s |" % (
            r["variant"], r["gru_run"], r["ff_twin"], r["gru_living"], r["ff_living"], r["difference"], r["ci_low"],
            r["ci_high"], fmt_p(r["wilcoxon_p"]), r["gru_longer"], r["gru_shorter"], r["equal"], r["gru_success"],
            r["ff_success"], r["ff_other_seeds"] or "none"))
    compared = [r for r in rows if r["status"] == "compared"]
    wins = sum(r["gru_lives_longer"] == "yes" for r in compared)
    need = (2 * len(variants) + 2) // 3  # two of three
    out.append("")
    if len(compared) == len(variants):
        out.append("**Goal (the GRU lives longer on at least %d of the %d variants): %s** (%d of %d)." % (
            need, len(variants), "met" if wins >= need else "not met", wins, len(variants)))
    else:
        out.append("**Goal (the GRU lives longer on at least %d of the %d variants): undecided**, %d of %d compared "
                   "(the GRU lives longer on %d); waiting for: %s." % (
                       need, len(variants), len(compared), len(variants), wins,
                       ", ".join(r["variant"] for r in rows if r["status"] != "compared")))
    for v, w in worst.items():
        if w:
            out += ["", "Evaluation seeds where %s's GRU hider loses most against its twin (seed: GRU / FF living "
                    "steps): %s." % (v, ", ".join("%d: %d / %d" % (s, a, b) for _, s, a, b in w))]
    ablated = [r for r in compared if r["memoryless_living"] != ""]
    if ablated:
        out += ["", "## What the memory does", "",
                "The same GRU policy with its state zeroed at every step (`evaluate.launch memoryless:=true`), so "
                "that it acts on the current image alone, on the same evaluation seeds. The gain is the GRU with "
                "memory minus without, per seed. The zeroed state is one the trained network met only at an "
                "episode's first step, so the ablation takes away the memory and also puts the heads off the "
                "states they were trained on: read a large gain as an upper bound on what memory does.", "",
                "| variant | living steps, GRU / GRU without memory / FF twin | memory gain [95 % CI] | Wilcoxon p | "
                "seeds longer / shorter / equal with memory | success %, GRU / without memory |",
                "| --- | --- | --- | --- | --- | --- |"]
        for r in ablated:
            out.append("| %s | %.1f / %.1f / %.1f | %+.1f [%+.1f, %+.1f] | %s | %d / %d / %d | %.0f / %.0f |" % (
                r["variant"], r["gru_living"], r["memoryless_living"], r["ff_living"], r["memory_gain"],
                r["memory_gain_ci_low"], r["memory_gain_ci_high"], fmt_p(r["memory_gain_p"]), r["memory_longer"],
                r["memory_shorter"], r["memory_equal"], r["gru_success"], r["memoryless_success"]))
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("evaluations")
    ap.add_argument("policies")
    ap.add_argument("output_stem")
    ap.add_argument("--variants", nargs="+", default=DEFAULT_VARIANTS, choices=KNOWN)
    ap.add_argument("--resamples", type=int, default=10000, help="bootstrap resamples (default 10000)")
    a = ap.parse_args()
    path = os.path.join(a.policies, "policies.yaml")
    if not os.path.exists(path):
        sys.exit("gru_vs_ff: %s does not exist" % path)
    with open(path) as f:
        shipped = {n: (e or {}) for n, e in (yaml.safe_load(f) or {}).items()}
    rows, worst = [], {}
    for v in a.variants:
        row, w = compare(v, shipped, a.evaluations, a.resamples)
        rows.append(row)
        worst[v] = w
    with open(a.output_stem + ".csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    text = markdown(rows, worst, a.variants)
    with open(a.output_stem + ".md", "w") as f:
        f.write(text)
    print(text, end="")


if __name__ == "__main__":
    main()
