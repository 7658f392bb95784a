#!/usr/bin/env python3
"""Draws a self-play's cross-play table (hideseek_pipeline selfplay --crossplay): the seeker's
capture rate for every hider generation (rows) against every seeker generation (columns), with
the hider's mean living steps in each cell.

usage: rosrun hideseek_analysis plot_crossplay.py CROSSPLAY.csv OUTPUT.png [TITLE]
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    if len(argv) not in (3, 4):
        sys.exit(__doc__)
    with open(argv[1]) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("plot_crossplay: %s holds no pair" % argv[1])
    hiders = list(dict.fromkeys(r["hider"] for r in rows))
    seekers = list(dict.fromkeys(r["seeker"] for r in rows))
    cell = {(r["hider"], r["seeker"]): r for r in rows}
    rate = [[100 * float(cell[h, s]["capture_rate"]) for s in seekers] for h in hiders]
    fig, ax = plt.subplots(figsize=(1.3 * len(seekers) + 2.5, 0.6 * len(hiders) + 2))
    image = ax.imshow(rate, cmap="viridis", vmin=0, vmax=100, aspect="auto")
    for i, h in enumerate(hiders):
        for j, s in enumerate(seekers):
            ax.text(j, i, "%.0f %%\n%.0f" % (rate[i][j], float(cell[h, s]["mean_living_steps"])), ha="center",
                    va="center", fontsize=8, color="white" if rate[i][j] < 60 else "black")
    ax.set_xticks(range(len(seekers)), seekers, rotation=30, ha="right")
    ax.set_yticks(range(len(hiders)), hiders)
    ax.set_xlabel("seeker")
    ax.set_ylabel("hider")
    fig.colorbar(image, ax=ax, label="capture rate (%)")
    ax.set_title((argv[3] if len(argv) == 4 else "cross-play") + "\neach cell: capture rate, mean living steps",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(argv[2], dpi=120)


if __name__ == "__main__":
    main(sys.argv)
