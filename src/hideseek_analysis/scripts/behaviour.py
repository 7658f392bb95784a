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
  moving average), a measure of oscillation.
"""
import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hideseek_analysis import STATE_NAMES, state_frequencies, state_index, transitions  # noqa: E402

BACKWARD = 2  # hideseek_game::Action::kBackward
BIN = 10
MAX_STEPS = 1000


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
        "row": {"episodes": int(ends.sum()), "steps": n, "mean_living_steps": round(float(living.mean()), 2),
                "success_rate": round(float(success.mean()), 4),
                "backward_share": round(float((d["action"] == BACKWARD).mean()), 4),
                "sees_seeker_share": round(float(d["S"].mean()), 4), "seen_share": round(float(d["H"].mean()), 4),
                "line_of_sight_breaks_per_100": round(100.0 * h_breaks / n, 3),
                "seeker_lost_per_100": round(100.0 * s_losses / n, 3),
                "distance_turns_per_100": round(100.0 * turns / n, 3)},
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
