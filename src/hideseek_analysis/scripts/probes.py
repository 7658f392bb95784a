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
    args = p.parse_args(argv)
    if args.command == "baselines":
        baselines(args.probe_dir, args.features_dir, args.out)
    else:
        run(args.probe_dir, args.features, args.baselines, args.out, args.run)
    return 0


if __name__ == "__main__":
    sys.exit(main())
