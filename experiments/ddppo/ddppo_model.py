#!/usr/bin/env python3
"""The speed-up to expect from training across N machines (docs/distributed.md), modelled from
what this machine measures: one rank's samples per second through the graph (make bench's
train_ros_samples_per_s), the gradient's bytes (ddppo_gradient_bytes) and PPO's all-reduces per
update (epochs x minibatches, config/ppo.yaml).

Each rank collects and trains on its own rollout of ARENAS x rollout_steps samples per update, in
the time T1 one machine takes, then waits for the update's all-reduces. Gloo's ring all-reduce
sends and receives 2 (N - 1) / N of the gradient per rank, and pays 2 (N - 1) latencies:
    t_allreduce(N) = 2 (N - 1) / N * bytes / bandwidth + 2 (N - 1) * latency
    speed-up(N)    = N * T1 / (T1 + allreduces_per_update * t_allreduce(N))
No overlap of communication with computation is assumed (the trainer overlaps none), and the
machines are assumed alike.

usage: ddppo_model.py SAMPLES_PER_S GRADIENT_BYTES [--ppo config/ppo.yaml] [--arenas 16]
                      [--latency-us 50] [--machines 1 2 4 8 16]
"""
import argparse
import os

import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def allreduce_s(n, size, bandwidth_bytes_per_s, latency_s):
    if n == 1:
        return 0.0
    return 2.0 * (n - 1) / n * size / bandwidth_bytes_per_s + 2.0 * (n - 1) * latency_s


def speedup(n, t1, per_update, size, bandwidth, latency):
    return n * t1 / (t1 + per_update * allreduce_s(n, size, bandwidth, latency))


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("samples_per_s", type=float, help="one rank's training samples/s through the graph")
    p.add_argument("gradient_bytes", type=float, help="bytes of one gradient all-reduce")
    p.add_argument("--ppo", default=os.path.join(ROOT, "config", "ppo.yaml"))
    p.add_argument("--arenas", type=int, default=16)
    p.add_argument("--latency-us", type=float, default=50.0, help="one message's latency")
    p.add_argument("--machines", type=int, nargs="+", default=[1, 2, 4, 8, 16])
    a = p.parse_args(argv)
    with open(a.ppo) as f:
        ppo = yaml.safe_load(f)
    per_update = int(ppo["epochs"]) * int(ppo["minibatches"])
    samples = a.arenas * int(ppo["rollout_steps"])
    t1 = samples / a.samples_per_s
    latency = a.latency_us * 1e-6
    print("One rank: %d samples per update in %.2f s (%.0f samples/s); %d all-reduces of %.2f MB per update."
          % (samples, t1, a.samples_per_s, per_update, a.gradient_bytes / 1e6))
    print()
    print("| machines | 1 Gbit/s: all-reduce time per update | speed-up | 10 Gbit/s: all-reduce time per update | speed-up |")
    print("| ---: | ---: | ---: | ---: | ---: |")
    for n in a.machines:
        row = ["%d" % n]
        for gbit in (1, 10):
            bw = gbit * 1e9 / 8
            row.append("%.2f s" % (per_update * allreduce_s(n, a.gradient_bytes, bw, latency)))
            row.append("%.2fx" % speedup(n, t1, per_update, a.gradient_bytes, bw, latency))
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
