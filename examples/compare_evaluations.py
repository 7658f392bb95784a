#!/usr/bin/python3
"""Two evaluations of your own compared with the project's analysis library (hideseek_analysis).

Each argument is an evaluate.launch output_dir (its episodes.csv: seed, living_steps, outcome) or
that file itself, of one policy each, evaluated on the same seeds:

    source devel/setup.bash
    roslaunch hideseek_world evaluate.launch policy:=shipped episodes:=20 output_dir:=/tmp/cmp/shipped
    roslaunch hideseek_world evaluate.launch policy:=scripted/flee episodes:=20 output_dir:=/tmp/cmp/flee
    /usr/bin/python3 examples/compare_evaluations.py /tmp/cmp/shipped /tmp/cmp/flee --out /tmp/cmp

It prints each side's mean and interquartile mean of living steps with 95 % bootstrap intervals,
the difference of the means (unpaired, and paired by evaluation seed: where the two played other
variants, as their evaluation.csv files say, it notes that a seed pairs like starts only on one
map) and the probability that an
episode of the first lives longer than one of the second, and draws their performance profiles.
With one run (one trained policy) a side, every interval covers the evaluation episodes only, not
the spread between training seeds: for that, evaluate several runs of each and pass stats.* a list
of per-run arrays (docs/analysis.md, The analysis as a library).
"""
import argparse
import os
import sys

from hideseek_analysis import stats as st
from hideseek_analysis.figures import performance_profile
from hideseek_analysis.runs import evaluation_by_seed, load_episodes, read_csv


def episodes_csv(path):
    return os.path.join(path, "episodes.csv") if os.path.isdir(path) else path


def played(episodes):
    """(variant, game) as evaluate.launch names them in the evaluation.csv beside `episodes`; None
    where it is not there (the game: in an evaluation written before 2026-12-02, which has no game
    column)."""
    rows = read_csv(os.path.join(os.path.dirname(os.path.abspath(episodes)), "evaluation.csv"))
    return (rows[-1].get("variant"), rows[-1].get("game")) if rows else (None, None)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("first", help="evaluate.launch's output_dir (or its episodes.csv) of the first policy")
    p.add_argument("second", help="the same of the second policy")
    p.add_argument("--labels", nargs=2, help="names for the two (default: the folders' names)")
    p.add_argument("--out", help="a folder for performance_profile.png (default: no figure)")
    p.add_argument("--seed", type=int, default=0, help="the bootstrap's random seed")
    p.add_argument("--reps", type=int, default=st.BOOTSTRAP, help="bootstrap resamples")
    a = p.parse_args(argv)
    paths = [episodes_csv(a.first), episodes_csv(a.second)]
    labels = a.labels or [os.path.basename(os.path.dirname(os.path.abspath(x))) for x in paths]
    try:
        living = [load_episodes(x)[0] for x in paths]
        by_seed = [evaluation_by_seed(x) for x in paths]
        paired = st.paired_difference(by_seed[0], by_seed[1], st.keyed_rng(a.seed, "paired"), a.reps)
    except (OSError, ValueError) as e:
        print("compare_evaluations: %s" % e, file=sys.stderr)
        return 2
    if labels[0] == labels[1]:
        print("compare_evaluations: both are named %s: give them names with --labels" % labels[0], file=sys.stderr)
        return 2
    for label, x in zip(labels, living):
        m, (lo, hi) = st.pooled_statistic(x, st.mean, st.keyed_rng(a.seed, "mean", label), a.reps)
        q, (qlo, qhi) = st.pooled_statistic(x, st.iqm, st.keyed_rng(a.seed, "iqm", label), a.reps)
        print("%s: %d episodes, mean living steps %.1f [%.1f, %.1f], IQM %.1f [%.1f, %.1f]"
              % (label, len(x), m, lo, hi, q, qlo, qhi))
    d, (lo, hi) = st.mean_difference(living[0], living[1], st.keyed_rng(a.seed, "difference"), a.reps)
    print("%s minus %s: %.1f [%.1f, %.1f] living steps (unpaired)" % (labels[0], labels[1], d, lo, hi))
    d, (lo, hi), n = paired
    print("%s minus %s: %.1f [%.1f, %.1f] living steps (paired over the %d seeds both played)"
          % (labels[0], labels[1], d, lo, hi, n))
    (variant_a, game_a), (variant_b, game_b) = [played(x) for x in paths]
    if None not in (variant_a, variant_b) and variant_a != variant_b:
        # A seed draws its variant's layout and spawns: on two maps one seed is two other starts.
        print("  (%s and %s are other variants: a seed is the same start only where both play one map;"
              " otherwise the pairing pairs nothing)" % (variant_a, variant_b))
    if None not in (game_a, game_b) and game_a != game_b:
        # Each game has its own maps and rules: one seed starts two other episodes.
        print("  (games %s and %s: each plays its own maps and rules, so a seed is not the same start"
              " and the pairing pairs nothing)" % (game_a, game_b))
    p_better, (lo, hi) = st.probability_of_improvement(living[0], living[1], st.keyed_rng(a.seed, "poi"),
                                                       a.reps)["episodes"]
    print("P(an episode of %s lives longer than one of %s) = %.2f [%.2f, %.2f]" % (labels[0], labels[1],
                                                                                  p_better, lo, hi))
    if a.out:
        os.makedirs(a.out, exist_ok=True)
        performance_profile(a.out, {(label, "greedy"): x for label, x in zip(labels, living)}, labels, a.seed,
                            a.reps, title="%s and %s (bands: 95 %% bootstrap over episodes)"
                            % tuple(labels))
        print("figure: %s" % os.path.join(a.out, "performance_profile.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
