#!/usr/bin/env python3
"""Table 2 of the paper beside this project's evaluations.

usage: table2.py PAPER_REFERENCE.yaml EVALUATIONS_DIR OUTPUT_STEM POLICIES_DIR
Reads EVALUATIONS_DIR/<run>_trained/evaluation.csv and EVALUATIONS_DIR/<variant>_random/evaluation.csv,
and POLICIES_DIR/policies.yaml (each shipped policy's variant, network, training seed, training steps,
wall time and training precision). Writes OUTPUT_STEM.md and .csv: one row per variant (its shipped policy, <variant>.pt), then a
row for each other evaluated run of that variant (a GRU hider <variant>_gru, another training seed
<variant>_seed<S>, ...), each beside the same random hider. Where two or more training seeds of one
variant and network were trained for the same steps, OUTPUT_STEM_seeds.csv and a second table in the
Markdown give their mean and sample standard deviation (the spread over training seeds), with each
run's training precision, since runs trained in fp32 and in bf16 are pooled there.
"""
import csv
import os
import statistics
import sys

import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hideseek_registry as registry  # noqa: E402

# Table 2's rows: the variants (config/variants) in the paper's order, then any the paper lacks.
VARIANTS = registry.paper_order()


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


def run_variant(name, entry):
    return registry.run_variant(name, entry, VARIANTS)


def run_network(name, entry):
    return registry.run_network(name, entry)


def runs_of(variant, shipped, evaluations):
    """The variant's shipped policy first, then its other evaluated runs (GRU first, then by name)."""
    names = [variant]
    others = sorted(n for n, e in shipped.items()
                    if n != variant and run_variant(n, e or {}) == variant)
    if variant + "_gru" not in others and os.path.isdir(os.path.join(evaluations, variant + "_gru_trained")):
        others.append(variant + "_gru")  # evaluated, not (yet) in policies.yaml
    others.sort(key=lambda n: (n != variant + "_gru", n))
    names += [n for n in others if os.path.isdir(os.path.join(evaluations, n + "_trained"))]
    return names


def seed_spread(rows):
    """Mean and sample standard deviation over training seeds of runs with equal variant, network, steps."""
    groups = {}
    for r in rows:
        if r["living_trained"] == "" or r["training_seed"] == "" or r["training_steps"] == "":
            continue
        key = (r["base_variant"], r["network"], int(r["training_steps"]))
        groups.setdefault(key, {})
        # One run per training seed: the first listed (the shipped policy before the others).
        groups[key].setdefault(int(r["training_seed"]), r)
    out = []
    for (variant, network, steps), by_seed in groups.items():
        if len(by_seed) < 2:
            continue
        runs = [by_seed[s] for s in sorted(by_seed)]
        living = [float(r["living_trained"]) for r in runs]
        success = [float(r["success_trained"]) for r in runs]
        out.append({
            "variant": variant, "network": network, "training_steps": steps,
            "training_seeds": " ".join(str(s) for s in sorted(by_seed)),
            "runs": " ".join(r["variant"] for r in runs),
            "precisions": " ".join(r["training_precision"] or "?" for r in runs),
            "living_mean": "%.1f" % statistics.mean(living), "living_std": "%.1f" % statistics.stdev(living),
            "living_min": "%.1f" % min(living), "living_max": "%.1f" % max(living),
            "success_mean": "%.2f" % statistics.mean(success), "success_std": "%.2f" % statistics.stdev(success),
        })
    return out


def main(paper_file, evaluations, stem, policies):
    with open(paper_file) as f:
        paper = yaml.safe_load(f)
    shipped = {}
    if os.path.exists(os.path.join(policies, "policies.yaml")):
        with open(os.path.join(policies, "policies.yaml")) as f:
            shipped = yaml.safe_load(f) or {}
    # The run registry names runs (basic_seed1, ...); the one whose weights are committed as
    # <variant>.pt (`weights`) is the variant's shipped policy, evaluated as <variant>_trained.
    for name, entry in list(shipped.items()):
        file_stem = str((entry or {}).get("weights", ""))[:-len(".pt")]
        if file_stem and file_stem != name and file_stem not in shipped:
            shipped[file_stem] = dict(entry, shipped_run=name)
            del shipped[name]
    for name, entry in shipped.items():
        variant = run_variant(name, entry or {})
        if variant is None:
            sys.exit("table2.py: %s/policies.yaml: entry '%s' names no variant (add 'variant: <one of %s>')"
                     % (policies, name, ", ".join(VARIANTS)))
        if variant not in VARIANTS:
            sys.exit("table2.py: %s/policies.yaml: entry '%s' has variant '%s', which is not one of: %s"
                     % (policies, name, variant, ", ".join(VARIANTS)))
    rows = []
    for base in VARIANTS:
        # A variant the paper lacks has no reference figures: "-".
        p = paper["variants"].get(base) or {k: "-" for k in ("living_trained", "living_random", "success_trained",
                                                              "success_random")}
        random = evaluation(os.path.join(evaluations, base + "_random"))
        for v in runs_of(base, shipped, evaluations):
            entry = shipped.get(v) or {}
            trained = evaluation(os.path.join(evaluations, v + "_trained"))
            rows.append({
                "variant": v,
                "base_variant": base,
                "network": run_network(v, entry),
                "training_seed": entry.get("training_seed", "") if trained else "",
                "living_trained": "%.1f" % trained[0] if trained else "",
                "living_random": "%.1f" % random[0] if random else "",
                "success_trained": "%.2f" % trained[1] if trained else "",
                "success_random": "%.2f" % random[1] if random else "",
                "paper_living_trained": p["living_trained"], "paper_living_random": p["living_random"],
                "paper_success_trained": p["success_trained"], "paper_success_random": p["success_random"],
                "trained_beats_random": ("yes" if trained[0] > random[0] else "no") if trained and random else "",
                "training_steps": entry.get("steps", "") if trained else "",
                "training_wall_h": "%.1f" % (entry["wall_s"] / 3600.0) if trained and "wall_s" in entry else "",
                "training_precision": entry.get("precision", "") if trained else "",
            })
    with open(stem + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    lines = [
        "Average living steps and success rate over the evaluation seeds 0..99 (at most 1000 steps), "
        "trained policy (`%s/<variant>.pt`, greedy) / uniformly random hider, beside the paper's "
        "(trained for %d steps). Training: the steps, precision and wall hours of the shipped checkpoint's run "
        "on a 2-core machine (fp32, or bf16 autocast where that machine's CPU had native bf16; machines "
        "differ, so wall hours compare runs only roughly). An empty cell: no policy shipped for that variant yet. Rows below a variant "
        "are its other runs (`%s/<run>.pt`): `<variant>_gru` the recurrent hider, `<variant>_seed<S>` "
        "training seed S, each beside the same random hider and the paper's feed-forward numbers." %
        (policies, paper["training_steps"], policies),
        "",
        "| variant | training seed | living steps, trained / random | paper | success %, trained / random | paper | training steps | precision | wall h |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in rows:
        lines.append("| %s | %s | %s / %s | %s / %s | %s / %s | %s / %s | %s | %s | %s |" % (
            r["variant"], r["training_seed"] if r["training_seed"] != "" else "-",
            r["living_trained"] or "-", r["living_random"] or "-", r["paper_living_trained"],
            r["paper_living_random"], r["success_trained"] or "-", r["success_random"] or "-",
            r["paper_success_trained"], r["paper_success_random"], r["training_steps"] or "-",
            r["training_precision"] or "-", r["training_wall_h"] or "-"))
    spread = seed_spread(rows)
    seeds_csv = stem + "_seeds.csv"
    if spread:
        with open(seeds_csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(spread[0].keys()))
            w.writeheader()
            w.writerows(spread)
        lines += [
            "",
            "Spread over training seeds (runs of one variant and network trained for the same steps; "
            "mean, sample standard deviation, lowest and highest run; the precision each run trained in, "
            "in the order of the seeds):",
            "",
            "| variant | network | training steps | seeds (runs) | precisions | living steps, mean ± std (min to max) | success %, mean ± std |",
            "| --- | --- | --- | --- | --- | --- | --- |",
        ]
        for g in spread:
            lines.append("| %s | %s | %d | %s (%s) | %s | %s ± %s (%s to %s) | %s ± %s |" % (
                g["variant"], g["network"], g["training_steps"], g["training_seeds"], g["runs"], g["precisions"],
                g["living_mean"], g["living_std"], g["living_min"], g["living_max"],
                g["success_mean"], g["success_std"]))
    elif os.path.exists(seeds_csv):
        os.remove(seeds_csv)  # from an earlier table with runs no longer evaluated
    with open(stem + ".md", "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(*sys.argv[1:])
