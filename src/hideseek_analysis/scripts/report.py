#!/usr/bin/env python3
"""Writes one variant's analysis report from the arrays the C++ extractor wrote.

usage: report.py INPUT_DIR OUTPUT_DIR --variant V --policy P --steps N [--tsne-samples K] [--probe-splits N]

INPUT_DIR holds
  steps_trained.csv, steps_random.csv   one row per step of the trained and of the random policy's
                                        rollouts: episode,step,S,H,O,distance (the states)
  features.csv                          one row per probed step: episode,step,S,H (the labels)
  features_trained.npy                  [rows, 512] float32 mid-level features of the trained network
  features_random.npy                   the same rows through a randomly initialised network
  memory_trained.npy, memory_random.npy GRU policies only: the GRU state [rows, 512] after each
                                        probed step, of the trained and of the random-init network
  layouts.csv                           obstacles of the episodes drawn top-down:
                                        episode,half_extent,x,y,size_x,size_y,yaw
OUTPUT_DIR receives probes.csv/.md (features, and the GRU state where there is one; mean and spread
over --probe-splits splits by episode), probe_splits.csv (every split's score), tsne_S.png, tsne_H.png, state_frequencies.csv/.png,
transitions.csv/.png, distance_time.png; every figure is labelled with variant, policy and
training steps.
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402
from matplotlib.transforms import Affine2D  # noqa: E402
from sklearn.manifold import TSNE  # noqa: E402

# In a checkout the package lies beside this folder; in an install space it is on the Python path.
PACKAGE = os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "python")
if os.path.isdir(PACKAGE):
    sys.path.insert(0, PACKAGE)
from hideseek_analysis import states as ha  # noqa: E402


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([r[k] for r in rows]) for k in rows[0]} if rows else {}


def complete_episodes(table):
    """The rows of the episodes the table holds from step 0 to their end (an outcome): a rollout of
    fixed length cuts some episodes short, which would over-weight their early states."""
    episodes, steps, outcome = table["episode"], table["step"].astype(int), table["outcome"].astype(int)
    started = set(episodes[steps == 0])
    ended = set(episodes[outcome != 0])
    keep = np.array([e in started and e in ended for e in episodes])
    return {k: v[keep] for k, v in table.items()}


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


def probes(labels, representations, out, splits=5):
    """representations: {"features": {"trained": X, "random_init": X}, optionally "gru_state": ...}.
    Writes probes.csv/.md (means over the splits) and probe_splits.csv (the balanced accuracy of every
    split: the same splits for every probe, so trained and random-init pair up split by split)."""
    rows, per_split = [], []
    for representation, arrays in representations.items():
        for target in ("S", "H"):
            for network in ("trained", "random_init"):
                r = ha.probe(arrays[network], labels[target].astype(int), labels["episode"], splits=splits)
                rows.append([target, network, r["accuracy"], r["balanced_accuracy"], r["majority_accuracy"],
                             r["positive_prior"], r["train_samples"], r["test_samples"], r["test_episodes"],
                             representation, r["balanced_accuracy_std"], r["splits"]])
                per_split += [[target, network, representation, k, b]
                              for k, b in enumerate(r["balanced_accuracy_per_split"])]
    write_table(os.path.join(out, "probes"), ["label", "network", "test_accuracy", "balanced_accuracy",
                                              "majority_class_accuracy", "positive_prior", "train_samples",
                                              "test_samples", "test_episodes", "representation",
                                              "balanced_accuracy_std", "splits"], rows)
    with open(os.path.join(out, "probe_splits.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["label", "network", "representation", "split", "balanced_accuracy"])
        w.writerows(per_split)
    return rows


# t-SNE's perplexity, the neighbours each point weighs; fewer samples take a smaller one.
PERPLEXITY = 30.0


def tsne_perplexity(samples):
    """PERPLEXITY, or at most a third of the other samples where there are fewer than 91 (scikit-learn
    needs it below the sample count; a third is the usual bound)."""
    return min(PERPLEXITY, max(1.0, (samples - 1) / 3.0))


def tsne(features, labels, out, title, max_samples, seed=0):
    rng = np.random.default_rng(seed)
    pick = rng.choice(len(features), size=min(max_samples, len(features)), replace=False)
    perplexity = tsne_perplexity(len(pick))
    if perplexity < PERPLEXITY:
        print("report: warning: t-SNE of %d samples only, at perplexity %.1f (%g with 91 or more): record more "
              "(analyze.launch's steps)" % (len(pick), perplexity, PERPLEXITY))
        title = "%s\n(%d samples, perplexity %.1f)" % (title, len(pick), perplexity)
    embedded = TSNE(n_components=2, init="pca", random_state=seed, perplexity=perplexity).fit_transform(features[pick])
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


def distance_time(trained, layouts, out, title):
    """Distance between the agents against time, each episode beside its top-down trajectory."""
    episodes = list(dict.fromkeys(layouts["episode"])) if layouts else []
    if not episodes:
        raise SystemExit("report: layouts.csv names no complete episode; record a longer rollout")
    fig, axes = plt.subplots(len(episodes), 2, figsize=(9, 3.2 * len(episodes)), squeeze=False,
                             gridspec_kw={"width_ratios": [1.6, 1]})
    for row, episode in enumerate(episodes):
        mine = trained["episode"] == episode
        steps = trained["step"][mine].astype(int)
        order = np.argsort(steps)
        steps = steps[order]
        col = {k: trained[k][mine][order].astype(float) for k in ("distance", "hider_x", "hider_y", "seeker_x",
                                                                  "seeker_y", "H")}
        outcome = int(trained["outcome"][mine][order][-1])
        ax = axes[row, 0]
        ax.plot(steps, col["distance"], color="k", lw=1)
        seen = col["H"] > 0
        ax.fill_between(steps, 0, col["distance"].max() * 1.05, where=seen, color="tab:red", alpha=0.15, lw=0,
                        label="seeker sees hider (H)")
        ax.set_xlabel("decision step")
        ax.set_ylabel("distance between agents, m")
        ax.set_ylim(0, col["distance"].max() * 1.05)
        ax.set_title("episode (seed) %s: %s after %d steps" % (episode, {1: "captured", 2: "survived"}.get(outcome, "?"),
                                                                len(steps)), fontsize=9)
        if row == 0:
            ax.legend(fontsize=7, loc="upper right")
        ax = axes[row, 1]
        boxes = layouts["episode"] == episode
        half = float(layouts["half_extent"][boxes][0])
        ax.add_patch(Rectangle((-half, -half), 2 * half, 2 * half, fill=False, color="k", lw=1.5))
        for x, y, sx, sy, yaw in zip(*(layouts[k][boxes].astype(float) for k in ("x", "y", "size_x", "size_y", "yaw"))):
            box = Rectangle((-sx / 2, -sy / 2), sx, sy, color="0.6")
            box.set_transform(Affine2D().rotate(yaw).translate(x, y) + ax.transData)
            ax.add_patch(box)
        ax.plot(col["hider_x"], col["hider_y"], color="tab:blue", lw=1, label="hider")
        ax.plot(col["seeker_x"], col["seeker_y"], color="tab:orange", lw=1, label="seeker")
        ax.plot(col["hider_x"][0], col["hider_y"][0], "o", color="tab:blue", ms=5)
        ax.plot(col["seeker_x"][0], col["seeker_y"][0], "o", color="tab:orange", ms=5)
        if outcome == 1:
            ax.plot(col["hider_x"][-1], col["hider_y"][-1], "x", color="tab:red", ms=8, mew=2, label="captured")
        ax.set_xlim(-half - 0.3, half + 0.3)
        ax.set_ylim(-half - 0.3, half + 0.3)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        if row == 0:
            ax.legend(fontsize=7, loc="upper right")
    fig.suptitle("Distance over time and trajectories (dots: start)\n" + title, fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "distance_time.png"), dpi=80)
    plt.close(fig)


# Below this many episodes with images the report warns that its probes rest on too few.
FEW_EPISODES = 20


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--variant", required=True)
    parser.add_argument("--policy", required=True)
    parser.add_argument("--steps", required=True, type=int, help="training steps of the policy")
    parser.add_argument("--tsne-samples", type=int, default=3000)
    parser.add_argument("--probe-splits", type=int, default=5,
                        help="random train/test splits by episode each probe is scored over (mean and spread)")
    a = parser.parse_args()
    if a.probe_splits < 1:
        raise SystemExit("report: --probe-splits must be at least 1, not %d" % a.probe_splits)
    os.makedirs(a.output, exist_ok=True)
    title = "%s, %s, %d training steps" % (a.variant, a.policy, a.steps)
    labels = read_csv(os.path.join(a.input, "features.csv"))
    representations = {}
    for representation, stem in (("features", "features"), ("gru_state", "memory")):
        if representation == "gru_state" and not os.path.exists(os.path.join(a.input, "memory_trained.npy")):
            continue  # a feed-forward policy has no memory
        representations[representation] = {n: np.load(os.path.join(a.input, "%s_%s.npy" % (stem, f))) for n, f in
                                           (("trained", "trained"), ("random_init", "random"))}
        for name, f in representations[representation].items():
            if len(f) != len(labels["episode"]):
                raise SystemExit("report: %s_%s.npy has %d rows, features.csv %d" %
                                 (stem, name, len(f), len(labels["episode"])))
    features = representations["features"]
    trained = read_csv(os.path.join(a.input, "steps_trained.csv"))
    random = read_csv(os.path.join(a.input, "steps_random.csv"))
    # State statistics over whole episodes only, on both sides.
    trained_whole, random_whole = complete_episodes(trained), complete_episodes(random)
    print("report: state statistics over %d whole episodes (%d steps) of the policy, %d (%d steps) of the random "
          "policy" % (len(set(trained_whole["episode"])), len(trained_whole["episode"]),
                      len(set(random_whole["episode"])), len(random_whole["episode"])))
    episodes = len(set(labels["episode"]))
    if episodes < FEW_EPISODES:
        print("report: warning: the images come from %d episodes only (%d images): the probes hold out 30 %% of the "
              "episodes, so their scores rest on a handful of episodes and move by many points between splits; "
              "record more (analyze.launch's steps)" % (episodes, len(labels["episode"])))
    print("report: probes of the %s, %d splits by episode" %
          (" and the ".join(r.replace("_", " ") for r in representations), a.probe_splits))
    probes(labels, representations, a.output, a.probe_splits)
    print("report: t-SNE of %d samples" % min(a.tsne_samples, len(labels["episode"])))
    tsne(features["trained"], labels, a.output, title, a.tsne_samples)
    print("report: state frequencies and transitions")
    state_frequencies(trained_whole, random_whole, a.output, title)
    transitions(trained_whole, a.output, title)
    print("report: distance over time")
    distance_time(trained, read_csv(os.path.join(a.input, "layouts.csv")), a.output, title)
    print("report: wrote", a.output)


if __name__ == "__main__":
    try:
        main()
    except ha.UnusableRecording as e:  # a recording the analysis cannot use (a label with one class): one line
        raise SystemExit("report: %s" % e)
