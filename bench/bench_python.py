#!/usr/bin/env python3
"""Time whole shots through the Python binding (python/libpool, ctypes) to show its overhead
over the C library (compare with pool-bench-shot, which runs the same kind of scenes in C).

    PYTHONPATH=python .venv/bin/python bench/bench_python.py [--runs N] [--seed S]

Per scene it prints the median and minimum wall time per shot of three ways to use a reused Sim:
  run      reset, add the balls, strike, run, read the pocketed ids (the candidate-shot loop)
  +events  the same plus the whole event list as Python objects (sim.events)
and, for the breaks, the C library's own time from pool-bench-shot is the reference.
"""

import argparse
import math
import os
import platform
import random
import statistics
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import libpool  # noqa: E402


def machine():
    model = platform.processor() or "unknown cpu"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return (f"machine: {model}, {os.cpu_count()} cores online, Python {platform.python_version()}"
            f", libpool {libpool.library_path()}")


def shoot(sim, shot, with_events):
    balls, strike = shot
    sim.reset()
    for b in balls:
        sim.add_ball(*b)
    sim.strike(0, *strike)
    sim.run()
    out = sim.pocketed
    if with_events:
        out = sim.events
    return out


def measure(sim, name, shots, runs, with_events, quiet=False):
    times = []
    events = 0
    for i in range(runs):
        shot = shots[i % len(shots)]
        t0 = time.perf_counter()
        shoot(sim, shot, with_events)
        times.append(time.perf_counter() - t0)
        events += sim.event_count
    if quiet:
        return
    label = f"{name} [{'+events' if with_events else 'run'}]"
    print(f"{label:40s} runs {runs:6d}  median {statistics.median(times) * 1e6:9.1f} us  "
          f"min {min(times) * 1e6:9.1f} us  events/shot {events / runs:6.1f}", flush=True)


def break_shot(gap, phi=0.0):
    balls = [(b.id, b.pos) for b in libpool.rack("8ball", gap=gap)]
    return balls, (8.0, phi)


def post_break_shots(sim, rng, tables=50, per_table=20):
    """Breaks with slightly varied aim, then random cue-ball strikes among the balls left (the
    cue ball re-spotted on the head spot if pocketed), as pool-bench-shot builds them."""
    t, R = sim.table, sim.params.ball_radius
    shots = []
    for _ in range(tables):
        balls, _ = break_shot(1e-4)
        shoot(sim, (balls, (8.0, (rng.random() - 0.5) * 0.01 * 180 / math.pi)), False)
        left = []
        for b in sim.balls:
            if b.motion == "pocketed" and b.id != 0:
                continue
            pos = (0.25 * t.length, 0.5 * t.width) if b.motion == "pocketed" else b.pos[:2]
            if all(math.hypot(pos[0] - p[0], pos[1] - p[1]) >= 2 * R for _, p in left):
                left.append((b.id, pos))
        if not any(i == 0 for i, _ in left):
            continue
        for _ in range(per_table):
            r, a = 0.7 * R * math.sqrt(rng.random()), rng.random() * 2 * math.pi
            theta = 0.0 if rng.random() < 0.7 else rng.random() * 0.5 * 180 / math.pi
            shots.append((left, (0.5 + 5.5 * rng.random(), rng.random() * 360.0, theta,
                                 r * math.cos(a), r * math.sin(a))))
    return shots


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=500, help="shots per break scene (post-break: 5x)")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    if args.runs < 1:
        ap.error("--runs: must be >= 1")
    print(machine())
    rng = random.Random(args.seed)
    with libpool.Sim() as sim:
        post = post_break_shots(sim, rng)
        scenes = [("break-frozen (8 m/s)", [break_shot(0.0)], args.runs),
                  ("break-gap-0.1mm (8 m/s)", [break_shot(1e-4)], args.runs),
                  ("post-break random shots", post, 5 * args.runs)]
        for name, shots, runs in scenes:
            for with_events in (False, True):
                measure(sim, name, shots, min(runs, 50), with_events, quiet=True)  # warm-up
                measure(sim, name, shots, runs, with_events)


if __name__ == "__main__":
    main()
