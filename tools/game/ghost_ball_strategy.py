#!/usr/bin/env python3
"""An example strategy for pool-game: ghost-ball aiming (python/libpool/aim.py) at the easiest
straight pot of a legal ball, the cue ball in hand placed straight behind it; breaks at 8 m/s from
the head spot; three cushion: a fixed bank at the red. Reads one turn per line on standard input,
answers one line per turn (docs/commands.md "pool-game"):

    build/release/tools/pool-game 9ball --strategy 'python3 tools/game/ghost_ball_strategy.py'
"""

import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from libpool import aim  # noqa: E402  (pure Python: needs no libpool.so)

SOLIDS, STRIPES = set(range(1, 8)), set(range(9, 16))


def legal_targets(turn, on_table):
    rules, state = turn["rules"], turn["state"]
    objects = [b for b in on_table if b != 0]
    if rules == "9ball":
        return [min(objects)] if objects else []
    group = state.get("group", "open")
    if group == "open":
        return [b for b in objects if b != 8]
    mine = [b for b in objects if b in (SOLIDS if group == "solids" else STRIPES)]
    return mine or [8]


def placement(target, pocket, table, radius, balls):
    """The cue ball 0.3 m straight behind the target, on its line to the pocket, if free."""
    length, width = table
    p = aim.pocket_points(length, width)[pocket]
    dx, dy = target[0] - p[0], target[1] - p[1]
    n = math.hypot(dx, dy)
    for back in (0.3, 0.2, 0.45, 0.12):
        x, y = target[0] + (2 * radius + back) * dx / n, target[1] + (2 * radius + back) * dy / n
        inside = 2 * radius < x < length - 2 * radius and 2 * radius < y < width - 2 * radius
        if inside and all(math.hypot(x - bx, y - by) > 2.2 * radius for bx, by in balls):
            return [x, y]
    return None


def answer(turn):
    state, table = turn["state"], (turn["table"]["length"], turn["table"]["width"])
    radius = turn["ball_radius"]
    balls = {b["id"]: tuple(b["pos"]) for b in turn["balls"]}
    length, width = table
    if turn["rules"] == "three_cushion":
        cue = state["cue_ball"]
        red = [b for b in balls if b not in (cue, state["opponent_cue_ball"])][0]
        c, r = balls[cue], balls[red]
        return {"strike": {"speed": 4.0, "phi": math.degrees(math.atan2(r[1] - c[1], r[0] - c[0])) + 20.0}}
    if state.get("break"):
        return {"strike": {"speed": 8.0, "phi": 0.0}, "cue_pos": [length / 4, width / 2]}
    targets = {b: balls[b] for b in legal_targets(turn, balls) if b in balls}
    others = [p for b, p in balls.items() if b != 0 and b not in targets]
    out = {}
    cue = balls.get(0)
    if state.get("ball_in_hand"):
        # Place the cue ball straight behind the easiest target, for a straight pot.
        for b, t in targets.items():
            for pocket in aim.POCKETS:
                spot = placement(t, pocket, table, radius, [p for k, p in balls.items() if k != 0])
                if spot:
                    cue = tuple(spot)
                    out["cue_pos"] = spot
                    break
            if "cue_pos" in out:
                break
        if cue is None:
            cue = (length / 4, width / 2)
            out["cue_pos"] = list(cue)
    shot = aim.best_pot(cue, targets, others, table, radius)
    if shot is None:  # no straight pot: hit the first legal ball full, softly
        t = next(iter(targets.values()))
        out["strike"] = {"speed": 2.0, "phi": math.degrees(math.atan2(t[1] - cue[1], t[0] - cue[0]))}
        return out
    out["strike"] = {"speed": shot.speed, "phi": shot.phi, "b": -0.2 * radius}
    if turn["rules"] == "8ball":
        out["call"] = {"ball": shot.ball, "pocket": shot.pocket}
    return out


def main():
    for line in sys.stdin:
        if line.strip():
            print(json.dumps(answer(json.loads(line))), flush=True)


if __name__ == "__main__":
    main()
