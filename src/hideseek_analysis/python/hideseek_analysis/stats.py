"""Statistics across training seeds, after the rliable method (Agarwal et al., "Deep RL at the
edge of the statistical precipice"), on numpy and scipy alone.

A variant's sample is its runs (training seeds), each with its evaluation episodes (seeds 0-99).
With few runs per variant the interquartile mean of the run scores is their mean (3 runs: nothing
is trimmed), so the IQM is taken over the pooled episodes of the variant's runs, and every interval
comes from a two-level bootstrap: resample the runs with replacement, then the episodes within
each drawn run. The interval so covers both the spread between training seeds and the spread
between evaluation episodes; with three seeds it is wide, and it can only be as wide as three
draws of the training seed allow (it does not cover seeds whose behaviour none of the three showed).
"""
import zlib

import numpy as np
from scipy import stats

BOOTSTRAP = 2000
CONFIDENCE = 0.95


def iqm(values):
    """Interquartile mean: the mean of the middle 50 % (scipy's trim_mean, 25 % cut at each end)."""
    return float(stats.trim_mean(np.asarray(values, dtype=np.float64), 0.25))


def mean(values):
    return float(np.mean(values))


def as_runs(runs, name="runs"):
    """A sample as the functions below take it: a list of per-run arrays of episode scores. One run
    may be given as a plain sequence of numbers (an evaluation of one policy); a run without
    episodes is refused, naming it."""
    runs = list(runs)
    if runs and np.ndim(runs[0]) == 0:
        runs = [runs]
    out = [np.asarray(r, dtype=np.float64) for r in runs]
    if not out:
        raise ValueError("%s: no runs" % name)
    for i, r in enumerate(out):
        if r.ndim != 1 or r.size == 0:
            raise ValueError("%s: run %d holds %s, not a non-empty sequence of episode scores"
                             % (name, i, "no episodes" if r.size == 0 else "an array of shape %s" % (r.shape,)))
    return out


def generator(rng):
    """`rng` as a numpy Generator: a Generator is used as it is, an integer seeds a new one."""
    if isinstance(rng, np.random.Generator):
        return rng
    if isinstance(rng, (int, np.integer)) and not isinstance(rng, bool):
        return np.random.default_rng(int(rng))
    raise TypeError("rng: a numpy Generator (keyed_rng(seed, key...)) or an integer seed, not %s" % type(rng).__name__)


def keyed_rng(seed, *key):
    """A generator of its own for one estimate, seeded from `seed` and a stable key (a variant, a
    claim): an interval then depends only on its own data and the seed, so a run added to one
    variant leaves every other variant's interval as it was."""
    return np.random.default_rng([int(seed)] + [zlib.crc32(str(k).encode()) for k in key])


def two_level_samples(runs, rng, reps=BOOTSTRAP):
    """Yields `reps` bootstrap samples of a variant: runs drawn with replacement, then episodes
    drawn with replacement within each drawn run; each sample is a list of per-run arrays."""
    runs = as_runs(runs)
    rng = generator(rng)
    for _ in range(reps):
        picked = rng.integers(0, len(runs), size=len(runs))
        yield [runs[i][rng.integers(0, len(runs[i]), size=len(runs[i]))] for i in picked]


def interval(estimates):
    """The percentile interval of bootstrap estimates at CONFIDENCE."""
    lo, hi = np.percentile(estimates, [50 * (1 - CONFIDENCE), 100 - 50 * (1 - CONFIDENCE)])
    return float(lo), float(hi)


def pooled_statistic(runs, statistic, rng, reps=BOOTSTRAP):
    """(point estimate, (low, high)) of `statistic` over the pooled episodes of `runs`, with the
    two-level bootstrap interval."""
    runs = as_runs(runs)
    rng = generator(rng)
    point = statistic(np.concatenate(runs))
    boot = [statistic(np.concatenate(s)) for s in two_level_samples(runs, rng, reps)]
    return point, interval(boot)


def performance_profile(runs, taus, rng, reps=BOOTSTRAP):
    """The fraction of pooled episodes whose score exceeds each tau, with two-level bootstrap bands:
    (profile, low, high), arrays over taus."""
    taus = np.asarray(taus, dtype=np.float64)

    def profile(x):
        return (x[None, :] > taus[:, None]).mean(axis=1)

    runs, rng = as_runs(runs), generator(rng)
    point = profile(np.concatenate(runs))
    boot = np.array([profile(np.concatenate(s)) for s in two_level_samples(runs, rng, reps)])
    lo, hi = np.percentile(boot, [50 * (1 - CONFIDENCE), 100 - 50 * (1 - CONFIDENCE)], axis=0)
    return point, lo, hi


def _poi(x, y):
    """P(X > Y) + P(X = Y) / 2 between two samples (the Mann-Whitney U statistic over n m)."""
    x = np.asarray(x, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64)
    greater = (x[:, None] > y[None, :]).mean()
    equal = (x[:, None] == y[None, :]).mean()
    return float(greater + 0.5 * equal)


def probability_of_improvement(runs_x, runs_y, rng, reps=BOOTSTRAP):
    """rliable's probability of improvement of X over Y, at two levels:

    - runs: P(a run of X scores a higher mean than a run of Y), over run means (what the paper's
      claim is about: training X rather than Y);
    - episodes: P(an episode of X lives longer than one of Y), over the pooled episodes, with the
      two-level bootstrap interval.

    Both intervals come from the same two-level bootstrap (each side's runs, then episodes within
    them). Returns {"runs": (p, (lo, hi)), "episodes": (p, (lo, hi))}."""
    runs_x, runs_y, rng = as_runs(runs_x, "runs_x"), as_runs(runs_y, "runs_y"), generator(rng)
    mx = [float(np.mean(r)) for r in runs_x]
    my = [float(np.mean(r)) for r in runs_y]
    run_boot, ep_boot = [], []
    for sx, sy in zip(two_level_samples(runs_x, rng, reps), two_level_samples(runs_y, rng, reps)):
        run_boot.append(_poi([s.mean() for s in sx], [s.mean() for s in sy]))
        ep_boot.append(_poi(np.concatenate(sx), np.concatenate(sy)))
    return {
        "runs": (_poi(mx, my), interval(run_boot)),
        "episodes": (_poi(np.concatenate(runs_x), np.concatenate(runs_y)), interval(ep_boot)),
    }


def mean_difference(runs_x, runs_y, rng, reps=BOOTSTRAP):
    """The difference of the pooled means, X minus Y, with the two-level bootstrap interval (each
    side's runs, then episodes within them, resampled on their own). Returns (d, (lo, hi))."""
    runs_x, runs_y, rng = as_runs(runs_x, "runs_x"), as_runs(runs_y, "runs_y"), generator(rng)
    point = float(np.mean(np.concatenate(runs_x)) - np.mean(np.concatenate(runs_y)))
    boot = [np.mean(np.concatenate(sx)) - np.mean(np.concatenate(sy))
            for sx, sy in zip(two_level_samples(runs_x, rng, reps), two_level_samples(runs_y, rng, reps))]
    return point, interval(boot)


def paired_difference(by_seed_x, by_seed_y, rng, reps=BOOTSTRAP):
    """The mean difference X minus Y over the evaluation seeds both played ({seed: score}, as
    runs.evaluation_by_seed gives), with a bootstrap interval over those seeds. For one run of each
    side (two policies evaluated on the same seeds): pairing by seed takes out what the seeds' maps
    and spawns do to both sides alike, and the interval covers the evaluation episodes only, never
    the spread between training seeds. Returns (d, (lo, hi), seeds)."""
    common = sorted(set(by_seed_x) & set(by_seed_y))
    if not common:
        raise ValueError("paired_difference: the two sides share no evaluation seed")
    diffs = np.array([by_seed_x[s] - by_seed_y[s] for s in common], dtype=np.float64)
    rng = generator(rng)
    boot = [diffs[rng.integers(0, len(diffs), len(diffs))].mean() for _ in range(reps)]
    return float(diffs.mean()), interval(boot), len(common)


def rank_correlation(runs_by_variant, reference, rng, reps=BOOTSTRAP):
    """Spearman's rho between the variants' mean scores (pooled episodes) and `reference` (the
    paper's figures, same order), with a two-level bootstrap interval (each variant resampled on its
    own). Returns (rho, (lo, hi))."""
    rng = generator(rng)  # one generator for every variant's sampler (an integer would give each the same draws)
    point = stats.spearmanr([np.mean(np.concatenate(r)) for r in runs_by_variant], reference)[0]
    generators = [two_level_samples(r, rng, reps) for r in runs_by_variant]
    boot = []
    for samples in zip(*generators):
        scores = [np.mean(np.concatenate(s)) for s in samples]
        rho = stats.spearmanr(scores, reference)[0]
        if np.isfinite(rho):
            boot.append(rho)
    # Constant scores leave rho undefined: no point and no interval rather than a made-up one.
    return float(point), (interval(boot) if boot else (float("nan"), float("nan")))


def boot_runs(per_variant, stat, rng, reps=BOOTSTRAP):
    """A statistic of per-variant lists of per-run values, with its bootstrap interval: each variant's
    runs resampled on their own. per_variant: {variant: [value per run]}; stat: dict -> number. With
    one run of a variant there is no interval over seeds: (point, (nan, nan))."""
    rng = generator(rng)
    point = stat({v: np.asarray(x, dtype=float) for v, x in per_variant.items()})
    if min(len(x) for x in per_variant.values()) < 2:
        return float(point), (np.nan, np.nan)
    boot = []
    for _ in range(reps):
        sample = {v: np.asarray(x, dtype=float)[rng.integers(0, len(x), len(x))] for v, x in per_variant.items()}
        boot.append(stat(sample))
    return float(point), interval(boot)


def mean_over_runs(values, rng, reps=BOOTSTRAP):
    """The mean of per-run values and its bootstrap interval over runs ((nan, nan) with one run)."""
    values, rng = np.asarray(values, dtype=float), generator(rng)
    if len(values) < 2:
        return float(values.mean()), (np.nan, np.nan)
    boot = [values[rng.integers(0, len(values), len(values))].mean() for _ in range(reps)]
    return float(values.mean()), interval(boot)
