"""Many strikes on one layout, on several threads: libpool.batch.run (the Python side of
pool-batch, docs/commands.md). Needs NumPy.

    import libpool.batch
    res = libpool.batch.run("rack.json", [(0, 8.0, 0.0, 0.0, 0.0, 0.0),
                                          (0, 7.5, 1.0, 0.0, 0.0, -0.01)], workers=2)
    res.stop_reason, res.events, res.end_time, res.first_hit, res.pos, res.state, res.pocketed

Each worker thread owns one C simulation, reset for every shot it takes; pool_sim_run is called
without the GIL, so the threads simulate in parallel. Every shot depends only on the layout and
its strike, so the arrays are identical whatever `workers` is, and each row holds exactly the
values of pool-batch's row for the same layout and strike.
"""

import json
import math
import os
import struct
import threading
from ctypes import PyDLL, byref, c_double, c_int, c_int32, c_void_p, string_at

import numpy as np

from . import MODEL_KINDS, PoolError, _ffi, _model_set, _model_value, model_names
from ._ffi import BallState as CBallState, Error as CError, SimDef, Strike

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

_PI = 3.14159265358979323846
_DEG = _PI / 180.0  # as the scenario parser and pool-batch convert degrees
_MAX_ABS = 1e9      # the scenario parser's and pool-batch's limit on numbers
_EV_BALL_BALL, _EV_LINK_BEGIN = 4, 9
_MOTION_POCKETED, _MOTION_OFF_TABLE = 6, 7
_ERR_OUT_OF_MEMORY, _ERR_INTERNAL = -3, -11
_FORMAT = "libpool-scenario/1"
_BALL_SIZE = struct.calcsize("=ii9d")
_EVENT_SIZE = 32
_ID = struct.Struct("=i")
BALL_DTYPE = np.dtype([("id", "<i4"), ("motion", "<i4"), ("pos", "<f8", 3), ("vel", "<f8", 3),
                       ("omega", "<f8", 3)])
assert BALL_DTYPE.itemsize == _BALL_SIZE == 80
_STRIKE_DTYPE = np.dtype([("speed", "<f8"), ("phi", "<f8"), ("theta", "<f8"), ("a", "<f8"),
                          ("b", "<f8")])
assert _STRIKE_DTYPE.itemsize == 40


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


def _fail(message):
    raise ValueError("layout: " + message)


def _reject_duplicates(pairs):
    out = {}
    for k, v in pairs:
        if k in out:
            raise ValueError(f"layout: (document): duplicate object key {k!r}")
        out[k] = v
    return out


def _reject_constant(name):
    raise ValueError(f"layout: (document): {name} is not valid JSON")


def _is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _number(v, path):
    if not _is_number(v):
        _fail(f"{path}: must be a number")
    x = float(v)
    if not math.isfinite(x):
        _fail(f"{path}: must be a finite number")
    if abs(x) > _MAX_ABS:
        _fail(f"{path}: {x:g} is too large (limit {_MAX_ABS:g})")
    return x


def _integer(v, path, lo, hi):
    if not isinstance(v, int) or isinstance(v, bool):
        _fail(f"{path}: must be an integer")
    if not lo <= v <= hi:
        _fail(f"{path}: {v} is out of range [{lo}, {hi}]")
    return v


def _fields(obj, path, allowed):
    for k in obj:
        if k not in allowed:
            if not k:
                _fail(f"{path or '(document)'}: unknown field \"\"")
            _fail(f"{path}.{k}: unknown field" if path else f"{k}: unknown field")


def _vec(v, path, min_n, start):
    if not isinstance(v, list) or not min_n <= len(v) <= 3:
        _fail(f"{path}: must be an array of 3 numbers" if min_n == 3
              else f"{path}: must be an array of {min_n} or 3 numbers")
    c = list(start)
    for i, x in enumerate(v):
        c[i] = _number(x, f"{path}[{i}]")
    return c


def _lib_message(path, code, err):
    """The scenario parser's fail_lib: the library's message, prefixed with path unless it
    already names a field."""
    message = err.message.decode("utf-8", "replace") if err.message else ""
    if not message:
        message = _ffi.load().pool_result_str(code).decode()
    for root in (path, "table", "params", "balls", "strike", "options", "models"):
        if message.startswith(root) and message[len(root):len(root) + 1] in (".", ":", "["):
            return message
    return f"{path}: {message}"


def _set_models(d, name, path):
    """Sets d.models to the model set `name` (the library's), or fails naming `path`."""
    try:
        d.models = _model_set(name, path)
    except PoolError as e:
        _fail(e.message)


def _derive_motion(pos, vel, omega, r):
    if pos[2] > r + 1e-9 or vel[2] != 0.0:
        return 4
    ux, uy = vel[0] - r * omega[1], vel[1] + r * omega[0]
    if ux != 0.0 or uy != 0.0:
        return 2
    if vel[0] != 0.0 or vel[1] != 0.0:
        return 3
    if omega[2] != 0.0:
        return 1
    return 0


def layout_text(layout):
    """The JSON text of a layout given as a path (str or os.PathLike), JSON text (a str or bytes
    whose first non-blank character is "{") or a dict; TypeError for anything else."""
    if isinstance(layout, dict):
        return json.dumps(layout)
    if isinstance(layout, (bytes, bytearray)):
        return layout.decode("utf-8")
    if isinstance(layout, str) and layout.lstrip().startswith("{"):
        return layout
    if isinstance(layout, (str, os.PathLike)):
        with open(layout, encoding="utf-8") as f:
            return f.read()
    raise TypeError("layout: expected a path, JSON text or a dict, got "
                    f"{type(layout).__name__}")


# The table's numeric fields of a scenario (docs/interfaces.md): cut angles in degrees.
_TABLE_NUMBERS = ("length", "width", "cushion_height", "corner_mouth", "side_mouth",
                  "corner_cut_angle", "side_cut_angle", "corner_jaw_radius", "side_jaw_radius",
                  "corner_shelf", "side_shelf", "corner_hole_radius", "side_hole_radius")


def load_layout(layout):
    """A Layout from a path (str or os.PathLike), JSON text (a str whose first non-blank character
    is "{") or an already parsed dict, by the rules of pool-sim's scenario parser (the same
    fields, ranges and library checks). Raises ValueError naming the field."""
    if isinstance(layout, Layout):
        return layout
    text = layout_text(layout)
    try:
        doc = json.loads(text, object_pairs_hook=_reject_duplicates, parse_constant=_reject_constant)
    except json.JSONDecodeError as e:
        _fail(f"(document): malformed JSON at line {e.lineno}, column {e.colno}: {e.msg}")
    return _parse_document(doc)


def _parse_document(doc):
    lib = _ffi.load()
    if not isinstance(doc, dict):
        _fail("(document): must be a JSON object")
    _fields(doc, "", ("format", "name", "description", "table", "params", "balls", "strike",
                      "options", "models", "game"))
    if "format" not in doc:
        _fail(f'format: missing (expected "{_FORMAT}")')
    if doc["format"] != _FORMAT:
        _fail(f'format: expected "{_FORMAT}"')
    for k in ("name", "description"):
        if k in doc and not isinstance(doc[k], str):
            _fail(f"{k}: must be a string")
    d = lib.pool_default_sim_def()
    err = CError()
    # table (a preset's balls and cloth become the params' defaults, as in pool-sim)
    t = doc.get("table")
    preset = None
    presets = "wpa-9ft, wpa-8ft, wpa-7ft, snooker, carom"
    if isinstance(t, str):  # "table": "wpa-8ft" is short for {"preset": "wpa-8ft"}
        if "\0" in t or lib.pool_table_preset(t.encode(), byref(d.table)) != 0:
            _fail(f'table: unknown preset "{t}" ({presets})')
        preset, t = t, None
    if t is not None:
        if not isinstance(t, dict):
            _fail("table: must be a preset name or an object")
        _fields(t, "table", ("preset",) + _TABLE_NUMBERS + ("pockets",))
        if "preset" in t:
            if not isinstance(t["preset"], str):
                _fail("table.preset: must be a string")
            if "\0" in t["preset"] or lib.pool_table_preset(t["preset"].encode(),
                                                             byref(d.table)) != 0:
                _fail(f'table.preset: unknown preset "{t["preset"]}" ({presets})')
            preset = t["preset"]
        if "pockets" in t:
            if t["pockets"] not in ("mouth_lines", "jaws", "none"):
                _fail('table.pockets: must be "jaws", "mouth_lines" or "none"')
            d.table.pockets = ("mouth_lines", "jaws", "none").index(t["pockets"])
        for k in _TABLE_NUMBERS:
            if k in t:
                v = _number(t[k], f"table.{k}")
                setattr(d.table, k, v * (math.pi / 180.0) if k.endswith("cut_angle") else v)
        r = lib.pool_table_def_validate(byref(d.table), byref(err))
        if r != 0:
            _fail(_lib_message("table", r, err))
    if preset is not None:
        lib.pool_params_preset(preset.encode(), byref(d.params))
    # params
    p = doc.get("params")
    if p is not None:
        if not isinstance(p, dict):
            _fail("params: must be an object")
        names = [n for n, _ in _ffi.Params._fields_]
        for k, v in p.items():
            if k not in names:
                _fail('params: unknown field ""' if not k else f"params.{k}: unknown field")
            setattr(d.params, k, _number(v, f"params.{k}"))
        r = lib.pool_params_validate(byref(d.params), byref(err))
        if r != 0:
            _fail(_lib_message("params", r, err))
    # options
    o = doc.get("options")
    if o is not None:
        if not isinstance(o, dict):
            _fail("options: must be an object")
        _fields(o, "options", ("airborne", "max_time", "max_events"))
        if "airborne" in o:
            if not isinstance(o["airborne"], bool):
                _fail("options.airborne: must be true or false")
            d.airborne = o["airborne"]
        if "max_time" in o:
            d.max_time = _number(o["max_time"], "options.max_time")
            if not d.max_time > 0.0:
                _fail("options.max_time: must be > 0")
        if "max_events" in o:
            d.max_events = _integer(o["max_events"], "options.max_events", 1, 2 ** 31 - 1)
    # models: a set's name, or an object whose "set" each kind overrides by a name the library
    # knows (the parser's parse_models)
    m = doc.get("models")
    if m is not None:
        if isinstance(m, str):
            _set_models(d, m, "models")
            m = {}
        if not isinstance(m, dict):
            _fail("models: must be a model set name or an object")
        _fields(m, "models", ("set",) + MODEL_KINDS)
        if "set" in m:
            _set_models(d, m["set"], "models.set")
        for kind in MODEL_KINDS:
            if kind not in m:
                continue
            if not isinstance(m[kind], str):
                _fail(f"models.{kind}: must be a string")
            value = _model_value(kind, m[kind])
            if value is None:
                _fail(f'models.{kind}: unknown model "{m[kind]}" ({", ".join(model_names(kind))})')
            setattr(d.models, kind, value)
    # balls
    if "balls" not in doc:
        _fail("balls: missing")
    balls_doc = doc["balls"]
    if not isinstance(balls_doc, list) or not balls_doc:
        _fail("balls: must be a non-empty array")
    if len(balls_doc) > 10000:
        _fail("balls: too many balls (limit 10000)")
    radius = d.params.ball_radius
    balls = []
    for i, b in enumerate(balls_doc):
        path = f"balls[{i}]"
        if not isinstance(b, dict):
            _fail(f"{path}: must be an object")
        _fields(b, path, ("id", "pos", "vel", "omega"))
        if "id" not in b:
            _fail(f"{path}.id: missing")
        bid = _integer(b["id"], f"{path}.id", -2 ** 31, 2 ** 31 - 1)
        if "pos" not in b:
            _fail(f"{path}.pos: missing")
        pos = _vec(b["pos"], f"{path}.pos", 2, (0.0, 0.0, radius))
        vel = _vec(b["vel"], f"{path}.vel", 2, (0.0, 0.0, 0.0)) if "vel" in b else [0.0] * 3
        omega = _vec(b["omega"], f"{path}.omega", 3, (0.0, 0.0, 0.0)) if "omega" in b else [0.0] * 3
        s = CBallState(bid, _derive_motion(pos, vel, omega, radius), _ffi.Vec3(*pos),
                       _ffi.Vec3(*vel), _ffi.Vec3(*omega))
        balls.append(s)
    # strike (the base strike), degrees kept as written
    strike_ball, strike = None, None
    s = doc.get("strike")
    if s is not None:
        if not isinstance(s, dict):
            _fail("strike: must be an object")
        _fields(s, "strike", STRIKE_FIELDS)
        if "ball" not in s:
            _fail("strike.ball: missing")
        strike_ball = _integer(s["ball"], "strike.ball", -2 ** 31, 2 ** 31 - 1)
        if strike_ball not in [b.id for b in balls]:
            _fail(f"strike.ball: no ball has id {strike_ball}")
        if "speed" not in s:
            _fail("strike.speed: missing")
        speed = _number(s["speed"], "strike.speed")
        rest = []
        for k in ("phi", "theta", "a", "b"):
            x = _number(s[k], f"strike.{k}") if k in s else 0.0
            if k == "theta" and not (0.0 <= x < 90.0):
                _fail("strike.theta: must be in [0, 90) degrees")
            rest.append(x)
        strike = (speed, *rest)
    layout = Layout(d, balls, strike_ball, strike, _parse_game(doc.get("game"), balls, strike))
    if d.airborne:
        _check_airborne(layout)
    else:
        _check_with_sim(layout)
    return layout


def _parse_game(game_doc, balls, strike):
    """The scenario parser's parse_game: rules and state, the balls a table of those rules, and
    a strike for the rules to judge."""
    if game_doc is None:
        return None
    from . import game
    if not isinstance(game_doc, dict):
        _fail('game: must be an object ("rules", "state")')
    _fields(game_doc, "game", ("rules", "state"))
    if "rules" not in game_doc:
        _fail("game.rules: missing (8ball, 9ball, three_cushion)")
    rules = game_doc["rules"]
    if not isinstance(rules, str):
        _fail("game.rules: must be a string (8ball, 9ball, three_cushion)")
    if rules not in game.RULES:
        _fail(f'game.rules: unknown rules "{rules}" (8ball, 9ball, three_cushion)')
    try:
        state = game.State.from_dict(rules, game_doc.get("state"))
    except ValueError as e:
        _fail(str(e))
    err = CError()
    arr = (CBallState * max(len(balls), 1))(*balls)
    c_state = state._to_c()
    if game._load().pool_game_check_balls(byref(c_state), arr, len(balls), byref(err)) != 0:
        _fail(err.message.decode("utf-8", "replace"))
    if strike is None:
        _fail("game: the rules judge a struck shot: the scenario needs a strike")
    return state


_TOUCH = 1e-9  # POOL_TOUCH_TOLERANCE
_MAX_SPEED = 100.0  # POOL_MAX_SPEED


def _strike_c(strike):
    speed, phi, theta, a, b = strike
    return Strike(speed, phi * _DEG, theta * _DEG, a, b)


def _check_airborne(layout):
    """The scenario parser's check_airborne: 3D positions (z >= R) and vertical velocities; the
    library's planar rules on each ball's projection on the cloth; 3D overlaps; the struck ball
    at rest on the cloth."""
    lib = _ffi.load()
    planar = SimDef.from_buffer_copy(layout.sim_def)
    planar.airborne = False
    err = CError()
    sim = c_void_p()
    r = lib.pool_sim_create(byref(planar), byref(sim), byref(err))
    if r != 0:
        _fail(_lib_message("options", r, err))
    try:
        radius = layout.sim_def.params.ball_radius
        balls = layout.balls
        for j, b in enumerate(balls):
            if b.pos.z < radius - _TOUCH:
                _fail(f"balls[{j}].pos: below the cloth (z = {b.pos.z:.9g} m, the centre of a "
                      f"ball on the cloth is at z = R = {radius:.9g} m)")
            if b.pos.z < radius:
                b.pos.z = radius
            v = b.vel
            if math.sqrt(v.x * v.x + v.y * v.y + v.z * v.z) > _MAX_SPEED:
                _fail(f"balls[{j}].vel: speed above the {_MAX_SPEED:g} m/s limit (POOL_MAX_SPEED)")
            for i in range(j):
                bi = balls[i]
                if bi.id == b.id:
                    _fail(f"balls[{j}].id: duplicate id {b.id} (also balls[{i}])")
                dx, dy, dz = b.pos.x - bi.pos.x, b.pos.y - bi.pos.y, b.pos.z - bi.pos.z
                depth = 2.0 * radius - math.sqrt(dx * dx + dy * dy + dz * dz)
                if depth > _TOUCH:
                    _fail(f"balls[{j}].pos: overlaps ball {bi.id} by {depth:.3g} m")
            projected = CBallState.from_buffer_copy(b)
            projected.pos.z = radius
            projected.vel.z = 0.0
            err = CError()
            r = lib.pool_sim_reset(sim, byref(planar), byref(err))
            if r == 0:
                r = lib.pool_sim_add_ball(sim, byref(projected), byref(err))
            if r != 0:
                message = err.message.decode("utf-8", "replace")
                if message.startswith("balls[0]"):
                    _fail(f"balls[{j}]" + message[len("balls[0]"):])
                _fail(_lib_message(f"balls[{j}]", r, err))
            b.motion = _derive_motion((b.pos.x, b.pos.y, b.pos.z), tuple(b.vel), tuple(b.omega),
                                      radius)
        if layout.strike is not None:
            b = next(x for x in balls if x.id == layout.strike_ball)
            if b.pos.z > radius + _TOUCH or b.vel.z != 0.0:
                _fail(f"strike.ball: ball {layout.strike_ball} must be at rest on the cloth to "
                      "be struck")
            projected = CBallState.from_buffer_copy(b)
            projected.pos.z = radius
            st = _strike_c(layout.strike)
            err = CError()
            r = lib.pool_sim_reset(sim, byref(planar), byref(err))
            if r == 0:
                r = lib.pool_sim_add_ball(sim, byref(projected), byref(err))
            if r == 0:
                vel, omega, err = _ffi.Vec3(), _ffi.Vec3(), CError()
                r = lib.pool_strike_velocities(byref(layout.sim_def.params), byref(st),
                                               byref(vel), byref(omega), byref(err))
            if r == 0:
                err = CError()
                r = lib.pool_sim_strike(sim, layout.strike_ball, byref(st), byref(err))
            if r != 0:
                _fail(_lib_message("strike", r, err))
    finally:
        lib.pool_sim_destroy(sim)


def _check_with_sim(layout):
    """The library's own checks of the balls (and the base strike), as the parser makes them."""
    lib = _ffi.load()
    err = CError()
    sim = c_void_p()
    r = lib.pool_sim_create(byref(layout.sim_def), byref(sim), byref(err))
    if r != 0:
        _fail(_lib_message("options", r, err))
    try:
        radius = layout.sim_def.params.ball_radius
        balls = layout.balls
        for j, bj in enumerate(balls):
            for i in range(j):
                bi = balls[i]
                if bi.id == bj.id:
                    _fail(f"balls[{j}].id: duplicate id {bj.id} (also balls[{i}])")
                dx, dy, dz = bj.pos.x - bi.pos.x, bj.pos.y - bi.pos.y, bj.pos.z - bi.pos.z
                depth = 2.0 * radius - math.sqrt(dx * dx + dy * dy + dz * dz)
                if depth > 1e-9:  # POOL_TOUCH_TOLERANCE
                    _fail(f"balls[{j}].pos: overlaps ball {bi.id} by {depth:.3g} m")
        for i, b in enumerate(balls):
            err = CError()
            r = lib.pool_sim_add_ball(sim, byref(b), byref(err))
            if r != 0:
                _fail(_lib_message(f"balls[{i}]", r, err))
        if layout.strike is not None:
            speed, phi, theta, a, b = layout.strike
            st = Strike(speed, phi * _DEG, theta * _DEG, a, b)
            vel, omega, err = _ffi.Vec3(), _ffi.Vec3(), CError()
            r = lib.pool_strike_velocities(byref(layout.sim_def.params), byref(st), byref(vel),
                                           byref(omega), byref(err))
            if r == 0:
                err = CError()
                r = lib.pool_sim_strike(sim, layout.strike_ball, byref(st), byref(err))
            if r != 0:
                _fail(_lib_message("strike", r, err))
    finally:
        lib.pool_sim_destroy(sim)


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


_fast = None
_fast_lock = threading.Lock()


def _fast_functions():
    """The short calls from a PyDLL handle: they keep the GIL (no hand-over between threads for
    a call of a microsecond); pool_sim_run from the binding's CDLL handle, which releases it."""
    global _fast
    if _fast is None:
        with _fast_lock:
            if _fast is None:
                cdll = _ffi.load()
                py = PyDLL(_ffi.library_path())
                fns = {}
                for name in ("pool_sim_reset", "pool_sim_add_ball", "pool_sim_strike",
                             "pool_sim_events", "pool_sim_event_states", "pool_sim_end_time",
                             "pool_sim_stop_reason", "pool_sim_state_at", "pool_sim_time"):
                    f = getattr(py, name)
                    restype, _ = _ffi._PROTOTYPES[name]
                    f.restype = restype if name not in ("pool_sim_events",
                                                        "pool_sim_event_states") else c_void_p
                    f.argtypes = None  # arguments are passed as ready ctypes objects
                    fns[name] = f
                fns["pool_sim_run"] = cdll.pool_sim_run
                _fast = fns
    return _fast


class _Shots:
    """Output arrays and the shared claim counter."""

    def __init__(self, n, m, chunk):
        self.n, self.m, self.chunk = n, m, chunk
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


def _worker(layout, shots, ball, c_strikes, bad_theta, fns):
    lib = _ffi.load()
    err = CError()
    sim = c_void_p()
    try:
        r = lib.pool_sim_create(byref(layout.sim_def), byref(sim), byref(err))
        if r != 0:
            raise PoolError(r, err.message.decode("utf-8", "replace"))
        _shoot(layout, shots, ball, c_strikes, bad_theta, fns, sim, err)
    except BaseException as e:  # reported by run(); stops the other workers too
        with shots.lock:
            if shots.failure is None:
                shots.failure = e
    finally:
        if sim:
            lib.pool_sim_destroy(sim)


def _shoot(layout, shots, ball, c_strikes, bad_theta, fns, sim, err):
    reset, add, strike = fns["pool_sim_reset"], fns["pool_sim_add_ball"], fns["pool_sim_strike"]
    run_, events_, states_ = fns["pool_sim_run"], fns["pool_sim_events"], fns["pool_sim_event_states"]
    end_time_, stop_, state_at_ = (fns["pool_sim_end_time"], fns["pool_sim_stop_reason"],
                                   fns["pool_sim_state_at"])
    time_ = fns["pool_sim_time"]
    lib = _ffi.load()
    m = shots.m
    def_p = byref(layout.sim_def)
    err_p = byref(err)
    ball_ps = [byref(b) for b in layout.balls]
    count = c_int()
    count_p = byref(count)
    strike_base = c_strikes.ctypes.data
    # Final states of a chunk of shots, copied to the outputs once the chunk is done.
    final = np.zeros((shots.chunk, m), dtype=BALL_DTYPE)
    final_base = final.ctypes.data
    final_pos, final_motion = final["pos"], final["motion"]
    row_size = m * _BALL_SIZE
    ev_stop, ev_events, ev_end, ev_hit, errors = (shots.stop, shots.events, shots.end_time,
                                                  shots.first_hit, shots.error)
    balls_list = ball.tolist()
    bad_list = bad_theta.tolist()
    while True:
        span = shots.claim()
        if span is None:
            return
        i0, i1 = span
        for i in range(i0, i1):
            b = balls_list[i]
            if bad_list[i]:
                ev_stop[i] = STOP_ERROR
                errors[i] = "strike.theta: must be in [0, 90) degrees"
                continue
            r = reset(sim, def_p, err_p)
            if r == 0:
                for bp in ball_ps:
                    r = add(sim, bp, err_p)
                    if r:
                        break
            if r == 0:
                r = strike(sim, c_int32(b), c_void_p(strike_base + 40 * i), err_p)
            if r != 0:
                message = err.message.decode("utf-8", "replace") or \
                    lib.pool_result_str(r).decode()
                err.message = b""  # clean for the next shot (successful calls leave it alone)
                if r in (_ERR_OUT_OF_MEMORY, _ERR_INTERNAL):
                    raise PoolError(r, f"shot {i}: {message}")
                ev_stop[i] = STOP_ERROR
                errors[i] = message if message.startswith("strike") else "strike: " + message
                continue
            r = run_(sim)
            t_end = end_time_(sim)
            if r == 0:
                r = state_at_(sim, c_double(t_end), c_void_p(final_base + row_size * (i - i0)))
            if r != 0:
                raise PoolError(r, "shot %d: simulation failed at t = %.17g s: %s" % (
                    i, time_(sim), lib.pool_sim_last_error(sim).decode("utf-8", "replace")))
            ev_stop[i] = stop_(sim)
            ev_end[i] = t_end
            if layout.game is not None:
                from . import game
                g = game.judge_shot(sim, layout.sim_def.table, layout.game, lib)
                shots.legal[i] = g.legal
                shots.fouls[i] = sum(1 << game.FOULS.index(f) for f in g.fouls)
                shots.outcome[i] = game.OUTCOMES.index(g.outcome)
                shots.points[i] = g.points
            evs = events_(sim, count_p)
            n = count.value
            ev_events[i] = n
            # First ball the struck ball hits: the first ball_ball or link_begin event whose
            # balls include it (pool-batch's first_hit).
            if n:
                raw = string_at(evs, n * _EVENT_SIZE)
                types = memoryview(raw).cast("i")[2::8]
                for k, ty in enumerate(types):
                    if ty != _EV_BALL_BALL and ty != _EV_LINK_BEGIN:
                        continue
                    ev = c_void_p(evs + k * _EVENT_SIZE)
                    nb = _ID.unpack_from(raw, k * _EVENT_SIZE + 20)[0]  # ball_count
                    after = string_at(states_(sim, ev), nb * _BALL_SIZE)
                    ids = [_ID.unpack_from(after, j * _BALL_SIZE)[0] for j in range(nb)]
                    if b in ids:
                        for x in ids:
                            if x != b:
                                ev_hit[i] = x
                                break
                        break
        shots.pos[i0:i1] = final_pos[:i1 - i0]
        shots.state[i0:i1] = final_motion[:i1 - i0]


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
    c_strikes = np.empty(n, dtype=_STRIKE_DTYPE)
    c_strikes["speed"] = values[:, 0]
    c_strikes["phi"] = values[:, 1] * _DEG
    c_strikes["theta"] = values[:, 2] * _DEG
    c_strikes["a"] = values[:, 3]
    c_strikes["b"] = values[:, 4]
    theta = values[:, 2]
    bad_theta = ~((theta >= 0.0) & (theta < 90.0))
    shots = _Shots(n, m, max(1, int(chunk)))
    fns = _fast_functions()
    args = (lay, shots, ball_col, c_strikes, bad_theta, fns)
    if workers == 1:
        _worker(*args)
    else:
        threads = [threading.Thread(target=_worker, args=args, daemon=True)
                   for _ in range(workers)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
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
