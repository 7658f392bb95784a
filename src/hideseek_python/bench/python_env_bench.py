#!/usr/bin/env python3
"""make bench's python_env_steps_per_s: hideseek.make_vec(VARIANT, NUM_ENVS) stepped from Python with
random hider actions (the scripted seeker plans as in the game, unlike world_core_bench's random
seeker), observations copied into numpy, for SECONDS after a warm-up.
usage: python_env_bench.py [num_envs=16] [seconds=10] [variant=basic]"""
import sys
import time

import numpy as np

import hideseek


def main():
    num_envs = int(sys.argv[1]) if len(sys.argv) > 1 else 16
    seconds = float(sys.argv[2]) if len(sys.argv) > 2 else 10.0
    variant = sys.argv[3] if len(sys.argv) > 3 else "basic"
    envs = hideseek.make_vec(variant, num_envs=num_envs, seed=0, game="v2")  # v2, as every bench line (comparable over time)
    envs.reset(seed=0)
    rng = np.random.default_rng(1)

    def run(budget):
        steps, start = 0, time.perf_counter()
        while time.perf_counter() - start < budget:
            envs.step(rng.integers(0, 5, num_envs))
            steps += num_envs
        return steps / (time.perf_counter() - start)

    run(0.5)  # llvmpipe compiles its shaders on first use
    print("python_env_steps_per_s %.0f" % run(seconds))


if __name__ == "__main__":
    main()
