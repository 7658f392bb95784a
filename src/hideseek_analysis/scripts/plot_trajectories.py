#!/usr/bin/env python3
"""Top-down trajectories and distance over time of played episodes (play_episodes' CSV).

usage: plot_trajectories.py EPISODES.csv MAP.yaml OUTPUT.png TITLE
One column per episode: above, the arena from above with its obstacles, the hider's path (blue)
and the seeker's (red) from their start (circle) to the end (cross: capture); below, the distance
between the agents against the step, shaded where the seeker sees the hider.
Obstacles come from EPISODES_layouts.yaml, which play_episodes writes beside its CSV with each
episode's own layout (stochastic maps draw new boxes every episode), or, for a CSV without one,
from MAP.yaml. Beside the figure, OUTPUT.md gets the same episodes in numbers: outcome, steps, the first step
at which the seeker sees the hider, how often each agent sees the other, the distance, and how
often the hider took each action.
"""
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Polygon  # noqa: E402
import yaml  # noqa: E402


def box_corners(center, size, yaw):
    c, s = math.cos(yaw), math.sin(yaw)
    hx, hy = size[0] / 2.0, size[1] / 2.0
    return [(center[0] + c * x - s * y, center[1] + s * x + c * y) for x, y in ((-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy))]


ACTIONS = ["stay", "forward", "backward", "left", "right"]


def episode_table(episodes, title):
    """Markdown: one row per episode, with what the figure shows in numbers."""
    lines = ["# " + title, "",
             "S: the hider sees the seeker; H: the seeker sees the hider; distances in m, the last"
             " column over the steps from 100 on (the chase once under way). Actions in % of the"
             " episode's steps.", "",
             "| seed | outcome | steps | first step with H | H % | S % | distance mean / min | "
             "from step 100: mean / min | " + " | ".join(ACTIONS) + " |",
             "| --- " * (8 + len(ACTIONS)) + "|"]
    for seed in sorted(episodes):
        rows = episodes[seed]
        n = len(rows)
        dist = [float(r["distance"]) for r in rows]
        late = dist[100:]
        first_h = next((int(r["step"]) for r in rows if r["H"] == "1"), None)
        counts = [sum(1 for r in rows if int(r["hider_action"]) == a) for a in range(len(ACTIONS))]
        lines.append("| %d | %s | %d | %s | %.1f | %.1f | %.2f / %.2f | %s | %s |" % (
            seed, rows[-1]["outcome"] or "running", n, "-" if first_h is None else first_h,
            100.0 * sum(r["H"] == "1" for r in rows) / n, 100.0 * sum(r["S"] == "1" for r in rows) / n,
            sum(dist) / n, min(dist), "%.2f / %.2f" % (sum(late) / len(late), min(late)) if late else "-",
            " | ".join("%.1f" % (100.0 * c / n) for c in counts)))
    return "\n".join(lines) + "\n"


def read_episodes(rows_file, map_file):
    """(seed -> its rows, the map's spec, seed -> its drawn layout where the map draws one per episode)."""
    episodes = defaultdict(list)
    with open(rows_file) as f:
        for r in csv.DictReader(f):
            episodes[int(r["seed"])].append(r)
    with open(map_file) as f:
        spec = yaml.safe_load(f)
    layouts = {}
    layouts_file = (rows_file[:-4] if rows_file.endswith(".csv") else rows_file) + "_layouts.yaml"
    if os.path.isfile(layouts_file):
        with open(layouts_file) as f:
            layouts = {int(e["seed"]): e for e in yaml.safe_load(f)["episodes"]}
    elif spec.get("type", "fixed") != "fixed":
        print("plot_trajectories: %s draws a new layout every episode and %s is missing: the obstacles drawn "
              "are the map's fixed ones only" % (map_file, layouts_file), file=sys.stderr)
    return episodes, spec, layouts


def draw_paths(ax, seed, rows, layout, first):
    """The arena top-down: obstacles, walls, both agents' paths; returns the arena's half extent."""
    half = float(layout.get("half_extent", 7.0))
    for ob in layout.get("obstacles") or []:
        ax.add_patch(Polygon(box_corners(ob["center"], ob["size"], float(ob.get("yaw", 0.0))), closed=True,
                             facecolor=(0.80, 0.62, 0.30), edgecolor="none"))
    ax.plot([-half, half, half, -half, -half], [-half, -half, half, half, -half], color="0.3", lw=2)
    for who, color in (("hider", "tab:blue"), ("seeker", "tab:red")):
        xs = [float(r[who + "_x"]) for r in rows]
        ys = [float(r[who + "_y"]) for r in rows]
        ax.plot(xs, ys, color=color, lw=1.0, label=who)
        ax.plot(xs[0], ys[0], "o", color=color, ms=6)
    outcome = rows[-1]["outcome"] or "running"
    if outcome == "captured":
        ax.plot(float(rows[-1]["hider_x"]), float(rows[-1]["hider_y"]), "kx", ms=9, mew=2)
    ax.set_xlim(-half, half)
    ax.set_ylim(-half, half)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_title("seed %d: %s after %d steps" % (seed, outcome, len(rows)), fontsize=9)
    if first:
        ax.legend(loc="lower left", fontsize=7)
    return half


def draw_distance(ax, rows, half, first):
    """The distance between the agents over the episode, shaded where the seeker sees the hider."""
    steps = [int(r["step"]) for r in rows]
    ax.plot(steps, [float(r["distance"]) for r in rows], color="k", lw=0.8)
    seen = [r["H"] == "1" for r in rows]
    ax.fill_between(steps, 0, 1, where=seen, color="tab:red", alpha=0.2, transform=ax.get_xaxis_transform(),
                    label="seeker sees hider")
    ax.set_xlabel("step")
    ax.set_ylim(0, 2 * half * 1.05)
    if first:
        ax.set_ylabel("distance (m)")
        ax.legend(loc="upper right", fontsize=7)


def main(rows_file, map_file, out, title):
    episodes, spec, layouts = read_episodes(rows_file, map_file)
    seeds = sorted(episodes)
    fig, axes = plt.subplots(2, len(seeds), figsize=(3.2 * len(seeds), 6.2), squeeze=False,
                             gridspec_kw={"height_ratios": [3, 1.4]})
    for col, seed in enumerate(seeds):
        half = draw_paths(axes[0][col], seed, episodes[seed], layouts.get(seed, spec), col == 0)
        draw_distance(axes[1][col], episodes[seed], half, col == 0)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=80)
    table = out.rsplit(".", 1)[0] + ".md"
    with open(table, "w") as f:
        f.write(episode_table(episodes, title))
    print("wrote", out, "and", table)


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(*sys.argv[1:])
