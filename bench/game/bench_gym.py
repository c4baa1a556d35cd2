#!/usr/bin/env python3
"""Environment steps per second of libpool.gym (docs/measurements.md "Games"): for each id, a
single environment (gym.make, with Gymnasium's checking wrappers) and the vectorised one
(PoolVectorEnv, 8 tables) on 1 and on every worker thread, random actions drawn beforehand,
fastfiz noise. Each
figure: median and minimum over RUNS runs of STEPS steps; the machine is printed first.

    PYTHONPATH=python .venv/bin/python bench/game/bench_gym.py [--runs 5] [--steps 2000]
"""

import argparse
import os
import platform
import statistics
import time

import gymnasium as gym
import numpy as np

import libpool.gym  # noqa: F401  (registers the ids)


def steps_per_second(make, steps):
    """Steps per second with actions drawn beforehand (Box.sample costs as much as a short step)."""
    env = make()
    env.reset(seed=0)
    actions = np.random.default_rng(0).uniform(-1, 1, (steps,) + env.action_space.shape).astype(np.float32)
    done = k = 0
    start = time.perf_counter()
    while done < steps:
        _, _, term, trunc, _ = env.step(actions[k % steps])
        k += 1
        if hasattr(term, "__len__"):
            done += len(term)
        else:
            done += 1
            if term or trunc:
                env.reset()
    rate = done / (time.perf_counter() - start)
    env.close()
    return rate


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--steps", type=int, default=2000)
    p.add_argument("--envs", type=int, default=8)
    a = p.parse_args()
    cpus = os.cpu_count() or 1
    print(f"bench_gym: {cpu_model()}, {cpus} CPUs, Python {platform.python_version()}, "
          f"gymnasium {gym.__version__}; {a.runs} runs of {a.steps} steps, fastfiz noise, "
          f"load average {os.getloadavg()[0]:.2f}")
    for env_id in ("libpool/PotBall-v0", "libpool/NineBall-v0", "libpool/ThreeCushion-v0"):
        rows = [("single", lambda: gym.make(env_id, noise="fastfiz"))]
        for workers in sorted({1, cpus}):
            rows.append((f"vector {a.envs} tables, {workers} worker(s)",
                         lambda w=workers: gym.make_vec(env_id, num_envs=a.envs, vectorization_mode="vector_entry_point",
                                                        workers=w, noise="fastfiz")))
        for name, make in rows:
            rates = [steps_per_second(make, a.steps) for _ in range(a.runs)]
            print(f"{env_id:26s} {name:30s} median {statistics.median(rates):8.0f} steps/s  min {min(rates):8.0f}")


if __name__ == "__main__":
    main()
