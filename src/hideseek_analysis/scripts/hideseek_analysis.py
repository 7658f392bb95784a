"""Statistics of the paper's analysis (its section on what the hider learns), on arrays that the
C++ side extracts from recorded games: linear probes of the mid-level features, the frequencies
of the eight (S, H, O) states and the transitions between them.

Statistics come from scikit-learn (LogisticRegression, GroupShuffleSplit, balanced accuracy);
nothing here re-implements what it provides.
"""
import numpy as np
from sklearn.linear_model import LogisticRegression
from sklearn.metrics import accuracy_score, balanced_accuracy_score
from sklearn.model_selection import GroupShuffleSplit
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

# The eight states in the paper's order of the bits: S (hider sees seeker), H (seeker sees
# hider), O (obstacle in the hider's view). State index = 4 S + 2 H + O.
STATE_NAMES = ["S%d H%d O%d" % ((i >> 2) & 1, (i >> 1) & 1, i & 1) for i in range(8)]


def probe(features, labels, groups, test_size=0.3, seed=0):
    """Fits a logistic-regression probe on a train split and scores it on a test split.

    The split is by group (episode), so that no episode lends steps to both sides. Returns the
    test accuracy with what a probe that always predicts the majority class would score, the
    positive class's prior, and the balanced accuracy (mean recall over both classes: 0.5 for
    any constant predictor), so a majority-class probe never looks good.
    """
    features = np.asarray(features, dtype=np.float64)
    labels = np.asarray(labels).astype(int)
    groups = np.asarray(groups)
    split = GroupShuffleSplit(n_splits=1, test_size=test_size, random_state=seed)
    train, test = next(split.split(features, labels, groups))
    if len(np.unique(labels[train])) < 2:
        raise ValueError("probe: the train split holds one class only; record more episodes")
    # Classes weighted by their inverse frequency: in a policy's own games one class can be rare
    # (a hider that is almost always in the seeker's view), and an unweighted fit would mostly
    # learn the prior. Balanced accuracy is then the score to read.
    model = make_pipeline(StandardScaler(), LogisticRegression(max_iter=2000, C=1.0, class_weight="balanced"))
    model.fit(features[train], labels[train])
    predicted = model.predict(features[test])
    prior = float(labels[test].mean())
    return {
        "accuracy": float(accuracy_score(labels[test], predicted)),
        "balanced_accuracy": float(balanced_accuracy_score(labels[test], predicted)),
        "majority_accuracy": max(prior, 1.0 - prior),
        "positive_prior": prior,
        "train_samples": int(len(train)),
        "test_samples": int(len(test)),
        "test_episodes": int(len(np.unique(groups[test]))),
    }


def state_index(s, h, o):
    """Index 0..7 of the (S, H, O) state of each step."""
    return 4 * np.asarray(s, dtype=int) + 2 * np.asarray(h, dtype=int) + np.asarray(o, dtype=int)


def state_frequencies(states):
    """Relative frequency of each of the eight states."""
    counts = np.bincount(np.asarray(states, dtype=int), minlength=8).astype(np.float64)
    return counts / max(counts.sum(), 1.0)


def transitions(states, episodes):
    """Probabilities of the 56 transitions between distinct states.

    Counts, within each episode, every step whose state differs from the previous step's; row i
    is then normalised to the probability of each destination given a change out of state i
    (diagonal 0). A state never left has a row of NaN. Returns (probabilities, counts), 8 x 8.
    """
    states = np.asarray(states, dtype=int)
    episodes = np.asarray(episodes)
    counts = np.zeros((8, 8), dtype=np.int64)
    same_episode = episodes[1:] == episodes[:-1]
    changed = states[1:] != states[:-1]
    for a, b in zip(states[:-1][same_episode & changed], states[1:][same_episode & changed]):
        counts[a, b] += 1
    totals = counts.sum(axis=1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        probabilities = np.where(totals > 0, counts / np.maximum(totals, 1), np.nan)
    return probabilities, counts
