#!/usr/bin/python3
"""The scripted seeker's stalls in play_episodes' step CSVs (docs/calibration.md, "The scripted
seeker's stalls").

A stall: over 200 consecutive steps the seeker moves less than 5 cm while it never sees the hider.
Only an episode with 200 consecutive steps unseen can show one (its "chances"). For each stall it
prints where it starts, how far the seeker stands from the nearest obstacle footprint or the
arena's wall (from the CSV's _layouts.yaml files), and how much it turns per step meanwhile.

usage: stalls.py STEPS.csv [STEPS.csv ...]   (each with STEPS_layouts.yaml beside it; NAME_a.csv and
NAME_b.csv, a play's two halves, are counted together as NAME)
"""
import collections
import csv
import math
import os
import re
import sys

import yaml

WINDOW, STILL = 200, 0.05


def footprint_distance(box, p):
    (cx, cy), (sx, sy), yaw = box["center"], box["size"], box.get("yaw", 0.0)
    dx, dy = p[0] - cx, p[1] - cy
    c, s = math.cos(-yaw), math.sin(-yaw)
    lx, ly = c * dx - s * dy, s * dx + c * dy
    return math.hypot(max(abs(lx) - sx / 2, 0), max(abs(ly) - sy / 2, 0))


def turned(a, b):
    d = float(b["seeker_yaw"]) - float(a["seeker_yaw"])
    return abs(math.atan2(math.sin(d), math.cos(d)))


def episodes(path):
    rows = collections.defaultdict(list)
    for r in csv.DictReader(open(path)):
        rows[int(r["seed"])].append(r)
    layouts = {e["seed"]: e for e in yaml.safe_load(open(os.path.splitext(path)[0] + "_layouts.yaml"))["episodes"]}
    return rows, layouts


def grouped(paths):
    """NAME_a.csv and NAME_b.csv as one play NAME: its episodes and layouts, by seed."""
    groups = collections.OrderedDict()
    for path in paths:
        name = re.sub(r"_[ab]$", "", os.path.splitext(os.path.basename(path))[0])
        rows, layouts = episodes(path)
        g = groups.setdefault(name, ({}, {}))
        g[0].update(rows)
        g[1].update(layouts)
    return groups


def main(paths):
    for name, (rows, layouts) in grouped(paths).items():
        chances = survived = 0
        stalls = []
        for seed, rs in sorted(rows.items()):
            survived += rs[-1]["outcome"] == "survived"
            unseen = longest = 0
            for r in rs:
                unseen = unseen + 1 if r["H"] == "0" else 0
                longest = max(longest, unseen)
            chances += longest > WINDOW
            for i in range(len(rs) - WINDOW):
                w = rs[i:i + WINDOW + 1]
                xs, ys = [float(x["seeker_x"]) for x in w], [float(x["seeker_y"]) for x in w]
                if any(x["H"] == "1" for x in w) or max(xs) - min(xs) >= STILL or max(ys) - min(ys) >= STILL:
                    continue
                p, e = (sum(xs) / len(xs), sum(ys) / len(ys)), layouts[seed]
                near = min([footprint_distance(b, p) for b in e["obstacles"]] +
                           [e["half_extent"] - max(abs(p[0]), abs(p[1]))])
                stalls.append("seed %d: from step %s at (%.2f, %.2f), %.2f m from the nearest obstacle, turning %.3f "
                              "rad a step, %s" % (seed, rs[i]["step"], p[0], p[1], near,
                                                  sum(turned(a, b) for a, b in zip(w, w[1:])) / WINDOW,
                                                  rs[-1]["outcome"]))
                break
        print("%s: %d episodes, %.2f living steps, %d survived, %d could show a stall, %d stalled" % (
            name, len(rows), sum(len(rs) for rs in rows.values()) / len(rows), survived, chances, len(stalls)))
        for s in stalls:
            print("  " + s)


if __name__ == "__main__":
    main(sys.argv[1:])
