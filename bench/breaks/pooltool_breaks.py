#!/usr/bin/env python3
"""The breaks of pool-bench-breaks in pooltool (https://github.com/ekiefl/pooltool), for comparing
their statistics with libpool's: N jittered 8-ball breaks on pooltool's default table, balls and
physics (its own defaults, whatever its version makes them), 15 balls 0.1 mm apart, the cue ball
on the head spot struck at the apex at SPEED m/s with 2 degrees of elevation and the aim jittered
uniformly within +-0.5 degree. Writes the libpool-breaks/1 JSON of pool-bench-breaks --json (one
model set, named after pooltool's version) for tools/pool-break-plot.

pooltool is not part of libpool and is not installed by tools/setup.sh; install it in a venv of
its own (pip install pooltool-billiards) and run this script with that venv's Python. Without
pooltool the script says so and exits with status 3.

Usage: pooltool_breaks.py [--breaks N] [--seed S] [--speed V] [-o FILE]
"""
import argparse
import json
import math
import random
import sys
import time


def jitter(seed, i):
    """pool-bench-breaks' aim jitter of break i, in [-1, 1) (splitmix64 of (seed, i))."""
    mask = (1 << 64) - 1
    z = (seed * 0x9E3779B97F4A7C15 + i * 0xBF58476D1CE4E5B9 + 0x94D049BB133111EB) & mask
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & mask
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & mask
    z ^= z >> 31
    return (z >> 11) * (1.0 / 9007199254740992.0) * 2.0 - 1.0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--breaks", type=int, default=200)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--speed", type=float, default=8.0)
    p.add_argument("-o", "--output", default=None, help="the libpool-breaks/1 JSON (default: none)")
    a = p.parse_args()
    if a.breaks < 1:
        p.error("--breaks: must be >= 1")
    try:
        import numpy as np
        import pooltool as pt
    except ImportError as e:
        print(f"pooltool_breaks.py: pooltool is not installed here ({e}); install it in a venv of its "
              "own (pip install pooltool-billiards) and run this script with that venv's python",
              file=sys.stderr)
        return 3

    table = pt.Table.default()
    moved, cushion, pocketed, cue_distance, scratch, events, displacement, seconds = ([] for _ in range(8))
    for i in range(a.breaks):
        random.seed(a.seed * 1000003 + i)
        np.random.seed((a.seed * 1000003 + i) % (2 ** 32))
        radius = pt.BallParams.default().R
        # pooltool spaces the balls (1 + f) R apart and wiggles them within f R: a mean gap of
        # about 2 f R, 0.1 mm here
        balls = pt.get_rack(pt.GameType.EIGHTBALL, table, spacing_factor=1e-4 / (2.0 * radius))
        head = np.array([0.5 * table.w, 0.25 * table.l, radius])
        balls["cue"].state.rvw[0] = head
        start = {k: np.array(b.state.rvw[0][:2]) for k, b in balls.items()}
        apex = min((b for k, b in balls.items() if k != "cue"), key=lambda b: abs(b.state.rvw[0][1] - 0.75 * table.l)
                   + abs(b.state.rvw[0][0] - 0.5 * table.w))
        d = apex.state.rvw[0][:2] - head[:2]
        phi = math.degrees(math.atan2(d[1], d[0])) + 0.5 * jitter(a.seed, i)
        system = pt.System(cue=pt.Cue(cue_ball_id="cue"), table=table, balls=balls)
        system.cue.set_state(V0=a.speed, phi=phi, theta=2.0, a=0.0, b=0.0)
        t0 = time.perf_counter()
        pt.simulate(system, inplace=True)
        seconds.append(time.perf_counter() - t0)
        events.append(len(system.events))
        hit = set()
        for ev in system.events:
            # the rails (libpool's cushions); a pocket's jaws (circular segments) are left out
            if ev.event_type == pt.EventType.BALL_LINEAR_CUSHION:
                hit.update(ident for ident in ev.ids if ident in balls)
        m = c = k = 0
        for ident, b in system.balls.items():
            dist = float(np.linalg.norm(np.array(b.state.rvw[0][:2]) - start[ident]))
            down = b.state.s == pt.constants.pocketed
            if ident == "cue":
                cue_distance.append(dist)
                scratch.append(1.0 if down else 0.0)
                continue
            displacement.append(dist)
            m += dist > 0.3
            c += ident in hit
            k += down
        moved.append(m)
        cushion.append(c)
        pocketed.append(k)
    name = f"pooltool {pt.__version__}"
    med = float(np.median(displacement))
    print(f"{name}: {a.breaks} breaks at {a.speed:g} m/s: median displacement {med:.3f} m, moved>0.3 "
          f"{np.mean(moved):.2f}, cushion {np.mean(cushion):.2f}, pocketed {np.mean(pocketed):.2f} "
          f"({100 * np.mean(np.array(pocketed) > 0):.0f} % of breaks), cue ball {np.median(cue_distance):.3f} m, "
          f"scratch {100 * np.mean(scratch):.1f} %, {np.median(events):.0f} events, "
          f"{1e3 * np.median(seconds):.1f} ms a break (median)")
    if a.output:
        doc = {"format": "libpool-breaks/1", "machine": "", "breaks": a.breaks, "seed": a.seed,
               "speed": a.speed,
               "sets": [{"name": name, "models": {"engine": name}, "moved": moved, "cushion": cushion,
                         "pocketed": pocketed, "cue_distance": cue_distance, "scratch": scratch,
                         "events": events, "displacement": displacement}]}
        with open(a.output, "w") as f:
            json.dump(doc, f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
