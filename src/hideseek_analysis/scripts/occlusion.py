#!/usr/bin/env python3
"""The occluded share of a fixed map: of all pairs of free points (where an agent's centre may
stand), the share whose line of sight a box or wall blocks. Every obstacle is taller than the
cameras, so the test is in the plane.

usage: occlusion.py MAP.yaml [MAP.yaml ...] [--grid M] [--radius M]

Free points: the points of a square grid of step --grid (default 0.25 m) through the centre that lie at least
--radius (default 0.4 m, an agent's) inside the arena and outside every obstacle grown by it.
A pair is occluded when the segment between its points crosses an obstacle (the obstacle itself,
not grown). Prints one line per map: its name, the free points, the pairs and the occluded share.
"""
import argparse
import sys

import numpy as np
import yaml


def boxes(spec):
    """(centre, half size, yaw) of every obstacle of a fixed map file."""
    out = []
    for o in spec.get("obstacles") or []:
        out.append((np.array(o["center"], float), 0.5 * np.array(o["size"], float), float(o.get("yaw", 0.0))))
    return out


def to_box_frame(points, centre, yaw):
    c, s = np.cos(-yaw), np.sin(-yaw)
    d = points - centre
    return np.stack([c * d[..., 0] - s * d[..., 1], s * d[..., 0] + c * d[..., 1]], axis=-1)


def free_points(spec, grid, radius):
    h = float(spec["half_extent"]) - radius
    k = int(np.floor(h / grid + 1e-9))
    axis = grid * np.arange(-k, k + 1)  # symmetric about the centre, as the maps are
    pts = np.array([(x, y) for y in axis for x in axis])
    keep = np.ones(len(pts), bool)
    for centre, half, yaw in boxes(spec):
        local = np.abs(to_box_frame(pts, centre, yaw))
        # Outside the box grown by the radius (rounded corners: the distance to the box).
        gap = np.maximum(local - half, 0.0)
        keep &= np.hypot(gap[:, 0], gap[:, 1]) >= radius - 1e-9
    return pts[keep]


def crosses(a, b, centre, half, yaw):
    """Whether each segment a[i] -> b[i] meets the box (Liang-Barsky in the box's frame)."""
    p, q = to_box_frame(a, centre, yaw), to_box_frame(b, centre, yaw)
    d = q - p
    t0, t1 = np.zeros(len(p)), np.ones(len(p))
    hit = np.ones(len(p), bool)
    for k in (0, 1):
        for sign in (-1.0, 1.0):
            # the slab sign * x_k <= half_k
            num = half[k] - sign * p[:, k]
            den = sign * d[:, k]
            parallel = np.abs(den) < 1e-12
            hit &= ~(parallel & (num < 0))
            with np.errstate(divide="ignore", invalid="ignore"):
                t = np.where(parallel, 0.0, num / np.where(parallel, 1.0, den))
            entering = ~parallel & (den < 0)
            leaving = ~parallel & (den > 0)
            t0 = np.where(entering, np.maximum(t0, t), t0)
            t1 = np.where(leaving, np.minimum(t1, t), t1)
    return hit & (t0 <= t1)


def occluded_share(spec, grid=0.25, radius=0.4):
    pts = free_points(spec, grid, radius)
    i, j = np.triu_indices(len(pts), k=1)
    blocked = np.zeros(len(i), bool)
    for centre, half, yaw in boxes(spec):
        blocked |= crosses(pts[i], pts[j], centre, half, yaw)
    return len(pts), len(i), float(blocked.mean())


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("maps", nargs="+")
    p.add_argument("--grid", type=float, default=0.25)
    p.add_argument("--radius", type=float, default=0.4)
    args = p.parse_args(argv)
    for path in args.maps:
        with open(path) as f:
            spec = yaml.safe_load(f)
        if spec.get("type") != "fixed":
            raise SystemExit("occlusion: %s is not a fixed map (type: %s)" % (path, spec.get("type")))
        n, pairs, share = occluded_share(spec, args.grid, args.radius)
        print("%s: %d free points, %d pairs, occluded share %.3f" % (path, n, pairs, share))
    return 0


if __name__ == "__main__":
    sys.exit(main())
