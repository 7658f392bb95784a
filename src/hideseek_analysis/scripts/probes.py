#!/usr/bin/env python3
"""Linear probes on the shared probe set (probe_set make): what a network's 512 mid-level features
say about S (the hider sees the seeker) and H (the seeker sees the hider), H also where S = 1 and
where S = 0.

Every representation is probed on the same images and the same split by episode: the trained
network of a run, five randomly initialised networks (seeds 0-4) and the raw pixels (the image
averaged over 4 x 4 blocks, 21 x 21 x 3 values). The probe is a logistic regression on
standardised features; its regularisation C is chosen on the train episodes alone by grouped
5-fold cross-validation (folds by episode) on balanced accuracy, then it is refitted on all train
episodes and scored once on the held-out test episodes.

usage:
  probes.py baselines PROBE_DIR FEATURES_DIR OUT.csv
      the random-init networks (FEATURES_DIR/random_init_<seed>.npy, seeds 0-4) and the pixels
  probes.py run PROBE_DIR FEATURES.npy BASELINES.csv OUT.csv [--run NAME]
      one run's trained features, with its gain over the mean of the random-init networks
  probes.py tsne PROBE_DIR FEATURES.npy OUT_DIR [--run NAME] [--baselines TSNE_BASELINES.csv]
      the t-SNE of one run's features on the probe set's test images: OUT_DIR/tsne.csv (each
      image's 2-D coordinates, for the picture) and OUT_DIR/tsne_neighbours.csv (how well the
      features' neighbourhoods separate S and H: 11-nearest-neighbour balanced accuracy in the 50
      principal components, neighbours from the image's own episode left out)
  probes.py tsne-baselines PROBE_DIR FEATURES_DIR OUT.csv
      the same neighbourhood scores for the random-init networks and the pixels, and the
      coordinates of random-init network 0 (tsne_random_init_0.csv beside OUT.csv)

The t-SNE is drawn on the test images only (the held-out 30 % of episodes, about 180 images per
variant): the same images for every run, few enough to draw, and the coordinates (not the
features) are what is committed. Features are standardised and reduced to 50 principal
components; the neighbourhood score is taken there, not in the 2-D embedding (which depends on
the t-SNE's perplexity and seed); the t-SNE (perplexity 30, PCA initialisation, seed 0) is for the
picture.
"""
import argparse
import csv
import os
import sys

# One BLAS thread: the probes are many small fits, and they usually share the cores with training.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
import numpy as np  # noqa: E402
from sklearn.linear_model import LogisticRegression  # noqa: E402
from sklearn.metrics import accuracy_score, balanced_accuracy_score  # noqa: E402
from sklearn.model_selection import GroupKFold  # noqa: E402
from sklearn.pipeline import make_pipeline  # noqa: E402
from sklearn.preprocessing import StandardScaler  # noqa: E402

CS = (0.001, 0.01, 0.1, 1.0, 10.0)
RANDOM_INIT_SEEDS = (0, 1, 2, 3, 4)
TARGETS = ("S", "H", "H|S=1", "H|S=0")
FIELDS = ["representation", "target", "C", "train_images", "test_images", "test_positive_prior", "accuracy",
          "balanced_accuracy"]


def load_labels(probe_dir):
    with open(os.path.join(probe_dir, "labels.csv")) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit("probes: %s/labels.csv holds no image" % probe_dir)
    return {
        "S": np.array([int(r["S"]) for r in rows]),
        "H": np.array([int(r["H"]) for r in rows]),
        "episode": np.array([int(r["episode"]) for r in rows]),
        "test": np.array([r["split"] == "test" for r in rows]),
        "variant": np.array([r["variant"] for r in rows]),
        "image": np.array([int(r["image"]) for r in rows]),
    }


def pixel_features(images):
    """The raw-pixel baseline: each image averaged over 4 x 4 blocks, in [0, 1]."""
    n, h, w, c = images.shape
    x = images[:, :h - h % 4, :w - w % 4].astype(np.float32) / 255.0
    x = x.reshape(n, h // 4, 4, w // 4, 4, c).mean(axis=(2, 4))
    return x.reshape(n, -1)


def target_rows(labels, target):
    """(mask of the images the target applies to, its 0/1 labels)."""
    if target == "S":
        return np.ones_like(labels["S"], dtype=bool), labels["S"]
    if target == "H":
        return np.ones_like(labels["H"], dtype=bool), labels["H"]
    s = 1 if target == "H|S=1" else 0
    return labels["S"] == s, labels["H"]


def probe(features, labels, target, cs=CS, folds=5):
    """Chooses C by grouped cross-validation on the train episodes, refits, scores the test ones."""
    mask, y = target_rows(labels, target)
    train = mask & ~labels["test"]
    test = mask & labels["test"]
    x = np.asarray(features, dtype=np.float64)
    if len(np.unique(y[train])) < 2 or len(np.unique(y[test])) < 2:
        raise ValueError("probe %s: a split holds one class only" % target)
    groups = labels["episode"][train]
    best = None
    for c in cs:
        scores = []
        for a, b in GroupKFold(n_splits=folds).split(x[train], y[train], groups):
            if len(np.unique(y[train][a])) < 2:
                continue
            model = make_pipeline(StandardScaler(), LogisticRegression(C=c, max_iter=3000, class_weight="balanced"))
            model.fit(x[train][a], y[train][a])
            scores.append(balanced_accuracy_score(y[train][b], model.predict(x[train][b])))
        score = float(np.mean(scores))
        if best is None or score > best[0] + 1e-12:
            best = (score, c)
    c = best[1]
    model = make_pipeline(StandardScaler(), LogisticRegression(C=c, max_iter=3000, class_weight="balanced"))
    model.fit(x[train], y[train])
    predicted = model.predict(x[test])
    return {"target": target, "C": c, "train_images": int(train.sum()), "test_images": int(test.sum()),
            "test_positive_prior": round(float(y[test].mean()), 4),
            "accuracy": round(float(accuracy_score(y[test], predicted)), 4),
            "balanced_accuracy": round(float(balanced_accuracy_score(y[test], predicted)), 4)}


def probe_all(features, labels, representation):
    return [dict(representation=representation, **probe(features, labels, t)) for t in TARGETS]


def write_rows(path, rows, fields):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in fields})


def baselines(probe_dir, features_dir, out):
    labels = load_labels(probe_dir)
    rows = []
    for seed in RANDOM_INIT_SEEDS:
        f = np.load(os.path.join(features_dir, "random_init_%d.npy" % seed))
        rows += probe_all(f, labels, "random_init_%d" % seed)
        print("probes: random_init_%d done" % seed, flush=True)
    images = np.load(os.path.join(probe_dir, "images.npy"))
    rows += probe_all(pixel_features(images), labels, "pixels")
    write_rows(out, rows, FIELDS)
    print("probes: baselines into %s" % out)


def run(probe_dir, features, baselines_csv, out, name):
    labels = load_labels(probe_dir)
    f = np.load(features)
    if f.shape[0] != len(labels["S"]):
        raise SystemExit("probes: %s holds %d rows, the probe set %d images" % (features, f.shape[0], len(labels["S"])))
    rows = probe_all(f, labels, "trained")
    with open(baselines_csv) as fh:
        base = list(csv.DictReader(fh))
    for r in rows:
        rand = [float(b["balanced_accuracy"]) for b in base
                if b["target"] == r["target"] and b["representation"].startswith("random_init_")]
        pix = [float(b["balanced_accuracy"]) for b in base if b["target"] == r["target"] and b["representation"] == "pixels"]
        r["random_init_mean"] = round(float(np.mean(rand)), 4)
        r["gain_over_random_init"] = round(r["balanced_accuracy"] - float(np.mean(rand)), 4)
        r["pixels"] = pix[0] if pix else ""
        r["run"] = name
    write_rows(out, rows, ["run"] + FIELDS + ["random_init_mean", "gain_over_random_init", "pixels"])
    for r in rows:
        print("probes: %s %s: balanced accuracy %.3f (random init %.3f, gain %+.3f), C %g" % (
            name, r["target"], r["balanced_accuracy"], r["random_init_mean"], r["gain_over_random_init"], r["C"]))


TSNE_TARGETS = ("S", "H")
TSNE_NEIGHBOURS = 11  # odd: a vote between two classes has no tie
TSNE_COMPONENTS = 50


def principal_components(features, seed=0):
    """The features standardised (as the probes see them), then their first 50 principal components."""
    from sklearn.decomposition import PCA
    x = StandardScaler().fit_transform(np.asarray(features, dtype=np.float64))
    keep = min(TSNE_COMPONENTS, x.shape[0] - 1, x.shape[1])
    return PCA(n_components=keep, random_state=seed).fit_transform(x) if keep < x.shape[1] else x


def tsne_embed(components, seed=0):
    """2-D t-SNE of principal components, deterministic in seed (for the picture only)."""
    from sklearn.manifold import TSNE
    perplexity = min(30.0, (components.shape[0] - 1) / 3.0)
    return TSNE(n_components=2, init="pca", random_state=seed, perplexity=perplexity).fit_transform(components)


def neighbour_score(points, y, groups=None, k=TSNE_NEIGHBOURS):
    """k-nearest-neighbour balanced accuracy of the 0/1 labels y, each point voted on by its k
    nearest other points outside its own group (its episode: neighbouring frames of one episode
    would make any representation look good): 0.5 where neighbourhoods ignore the label, 1 where
    every neighbourhood is pure. k is odd, so no vote ties."""
    y = np.asarray(y)
    if len(np.unique(y)) < 2:
        raise ValueError("neighbour score: the labels hold one class only")
    x = np.asarray(points, dtype=np.float64)
    g = np.arange(len(y)) if groups is None else np.asarray(groups)
    sq = (x * x).sum(axis=1)
    d = sq[:, None] + sq[None, :] - 2.0 * x @ x.T
    d[g[:, None] == g[None, :]] = np.inf  # the point itself and its own episode
    k = min(k, int(np.isfinite(d).sum(axis=1).min()))
    if k < 1:
        raise ValueError("neighbour score: a point has no neighbour outside its own group")
    nearest = np.argpartition(d, k - 1, axis=1)[:, :k]
    predicted = (y[nearest].mean(axis=1) > 0.5).astype(int)
    return round(float(balanced_accuracy_score(y, predicted)), 4)


def episode_groups(labels, rows):
    """One group per (variant, episode): episode numbers repeat across variants."""
    keys = ["%s/%d" % (v, e) for v, e in zip(labels["variant"][rows], labels["episode"][rows])]
    return np.unique(keys, return_inverse=True)[1]


def neighbour_scores(components, labels, rows):
    groups = episode_groups(labels, rows)
    return {t: neighbour_score(components, labels[t][rows], groups) for t in TSNE_TARGETS}


def write_coordinates(path, images, points):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["image", "x", "y"])
        for i, (a, b) in zip(images, points):
            w.writerow([int(i), round(float(a), 2), round(float(b), 2)])


def tsne_run(probe_dir, features, out_dir, name, baselines_csv=None):
    labels = load_labels(probe_dir)
    f = np.load(features)
    if f.shape[0] != len(labels["S"]):
        raise SystemExit("probes: %s holds %d rows, the probe set %d images" % (features, f.shape[0], len(labels["S"])))
    test = np.flatnonzero(labels["test"])
    components = principal_components(f[test])
    write_coordinates(os.path.join(out_dir, "tsne.csv"), labels["image"][test], tsne_embed(components))
    scores = neighbour_scores(components, labels, test)
    base = []
    if baselines_csv and os.path.exists(baselines_csv):
        with open(baselines_csv) as fh:
            base = list(csv.DictReader(fh))
    rows = []
    for t in TSNE_TARGETS:
        rand = [float(b["neighbour_balanced_accuracy"]) for b in base
                if b["target"] == t and b["representation"].startswith("random_init_")]
        pix = [b["neighbour_balanced_accuracy"] for b in base if b["target"] == t and b["representation"] == "pixels"]
        rows.append({"run": name, "target": t, "images": len(test), "neighbours": TSNE_NEIGHBOURS,
                     "neighbour_balanced_accuracy": scores[t],
                     "random_init_mean": round(float(np.mean(rand)), 4) if rand else "",
                     "random_init_min": round(float(np.min(rand)), 4) if rand else "",
                     "random_init_max": round(float(np.max(rand)), 4) if rand else "",
                     "pixels": pix[0] if pix else ""})
        print("probes: %s %s: %d-neighbour balanced accuracy %.3f%s" % (
            name, t, TSNE_NEIGHBOURS, scores[t],
            " (random init %.3f, %.3f to %.3f)" % (np.mean(rand), min(rand), max(rand)) if rand else ""))
    write_rows(os.path.join(out_dir, "tsne_neighbours.csv"), rows,
               ["run", "target", "images", "neighbours", "neighbour_balanced_accuracy", "random_init_mean",
                "random_init_min", "random_init_max", "pixels"])


def tsne_baselines(probe_dir, features_dir, out):
    labels = load_labels(probe_dir)
    test = np.flatnonzero(labels["test"])
    reps = [("random_init_%d" % s, np.load(os.path.join(features_dir, "random_init_%d.npy" % s))[test])
            for s in RANDOM_INIT_SEEDS]
    reps.append(("pixels", pixel_features(np.load(os.path.join(probe_dir, "images.npy"))[test])))
    rows = []
    for name, f in reps:
        components = principal_components(f)
        if name == "random_init_0":  # drawn beside the runs' embeddings (seed_figures.py)
            write_coordinates(os.path.join(os.path.dirname(os.path.abspath(out)), "tsne_random_init_0.csv"),
                              labels["image"][test], tsne_embed(components))
        scores = neighbour_scores(components, labels, test)
        rows += [{"representation": name, "target": t, "images": len(test), "neighbours": TSNE_NEIGHBOURS,
                  "neighbour_balanced_accuracy": scores[t]} for t in TSNE_TARGETS]
        print("probes: neighbourhoods of %s done" % name, flush=True)
    write_rows(out, rows, ["representation", "target", "images", "neighbours", "neighbour_balanced_accuracy"])
    print("probes: neighbourhood baselines into %s" % out)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="command", required=True)
    b = sub.add_parser("baselines")
    b.add_argument("probe_dir")
    b.add_argument("features_dir")
    b.add_argument("out")
    r = sub.add_parser("run")
    r.add_argument("probe_dir")
    r.add_argument("features")
    r.add_argument("baselines")
    r.add_argument("out")
    r.add_argument("--run", default="")
    t = sub.add_parser("tsne")
    t.add_argument("probe_dir")
    t.add_argument("features")
    t.add_argument("out_dir")
    t.add_argument("--run", default="")
    t.add_argument("--baselines", default=None)
    tb = sub.add_parser("tsne-baselines")
    tb.add_argument("probe_dir")
    tb.add_argument("features_dir")
    tb.add_argument("out")
    args = p.parse_args(argv)
    if args.command == "baselines":
        baselines(args.probe_dir, args.features_dir, args.out)
    elif args.command == "tsne":
        tsne_run(args.probe_dir, args.features, args.out_dir, args.run, args.baselines)
    elif args.command == "tsne-baselines":
        tsne_baselines(args.probe_dir, args.features_dir, args.out)
    else:
        run(args.probe_dir, args.features, args.baselines, args.out, args.run)
    return 0


if __name__ == "__main__":
    sys.exit(main())
