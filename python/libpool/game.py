"""The rules of 8-ball, 9-ball and three cushion applied to a shot (libpool games, docs/games.md),
and the noise on the cue parameters, through ctypes on libpool_games.so.

    import libpool
    from libpool import game
    with libpool.Sim() as sim:
        sim.rack("9ball")
        sim.break_strike(8.0)
        sim.run()
        result = game.judge(sim, game.State.default("9ball"))
    result.legal, result.fouls, result.outcome, result.pocketed, result.state

A State is what the rules need from earlier shots, seen from the player about to shoot; its dict
(State.to_dict, State.from_dict) is the "state" of docs/interfaces.md "Games". judge() returns a
Result whose .state is the next shot's. Angles are degrees, as everywhere in this package.
"""

import ctypes
import math
from ctypes import POINTER, byref, c_bool, c_char, c_char_p, c_double, c_int, c_int32, c_uint32, c_uint64
from dataclasses import dataclass, field, fields
from typing import List, Optional, Tuple

from . import PoolError, _ffi
from ._ffi import BallState as CBallState, Error as CError, Event as CEvent, Params, TableDef, Vec3

__all__ = ["RULES", "OUTCOMES", "FOULS", "REASONS", "GROUPS", "POCKETS", "NO_BALL", "State", "Result",
           "Noise", "judge", "judge_shot", "rack", "spot_position", "carom_sim_def", "noise",
           "noise_presets", "normal", "noisy_strike", "library_path"]

RULES = ("8ball", "9ball", "three_cushion")
OUTCOMES = ("continue", "turn_over", "win", "loss")
FOULS = ("scratch", "no_contact", "wrong_ball_first", "no_rail", "ball_off_table", "illegal_break",
         "wrong_cue_ball", "bad_placement")
REASONS = ("none", "eight_early", "eight_wrong_pocket", "eight_on_foul", "eight_off_table",
           "eight_pocketed", "nine_pocketed", "three_fouls", "target_reached", "eight_on_break",
           "push_out", "safety", "not_called")
GROUPS = ("open", "solids", "stripes")
POCKETS = ("sw", "se", "nw", "ne", "s", "n")
NO_BALL = -(2 ** 31)  # POOL_GAME_NO_BALL
MAX_BALLS = 16        # POOL_GAME_MAX_BALLS
_POCKET_NONE = -1
_DEG = math.pi / 180.0  # the scenario parser's factor (libpool.__init__._DEG)


# ---- the C mirrors (games/include/pool/game.h, noise.h) ----------------------------------------

class CState(ctypes.Structure):
    """pool_game_state."""
    _fields_ = [("rules", c_int), ("player", c_int), ("break_shot", c_bool), ("cue_ball", c_int32),
                ("opponent_cue_ball", c_int32), ("group", c_int), ("called_ball", c_int32),
                ("called_pocket", c_int), ("safety", c_bool), ("push_out", c_bool),
                ("push_out_available", c_bool), ("ball_in_hand", c_bool),
                ("behind_head_string", c_bool), ("fouls", c_int), ("opponent_fouls", c_int),
                ("points", c_int), ("opponent_points", c_int), ("target_points", c_int)]


class CShot(ctypes.Structure):
    """pool_game_shot."""
    _fields_ = [("events", POINTER(CEvent)), ("event_count", c_int),
                ("event_states", POINTER(CBallState)), ("balls", POINTER(CBallState)),
                ("ball_count", c_int)]


class CResult(ctypes.Structure):
    """pool_game_result."""
    _fields_ = [("legal", c_bool), ("fouls", c_uint32), ("outcome", c_int), ("reason", c_int),
                ("ball_in_hand", c_bool), ("behind_head_string", c_bool), ("rerack_option", c_bool),
                ("pass_option", c_bool), ("points", c_int), ("first_hit", c_int32),
                ("rails_after_contact", c_int), ("cue_cushions", c_int), ("pocketed_count", c_int),
                ("pocketed", c_int32 * MAX_BALLS), ("pocketed_in", c_int * MAX_BALLS),
                ("off_table_count", c_int), ("off_table", c_int32 * MAX_BALLS),
                ("spot_count", c_int), ("spot", c_int32 * MAX_BALLS), ("next", CState)]


class CNoise(ctypes.Structure):
    """pool_noise: standard deviations in the C units (m/s, rad, rad, m, m)."""
    _fields_ = [("speed", c_double), ("phi", c_double), ("theta", c_double), ("a", c_double),
                ("b", c_double)]


STRUCTS = {"pool_game_state": CState, "pool_game_shot": CShot, "pool_game_result": CResult,
           "pool_noise": CNoise}

_E = POINTER(CError)
_PROTOTYPES = {
    "pool_game_default_state": (CState, [c_int]),
    "pool_game_state_validate": (c_int, [POINTER(CState), _E]),
    "pool_game_check_balls": (c_int, [POINTER(CState), POINTER(CBallState), c_int, _E]),
    "pool_game_judge": (c_int, [POINTER(CState), POINTER(CShot), POINTER(TableDef), POINTER(CResult), _E]),
    "pool_game_spot_position": (c_int, [POINTER(CState), c_int32, POINTER(TableDef), c_double,
                                        POINTER(CBallState), c_int, POINTER(Vec3)]),
    "pool_game_rack": (c_int, [c_int, POINTER(TableDef), POINTER(Params), c_double, POINTER(CBallState),
                               c_int]),
    "pool_game_shoot": (c_int, [ctypes.c_void_p, POINTER(_ffi.SimDef), POINTER(CBallState), c_int,
                                POINTER(_ffi.Strike), POINTER(CState), POINTER(CResult), POINTER(CBallState), _E]),
    "pool_noise_preset": (c_int, [c_char_p, POINTER(CNoise)]),
    "pool_noise_parse": (c_int, [c_char_p, POINTER(CNoise), _E]),
    "pool_noise_normal": (c_double, [c_uint64, c_uint64, c_uint32]),
}


LIBRARY = _ffi.Companion("libpool_games.so", "LIBPOOL_GAMES_PATH", "games", _PROTOTYPES)


def library_path():
    """Where libpool_games.so is: bundled next to this file (pip install ./python), else
    $LIBPOOL_GAMES_PATH, else beside the libpool.so in use when that is a build tree's
    (build/X/libpool/libpool.so -> build/X/games/libpool_games.so), else the repository's
    build/release tree, else the system's library search."""
    return LIBRARY.path()


def _load():
    return LIBRARY.load()


def _fail(code, err):
    raise PoolError(code, err.message.decode("utf-8", "replace"))


# ---- the state ---------------------------------------------------------------------------------

@dataclass
class State:
    """The rules' state before a shot (docs/interfaces.md "Games"), the shooter's view. Fields a
    file leaves out are False / 0 / "open"; State.default(rules) is the break."""
    rules: str
    player: int = 0
    break_shot: bool = False
    cue_ball: int = 0
    opponent_cue_ball: int = 1
    group: str = "open"
    called_ball: Optional[int] = None
    called_pocket: Optional[str] = None
    safety: bool = False
    push_out: bool = False
    push_out_available: bool = False
    ball_in_hand: bool = False
    behind_head_string: bool = False
    fouls: int = 0
    opponent_fouls: int = 0
    points: int = 0
    opponent_points: int = 0
    target: int = 0

    @staticmethod
    def default(rules):
        """A game's first shot: the break (8-ball and 9-ball from behind the head string)."""
        return State._from_c(_load().pool_game_default_state(_rules_value(rules)))

    # The JSON keys of docs/interfaces.md, and their fields.
    _KEYS = {"player": "player", "break": "break_shot", "cue_ball": "cue_ball",
             "opponent_cue_ball": "opponent_cue_ball", "group": "group", "safety": "safety",
             "push_out": "push_out", "push_out_available": "push_out_available",
             "ball_in_hand": "ball_in_hand", "behind_head_string": "behind_head_string",
             "fouls": "fouls", "opponent_fouls": "opponent_fouls", "points": "points",
             "opponent_points": "opponent_points", "target": "target"}

    @staticmethod
    def from_dict(rules, d=None):
        """The state of a scenario's "game": {"rules": rules, "state": d}, checked as pool-sim
        checks it (ValueError naming the field, "game.state.fouls: ...")."""
        s = State(_rules_name(rules))
        if d is None:
            d = {}
        if not isinstance(d, dict):
            raise ValueError("game.state: must be an object")
        for k, v in d.items():
            if k == "called":
                if not isinstance(v, dict):
                    raise ValueError('game.state.called: must be an object ("ball", "pocket")')
                for ck, cv in v.items():
                    if ck == "ball":
                        if not isinstance(cv, int) or isinstance(cv, bool):
                            raise ValueError("game.state.called.ball: must be a ball id (a 32-bit integer)")
                        s.called_ball = cv
                    elif ck == "pocket":
                        if cv not in POCKETS:
                            raise ValueError('game.state.called.pocket: must be one of "sw", "se", "nw", '
                                             '"ne", "s", "n"')
                        s.called_pocket = cv
                    else:
                        raise ValueError(f"game.state.called.{ck}: unknown field")
                continue
            name = State._KEYS.get(k)
            if name is None:
                raise ValueError(f"game.state.{k}: unknown field")
            if name == "group":
                if v not in GROUPS:
                    raise ValueError('game.state.group: must be "open", "solids" or "stripes"')
            elif isinstance(getattr(s, name), bool):
                if not isinstance(v, bool):
                    raise ValueError(f"game.state.{k}: must be true or false")
            elif name in ("cue_ball", "opponent_cue_ball"):
                if not isinstance(v, int) or isinstance(v, bool) or not -2 ** 31 < v < 2 ** 31:
                    raise ValueError(f"game.state.{k}: must be a ball id (a 32-bit integer)")
            elif not isinstance(v, int) or isinstance(v, bool) or not 0 <= v <= 1000000000:
                raise ValueError(f"game.state.{k}: must be a whole number from 0 to 1000000000")
            setattr(s, name, v)
        s.validate()
        return s

    def to_dict(self):
        """The "state" object pool-sim writes: the fields of this game."""
        d = {"player": self.player, "break": self.break_shot}
        if self.rules == "three_cushion":
            d["cue_ball"], d["opponent_cue_ball"] = self.cue_ball, self.opponent_cue_ball
        if self.rules == "8ball":
            d["group"] = self.group
            if self.called_ball is not None or self.called_pocket is not None:
                d["called"] = {k: v for k, v in (("ball", self.called_ball), ("pocket", self.called_pocket))
                               if v is not None}
        if self.rules != "three_cushion":
            d["safety"] = self.safety
        if self.rules == "9ball":
            d["push_out"], d["push_out_available"] = self.push_out, self.push_out_available
        if self.rules != "three_cushion":
            d["ball_in_hand"], d["behind_head_string"] = self.ball_in_hand, self.behind_head_string
        d["fouls"], d["opponent_fouls"] = self.fouls, self.opponent_fouls
        if self.rules == "three_cushion":
            d["points"], d["opponent_points"], d["target"] = self.points, self.opponent_points, self.target
        return d

    def validate(self):
        """Raises ValueError naming the field when the library refuses the state."""
        err = CError()
        c = self._to_c()
        code = _load().pool_game_state_validate(byref(c), byref(err))
        if code != 0:
            raise ValueError(err.message.decode("utf-8", "replace"))

    def _to_c(self):
        c = CState()
        c.rules = _rules_value(self.rules)
        c.player, c.break_shot = self.player, self.break_shot
        c.cue_ball, c.opponent_cue_ball = self.cue_ball, self.opponent_cue_ball
        if self.group not in GROUPS:
            raise ValueError(f'game.state.group: must be "open", "solids" or "stripes", not {self.group!r}')
        c.group = GROUPS.index(self.group)
        c.called_ball = NO_BALL if self.called_ball is None else self.called_ball
        if self.called_pocket is not None and self.called_pocket not in POCKETS:
            raise ValueError(f"game.state.called.pocket: unknown pocket {self.called_pocket!r}")
        c.called_pocket = _POCKET_NONE if self.called_pocket is None else POCKETS.index(self.called_pocket)
        c.safety, c.push_out, c.push_out_available = self.safety, self.push_out, self.push_out_available
        c.ball_in_hand, c.behind_head_string = self.ball_in_hand, self.behind_head_string
        c.fouls, c.opponent_fouls = self.fouls, self.opponent_fouls
        c.points, c.opponent_points, c.target_points = self.points, self.opponent_points, self.target
        return c

    @staticmethod
    def _from_c(c):
        return State(RULES[c.rules], c.player, c.break_shot, c.cue_ball, c.opponent_cue_ball,
                     GROUPS[c.group], None if c.called_ball == NO_BALL else c.called_ball,
                     None if c.called_pocket < 0 else POCKETS[c.called_pocket], c.safety, c.push_out,
                     c.push_out_available, c.ball_in_hand, c.behind_head_string, c.fouls,
                     c.opponent_fouls, c.points, c.opponent_points, c.target_points)


def _rules_value(rules):
    if rules not in RULES:
        raise ValueError(f"game.rules: unknown rules {rules!r} (8ball, 9ball, three_cushion)")
    return RULES.index(rules)


def _rules_name(rules):
    _rules_value(rules)
    return rules


# ---- judging ------------------------------------------------------------------------------------

@dataclass
class Result:
    """A judged shot: the "game" object of a pool-sim result (docs/interfaces.md "Games")."""
    rules: str
    legal: bool
    fouls: List[str]
    outcome: str
    reason: str
    ball_in_hand: bool
    behind_head_string: bool
    rerack_option: bool
    pass_option: bool
    points: int
    first_hit: Optional[int]
    rails_after_contact: int
    cue_cushions: int
    pocketed: List[int]
    pockets: List[str]
    off_table: List[int]
    spot: List[int]
    state: State

    def to_dict(self):
        """The object pool-sim writes under "game"."""
        d = {f.name: getattr(self, f.name) for f in fields(self)}
        d["state"] = self.state.to_dict()
        return d

    @staticmethod
    def _from_c(rules, c):
        return Result(rules, c.legal, [FOULS[k] for k in range(len(FOULS)) if c.fouls >> k & 1],
                      OUTCOMES[c.outcome], REASONS[c.reason], c.ball_in_hand, c.behind_head_string,
                      c.rerack_option, c.pass_option, c.points,
                      None if c.first_hit == NO_BALL else c.first_hit, c.rails_after_contact,
                      c.cue_cushions, list(c.pocketed[:c.pocketed_count]),
                      [POCKETS[p] for p in c.pocketed_in[:c.pocketed_count]],
                      list(c.off_table[:c.off_table_count]), list(c.spot[:c.spot_count]),
                      State._from_c(c.next))


def judge_shot(sim_handle, table, state, lib=None):
    """judge() on a raw pool_sim handle (c_void_p) and TableDef: for the batch and the gym, which
    own their simulations. The caller holds whatever lock guards the handle."""
    plib = lib or _ffi.load()
    glib = _load()
    count = c_int()
    shot = CShot()
    shot.events = plib.pool_sim_events(sim_handle, byref(count))
    shot.event_count = count.value
    if count.value > 0:
        first = plib.pool_sim_event_states(sim_handle, shot.events)
        base = ctypes.cast(first, ctypes.c_void_p).value - shot.events[0].first_state * ctypes.sizeof(CBallState)
        shot.event_states = ctypes.cast(base, POINTER(CBallState))
    shot.balls = plib.pool_sim_balls(sim_handle)
    shot.ball_count = plib.pool_sim_ball_count(sim_handle)
    c_state = state._to_c()
    result = CResult()
    err = CError()
    code = glib.pool_game_judge(byref(c_state), byref(shot), byref(table), byref(result), byref(err))
    if code != 0:
        _fail(code, err)
    return Result._from_c(state.rules, result)


def judge(sim, state):
    """Judges the shot a libpool.Sim has run under state (a State, or a (rules, state dict)
    pair): fouls, outcome, points, first ball hit, rails after contact, pocketed balls and the
    next state. Raises PoolError (the message names the field) when the rules refuse the shot:
    no strike first, a ball id the game has no ball for, three cushion without three balls."""
    if isinstance(state, tuple):
        state = State.from_dict(*state)
    with sim.lock:
        return judge_shot(sim._p(), sim._def.table, state)


# ---- setting up tables --------------------------------------------------------------------------

def carom_sim_def():
    """The carom table three cushion is played on, as pool-game builds it: the "carom" preset
    (2.84 x 1.42 m, nose 37 mm, pockets "none") with its balls, 61.5 mm and 210 g (a SimDef)."""
    lib = _ffi.load()
    d = lib.pool_default_sim_def()
    lib.pool_table_preset(b"carom", byref(d.table))
    lib.pool_params_preset(b"carom", byref(d.params))
    return d


def rack(rules, gap=0.0, table=None, params=None):
    """The opening position of a game as (id, (x, y)) pairs: pool_rack's racks, UMB's start for
    three cushion (on carom_sim_def()'s table unless table/params are given)."""
    lib = _ffi.load()
    d = carom_sim_def() if rules == "three_cushion" else lib.pool_default_sim_def()
    t = table if table is not None else d.table
    p = params if params is not None else d.params
    out = (CBallState * MAX_BALLS)()
    n = _load().pool_game_rack(_rules_value(rules), byref(t), byref(p), float(gap), out, MAX_BALLS)
    if n < 0:
        raise PoolError(n, "rack: the opening position does not fit the table")
    return [(out[i].id, (out[i].pos.x, out[i].pos.y)) for i in range(n)]


def spot_position(state, ball_id, balls, table=None, radius=None):
    """Where the rules put ball_id back (WPA 1.4, UMB art. 28): (x, y), or None when there is no
    room. balls: the balls on the table as (id, (x, y)) pairs."""
    lib = _ffi.load()
    d = lib.pool_default_sim_def()
    t = table if table is not None else (carom_sim_def().table if state.rules == "three_cushion" else d.table)
    r = float(radius) if radius is not None else (0.03075 if state.rules == "three_cushion"
                                                  else d.params.ball_radius)
    arr = (CBallState * max(len(balls), 1))()
    for i, (bid, (x, y)) in enumerate(balls):
        arr[i].id, arr[i].pos = bid, Vec3(x, y, r)
    pos = Vec3()
    c_state = state._to_c()
    if _load().pool_game_spot_position(byref(c_state), int(ball_id), byref(t), r, arr, len(balls), byref(pos)):
        return None
    return (pos.x, pos.y)


# ---- noise --------------------------------------------------------------------------------------

@dataclass
class Noise:
    """Standard deviations of Gaussian noise on the cue parameters, in this package's units:
    speed m/s, phi and theta degrees, a and b m."""
    speed: float = 0.0
    phi: float = 0.0
    theta: float = 0.0
    a: float = 0.0
    b: float = 0.0

    def is_zero(self):
        return not (self.speed or self.phi or self.theta or self.a or self.b)


def noise_presets():
    """The named presets: ("none", "fastfiz")."""
    return ("none", "fastfiz")


def noise(spec):
    """A Noise from a preset name ("fastfiz": the Computational Pool tournaments' sd of a and b
    0.5 mm, theta 0.1 deg, phi 0.125 deg, speed 0.075 m/s; "none") or NAME=SD pairs
    ("phi=0.2,speed=0.05"), parsed by the library (ValueError naming the part at fault). A Noise
    is returned as it is."""
    if isinstance(spec, Noise):
        return spec
    if not isinstance(spec, str):
        raise TypeError(f"noise: expected a preset name, a spec or a Noise, got {type(spec).__name__}")
    c = CNoise()
    err = CError()
    if _load().pool_noise_parse(spec.encode("utf-8"), byref(c), byref(err)) != 0:
        raise ValueError(err.message.decode("utf-8", "replace"))
    # Degrees exactly as pool-batch uses them (pool_batch_noisy: the radians divided back).
    return Noise(c.speed, c.phi / _DEG, c.theta / _DEG, c.a, c.b)


def normal(seed, sample, k):
    """The k-th standard normal deviate of sample `sample` under `seed` (pool_noise_normal)."""
    return _load().pool_noise_normal(int(seed) & (2 ** 64 - 1), int(sample) & (2 ** 64 - 1), int(k))


def noisy_strike(strike, spec, seed, sample):
    """Strike (speed, phi, theta, a, b) in m/s, degrees, m with noise: sample `sample` of `seed`,
    each parameter nominal + sd * normal(seed, sample, k) for k = 0..4, exactly nominal where its
    sd is 0, theta folded to |theta|: pool-batch --noise's strike `sample`, bit for bit."""
    n = noise(spec)
    out = []
    for k, (x, sd) in enumerate(zip(strike, (n.speed, n.phi, n.theta, n.a, n.b))):
        out.append(x + sd * normal(seed, sample, k) if sd > 0.0 else float(x))
    out[2] = abs(out[2])
    return tuple(out)
