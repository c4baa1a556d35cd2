"""Ghost-ball aiming: the straight-line baseline a pool player learns first, with no physics beyond
the geometry of two touching balls (pure Python, no libpool needed).

To pot ball T in pocket P, the cue ball must arrive where it touches T on the line P-T extended:
the ghost ball G = T - 2R (P - T)/|P - T|. Aim the cue at G. Throw, squirt, cushions and
everything else libpool simulates are ignored, which is what makes it a baseline.

    from libpool import aim
    shot = aim.best_pot((0.6, 0.6), {3: (1.9, 0.9)}, others, table, 0.028575)
    shot.phi, shot.speed, shot.ball, shot.pocket

Angles in degrees as everywhere in the Python API; lengths in metres.
"""

import math
from dataclasses import dataclass
from typing import Dict, Iterable, Optional, Sequence, Tuple

__all__ = ["Pot", "pocket_points", "ghost_ball", "path_clear", "best_pot", "POCKETS"]

POCKETS = ("sw", "se", "nw", "ne", "s", "n")

# A cut thinner than this rarely pots a ball and throws its direction far off: not tried.
MAX_CUT_DEG = 75.0


@dataclass
class Pot:
    """A straight pot: ball into pocket, the cue aimed at phi (degrees) at speed (m/s)."""
    ball: int
    pocket: str
    phi: float
    speed: float
    cut: float          # degrees between the cue ball's path and the object ball's
    distance: float     # m, cue ball to ghost ball plus object ball to pocket
    ghost: Tuple[float, float]


def pocket_points(length, width):
    """Aiming point of each pocket (the table's corners and the middle of the long rails)."""
    return {"sw": (0.0, 0.0), "se": (length, 0.0), "nw": (0.0, width), "ne": (length, width),
            "s": (length / 2, 0.0), "n": (length / 2, width)}


def ghost_ball(target, pocket, radius):
    """Where the cue ball's centre must be when it meets `target` to send it to `pocket`."""
    dx, dy = pocket[0] - target[0], pocket[1] - target[1]
    n = math.hypot(dx, dy)
    return (target[0] - 2 * radius * dx / n, target[1] - 2 * radius * dy / n)


def _segment_distance(p, a, b):
    ax, ay = b[0] - a[0], b[1] - a[1]
    t = ((p[0] - a[0]) * ax + (p[1] - a[1]) * ay) / max(ax * ax + ay * ay, 1e-18)
    t = min(1.0, max(0.0, t))
    return math.hypot(p[0] - (a[0] + t * ax), p[1] - (a[1] + t * ay))


def path_clear(a, b, balls: Iterable[Tuple[float, float]], radius):
    """No ball centre within 2R of the segment a-b (a ball travelling it touches none)."""
    return all(_segment_distance(p, a, b) >= 2 * radius for p in balls)


def best_pot(cue, targets: Dict[int, Tuple[float, float]], others: Sequence[Tuple[float, float]],
             table: Tuple[float, float], radius: float, pockets: Sequence[str] = POCKETS) -> Optional[Pot]:
    """The easiest straight pot of one of `targets` (id -> (x, y)) with the cue ball at `cue`:
    paths clear of the other balls (`others` and the other targets), the cut at most MAX_CUT_DEG,
    the smallest cut-weighted distance. None when there is none."""
    length, width = table
    points = pocket_points(length, width)
    best = None
    for ball, t in targets.items():
        obstacles = list(others) + [p for b, p in targets.items() if b != ball]
        for name in pockets:
            p = points[name]
            g = ghost_ball(t, p, radius)
            to_ghost = (g[0] - cue[0], g[1] - cue[1])
            d_cue = math.hypot(*to_ghost)
            d_obj = math.hypot(p[0] - t[0], p[1] - t[1])
            if d_cue < 1e-9:
                continue
            # Cut angle: between the cue ball's path and the object ball's (ghost to target).
            ox, oy = t[0] - g[0], t[1] - g[1]
            cos_cut = (to_ghost[0] * ox + to_ghost[1] * oy) / (d_cue * math.hypot(ox, oy))
            cut = math.degrees(math.acos(max(-1.0, min(1.0, cos_cut))))
            if cut > MAX_CUT_DEG:
                continue
            if not path_clear(cue, g, obstacles, radius) or not path_clear(t, p, obstacles, radius):
                continue
            # The object ball leaves with about cos(cut) of the cue ball's speed (elastic, no
            # friction): ask for enough to reach the pocket and some to spare.
            speed = min(7.0, 0.9 + 1.1 * d_cue + 1.6 * d_obj / max(math.cos(math.radians(cut)), 0.25))
            score = (d_cue + d_obj) / max(math.cos(math.radians(cut)), 0.05) ** 2
            phi = math.degrees(math.atan2(to_ghost[1], to_ghost[0]))
            shot = Pot(ball, name, phi, speed, cut, d_cue + d_obj, g)
            if best is None or score < best[0]:
                best = (score, shot)
    return None if best is None else best[1]
