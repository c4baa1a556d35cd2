"""Shot planning: the best shots of a position ranked by their chance of success under the noise
of a real stroke (search(): libpool planning, pool/aim.h, through ctypes on libpool_planning.so,
docs/planning.md), and ghost-ball aiming, the straight-line baseline a pool player learns first
(best_pot() and its helpers: pure Python, no library needed).

    from libpool import aim
    shots = aim.search({0: (0.6, 0.6), 3: (1.9, 0.9), 5: (1.2, 1.1)}, noise="fastfiz", top=3)
    shots[0].strike, shots[0].ball, shots[0].pocket, shots[0].kind, shots[0].p_success, shots[0].ci95

To pot ball T in pocket P, the cue ball must arrive where it touches T on the line P-T extended:
the ghost ball G = T - 2R (P - T)/|P - T|. Aim the cue at G. Throw, squirt, cushions and
everything else libpool simulates are ignored, which is what makes it a baseline.

    from libpool import aim
    shot = aim.best_pot((0.6, 0.6), {3: (1.9, 0.9)}, others, table, 0.028575)
    shot.phi, shot.speed, shot.ball, shot.pocket

Angles in degrees as everywhere in the Python API; lengths in metres.
"""

import ctypes
import ctypes.util
import math
import os
import threading
from ctypes import POINTER, byref, c_bool, c_double, c_int, c_int32, c_longlong, c_uint, c_uint64
from dataclasses import dataclass
from typing import Dict, Iterable, Optional, Sequence, Tuple

__all__ = ["Pot", "pocket_points", "ghost_ball", "path_clear", "best_pot", "POCKETS", "KINDS", "Shot",
           "Stats", "search", "library_path"]

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


# ---- the search: libpool planning (planning/include/pool/aim.h) --------------------------------

KINDS = ("straight", "bank", "kick", "combination", "carom")
RAILS = ("south", "north", "west", "east")
NO_BALL = -(2 ** 31)  # POOL_AIM_NO_BALL
_DEG = math.pi / 180.0


@dataclass
class Shot:
    """A shot found: the strike (speed m/s, phi and theta degrees, a and b m), the ball it pots,
    the pocket, its kind, the second ball of a combination or carom (via), the cushion of a bank
    or kick (rail), p_success with its 95 % interval ci95 and the samples behind it, where the cue
    ball ends without noise, and the position score (None unless asked for)."""
    strike: Dict[str, float]
    ball: int
    pocket: str
    kind: str
    via: Optional[int]
    rail: Optional[str]
    p_success: float
    ci95: Tuple[float, float]
    samples: int
    cue_ball_final: Tuple[float, float]
    position: Optional[int]

    def to_dict(self, rank=None, cue_ball=0):
        """The object of pool-aim's JSON list (docs/interfaces.md "Shot planning")."""
        d = {"strike": dict(ball=cue_ball, **self.strike), "ball": self.ball, "pocket": self.pocket,
             "kind": self.kind, "via": self.via, "rail": self.rail, "p_success": self.p_success,
             "ci95": list(self.ci95), "samples": self.samples, "cue_ball_final": list(self.cue_ball_final)}
        if rank is not None:
            d = dict(rank=rank, **d)
        if self.position is not None:
            d["position"] = self.position
        return d


@dataclass
class Stats:
    """What a search did (pool_aim_stats)."""
    candidates: int
    blocked: int
    refined: int
    potting: int
    simulations: int
    seconds: float
    budget_reached: bool


def _c_types():
    from . import _ffi
    from . import game as _game

    class CDef(ctypes.Structure):
        _fields_ = [("sim", _ffi.SimDef), ("balls", POINTER(_ffi.BallState)), ("ball_count", c_int),
                    ("cue_ball", c_int32), ("ball", c_int32), ("pocket", c_int), ("kinds", c_uint),
                    ("game", POINTER(_game.CState)), ("noise", _game.CNoise), ("seed", c_uint64),
                    ("samples", c_int), ("top", c_int), ("time_budget", c_double), ("threads", c_int),
                    ("position", c_bool), ("distinct", c_bool)]

    class CShot(ctypes.Structure):
        _fields_ = [("strike", _ffi.Strike), ("ball", c_int32), ("pocket", c_int), ("kind", c_int),
                    ("via", c_int32), ("rail", c_int), ("p_success", c_double), ("ci_low", c_double),
                    ("ci_high", c_double), ("samples", c_int), ("cue_final", _ffi.Vec3), ("position", c_int)]

    class CStats(ctypes.Structure):
        _fields_ = [("candidates", c_int), ("blocked", c_int), ("refined", c_int), ("potting", c_int),
                    ("simulations", c_longlong), ("seconds", c_double), ("budget_reached", c_bool)]

    return CDef, CShot, CStats


_lib = None
_types = None
_lock = threading.Lock()


def library_path():
    """Where libpool_planning.so is: bundled next to this file (pip install ./python), else
    $LIBPOOL_PLANNING_PATH, else beside the libpool.so in use when that is a build tree's
    (build/X/libpool/libpool.so -> build/X/planning/libpool_planning.so), else the repository's
    build/release tree, else the system's library search."""
    from . import _ffi
    here = os.path.dirname(os.path.abspath(__file__))
    bundled = os.path.join(here, "libpool_planning.so")
    if os.path.exists(bundled):
        return bundled
    env = os.environ.get("LIBPOOL_PLANNING_PATH")
    if env:
        return env
    pool = _ffi.library_path()
    if pool:
        beside = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(pool))), "planning",
                              "libpool_planning.so")
        if os.path.exists(beside):
            return beside
    built = os.path.join(os.path.dirname(os.path.dirname(here)), "build", "release", "planning",
                         "libpool_planning.so")
    if os.path.exists(built):
        return built
    return ctypes.util.find_library("pool_planning")


def _load():
    global _lib, _types
    if _lib is not None:
        return _lib
    with _lock:
        if _lib is None:
            from . import _ffi
            from . import game as _game
            _ffi.load()
            _game._load()  # libpool.so and libpool_games.so first: libpool_planning.so needs both
            path = library_path()
            if path is None:
                raise OSError("libpool_planning.so not found: set LIBPOOL_PLANNING_PATH, build the "
                              "repository into build/release, or pip install ./python")
            lib = ctypes.CDLL(path)
            CDef, CShot, CStats = _c_types()
            lib.pool_default_aim_def.restype = CDef
            lib.pool_default_aim_def.argtypes = []
            lib.pool_aim_search.restype = c_int
            lib.pool_aim_search.argtypes = [POINTER(CDef), POINTER(CShot), c_int, POINTER(c_int), POINTER(CStats),
                                            POINTER(_ffi.Error)]
            _types = (CDef, CShot, CStats)
            _lib = lib
    return _lib


def structs():
    """The ctypes mirrors of pool_aim_def, pool_aim_shot and pool_aim_stats, by C name (tests
    compare them with the C layout)."""
    _load()
    return dict(zip(("pool_aim_def", "pool_aim_shot", "pool_aim_stats"), _types))


def _balls_of(balls, radius):
    """Balls at rest on the cloth as (id, (x, y)) pairs, from a dict id -> (x, y), pairs, or a Sim
    (its balls as they stand, pocketed ones left out)."""
    from . import Sim
    if isinstance(balls, Sim):
        return [(b.id, b.pos[:2]) for b in balls.balls if b.motion not in ("pocketed", "off_table")]
    items = balls.items() if isinstance(balls, dict) else balls
    out = []
    for item in items:
        try:
            i, pos = item
            x, y = pos[0], pos[1]
        except (TypeError, ValueError, IndexError):
            raise TypeError(f"balls: expected (id, (x, y)) pairs or a dict id -> (x, y), got {item!r}") from None
        if isinstance(i, bool) or not isinstance(i, int):
            raise TypeError(f"balls: a ball id must be an int, got {type(i).__name__}")
        out.append((i, (float(x), float(y))))
    return out


def search(balls, cue_ball=0, ball=None, pocket=None, kinds=None, game=None, noise="fastfiz", seed=1,
           samples=400, top=5, time_budget=0.0, threads=0, position=False, table=None, params=None,
           models=None, distinct=False, with_stats=False):
    """The best shots of a position, best first (a list of Shot; with_stats, (shots, Stats)).

    balls: a dict id -> (x, y), (id, (x, y)) pairs, or a Sim whose balls are at rest; cue_ball the
    struck ball; ball and pocket restrict the search (None: any); kinds a list of KINDS (None:
    all); game a libpool.game.State whose rules judge success (None: the ball in the pocket, the
    cue ball on the table); noise a preset name, a spec ("phi=0.2,speed=0.05") or a
    libpool.game.Noise; samples behind each p_success; top the shots wanted; time_budget seconds
    (0: none, and the result depends on the input alone); threads (0: all CPUs); position scores
    where the cue ball ends; distinct keeps one shot per ball, pocket, kind, second ball and cushion
    (its best speed and spin); table, params and models as for Sim. Errors raise PoolError with the
    library's message naming the field ("aim.ball: no object ball has id 9")."""
    from . import PoolError, _ffi, _sim_def
    from . import game as _game
    lib = _load()
    CDef, CShot, CStats = _types
    d = lib.pool_default_aim_def()
    d.sim = _sim_def(table, params, None, None, False, models)
    pairs = _balls_of(balls, d.sim.params.ball_radius)
    R = d.sim.params.ball_radius
    arr = (_ffi.BallState * max(len(pairs), 1))()
    for k, (i, (x, y)) in enumerate(pairs):
        arr[k].id = i
        arr[k].pos = _ffi.Vec3(x, y, R)
    d.balls = arr
    d.ball_count = len(pairs)
    d.cue_ball = int(cue_ball)
    d.ball = NO_BALL if ball is None else int(ball)
    if pocket is None:
        d.pocket = -1
    elif pocket in POCKETS:
        d.pocket = POCKETS.index(pocket)
    else:
        raise ValueError(f"pocket: {pocket!r} is not a pocket ({', '.join(POCKETS)})")
    mask = 0
    for kind in kinds or ():
        if kind not in KINDS:
            raise ValueError(f"kinds: {kind!r} is not a kind of shot ({', '.join(KINDS)})")
        mask |= 1 << KINDS.index(kind)
    d.kinds = mask
    state = None
    if game is not None:
        if not isinstance(game, _game.State):
            raise TypeError(f"game: expected a libpool.game.State, got {type(game).__name__}")
        state = game._to_c()
        d.game = ctypes.pointer(state)
    n = _game.noise(noise)
    d.noise = _game.CNoise(n.speed, n.phi * _DEG, n.theta * _DEG, n.a, n.b)
    d.seed = int(seed) & (2 ** 64 - 1)
    d.samples = int(samples)
    d.top = int(top)
    d.time_budget = float(time_budget)
    d.threads = int(threads)
    d.position = bool(position)
    d.distinct = bool(distinct)
    out = (CShot * max(d.top, 1))()
    count = c_int(0)
    stats = CStats()
    err = _ffi.Error()
    code = lib.pool_aim_search(byref(d), out, d.top, byref(count), byref(stats), byref(err))
    if code != 0:
        raise PoolError(code, err.message.decode("utf-8", "replace"))
    shots = []
    for c in out[:count.value]:
        shots.append(Shot(
            strike={"speed": c.strike.speed, "phi": c.strike.phi / _DEG, "theta": c.strike.theta / _DEG,
                    "a": c.strike.a, "b": c.strike.b},
            ball=c.ball, pocket=POCKETS[c.pocket], kind=KINDS[c.kind], via=None if c.via == NO_BALL else c.via,
            rail=RAILS[c.rail] if 0 <= c.rail < 4 else None, p_success=c.p_success, ci95=(c.ci_low, c.ci_high),
            samples=c.samples, cue_ball_final=(c.cue_final.x, c.cue_final.y),
            position=None if c.position < 0 else c.position))
    if with_stats:
        return shots, Stats(stats.candidates, stats.blocked, stats.refined, stats.potting, stats.simulations,
                            stats.seconds, stats.budget_reached)
    return shots
