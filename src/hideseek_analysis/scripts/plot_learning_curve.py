#!/usr/bin/env python3
"""Plots a training run's learning curve from its training_log.csv.

usage: rosrun hideseek_analysis plot_learning_curve.py RUN_DIR/training_log.csv [OUTPUT.png] [TITLE]

A row whose episode window is empty (mean_length 0: no episode has ended since the run started,
or since a resume from a checkpoint written before checkpoints kept the window) is left as a gap
in the length and return curves rather than drawn as a fall to 0.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    path = sys.argv[1]
    output = sys.argv[2] if len(sys.argv) > 2 else path.rsplit(".", 1)[0] + ".png"
    with open(path) as f:
        rows = [r for r in csv.DictReader(f)]
    if not rows:
        sys.exit("%s: no updates logged yet" % path)
    steps = [int(r["steps"]) for r in rows]
    empty = [float(r["mean_length"]) <= 0.0 for r in rows]
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.6))
    for ax, key, label in zip(axes, ["mean_length", "mean_return", "entropy"],
                              ["episode length (steps, last 100)", "episode return (last 100)", "policy entropy"]):
        values = [float(r[key]) for r in rows]
        if key != "entropy":
            values = [float("nan") if e else v for v, e in zip(values, empty)]
        ax.plot(steps, values, lw=1.2)
        ax.set_xlabel("environment steps")
        ax.ticklabel_format(axis="x", style="sci", scilimits=(0, 0))  # 1e5 or 1e6 below the axis, never long labels that collide
        ax.set_title(label)
        ax.grid(alpha=0.3)
    fig.suptitle(sys.argv[3] if len(sys.argv) > 3 else path)
    fig.tight_layout()
    fig.savefig(output, dpi=110)
    print("wrote", output)


if __name__ == "__main__":
    main()
