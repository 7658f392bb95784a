#!/usr/bin/env python3
"""What a hider does, from its rollouts (play_episodes' per-step CSV): the small per-run outputs
that the analysis across training seeds aggregates, so that a run's weights may go once they are
committed.

usage: behaviour.py STEPS.csv OUT_DIR [--run NAME]

Writes into OUT_DIR:
- states.csv: the eight (S, H, O) states, steps and frequency;
- transitions.csv: the 56 transitions between distinct states within episodes, counts and
  P(to | a change out of from);
- distance.csv: the mean distance between the agents at each step of the episode (steps 0-999 in
  bins of 10) and how many episodes are still running there;
- behaviour.csv: one row: episodes, steps, mean living steps, success, the share of steps the hider
  walks backward, keeps the seeker in view (S), is seen (H), and how often per 100 steps it breaks
  the seeker's line of sight (H from 1 to 0), loses sight of the seeker (S from 1 to 0), and how
  often the distance between the agents turns from growing to shrinking or back (its 5-step
  moving average: every wobble counts), and how often it swings by at least SWING_M (1 m) either
  way, the paper's oscillation (a hider that lets the seeker come metres closer, then runs);
- swings.csv: the swings per 100 steps at each of SWING_THRESHOLDS, the threshold's effect.
"""
import argparse
import csv
import os
import sys

import numpy as np

# In a checkout the package lies beside this folder; in an install space it is on the Python path.
PACKAGE = os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "python")
if os.path.isdir(PACKAGE):
    sys.path.insert(0, PACKAGE)
from hideseek_analysis.states import STATE_NAMES, state_frequencies, state_index, transitions  # noqa: E402

BACKWARD = 2  # hideseek_game::Action::kBackward
BIN = 10
MAX_STEPS = 1000
SWING_M = 1.0  # the paper's faster hiders let the distance swing by metres
SWING_THRESHOLDS = (0.25, 0.5, 1.0, 2.0)


def swings(x, threshold):
    """How often the distance x reverses by at least `threshold`: once it has moved one way by the
    threshold, each time it comes back from its extreme by the threshold or more (a zigzag with
    hysteresis: a wobble smaller than the threshold never counts)."""
    trend, count = 0, 0
    lo = hi = ext = x[0]
    for v in x[1:]:
        if trend == 0:
            lo, hi = min(lo, v), max(hi, v)
            if v - lo >= threshold:
                trend, ext = 1, v
            elif hi - v >= threshold:
                trend, ext = -1, v
        elif trend * (v - ext) > 0:
            ext = v
        elif trend * (ext - v) >= threshold:
            trend, ext, count = -trend, v, count + 1
    return count


def read_steps(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit("behaviour: %s holds no step" % path)
    # play_episodes writes its arenas' steps interleaved: put each episode's steps together, in order.
    rows.sort(key=lambda r: (int(r["seed"]), int(r["step"])))
    col = {k: np.array([r[k] for r in rows]) for k in ("seed", "step", "S", "H", "O", "distance", "hider_action",
                                                         "outcome")}
    return {
        "seed": col["seed"].astype(int), "step": col["step"].astype(int), "S": col["S"].astype(int),
        "H": col["H"].astype(int), "O": col["O"].astype(int), "distance": col["distance"].astype(float),
        "action": col["hider_action"].astype(int), "outcome": col["outcome"],
    }


def summarise(d):
    """The per-run figures (dict of arrays and numbers) from read_steps' columns."""
    states = state_index(d["S"], d["H"], d["O"])
    freq = state_frequencies(states)
    counts = np.bincount(states, minlength=8)
    prob, tcounts = transitions(states, d["seed"])
    ends = d["outcome"] != ""
    living = d["step"][ends] + 1
    success = d["outcome"][ends] == "survived"
    same = d["seed"][1:] == d["seed"][:-1]
    h_breaks = int(((d["H"][:-1] == 1) & (d["H"][1:] == 0) & same).sum())
    s_losses = int(((d["S"][:-1] == 1) & (d["S"][1:] == 0) & same).sum())
    # How much the distance oscillates: turns of its 5-step moving average (the sign of its change
    # flips) per 100 steps, within episodes.
    turns = 0
    for seed in np.unique(d["seed"]):
        x = d["distance"][d["seed"] == seed]
        if len(x) < 7:
            continue
        change = np.diff(np.convolve(x, np.ones(5) / 5, mode="valid"))
        change = change[np.abs(change) > 1e-6]
        turns += int((np.sign(change[1:]) != np.sign(change[:-1])).sum())
    swung = {t: sum(swings(d["distance"][d["seed"] == seed], t) for seed in np.unique(d["seed"]))
             for t in SWING_THRESHOLDS}
    bins = np.arange(0, MAX_STEPS, BIN)
    which = np.minimum(d["step"] // BIN, len(bins) - 1)
    mean_distance = np.full(len(bins), np.nan)
    running = np.zeros(len(bins), dtype=int)
    for b in range(len(bins)):
        m = which == b
        if m.any():
            mean_distance[b] = d["distance"][m].mean()
            running[b] = len(np.unique(d["seed"][m]))
    n = len(states)
    return {
        "freq": freq, "counts": counts, "prob": prob, "tcounts": tcounts, "bins": bins,
        "mean_distance": mean_distance, "running": running,
        "swings": {t: round(100.0 * c / n, 3) for t, c in swung.items()},
        "row": {"episodes": int(ends.sum()), "steps": n, "mean_living_steps": round(float(living.mean()), 2),
                "success_rate": round(float(success.mean()), 4),
                "backward_share": round(float((d["action"] == BACKWARD).mean()), 4),
                "sees_seeker_share": round(float(d["S"].mean()), 4), "seen_share": round(float(d["H"].mean()), 4),
                "line_of_sight_breaks_per_100": round(100.0 * h_breaks / n, 3),
                "seeker_lost_per_100": round(100.0 * s_losses / n, 3),
                "distance_turns_per_100": round(100.0 * turns / n, 3),
                "distance_swings_per_100": round(100.0 * swung[SWING_M] / n, 3)},
    }


def write(out_dir, s, name):
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "states.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "state", "S", "H", "O", "steps", "frequency"])
        for i in range(8):
            w.writerow([name, STATE_NAMES[i], (i >> 2) & 1, (i >> 1) & 1, i & 1, int(s["counts"][i]),
                        round(float(s["freq"][i]), 5)])
    with open(os.path.join(out_dir, "transitions.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "from", "to", "count", "probability"])
        for a in range(8):
            for b in range(8):
                if a != b:
                    p = s["prob"][a, b]
                    w.writerow([name, STATE_NAMES[a], STATE_NAMES[b], int(s["tcounts"][a, b]),
                                "" if np.isnan(p) else round(float(p), 5)])
    with open(os.path.join(out_dir, "distance.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "step_bin_start", "mean_distance", "episodes_running"])
        for b, m, r in zip(s["bins"], s["mean_distance"], s["running"]):
            w.writerow([name, int(b), "" if np.isnan(m) else round(float(m), 4), int(r)])
    with open(os.path.join(out_dir, "swings.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "threshold_m", "swings_per_100"])
        for t, per_100 in s["swings"].items():
            w.writerow([name, t, per_100])
    with open(os.path.join(out_dir, "behaviour.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["run"] + list(s["row"]))
        w.writeheader()
        w.writerow(dict(run=name, **s["row"]))


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("steps")
    p.add_argument("out_dir")
    p.add_argument("--run", default="")
    args = p.parse_args(argv)
    s = summarise(read_steps(args.steps))
    write(args.out_dir, s, args.run)
    r = s["row"]
    print("behaviour: %s: %d episodes, %d steps, living %.1f, success %.0f %%, backward %.0f %%, S %.0f %%, H %.0f %%" % (
        args.run, r["episodes"], r["steps"], r["mean_living_steps"], 100 * r["success_rate"], 100 * r["backward_share"],
        100 * r["sees_seeker_share"], 100 * r["seen_share"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
