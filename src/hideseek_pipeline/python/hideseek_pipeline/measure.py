"""Training throughput measured one way (make bench, and the throughput studies in
experiments/throughput through its command line). A run through train.launch is timed from its
log: samples/s between the end of update WARMUP and the end of a later update, and where the
hider's loop went (loop_profile.csv) over the same updates. The first updates load the network,
fault the buffers in and let the graph connect: they are warm-up, left out of every figure.

  python3 -m hideseek_pipeline.measure samples-per-s TRAINING_LOG [FIRST [LAST]]
  python3 -m hideseek_pipeline.measure loop-shares LOOP_PROFILE [FIRST [LAST]]
  python3 -m hideseek_pipeline.measure rollout-steps PPO_CONFIG
"""
import csv
import os
import sys

import yaml

WARMUP = int(os.environ.get("MEASURE_WARMUP", "2"))


class MeasureError(Exception):
    pass


def rollout_steps(ppo_config):
    """A PPO configuration's steps per arena per update."""
    with open(ppo_config) as f:
        steps = (yaml.safe_load(f) or {}).get("rollout_steps")
    if not steps:
        raise MeasureError("%s has no rollout_steps" % ppo_config)
    return int(steps)


def _rows(path):
    """The rows after the header, each update number first and numbers after; MeasureError naming
    the file where a row is malformed."""
    with open(path) as f:
        rows = list(csv.reader(f))[1:]
    try:
        return [[int(r[0])] + [float(x) if x != "" else float("nan") for x in r[1:6]] for r in rows]
    except (ValueError, IndexError) as e:
        raise MeasureError("%s: a malformed row (%s)" % (path, e))


def samples_per_s(log, first=None, last=0):
    """Samples/s from the end of update `first` (default: the warm-up's last) to the end of update
    `last` (0: the log's last), from the log's own step counts and wall times (columns 1-3)."""
    first = WARMUP if first is None else first
    start = end = None
    for r in _rows(log):
        update = r[0]
        if update == first:
            start = (r[1], r[2])
        if last == 0 or update <= last:
            end = (r[1], r[2])
    if start is None or end is None or end[1] <= start[1]:
        raise MeasureError("%s holds no updates after update %d" % (log, first))
    return (end[0] - start[0]) / (end[1] - start[1])


def loop_shares(profile, first=None, last=0):
    """The hider's loop over updates first + 1 to last of its loop_profile.csv: (update, inference,
    wait, other), each a share of the loop's time (columns: update, ?, wait, inference, update, other)."""
    first = WARMUP if first is None else first
    wait = inference = update = other = 0.0
    for r in _rows(profile):
        if r[0] > first and (last == 0 or r[0] <= last):
            wait, inference, update, other = wait + r[2], inference + r[3], update + r[4], other + r[5]
    total = wait + inference + update + other
    if total <= 0:
        raise MeasureError("%s holds no loop after update %d" % (profile, first))
    return tuple(x / total for x in (update, inference, wait, other))


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    commands = {"samples-per-s": lambda a: "%.0f" % samples_per_s(a[0], *map(int, a[1:])),
                "loop-shares": lambda a: " ".join("%.3f" % x for x in loop_shares(a[0], *map(int, a[1:]))),
                "rollout-steps": lambda a: rollout_steps(a[0])}
    if len(argv) < 2 or argv[0] not in commands:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        print(commands[argv[0]](argv[1:]))
    except (MeasureError, OSError, ValueError, IndexError) as e:
        print("measure: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
