"""Many strikes on one layout, on several threads: libpool.batch.run (the Python side of
pool-batch, docs/commands.md). Needs NumPy.

    import libpool.batch
    res = libpool.batch.run("rack.json", [(0, 8.0, 0.0, 0.0, 0.0, 0.0),
                                          (0, 7.5, 1.0, 0.0, 0.0, -0.01)], workers=2)
    res.stop_reason, res.events, res.end_time, res.first_hit, res.pos, res.state, res.pocketed

The layout is read by libpool_scenario's parser and every shot is libpool_scenario's batch shot
(pool/batch.h), the very code pool-sim and pool-batch run: the same fields, ranges and messages,
the same shots. Each worker thread owns one C simulation and hands it chunks of strikes; the C
call releases the GIL, so the threads simulate in parallel. Every shot depends only on the layout
and its strike, so the arrays are identical whatever `workers` is, and each row holds exactly the
values of pool-batch's row for the same layout and strike.
"""

import ctypes
import json
import math
import os
import threading
from ctypes import POINTER, byref, c_void_p, cast, create_string_buffer

import numpy as np

from . import PoolError, _ffi, _scenario
from ._ffi import BallState as CBallState, SimDef

__all__ = ["run", "BatchResult", "load_layout", "Layout", "STOP_ERROR", "STOP_NAMES",
           "MOTION_NAMES", "NO_HIT", "STRIKE_FIELDS"]

# stop_reason codes: the library's pool_stop_reason, and -1 for a strike the library refused.
STOP_ERROR = -1
STOP_NAMES = {-1: "error", 1: "rest", 2: "max_time", 3: "max_events"}
# state codes: pool_motion (pool/ball.h); -1 in the rows of refused strikes.
MOTION_NAMES = {0: "stationary", 1: "spinning", 2: "sliding", 3: "rolling", 4: "airborne",
                5: "linked", 6: "pocketed", 7: "off_table"}
# first_hit when the struck ball hits no ball (outside the 32-bit range of ball ids).
NO_HIT = -(2 ** 31) - 1
STRIKE_FIELDS = ("ball", "speed", "phi", "theta", "a", "b")

_MAX_ABS = 1e9  # POOL_SCENARIO_MAX_ABS: the scenario parser's and pool-batch's limit on numbers
_MOTION_POCKETED, _MOTION_OFF_TABLE = 6, 7
BALL_DTYPE = np.dtype([("id", "<i4"), ("motion", "<i4"), ("pos", "<f8", 3), ("vel", "<f8", 3),
                       ("omega", "<f8", 3)])
assert BALL_DTYPE.itemsize == 80


# ---- the layout: a libpool-scenario/1 document ------------------------------------------------

class Layout:
    """A parsed, validated libpool-scenario/1 document: def (SimDef), balls (C BallState list,
    z = R where the file gave [x, y]), base strike (ball id, and speed, phi and theta in DEGREES
    as written, a, b; or None)."""

    def __init__(self, sim_def, balls, strike_ball, strike, game=None):
        self.sim_def = sim_def
        self.balls = balls
        self.strike_ball = strike_ball
        self.strike = strike  # (speed, phi_deg, theta_deg, a, b) or None
        self.game = game      # libpool.game.State of the layout's "game", or None

    @property
    def ball_ids(self):
        return [b.id for b in self.balls]


def _json_value_problem(v, path):
    """What JSON cannot carry in a layout dict, as the parser would name it ("balls[0].pos[1]:
    must be a finite number"), or None. JSON has no NaN or infinity, and json.dumps knows only
    its own types."""
    if isinstance(v, dict):
        for k, x in v.items():
            problem = _json_value_problem(x, f"{path}.{k}" if path else str(k))
            if problem:
                return problem
    elif isinstance(v, (list, tuple)):
        for i, x in enumerate(v):
            problem = _json_value_problem(x, f"{path}[{i}]")
            if problem:
                return problem
    elif isinstance(v, float) and not math.isfinite(v):
        return f"{path}: must be a finite number"
    elif not (v is None or isinstance(v, (str, int, float))):
        return f"{path}: must be a JSON value (a number, string, boolean, array or object), got " \
               f"{type(v).__name__}"
    return None


def layout_text(layout):
    """The JSON text of a layout given as a path (str or os.PathLike), JSON text (a str or bytes
    whose first non-blank character is "{") or a dict; TypeError for anything else, ValueError
    for a dict holding what JSON cannot (NaN, objects that are no JSON values)."""
    if isinstance(layout, dict):
        problem = _json_value_problem(layout, "")
        if problem:
            raise ValueError("layout: " + problem)
        return json.dumps(layout, allow_nan=False)
    if isinstance(layout, (bytes, bytearray)):
        return layout.decode("utf-8")
    if isinstance(layout, str) and layout.lstrip().startswith("{"):
        return layout
    if isinstance(layout, (str, os.PathLike)):
        with open(layout, encoding="utf-8") as f:
            return f.read()
    raise TypeError("layout: expected a path, JSON text or a dict, got "
                    f"{type(layout).__name__}")


def load_layout(layout):
    """A Layout from a path (str or os.PathLike), JSON text (a str whose first non-blank character
    is "{") or an already parsed dict, read by pool-sim's own scenario parser (libpool_scenario:
    the same fields, ranges, library checks and messages). Raises ValueError naming the field."""
    if isinstance(layout, Layout):
        return layout
    data = layout_text(layout).encode("utf-8", "surrogatepass")
    lib = _scenario.load()
    c = _scenario.CScenario()
    err = create_string_buffer(_scenario.MESSAGE_SIZE)
    if lib.pool_scenario_parse(data, len(data), byref(c), err, len(err)) != 0:
        raise ValueError("layout: " + err.value.decode("utf-8", "replace"))
    try:
        balls = [CBallState.from_buffer_copy(c.balls[i]) for i in range(c.ball_count)]
        strike_ball, strike = None, None
        if c.has_strike:
            w = c.written
            strike_ball, strike = c.strike_ball, (w.speed, w.phi, w.theta, w.a, w.b)
        from . import game
        state = game.State._from_c(c.game) if c.has_game else None
        return Layout(SimDef.from_buffer_copy(c.sim_def), balls, strike_ball, strike, state)
    finally:
        lib.pool_scenario_free(byref(c))


# ---- strikes ----------------------------------------------------------------------------------

def _strike_table(strikes, base_ball, base, n_hint=None):
    """(ball int32 [n], values float64 [n, 5]: speed, phi, theta in degrees, a, b) from the
    accepted strike forms; absent values come from the base strike."""
    base_v = list(base) if base is not None else [math.nan, 0.0, 0.0, 0.0, 0.0]
    if isinstance(strikes, np.ndarray) and strikes.dtype.names is not None:
        names = strikes.dtype.names
        for k in names:
            if k not in STRIKE_FIELDS:
                raise ValueError(f"strikes: unknown field {k!r} (ball, speed, phi, theta, a, b)")
            if strikes.dtype[k].kind not in "iuf":
                raise TypeError(f"strikes.{k}: expected numbers, got {strikes.dtype[k]}")
        arr = strikes.reshape(-1)
        n = len(arr)
        if base is None and "speed" not in names:
            raise ValueError("strikes: no speed field (the layout has no strike to take the "
                             "speed from)")
        ball_col = arr["ball"] if "ball" in names else np.full(n, base_ball)
        values = np.empty((n, 5), dtype=np.float64)
        for j, k in enumerate(STRIKE_FIELDS[1:]):
            values[:, j] = arr[k] if k in names else base_v[j]
    else:
        if not isinstance(strikes, np.ndarray):
            # A bool is not a speed, a string not a number: NumPy would convert both silently.
            for i, row in enumerate(strikes):
                if isinstance(row, (str, bytes)):
                    raise TypeError(f"strikes[{i}]: expected a row of 6 numbers, got {row!r}")
                for j, x in enumerate(row):
                    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, float, np.number)):
                        name = STRIKE_FIELDS[j] if j < len(STRIKE_FIELDS) else str(j)
                        raise TypeError(f"strikes[{i}].{name}: expected a number, got "
                                        f"{type(x).__name__} {x!r}")
        elif strikes.dtype.kind not in "iuf":
            raise TypeError(f"strikes: expected numbers, got an array of {strikes.dtype}")
        a = np.asarray(strikes, dtype=np.float64)
        if a.ndim == 1 and a.size == 0:
            a = a.reshape(0, 6)
        if a.ndim != 2 or a.shape[1] != 6:
            raise ValueError("strikes: expected rows of 6 numbers (ball, speed, phi_deg, "
                             f"theta_deg, a, b), got an array of shape {a.shape}")
        ball_col = a[:, 0]
        values = np.ascontiguousarray(a[:, 1:])
    ball_f = np.asarray(ball_col, dtype=np.float64)
    bad = ~((ball_f == np.floor(ball_f)) & (ball_f >= -2 ** 31) & (ball_f <= 2 ** 31 - 1))
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"strikes[{i}].ball: must be a ball id (a 32-bit integer)")
    bad = ~np.isfinite(values) | (np.abs(values) > _MAX_ABS)
    if bad.any():
        i, j = (int(x) for x in np.argwhere(bad)[0])
        x = values[i, j]
        if j == 0 and math.isnan(x) and base is None:
            raise ValueError(f"strikes[{i}].speed: missing (the layout has no strike to take "
                             "the speed from)")
        if not math.isfinite(x):
            raise ValueError(f"strikes[{i}].{STRIKE_FIELDS[j + 1]}: must be a finite number, "
                             f"got {x:g}")
        raise ValueError(f"strikes[{i}].{STRIKE_FIELDS[j + 1]}: {x:g} is too large "
                         f"(limit {_MAX_ABS:g})")
    return ball_f.astype(np.int32), values


# ---- the run ----------------------------------------------------------------------------------

class BatchResult:
    """Per-shot arrays of libpool.batch.run, rows in strike order (n shots, m balls of the
    layout, in the layout's order):

    ball_ids     int32 [m]        the layout's ball ids (columns of pos, state, pocketed...)
    ball         int32 [n]        the struck ball of each shot
    strikes      float64 [n, 5]   speed m/s, phi deg, theta deg, a m, b m as simulated
    stop_reason  int8 [n]         1 rest, 2 max_time, 3 max_events, -1 (STOP_ERROR) refused
    error        list of n str    "" or, for a refused strike, pool-batch's message
    events       int32 [n]        events processed (0 for refused strikes)
    end_time     float64 [n]      s, the instant of the final states (NaN if refused)
    first_hit    int64 [n]        id of the first ball the struck ball hits, NO_HIT for none
    pos          float64 [n,m,3]  final positions at end_time (NaN if refused)
    state        int8 [n, m]      final pool_motion codes (MOTION_NAMES; -1 if refused)
    pocketed     bool [n, m]      state == pocketed
    off_table    bool [n, m]      state == off_table

    With a "game" in the layout (pool-batch's game columns; libpool.game.judge of each shot):
    legal        int8 [n]         1 legal, 0 a foul, -1 refused strike
    fouls        uint32 [n]       foul bits, bit k = libpool.game.FOULS[k]
    outcome      int8 [n]         index in libpool.game.OUTCOMES, -1 refused
    points       int32 [n]        what the shot scored
    """

    def __init__(self, **fields):
        self.__dict__.update(fields)

    def __len__(self):
        return len(self.stop_reason)

    def stop_names(self):
        """stop_reason as names ("rest", "max_time", "max_events", "error")."""
        return [STOP_NAMES[int(c)] for c in self.stop_reason]

    def __repr__(self):
        return f"BatchResult({len(self)} shots, {len(self.ball_ids)} balls)"




def _c_layout(layout):
    """The pool_scenario of a Layout for pool_batch_run, and the ball array it points to (keep
    it alive as long as the scenario)."""
    c = _scenario.CScenario()
    c.sim_def = layout.sim_def
    balls = (CBallState * max(1, len(layout.balls)))(*layout.balls)
    c.ball_count = len(layout.balls)
    c.balls = cast(balls, POINTER(CBallState))
    if layout.game is not None:
        c.has_game = True
        c.game = layout.game._to_c()
    return c, balls


def _record_dtype():
    """The fields of pool_batch_shot that fill the arrays, as a NumPy view of the C records."""
    rec, verdict = _scenario.CBatchShot, _scenario.game.CResult
    base = rec.game.offset
    fields = {"result": ("<i4", rec.result.offset), "stop_reason": ("<i4", rec.stop_reason.offset),
              "events": ("<i4", rec.events.offset), "end_time": ("<f8", rec.end_time.offset),
              "hit": ("?", rec.hit.offset), "first_hit": ("<i4", rec.first_hit.offset),
              "judged": ("?", rec.judged.offset), "legal": ("?", base + verdict.legal.offset),
              "fouls": ("<u4", base + verdict.fouls.offset),
              "outcome": ("<i4", base + verdict.outcome.offset),
              "points": ("<i4", base + verdict.points.offset)}
    return np.dtype({"names": list(fields), "formats": [f for f, _ in fields.values()],
                     "offsets": [o for _, o in fields.values()], "itemsize": ctypes.sizeof(rec)})


_RECORD = _record_dtype()


class _Shots:
    """Output arrays and the shared claim counter."""

    def __init__(self, n, m, chunk, game):
        self.n, self.m, self.chunk, self.game = n, m, chunk, game
        self.stop = np.zeros(n, dtype=np.int8)
        self.events = np.zeros(n, dtype=np.int32)
        self.end_time = np.full(n, math.nan)
        self.first_hit = np.full(n, NO_HIT, dtype=np.int64)
        self.pos = np.zeros((n, m, 3), dtype=np.float64)
        self.state = np.zeros((n, m), dtype=np.int8)
        self.error = [""] * n
        self.legal = np.full(n, -1, dtype=np.int8)
        self.fouls = np.zeros(n, dtype=np.uint32)
        self.outcome = np.full(n, -1, dtype=np.int8)
        self.points = np.zeros(n, dtype=np.int32)
        self.next = 0
        self.lock = threading.Lock()
        self.failure = None

    def claim(self):
        with self.lock:
            if self.failure is not None or self.next >= self.n:
                return None
            i = self.next
            self.next = min(self.n, i + self.chunk)
            return i, self.next

    def store(self, i0, records, messages, finals):
        """Copies the records (a _RECORD view; messages: the C records) and final states of shots
        i0.. into the output arrays."""
        i1 = i0 + len(records)
        ok = records["result"] == 0
        self.stop[i0:i1] = np.where(ok, records["stop_reason"], STOP_ERROR)
        self.events[i0:i1] = np.where(ok, records["events"], 0)
        self.end_time[i0:i1] = np.where(ok, records["end_time"], math.nan)
        # (int64 before the choice: NumPy 2 would cast NO_HIT to the records' int32.)
        self.first_hit[i0:i1] = np.where(ok & records["hit"], records["first_hit"].astype(np.int64),
                                         NO_HIT)
        self.pos[i0:i1] = finals["pos"]
        self.state[i0:i1] = finals["motion"]
        for k in np.flatnonzero(~ok):
            self.error[i0 + k] = messages[k].message.decode("utf-8", "replace")
        if self.game:
            judged = records["judged"]
            self.legal[i0:i1] = np.where(judged, records["legal"].astype(np.int8), -1)
            self.fouls[i0:i1] = np.where(judged, records["fouls"], 0)
            self.outcome[i0:i1] = np.where(judged, records["outcome"], -1)
            self.points[i0:i1] = np.where(judged, records["points"], 0)


def _worker(c_layout, shots, strikes):
    """Claims chunks of shots and runs each in one pool_batch_run call (without the GIL) on a
    simulation of its own."""
    lib = _scenario.load()
    sim = c_void_p()
    records = (_scenario.CBatchShot * shots.chunk)()
    finals = np.zeros((shots.chunk, shots.m), dtype=BALL_DTYPE)
    finals_p = finals.ctypes.data_as(POINTER(CBallState))
    record_view = np.frombuffer(records, dtype=_RECORD)
    try:
        while True:
            span = shots.claim()
            if span is None:
                return
            i0, i1 = span
            done = lib.pool_batch_run(byref(c_layout), strikes[i0:i1].ctypes.data_as(
                POINTER(_scenario.CBatchStrike)), i1 - i0, byref(sim), records, finals_p)
            if done < i1 - i0 or records[done - 1].failed:
                r = records[done - 1]
                raise PoolError(r.result, f"shot {i0 + done - 1}: " +
                                r.message.decode("utf-8", "replace"))
            shots.store(i0, record_view[:done], records, finals[:done])
    except BaseException as e:  # reported by run(); stops the other workers too
        with shots.lock:
            if shots.failure is None:
                shots.failure = e
    finally:
        if sim:
            _ffi.load().pool_sim_destroy(sim)


def run(layout, strikes, workers=None, ball=None, chunk=64):
    """Simulates every strike on the layout, on `workers` threads (default os.cpu_count()), and
    returns a BatchResult of NumPy arrays, rows in strike order, identical whatever `workers` is
    and equal to pool-batch's rows for the same layout and strikes.

    layout: a libpool-scenario/1 document as a path, JSON text or dict (load_layout), or a Layout.
      Its strike, if any, is the base strike: values a strike does not give come from it.
    strikes: rows of 6 numbers (ball, speed m/s, phi deg, theta deg, a m, b m): a sequence of
      sequences or an array of shape (n, 6); or a NumPy structured array with fields among
      ball, speed, phi, theta, a, b (absent fields take the base strike's values).
    ball: the struck ball of structured rows without a "ball" field (default: the layout's strike
      ball, else its first ball), as pool-batch --ball.
    A strike the library refuses gives a row with stop_reason STOP_ERROR and pool-batch's message
    in error; bad input (non-numbers, |x| > 1e9, non-integer ball ids) raises ValueError; a shot
    the library fails to simulate (out of memory) raises PoolError."""
    lay = load_layout(layout)
    ids = lay.ball_ids
    if ball is None:
        base_ball = lay.strike_ball if lay.strike_ball is not None else ids[0]
    else:
        base_ball = _ffi_int32(ball, "ball")
        if base_ball not in ids:
            raise ValueError(f"ball: no ball of the layout has id {base_ball}")
    ball_col, values = _strike_table(strikes, base_ball, lay.strike)
    n, m = len(ball_col), len(ids)
    if workers is None:
        workers = os.cpu_count() or 1
    workers = int(workers)
    if workers < 1:
        raise ValueError("workers: must be >= 1")
    workers = max(1, min(workers, n))
    c_strikes = np.empty(n, dtype=np.dtype(_scenario.CBatchStrike))
    c_strikes["ball"] = ball_col
    for j, k in enumerate(STRIKE_FIELDS[1:]):
        c_strikes[k] = values[:, j]
    c_layout, c_balls = _c_layout(lay)
    shots = _Shots(n, m, max(1, int(chunk)), lay.game is not None)
    args = (c_layout, shots, c_strikes)
    if workers == 1:
        _worker(*args)
    else:
        threads = [threading.Thread(target=_worker, args=args, daemon=True)
                   for _ in range(workers)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    del c_balls  # the C layout pointed to it until here
    if shots.failure is not None:
        raise shots.failure
    refused = shots.stop == STOP_ERROR
    pos, state = shots.pos, shots.state
    pos[refused] = math.nan
    state[refused] = -1
    return BatchResult(
        ball_ids=np.array(ids, dtype=np.int32), ball=ball_col, strikes=values,
        stop_reason=shots.stop, error=shots.error, events=shots.events,
        end_time=shots.end_time, first_hit=shots.first_hit, pos=pos, state=state,
        pocketed=state == _MOTION_POCKETED, off_table=state == _MOTION_OFF_TABLE,
        **({"legal": shots.legal, "fouls": shots.fouls, "outcome": shots.outcome,
            "points": shots.points} if lay.game is not None else {}))


def _ffi_int32(v, name):
    if isinstance(v, bool) or int(v) != v or not -2 ** 31 <= int(v) < 2 ** 31:
        raise ValueError(f"{name}: must be a 32-bit integer")
    return int(v)
