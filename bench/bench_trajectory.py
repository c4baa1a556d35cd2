#!/usr/bin/env python3
"""Sim.trajectory against the C loop it replaces: every ball of a frozen 8-ball break at 8 m/s at
10,000 evenly spaced times. Prints the median and minimum of the runs of Sim.trajectory and of a
Python loop of Sim.state_at, then runs pool-bench-trajectory (the C loop of pool_sim_state_at
and one pool_sim_states_at call) for the reference.

    PYTHONPATH=python .venv/bin/python bench/bench_trajectory.py [--times N] [--runs R]
        [--c-bench build/release/bench/pool-bench-trajectory]
"""
import argparse
import os
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
import numpy as np  # noqa: E402

import libpool  # noqa: E402


def timed(fn, runs):
    out = []
    for _ in range(runs):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return statistics.median(out), min(out)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--times", type=int, default=10000)
    p.add_argument("--runs", type=int, default=21)
    p.add_argument("--c-bench", default=os.path.join(ROOT, "build", "release", "bench",
                                                      "pool-bench-trajectory"))
    args = p.parse_args()
    with libpool.Sim() as sim:
        sim.rack("8ball", gap=0.0)
        sim.break_strike(8.0)
        sim.run()
        times = np.linspace(0.0, sim.end_time, args.times)
        med, low = timed(lambda: sim.trajectory(times), args.runs)
        print(f"Sim.trajectory ({args.times} times, {sim.ball_count} balls): "
              f"median {med * 1e3:.3f} ms, min {low * 1e3:.3f} ms")
        py_runs = max(3, args.runs // 7)
        med, low = timed(lambda: [sim.state_at(t) for t in times.tolist()], py_runs)
        print(f"Python loop of Sim.state_at: median {med * 1e3:.3f} ms, min {low * 1e3:.3f} ms "
              f"({py_runs} runs)")
    if os.path.exists(args.c_bench):
        sys.stdout.flush()
        subprocess.run([args.c_bench, "--times", str(args.times), "--runs", str(args.runs)],
                       check=True)
    else:
        print(f"(no {args.c_bench}: build the project for the C reference)")


if __name__ == "__main__":
    main()
