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


class UnusableRecording(ValueError):
    """A recording the analysis cannot use as it is (a label with one class only): record more."""


def probe(features, labels, groups, test_size=0.3, seed=0, splits=5):
    """Fits a logistic-regression probe on a train split and scores it on a test split, over
    `splits` random splits, and returns the mean scores with the spread of the balanced accuracy.
    The splits depend on the groups and the seed only, so two probes of the same steps (trained and
    random-init features) see the same splits and their per-split scores pair up.

    Each split is by group (episode), so that no episode lends steps to both sides. Returns the
    test accuracy with what a probe that always predicts the majority class would score, the
    positive class's prior, and the balanced accuracy (mean recall over both classes: 0.5 for
    any constant predictor), so a majority-class probe never looks good. Where one class is rare
    the test split holds few of its samples and one split's score moves by points: the standard
    deviation over splits says how far a difference between two probes can be trusted.
    """
    if splits < 1:
        raise ValueError("probe: splits must be at least 1, not %d" % splits)
    features = np.asarray(features, dtype=np.float64)
    labels = np.asarray(labels).astype(int)
    groups = np.asarray(groups)
    scores = []
    for train, test in GroupShuffleSplit(n_splits=splits, test_size=test_size, random_state=seed).split(
            features, labels, groups):
        if len(np.unique(labels[train])) < 2:
            raise UnusableRecording("probe: the train split holds one class only; record more episodes")
        # Classes weighted by their inverse frequency: in a policy's own games one class can be rare
        # (a hider that is almost always in the seeker's view), and an unweighted fit would mostly
        # learn the prior. Balanced accuracy is then the score to read.
        model = make_pipeline(StandardScaler(), LogisticRegression(max_iter=2000, C=1.0, class_weight="balanced"))
        model.fit(features[train], labels[train])
        predicted = model.predict(features[test])
        prior = float(labels[test].mean())
        scores.append({
            "accuracy": float(accuracy_score(labels[test], predicted)),
            "balanced_accuracy": float(balanced_accuracy_score(labels[test], predicted)),
            "majority_accuracy": max(prior, 1.0 - prior),
            "positive_prior": prior,
            "train_samples": len(train),
            "test_samples": len(test),
            "test_episodes": len(np.unique(groups[test])),
        })
    result = {k: float(np.mean([s[k] for s in scores])) for k in scores[0]}
    for k in ("train_samples", "test_samples", "test_episodes"):
        result[k] = int(round(result[k]))
    result["balanced_accuracy_per_split"] = [s["balanced_accuracy"] for s in scores]
    result["balanced_accuracy_std"] = float(np.std(result["balanced_accuracy_per_split"]))
    result["splits"] = splits
    return result


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


# The same statistics read back from a run's analysis tables (states.csv, transitions.csv), as the
# analysis across training seeds sees them.

def state_freq(rows, predicate):
    """The share of steps in the states of states.csv `rows` that match predicate(S, H, O)."""
    return sum(float(r["frequency"]) for r in rows if predicate(int(r["S"]), int(r["H"]), int(r["O"])))


def _sh(name):
    parts = name.split()
    return int(parts[0][1]), int(parts[1][1])


def transition_rate(transitions_rows, states_rows, src, dst):
    """Transitions from a state matching src to one matching dst per 100 of the run's steps (src,
    dst: (S, H) pairs; O either): how often the hider does it, whatever else it does."""
    steps = sum(int(r["steps"]) for r in states_rows)
    n = sum(int(r["count"]) for r in transitions_rows if _sh(r["from"]) == src and _sh(r["to"]) == dst)
    return 100.0 * n / steps if steps else np.nan


def _steps_in(states_rows, src):
    return sum(int(r["steps"]) for r in states_rows if (int(r["S"]), int(r["H"])) == tuple(src))


def time_in(states_rows, src):
    """The share of the run's steps spent in a state matching src ((S, H); O either), from the
    step counts (exact, where states.csv's frequency column is rounded)."""
    steps = sum(int(r["steps"]) for r in states_rows)
    return _steps_in(states_rows, src) / steps if steps else np.nan


def leave_rate(transitions_rows, states_rows, src):
    """Changes out of a state matching src ((S, H); O either) per 100 steps spent in it: how
    quickly the hider leaves it once there."""
    there = _steps_in(states_rows, src)
    out_of = sum(int(r["count"]) for r in transitions_rows if _sh(r["from"]) == src and _sh(r["to"]) != src)
    return 100.0 * out_of / there if there else np.nan


def transition_factors(transitions_rows, states_rows, src, dst):
    """A transition's rate per 100 steps as the product of its three factors: the share of steps
    in src, the changes out of src per 100 steps there, and P(dst | a change out of src). Returns
    a dict of the four. rate = time_in x leave_rate x given exactly wherever the hider is in src and
    leaves it; where it never leaves, the rate is 0 and `given` NaN (it goes nowhere); where it is
    never in src, `leave_rate` and `given` are NaN."""
    return {"time_in": time_in(states_rows, src), "leave_rate": leave_rate(transitions_rows, states_rows, src),
            "given": transition_prob(transitions_rows, src, dst),
            "rate": transition_rate(transitions_rows, states_rows, src, dst)}


def transition_prob(rows, src, dst):
    """P(to a state matching dst | a change out of a state matching src), from transition counts
    (src, dst: (S, H) pairs; O either)."""
    out_of = sum(int(r["count"]) for r in rows if _sh(r["from"]) == src and _sh(r["to"]) != src)
    into = sum(int(r["count"]) for r in rows if _sh(r["from"]) == src and _sh(r["to"]) == dst)
    return into / out_of if out_of else np.nan
