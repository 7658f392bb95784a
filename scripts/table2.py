#!/usr/bin/env python3
"""Table 2 of the paper beside this project's evaluations.

usage: table2.py PAPER_REFERENCE.yaml EVALUATIONS_DIR OUTPUT_STEM POLICIES_DIR
Reads EVALUATIONS_DIR/<variant>_{trained,random}/evaluation.csv and POLICIES_DIR/policies.yaml (each
shipped policy's training steps and wall time), writes OUTPUT_STEM.md and .csv. A GRU hider evaluated
into EVALUATIONS_DIR/<variant>_gru_trained gets its own row, <variant>_gru, beside the same random hider.
"""
import csv
import os
import sys

import yaml

VARIANTS = ["basic", "fasterhider", "visibilityreward_faster", "stochasticseeker", "stochasticmaps",
            "visibilityreward", "slowerhider"]


def evaluation(folder):
    path = os.path.join(folder, "evaluation.csv")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return None
    row = rows[-1]
    return float(row["avg_living_steps"]), 100.0 * float(row["success_rate"]), int(row["episodes"])


def main(paper_file, evaluations, stem, policies):
    with open(paper_file) as f:
        paper = yaml.safe_load(f)
    shipped = {}
    if os.path.exists(os.path.join(policies, "policies.yaml")):
        with open(os.path.join(policies, "policies.yaml")) as f:
            shipped = yaml.safe_load(f) or {}
    rows = []
    names = [(name, v) for v in VARIANTS for name in (v, v + "_gru")
             if name == v or os.path.isdir(os.path.join(evaluations, name + "_trained"))]
    for v, base in names:
        p = paper["variants"][base]
        trained = evaluation(os.path.join(evaluations, v + "_trained"))
        random = evaluation(os.path.join(evaluations, base + "_random"))
        rows.append({
            "variant": v,
            "living_trained": "%.1f" % trained[0] if trained else "",
            "living_random": "%.1f" % random[0] if random else "",
            "success_trained": "%.2f" % trained[1] if trained else "",
            "success_random": "%.2f" % random[1] if random else "",
            "paper_living_trained": p["living_trained"], "paper_living_random": p["living_random"],
            "paper_success_trained": p["success_trained"], "paper_success_random": p["success_random"],
            "trained_beats_random": ("yes" if trained[0] > random[0] else "no") if trained and random else "",
            "training_steps": shipped.get(v, {}).get("steps", "") if trained else "",
            "training_wall_h": "%.1f" % (shipped[v]["wall_s"] / 3600.0) if trained and "wall_s" in shipped.get(v, {}) else "",
        })
    with open(stem + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    lines = [
        "Average living steps and success rate over the evaluation seeds 0..99 (at most 1000 steps), "
        "trained policy (`%s/<variant>.pt`, greedy) / uniformly random hider, beside the paper's "
        "(trained for %d steps). Training: the steps and wall hours of the shipped checkpoint's run on this "
        "2-core machine (fp32). An empty cell: no policy shipped for that variant yet. Rows `<variant>_gru`: "
        "the recurrent hider (`%s/<variant>_gru.pt`), beside the paper's feed-forward numbers." %
        (policies, paper["training_steps"], policies),
        "",
        "| variant | living steps, trained / random | paper | success %, trained / random | paper | training steps | wall h |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in rows:
        lines.append("| %s | %s / %s | %s / %s | %s / %s | %s / %s | %s | %s |" % (
            r["variant"], r["living_trained"] or "-", r["living_random"] or "-", r["paper_living_trained"],
            r["paper_living_random"], r["success_trained"] or "-", r["success_random"] or "-",
            r["paper_success_trained"], r["paper_success_random"], r["training_steps"] or "-",
            r["training_wall_h"] or "-"))
    with open(stem + ".md", "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(*sys.argv[1:])
