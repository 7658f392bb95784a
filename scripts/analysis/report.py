#!/usr/bin/env python3
"""Writes one variant's analysis report from the arrays the C++ extractor wrote.

usage: report.py INPUT_DIR OUTPUT_DIR --variant V --policy P --steps N [--tsne-samples K]

INPUT_DIR holds
  steps_trained.csv, steps_random.csv   one row per step of the trained and of the random policy's
                                        rollouts: episode,step,S,H,O,distance (the states)
  features.csv                          one row per probed step: episode,step,S,H (the labels)
  features_trained.npy                  [rows, 512] float32 mid-level features of the trained network
  features_random.npy                   the same rows through a randomly initialised network
OUTPUT_DIR receives probes.csv/.md, tsne_S.png, tsne_H.png, state_frequencies.csv/.png,
transitions.csv/.png; every figure is labelled with variant, policy and training steps.
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from sklearn.manifold import TSNE  # noqa: E402

import hideseek_analysis as ha  # noqa: E402


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([r[k] for r in rows]) for k in rows[0]} if rows else {}


def states_of(table):
    return ha.state_index(table["S"].astype(int), table["H"].astype(int), table["O"].astype(int))


def write_table(stem, header, rows):
    with open(stem + ".csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
    with open(stem + ".md", "w") as f:
        f.write("| " + " | ".join(header) + " |\n| " + " | ".join("---" for _ in header) + " |\n")
        for r in rows:
            f.write("| " + " | ".join(("%.4f" % v) if isinstance(v, float) else str(v) for v in r) + " |\n")


def probes(labels, features, out, tag):
    rows = []
    for target in ("S", "H"):
        for network in ("trained", "random_init"):
            r = ha.probe(features[network], labels[target].astype(int), labels["episode"])
            rows.append([target, network, r["accuracy"], r["balanced_accuracy"], r["majority_accuracy"],
                         r["positive_prior"], r["train_samples"], r["test_samples"], r["test_episodes"]])
    write_table(os.path.join(out, "probes"), ["label", "network", "test_accuracy", "balanced_accuracy",
                                              "majority_class_accuracy", "positive_prior", "train_samples",
                                              "test_samples", "test_episodes"], rows)
    return rows


def tsne(features, labels, out, title, max_samples, seed=0):
    rng = np.random.default_rng(seed)
    pick = rng.choice(len(features), size=min(max_samples, len(features)), replace=False)
    embedded = TSNE(n_components=2, init="pca", random_state=seed, perplexity=30).fit_transform(features[pick])
    for target, meaning in (("S", "hider sees seeker"), ("H", "seeker sees hider")):
        fig, ax = plt.subplots(figsize=(5, 5))
        on = labels[target].astype(int)[pick] == 1
        ax.scatter(*embedded[~on].T, s=3, c="tab:blue", label="%s = 0" % target)
        ax.scatter(*embedded[on].T, s=3, c="tab:red", label="%s = 1 (%s)" % (target, meaning))
        ax.set_xticks([])
        ax.set_yticks([])
        ax.legend(markerscale=4, fontsize=8)
        ax.set_title("t-SNE of mid-level features, coloured by %s\n%s" % (target, title), fontsize=9)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "tsne_%s.png" % target), dpi=90)
        plt.close(fig)


def state_frequencies(trained, random, out, title):
    ft, fr = ha.state_frequencies(states_of(trained)), ha.state_frequencies(states_of(random))
    rows = [[ha.STATE_NAMES[i], float(ft[i]), float(fr[i]), float(ft[i] - fr[i])] for i in range(8)]
    write_table(os.path.join(out, "state_frequencies"), ["state", "trained", "random", "trained_minus_random"], rows)
    fig, ax = plt.subplots(figsize=(7, 3.5))
    ax.bar(range(8), ft - fr, color=["tab:red" if d < 0 else "tab:green" for d in ft - fr])
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xticks(range(8))
    ax.set_xticklabels(ha.STATE_NAMES, rotation=30, fontsize=8)
    ax.set_ylabel("relative frequency, trained - random")
    ax.set_title("State frequencies\n" + title, fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "state_frequencies.png"), dpi=90)
    plt.close(fig)
    return ft - fr


def transitions(trained, out, title):
    p, counts = ha.transitions(states_of(trained), trained["episode"])
    rows = [[ha.STATE_NAMES[a], ha.STATE_NAMES[b], float(p[a, b]) if not np.isnan(p[a, b]) else "",
             int(counts[a, b])] for a in range(8) for b in range(8) if a != b]
    write_table(os.path.join(out, "transitions"), ["from", "to", "probability", "count"], rows)
    fig, ax = plt.subplots(figsize=(6, 5))
    shown = np.where(np.eye(8, dtype=bool), np.nan, p)
    image = ax.imshow(shown, cmap="viridis", vmin=0, vmax=1)
    ax.set_xticks(range(8))
    ax.set_yticks(range(8))
    ax.set_xticklabels(ha.STATE_NAMES, rotation=45, ha="right", fontsize=7)
    ax.set_yticklabels(ha.STATE_NAMES, fontsize=7)
    ax.set_xlabel("to")
    ax.set_ylabel("from")
    fig.colorbar(image, ax=ax, label="P(to | a change out of from)")
    ax.set_title("Transitions between distinct states\n" + title, fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "transitions.png"), dpi=90)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--variant", required=True)
    parser.add_argument("--policy", required=True)
    parser.add_argument("--steps", required=True, type=int, help="training steps of the policy")
    parser.add_argument("--tsne-samples", type=int, default=3000)
    a = parser.parse_args()
    os.makedirs(a.output, exist_ok=True)
    title = "%s, %s, %d training steps" % (a.variant, a.policy, a.steps)
    labels = read_csv(os.path.join(a.input, "features.csv"))
    features = {n: np.load(os.path.join(a.input, "features_%s.npy" % f)) for n, f in
                (("trained", "trained"), ("random_init", "random"))}
    for name, f in features.items():
        if len(f) != len(labels["episode"]):
            raise SystemExit("report: features_%s.npy has %d rows, features.csv %d" % (name, len(f), len(labels["episode"])))
    trained = read_csv(os.path.join(a.input, "steps_trained.csv"))
    random = read_csv(os.path.join(a.input, "steps_random.csv"))
    print("report: probes")
    probes(labels, features, a.output, title)
    print("report: t-SNE of %d samples" % min(a.tsne_samples, len(labels["episode"])))
    tsne(features["trained"], labels, a.output, title, a.tsne_samples)
    print("report: state frequencies and transitions")
    state_frequencies(trained, random, a.output, title)
    transitions(trained, a.output, title)
    print("report: wrote", a.output)


if __name__ == "__main__":
    main()
