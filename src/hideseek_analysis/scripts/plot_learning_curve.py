#!/usr/bin/env python3
"""Plots a training run's learning curve from its training_log.csv, or several runs' on one plot.

usage: rosrun hideseek_analysis plot_learning_curve.py RUN_DIR/training_log.csv [OUTPUT.png] [TITLE]
       rosrun hideseek_analysis plot_learning_curve.py --run LABEL LOG.csv --run LABEL LOG.csv ... \\
           --output OUTPUT.png [--title TITLE] [--mark STEPS ...]

--mark draws a dashed vertical line at that step in every panel (self-play: where a generation ends
and both learners meet new opponents).

A row whose episode window is empty (mean_length 0: no episode has ended since the run started,
or since a resume from a checkpoint written before checkpoints kept the window) is left as a gap
in the length and return curves rather than drawn as a fall to 0.
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PANELS = [("mean_length", "episode length (steps, last 100)"), ("mean_return", "episode return (last 100)"),
          ("entropy", "policy entropy")]


def read_log(path):
    """The log's rows as (steps, {column: values}); exits with a message naming the file if unusable."""
    try:
        with open(path) as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        sys.exit("plot_learning_curve: cannot read %s: %s" % (path, e.strerror))
    if not rows:
        sys.exit("%s: no updates logged yet" % path)
    missing = [k for k in ["steps"] + [k for k, _ in PANELS] if k not in rows[0]]
    if missing:
        sys.exit("%s: not a training log (no column %s)" % (path, ", ".join(missing)))
    steps = [int(r["steps"]) for r in rows]
    empty = [float(r["mean_length"]) <= 0.0 for r in rows]
    columns = {}
    for key, _ in PANELS:
        values = [float(r[key]) for r in rows]
        if key != "entropy":
            values = [float("nan") if e else v for v, e in zip(values, empty)]
        columns[key] = values
    return steps, columns


def plot(runs, output, title, marks=()):
    """runs: [(label or None, path)]; one line per run in each panel, a legend when labelled; a
    dashed vertical line at each step of `marks`."""
    fig, axes = plt.subplots(1, len(PANELS), figsize=(13, 3.6))
    for label, path in runs:
        steps, columns = read_log(path)
        for ax, (key, _) in zip(axes, PANELS):
            ax.plot(steps, columns[key], lw=1.2, label=label)
    for ax, (_, name) in zip(axes, PANELS):
        for step in marks:
            ax.axvline(step, color="0.4", lw=0.8, ls="--")
        ax.set_xlabel("environment steps")
        ax.ticklabel_format(axis="x", style="sci", scilimits=(0, 0))  # 1e5 or 1e6 below the axis, never long labels that collide
        ax.set_title(name)
        ax.grid(alpha=0.3)
    if any(label for label, _ in runs):
        axes[0].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(output, dpi=110)
    plt.close(fig)
    print("wrote", output)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if argv else 1)
    if any(a.startswith("--") for a in argv):
        parser = argparse.ArgumentParser(description="Learning curves of several runs on one plot.")
        parser.add_argument("--run", nargs=2, action="append", required=True, metavar=("LABEL", "LOG"),
                            help="a run's label and its training_log.csv; repeat for each run")
        parser.add_argument("--output", required=True, help="the PNG to write")
        parser.add_argument("--title", default="", help="the figure's title")
        parser.add_argument("--mark", type=int, action="append", default=[], metavar="STEPS",
                            help="a dashed vertical line at this step; repeat for each")
        args = parser.parse_args(argv)
        plot([(label, path) for label, path in args.run], args.output, args.title, args.mark)
        return
    path = argv[0]
    output = argv[1] if len(argv) > 1 else path.rsplit(".", 1)[0] + ".png"
    plot([(None, path)], output, argv[2] if len(argv) > 2 else path)


if __name__ == "__main__":
    main()
