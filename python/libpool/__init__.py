"""libpool from Python: exact, event-driven pool (billiards) shots through ctypes.

    import libpool
    with libpool.Sim() as sim:
        sim.rack("8ball")
        sim.break_strike(8.0)
        sim.run()
        print(sim.pocketed)

Angles are DEGREES in this module (as in the scenario files); the C API takes radians.
Lengths in metres, speeds in m/s, spins in rad/s. Failed calls raise PoolError.

Threads: every Sim has a lock (Sim.lock) that each of its methods holds while it uses the C
simulation, so calls on one Sim from several threads run one at a time; close() waits for a call
running in another thread. Everything returned is a Python copy that close() cannot invalidate.
"""

import math
import numbers
import struct
import sys
import threading
from ctypes import addressof, byref, c_double, c_int, c_void_p, cast, sizeof, string_at
from dataclasses import dataclass
from typing import Optional, Tuple

from . import _ffi
from ._ffi import Allocator, BallState as CBallState, Error as CError, Event as CEvent, Params
from ._ffi import Models, SimDef, Strike, TableDef, Vec3, library_path

__all__ = [
    "PoolError", "Ball", "EventRecord", "Sim", "TableDef", "Params", "Strike", "SimDef", "Vec3",
    "Allocator", "table_preset", "params_preset", "default_table", "default_params", "default_sim_def",
    "validate_table", "validate_params", "strike_velocities", "rack", "break_strike",
    "quartic_real_roots", "quartic_smallest_root_in", "library_path", "RESULT_NAMES",
    "Models", "MODEL_KINDS", "model_names", "make_models", "models_dict", "model_sets",
    "default_models", "thesis_models",
    "version", "ball_on_cloth", "MOTION_NAMES", "EVENT_TYPES", "STOP_REASONS", "write_result",
]

# pool_result values by name (pool/base.h).
RESULT_NAMES = {
    0: "POOL_OK", -1: "POOL_ERR_INVALID_ARGUMENT", -2: "POOL_ERR_NON_FINITE",
    -3: "POOL_ERR_OUT_OF_MEMORY", -4: "POOL_ERR_OVERLAP", -5: "POOL_ERR_OFF_TABLE",
    -6: "POOL_ERR_DUPLICATE_ID", -7: "POOL_ERR_UNKNOWN_BALL", -8: "POOL_ERR_BAD_STRIKE",
    -9: "POOL_ERR_UNKNOWN_PRESET", -10: "POOL_ERR_STATE", -11: "POOL_ERR_INTERNAL",
}
_ERR_INVALID_ARGUMENT = -1
_ERR_NON_FINITE = -2
_ERR_STATE = -10
# Names by code, as in result files and pool/ball.h, pool/event.h, pool/sim.h.
MOTION_NAMES = ("stationary", "spinning", "sliding", "rolling", "airborne", "linked", "pocketed",
                "off_table")
EVENT_TYPES = ("strike", "slide_roll", "roll_stop", "spin_stop", "ball_ball", "ball_cushion",
               "ball_table", "pocket", "off_table", "link_begin", "link_step", "link_end")
STOP_REASONS = ("none", "rest", "max_time", "max_events")
_STOP_NAMES = {0: None, 1: "rest", 2: "max_time", 3: "max_events"}
_RACKS = {"8ball": 0, "9ball": 1, "snooker": 2, "carom": 3}
_MOTION_POCKETED = 6
# Records are plain slotted dataclasses: frozen ones cost about twice as much to build, and a
# break builds a few hundred of them.
_DATACLASS_OPTS = {"slots": True} if sys.version_info >= (3, 10) else {}
_DEG = math.pi / 180.0  # the factor pool-sim's scenario parser uses, so results match bit for bit


def _lib():
    return _ffi.load()


class PoolError(Exception):
    """A libpool call failed. code: the pool_result (negative int); name: e.g. "POOL_ERR_OVERLAP";
    reason: pool_result_str(code); message: the pool_error message naming the field (may be "")."""

    def __init__(self, code, message=""):
        self.code = int(code)
        self.name = RESULT_NAMES.get(self.code, "POOL_ERR_UNKNOWN")
        self.reason = _lib().pool_result_str(self.code).decode()
        self.message = message
        super().__init__(f"{message} ({self.reason})" if message else self.reason)


def _check(code, err=None):
    if code < 0:
        raise PoolError(code, err.message.decode("utf-8", "replace") if err is not None else "")
    return code


# Strict arguments: a bool is not a number, a string is not a number, a float is not an id; the
# message names the argument. Types raise TypeError, values PoolError (POOL_ERR_INVALID_ARGUMENT
# or POOL_ERR_NON_FINITE), as the library's own checks do.

def _type_name(v):
    return type(v).__name__


def _real(v, name):
    """v as a float: any real number (int, float, NumPy scalars), never a bool or a string."""
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        raise TypeError(f"{name}: expected a number, got {_type_name(v)} {v!r}")
    return float(v)


def _finite(v, name):
    x = _real(v, name)
    if not math.isfinite(x):
        raise PoolError(_ERR_NON_FINITE, f"{name}: must be a finite number, got {x!r}")
    return x


def _bool(v, name):
    if not isinstance(v, bool) and type(v).__name__ != "bool_":  # Python's or NumPy's bool
        raise TypeError(f"{name}: expected True or False, got {_type_name(v)} {v!r}")
    return bool(v)


def _vec_values(v, name):
    """The numbers of a sequence, each checked (a string is refused, not iterated)."""
    if isinstance(v, (str, bytes)) or not hasattr(v, "__len__"):
        raise TypeError(f"{name}: expected a sequence of numbers, got {_type_name(v)} {v!r}")
    return tuple(_finite(x, f"{name}[{i}]") for i, x in enumerate(v))


def _vec(v, name):
    t = _vec_values(v, name)
    if len(t) != 3:
        raise PoolError(_ERR_INVALID_ARGUMENT, f"{name}: expected 3 numbers, got {len(t)}")
    return Vec3(*t)


def _c_string(value, name):
    """value as the bytes of a C string argument. C reads a string up to its first NUL, so
    "wpa-9ft\\x00x" would silently arrive as "wpa-9ft": a NUL is refused, as is text that has no
    UTF-8 form (lone surrogates) and anything that is not a str (ValueError / TypeError naming
    the argument)."""
    if not isinstance(value, str):
        raise TypeError(f"{name}: expected a str, got {type(value).__name__}")
    if "\0" in value:
        raise ValueError(f"{name}: contains a NUL character: {value!r}")
    try:
        return value.encode("utf-8")
    except UnicodeEncodeError:
        raise ValueError(f"{name}: not valid text (no UTF-8 form): {value!r}") from None


def _int32(v, name):
    """An int (or NumPy integer) in the 32-bit range: 3.0, "3" and True are refused."""
    if isinstance(v, bool) or not isinstance(v, numbers.Integral):
        raise TypeError(f"{name}: expected an int, got {_type_name(v)} {v!r}")
    if not -2**31 <= int(v) < 2**31:
        raise PoolError(_ERR_INVALID_ARGUMENT, f"{name}: must be a 32-bit integer, got {v}")
    return int(v)


@dataclass(**_DATACLASS_OPTS)
class Ball:
    """One ball's state: id, motion name ("sliding", "pocketed", ...), pos, vel, omega (tuples)."""
    id: int
    motion: str
    pos: Tuple[float, float, float]
    vel: Tuple[float, float, float]
    omega: Tuple[float, float, float]

    @staticmethod
    def _from_c(s):
        return Ball(s.id, _motion_name(s.motion), (s.pos.x, s.pos.y, s.pos.z),
                    (s.vel.x, s.vel.y, s.vel.z), (s.omega.x, s.omega.y, s.omega.z))


@dataclass(**_DATACLASS_OPTS)
class EventRecord:
    """One processed event: time (s), type name ("ball_ball", ...), ids of the balls involved,
    rail and pocket names (None when not applicable), the balls' states just after it, and the
    part of the cushion a ball_cushion event touched ("nose", "facing", "jaw"; None otherwise)."""
    time: float
    type: str
    balls: Tuple[int, ...]
    rail: Optional[str]
    pocket: Optional[str]
    after: Tuple[Ball, ...]
    part: Optional[str] = None


_name_cache = {}


def _name(fn, value):
    key = (fn, value)
    if key not in _name_cache:
        s = getattr(_lib(), fn)(value)
        _name_cache[key] = s.decode() if s is not None else None
    return _name_cache[key]


def _name_table(fn):
    return lambda value: _name(fn, value)


def _motion_name(m):
    return _name("pool_motion_name", m)


# Raw layouts for bulk reads (one string_at + iter_unpack instead of a ctypes attribute access
# per number); checked against the ctypes mirrors at import, which the tests check against C.
_BALL_FMT = struct.Struct("=ii9d")
_EVENT_FMT = struct.Struct("=d6i")  # time, type, rail, pocket, ball_count, first_state, part
assert _BALL_FMT.size == sizeof(CBallState) and _EVENT_FMT.size == sizeof(CEvent)


def _copy_balls(ptr, n):
    """The bytes of n pool_ball_state at ptr: a copy, so later calls and close() may free them."""
    return string_at(ptr, n * _BALL_FMT.size) if n > 0 else b""


def _unpack_balls(raw):
    """Ball records from bytes copied by _copy_balls."""
    return [Ball(i, _motion_name(m), (px, py, pz), (vx, vy, vz), (wx, wy, wz))
            for i, m, px, py, pz, vx, vy, vz, wx, wy, wz in _BALL_FMT.iter_unpack(raw)]


# ---- tables, parameters, strikes, racks --------------------------------------------------------

def default_table():
    """The WPA 9 ft table (pool_default_table_def)."""
    return _lib().pool_default_table_def()


def table_preset(name):
    """A TableDef by preset name: "wpa-9ft", "wpa-8ft", "wpa-7ft", "snooker", "carom". A name
    holding a NUL character raises ValueError (TypeError if not a str); an unknown one, PoolError.
    Snooker and carom are played with their own balls and cloth: params_preset."""
    return _table_preset(name, "table_preset: name")


def params_preset(name):
    """The Params a table preset is played with (its balls and cloth; pool_params_preset)."""
    p = Params()
    code = _lib().pool_params_preset(_c_string(name, "params_preset: name"), byref(p))
    if code < 0:
        raise PoolError(code, f"table.preset: unknown preset '{name}'")
    return p


def _table_preset(name, arg):
    t = TableDef()
    code = _lib().pool_table_preset(_c_string(name, arg), byref(t))
    if code < 0:
        raise PoolError(code, f"table.preset: unknown preset '{name}'")
    return t


def default_params():
    """docs/physics.md defaults (pool_default_params); edit the fields, e.g. p.mu_slide = 0.25."""
    return _lib().pool_default_params()


def default_sim_def():
    """pool_default_sim_def(): WPA 9 ft, default params, planar, max_time 120 s, 100000 events,
    the default models (default_models())."""
    return _lib().pool_default_sim_def()


def validate_table(table):
    """Raises PoolError naming the field if the table is invalid."""
    err = CError()
    _check(_lib().pool_table_def_validate(byref(table), byref(err)), err)


def validate_params(params):
    """Raises PoolError naming the field if a parameter is out of range."""
    err = CError()
    _check(_lib().pool_params_validate(byref(params), byref(err)), err)


def make_strike(speed, phi_deg=0.0, theta_deg=0.0, a=0.0, b=0.0):
    """A C Strike from degrees (converted as pool-sim converts the scenario file's degrees).
    Numbers only (TypeError otherwise); theta_deg in [0, 90) degrees (PoolError naming it)."""
    speed = _finite(speed, "strike.speed")
    phi = _finite(phi_deg, "strike.phi_deg")
    theta = _finite(theta_deg, "strike.theta_deg")
    if not 0.0 <= theta < 90.0:
        raise PoolError(_ERR_INVALID_ARGUMENT,
                        f"strike.theta_deg: must be in [0, 90) degrees, got {theta:g}")
    return Strike(speed, phi * _DEG, theta * _DEG, _finite(a, "strike.a"), _finite(b, "strike.b"))


def strike_velocities(speed, phi_deg=0.0, theta_deg=0.0, a=0.0, b=0.0, params=None):
    """(vel, omega) the strike gives a ball at rest, as tuples (pool_strike_velocities)."""
    p = params if params is not None else default_params()
    s = make_strike(speed, phi_deg, theta_deg, a, b)
    vel, omega, err = Vec3(), Vec3(), CError()
    _check(_lib().pool_strike_velocities(byref(p), byref(s), byref(vel), byref(omega),
                                         byref(err)), err)
    return tuple(vel), tuple(omega)


def break_strike(speed):
    """pool_break_strike: centre ball, level cue, straight at the apex (a C Strike, radians)."""
    return _lib().pool_break_strike(_finite(speed, "break_strike.speed"))


def version():
    """The version of the libpool.so in use: (major, minor, patch), from pool_version()."""
    v = _lib().pool_version()
    return (v // 10000, v // 100 % 100, v % 100)


def ball_on_cloth(id, x, y, params=None):
    """A Ball at rest on the cloth at (x, y) m: z = the ball radius of params (default
    default_params()), no velocity or spin (pool_ball_on_cloth)."""
    bid = _int32(id, "ball.id")
    px, py = _finite(x, "ball.x"), _finite(y, "ball.y")
    if params is not None and not isinstance(params, Params):
        raise TypeError(f"params: expected a Params, got {_type_name(params)}")
    p = params if params is not None else default_params()
    return Ball._from_c(_lib().pool_ball_on_cloth(bid, px, py, byref(p)))


def rack(kind, gap=0.0, table=None, params=None):
    """The balls of a standard rack ("8ball" or "9ball"; cue ball id 0 first) as Ball records;
    gap in metres between neighbours (0 = frozen)."""
    return [Ball._from_c(s) for s in _rack_c(kind, gap, table, params)]


def _rack_c(kind, gap, table, params):
    if not isinstance(kind, str):
        raise TypeError(f"rack: kind: expected a str, got {_type_name(kind)}")
    if kind not in _RACKS:
        raise PoolError(_ERR_INVALID_ARGUMENT,
                        f"rack: unknown kind '{kind}' (8ball, 9ball, snooker or carom)")
    t = table if table is not None else default_table()
    p = params if params is not None else default_params()
    out = (CBallState * 32)()
    n = _check(_lib().pool_rack(_RACKS[kind], byref(t), byref(p), _finite(gap, "rack.gap"), out,
                                32))
    return out[:n]


# ---- models (docs/physics.md "Models") ------------------------------------------------------

# The keys of a scenario's "models" object, with the C functions naming their models.
MODEL_KINDS = ("cushion", "ball_ball_friction", "squirt")
_MODEL_FUNCTIONS = {
    "cushion": ("pool_cushion_model_name", "pool_cushion_model_from_name"),
    "ball_ball_friction": ("pool_ball_friction_model_name", "pool_ball_friction_model_from_name"),
    "squirt": ("pool_squirt_model_name", "pool_squirt_model_from_name"),
}
_MAX_MODELS_PER_KIND = 16  # model enumerations are small; bounds the search for their names


def model_names(kind):
    """The names of one kind's models, the thesis law first, as the library knows them:
    model_names("cushion") == ["petit", "mathavan2010"]. An unknown kind raises PoolError."""
    if kind not in _MODEL_FUNCTIONS:
        raise PoolError(_ERR_INVALID_ARGUMENT,
                        f"models.{kind}: unknown field ({', '.join(MODEL_KINDS)})")
    name_fn, from_name = _MODEL_FUNCTIONS[kind]
    names = []
    for m in range(_MAX_MODELS_PER_KIND):
        name = _name(name_fn, m)
        # A value is a model when its name reads back as itself (the library's one list).
        if name is not None and getattr(_lib(), from_name)(name.encode()) == m:
            names.append(name)
    return names


def _model_value(kind, name):
    """The enum value of a model by name, or None when the library does not know it."""
    if not isinstance(name, str) or "\0" in name:
        return None
    try:
        encoded = name.encode("utf-8")
    except UnicodeEncodeError:
        return None
    value = getattr(_lib(), _MODEL_FUNCTIONS[kind][1])(encoded)
    return value if value >= 0 else None


def model_sets():
    """The names of the model sets, as the library knows them: ["default", "thesis"]."""
    names, i = [], 0
    while (name := _lib().pool_models_preset_name(i)) is not None:
        names.append(name.decode())
        i += 1
    return names


def default_models():
    """The default laws (a Models): "mathavan2010" cushions, "alciatore" ball-ball friction, no
    squirt: the measured ones (docs/physics.md "Models")."""
    return _lib().pool_default_models()


def thesis_models():
    """The "thesis" model set (a Models, all zero): the 2012 work's laws, "petit", "constant",
    "none", which were the defaults before issue 25."""
    return _lib().pool_thesis_models()


def _model_set(name, path):
    """The Models of a set by name, or PoolError naming `path`."""
    out = Models()
    if isinstance(name, str) and "\0" not in name:
        try:
            if _lib().pool_models_preset(name.encode("utf-8"), byref(out)) == 0:
                return out
        except UnicodeEncodeError:
            pass
    elif not isinstance(name, str):
        raise PoolError(_ERR_INVALID_ARGUMENT, f"{path}: must be a string")
    raise PoolError(_ERR_INVALID_ARGUMENT,
                    f'{path}: unknown model set "{name}" ({", ".join(model_sets())})')


def make_models(models=None, **names):
    """A C Models (pool_models) as a scenario's "models" gives it: None (the defaults), a model
    set's name ("thesis", "default"), a dict of names, make_models({"cushion": "petit"}) or
    make_models(cushion="petit", squirt="endmass"), whose "set" (default "default") is
    overridden kind by kind: make_models({"set": "thesis", "squirt": "endmass"}); or a Models
    (copied; names then override it). Unknown sets, kinds or names raise PoolError
    (POOL_ERR_INVALID_ARGUMENT) naming the field, e.g. 'models.cushion: unknown model "foo"
    (petit, mathavan2010)'."""
    if isinstance(models, Models):
        out = Models.from_buffer_copy(models)
        if not names:
            return out
        models = {}
    elif models is None:
        out, models = default_models(), {}
    elif isinstance(models, str):
        out, models = _model_set(models, "models"), {}
    elif isinstance(models, dict):
        out = _model_set(models["set"], "models.set") if "set" in models else default_models()
        models = {k: v for k, v in models.items() if k != "set"}
    else:
        raise TypeError(f"models: expected a model set name, a dict of names or a Models, got "
                        f"{type(models).__name__}")
    for kind, name in list(models.items()) + list(names.items()):
        if kind not in _MODEL_FUNCTIONS:
            raise PoolError(_ERR_INVALID_ARGUMENT,
                            f"models.{kind}: unknown field ({', '.join(MODEL_KINDS)})")
        value = _model_value(kind, name)
        if value is None:
            raise PoolError(_ERR_INVALID_ARGUMENT,
                            f'models.{kind}: unknown model "{name}" '
                            f"({', '.join(model_names(kind))})")
        setattr(out, kind, value)
    return out


def models_dict(models):
    """A Models as names: {"cushion": "petit", "ball_ball_friction": "constant", "squirt": "none"}
    (None for a value the library has no name for)."""
    return {kind: _name(_MODEL_FUNCTIONS[kind][0], getattr(models, kind)) for kind in MODEL_KINDS}


# ---- quartic ----------------------------------------------------------------------------------

def quartic_real_roots(coeffs):
    """Real roots, ascending with multiplicity, of c0 x^4 + c1 x^3 + c2 x^2 + c3 x + c4
    (coeffs = [c0, ..., c4]; leading zeros give lower degrees)."""
    c = (c_double * 5)(*_five(coeffs))
    r = (c_double * 4)()
    n = _lib().pool_quartic_real_roots(c, r)
    return list(r[:n])


def quartic_smallest_root_in(coeffs, lo, hi):
    """Smallest real root in [lo, hi], or None."""
    c = (c_double * 5)(*_five(coeffs))
    r = c_double()
    n = _lib().pool_quartic_smallest_root_in(c, float(lo), float(hi), byref(r))
    return r.value if n >= 0 else None


def _five(coeffs):
    c = [float(x) for x in coeffs]
    if len(c) != 5:
        raise PoolError(_ERR_INVALID_ARGUMENT, f"coeffs: expected 5 numbers, got {len(c)}")
    return c


# ---- the simulation ---------------------------------------------------------------------------

def _sim_def(table, params, max_time, max_events, airborne, models=None):
    d = default_sim_def()
    if table is not None:
        if isinstance(table, str):
            d.table = _table_preset(table, "table")
            d.params = params_preset(table)  # a preset's own balls and cloth
        elif isinstance(table, TableDef):
            d.table = table
        else:
            raise TypeError(f"table: expected a preset name or a TableDef, got {_type_name(table)}")
    if params is not None:
        if not isinstance(params, Params):
            raise TypeError(f"params: expected a Params (default_params()), got "
                            f"{_type_name(params)}")
        d.params = params
    if max_time is not None:
        d.max_time = _finite(max_time, "max_time")
    if max_events is not None:
        d.max_events = _int32(max_events, "max_events")
    d.airborne = _bool(airborne, "airborne")
    if models is not None:
        d.models = make_models(models)
    return d


class Sim:
    """One pool_sim: add balls, strike, run, read events and states. Use as a context manager or
    call close(); reset() starts a new shot reusing every buffer (the candidate-shot loop).

    table: a preset name ("wpa-9ft"...) or a TableDef; params: a Params (default_params());
    max_time in s, max_events; airborne: True for motion off the cloth (jumps, hops, balls
    leaving the table; False, the default, is planar); models: the laws (docs/physics.md
    "Models"), as make_models takes them: a set's name ("thesis": the 2012 work's laws), a
    dict of names, e.g. {"squirt": "endmass"} or {"set": "thesis", "squirt": "endmass"}
    (kinds not given come from the set, default "default"), or a Models. Without it the
    defaults: "mathavan2010" cushions, "alciatore" ball-ball friction. Their parameters
    (throw_a, throw_b, throw_c, cue_end_mass, e_cushion_mathavan, mu_cushion_mathavan) are
    in params.

    Threads: each method holds the Sim's lock (Sim.lock, reentrant) while it uses the C
    simulation, so calls from several threads run one after the other (a long run() makes the
    others wait); hold the lock yourself to make a sequence of calls atomic. close() waits for a
    call running in another thread, which then returns normally; calls after close() raise
    PoolError (POOL_ERR_STATE, "sim: closed"). What the methods return is copied out of the
    simulation before the lock is released."""

    def __init__(self, table=None, params=None, max_time=None, max_events=None, airborne=False,
                 models=None):
        # Before anything that can raise, so close() and __del__ work on a half-made Sim.
        self._sim = None
        self._lock = threading.RLock()
        self._def = _sim_def(table, params, max_time, max_events, airborne, models)
        lib = _lib()
        # Kept so __del__ can still free the simulation at interpreter shutdown, when the module's
        # globals may already be gone.
        self._destroy = lib.pool_sim_destroy
        handle = c_void_p()
        err = CError()
        _check(lib.pool_sim_create(byref(self._def), byref(handle), byref(err)), err)
        self._sim = handle
        self._count = c_int()  # these three are reused by the hot calls, under the lock
        self._err = CError()
        self._states = None  # state_at buffer, grown to the ball count

    # lifetime
    @property
    def lock(self):
        """The Sim's reentrant lock: `with sim.lock:` makes several calls one atomic step for
        other threads (e.g. reset, rack, strike, run). Every method takes it too."""
        return self._lock

    @property
    def closed(self):
        """True once close() has freed the simulation."""
        return not self._sim

    def close(self):
        """Frees the simulation (idempotent). If another thread is inside a call on this Sim,
        waits for that call to return (it completes normally); later calls raise PoolError."""
        lock = getattr(self, "_lock", None)
        if lock is None:  # __init__ did not get that far
            return
        with lock:
            handle, self._sim = self._sim, None
            if handle:
                self._destroy(handle)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        # Called only once nothing refers to this Sim, so no thread can be inside one of its
        # methods (each holds self): freeing needs no lock, and taking none means a finalizer run
        # by the garbage collector in any thread can never block, even on a lock that a thread
        # took with `with sim.lock:` and still holds.
        handle = getattr(self, "_sim", None)
        if handle:
            self._sim = None
            try:
                self._destroy(handle)
            except Exception:  # nothing to report to from a finalizer
                pass

    # copy.copy would give two Sims one C simulation, freed twice: refused, as is pickling.
    def __copy__(self):
        raise TypeError("a Sim cannot be copied (it owns a C simulation): make another Sim")

    def __deepcopy__(self, memo):
        self.__copy__()

    def __reduce_ex__(self, protocol):
        raise TypeError("a Sim cannot be pickled (it owns a C simulation)")

    def _p(self):
        """The C handle; call with the lock held, and use it only until releasing the lock."""
        if not self._sim:
            raise PoolError(_ERR_STATE, "sim: closed")
        return self._sim

    @property
    def definition(self):
        """The SimDef in use (a copy)."""
        with self._lock:
            src = self._def
            d = SimDef()
            d.table, d.params, d.airborne = src.table, src.params, src.airborne
            d.max_time, d.max_events = src.max_time, src.max_events
            d.models = src.models
        return d

    @property
    def table(self):
        return self.definition.table

    @property
    def params(self):
        return self.definition.params

    @property
    def models(self):
        """The models in use, by name: {"cushion": "mathavan2010", "ball_ball_friction":
        "alciatore", "squirt": "none"} unless chosen otherwise."""
        return models_dict(self.definition.models)

    def reset(self, table=None, params=None, max_time=None, max_events=None, airborne=None,
              models=None):
        """Removes every ball and event (a new shot), keeping memory. With arguments, changes the
        definition too (others keep their current values; models replaces the models as a whole,
        so reset(models={}) goes back to the defaults)."""
        with self._lock:
            p = self._p()
            err = CError()
            self._rack_states = None
            if table is None and params is None and max_time is None and max_events is None \
                    and airborne is None and models is None:
                _check(_lib().pool_sim_reset(p, None, byref(err)), err)
                return
            cur = self._def
            d = _sim_def(table if table is not None else cur.table,
                         params if params is not None else cur.params,
                         max_time if max_time is not None else cur.max_time,
                         max_events if max_events is not None else cur.max_events,
                         airborne if airborne is not None else cur.airborne,
                         models if models is not None else cur.models)
            _check(_lib().pool_sim_reset(p, byref(d), byref(err)), err)
            self._def = d

    # setup
    def add_ball(self, id, pos, vel=(0.0, 0.0, 0.0), omega=(0.0, 0.0, 0.0)):
        """Adds a ball before the shot. pos is (x, y) on the cloth (z = R) or (x, y, z)."""
        with self._lock:
            if type(id) is not int or not -0x80000000 <= id <= 0x7FFFFFFF:
                id = _int32(id, "ball.id")
            pos = _vec_values(pos, "ball.pos")
            if len(pos) == 2:
                pos = (pos[0], pos[1], self._def.params.ball_radius)
            # Vec3(*v) would zero-fill a short sequence silently, hence the length checks.
            s = CBallState(id, 0, _vec(pos, "ball.pos"), _vec(vel, "ball.vel"),
                           _vec(omega, "ball.omega"))
            _check(_lib().pool_sim_add_ball(self._p(), byref(s), byref(self._err)), self._err)

    def _add_c(self, states):
        with self._lock:
            p, err, add = self._p(), self._err, _lib().pool_sim_add_ball
            for s in states:
                _check(add(p, byref(s), byref(err)), err)

    def add_balls(self, balls):
        """Adds Ball records (e.g. from rack() or state_at())."""
        with self._lock:
            for b in balls:
                self.add_ball(b.id, b.pos, b.vel, b.omega)

    def rack(self, kind, gap=0.0):
        """Adds a standard rack ("8ball", "9ball", "snooker" or "carom"; cue ball id 0) for this
        sim's table and ball radius; returns the balls added."""
        with self._lock:
            states = _rack_c(kind, gap, self._def.table, self._def.params)
            self._add_c(states)
            self._rack_states = (CBallState * len(states))(*states)
        return [Ball._from_c(s) for s in states]

    def strike(self, ball_id, speed, phi_deg=0.0, theta_deg=0.0, a=0.0, b=0.0):
        """Cue strike at the current time: speed m/s, phi (aim from +x, counter-clockwise) and
        theta (elevation) in DEGREES, tip offsets a (right) and b (up) in m, a^2 + b^2 < R^2."""
        self.strike_c(ball_id, make_strike(speed, phi_deg, theta_deg, a, b))

    def strike_c(self, ball_id, strike):
        """Cue strike with a C Strike (radians), e.g. break_strike(speed)."""
        ball = _int32(ball_id, "strike.ball")
        with self._lock:
            err = self._err
            _check(_lib().pool_sim_strike(self._p(), ball, byref(strike), byref(err)), err)

    def break_strike(self, speed, ball_id=0):
        """The centre-ball break on the cue ball: aimed at the first object ball of the last
        rack() (pool_rack_break_strike), else straight along +x (pool_break_strike)."""
        racked = getattr(self, "_rack_states", None)
        if racked is not None:
            self.strike_c(ball_id, _lib().pool_rack_break_strike(racked, len(racked), float(speed)))
        else:
            self.strike_c(ball_id, break_strike(speed))

    # running
    def step(self):
        """Processes the next event; False when the shot is over (see stop_reason)."""
        with self._lock:
            return self._run_check(_lib().pool_sim_step(self._p())) == 1

    def run(self):
        """Runs the shot to its end (rest, max_time or max_events); returns stop_reason. Other
        threads' calls on this Sim, close() included, wait until it returns."""
        with self._lock:
            self._run_check(_lib().pool_sim_run(self._p()))
            return self.stop_reason

    def run_until(self, t):
        """Processes every event at or before t (s)."""
        t = _real(t, "t")
        if math.isnan(t):
            raise PoolError(_ERR_INVALID_ARGUMENT, "t: must be a time in s, got nan")
        with self._lock:
            self._run_check(_lib().pool_sim_run_until(self._p(), t))

    def _run_check(self, code):
        """code of a call that runs the shot; a failure raises PoolError with what the library
        says it met (pool_sim_last_error: a LINK step's unsolved LCP, memory running out...).
        Call with the lock held."""
        if code < 0:
            raise PoolError(code, _lib().pool_sim_last_error(self._p()).decode("utf-8", "replace"))
        return code

    # results
    @property
    def stop_reason(self):
        """None while events remain, else "rest", "max_time" or "max_events"."""
        with self._lock:
            return _STOP_NAMES[_lib().pool_sim_stop_reason(self._p())]

    @property
    def time(self):
        """s, time of the last processed event."""
        with self._lock:
            return _lib().pool_sim_time(self._p())

    @property
    def end_time(self):
        """s, the instant the final states belong to: max_time for a shot cut there, else time."""
        with self._lock:
            return _lib().pool_sim_end_time(self._p())

    @property
    def ball_count(self):
        with self._lock:
            return _lib().pool_sim_ball_count(self._p())

    def _balls_bytes(self):
        with self._lock:
            lib, p = _lib(), self._p()
            return _copy_balls(lib.pool_sim_balls(p), lib.pool_sim_ball_count(p))

    @property
    def balls(self):
        """Every ball as of the last event that involved it, by insertion order."""
        return _unpack_balls(self._balls_bytes())

    @property
    def pocketed(self):
        """Ids of the balls pocketed so far."""
        return [rec[0] for rec in _BALL_FMT.iter_unpack(self._balls_bytes())
                if rec[1] == _MOTION_POCKETED]

    @property
    def event_count(self):
        with self._lock:
            _lib().pool_sim_events(self._p(), byref(self._count))
            return self._count.value

    @property
    def events(self):
        """Every processed event, in time order, as EventRecord."""
        with self._lock:
            # Copy the C arrays while holding the lock; build the records after releasing it.
            lib, p = _lib(), self._p()
            evs = lib.pool_sim_events(p, byref(self._count))
            n = self._count.value
            if n == 0:
                return []
            events = list(_EVENT_FMT.iter_unpack(string_at(evs, n * _EVENT_FMT.size)))
            # The after-states of all events live in one array indexed by first_state
            # (pool/event.h); copy it at once when pool_sim_event_states confirms that, else
            # event by event.
            first = cast(lib.pool_sim_event_states(p, evs), c_void_p).value
            last = cast(lib.pool_sim_event_states(p, byref(evs[n - 1])), c_void_p).value
            base = first - events[0][5] * _BALL_FMT.size
            if last == base + events[-1][5] * _BALL_FMT.size:
                shared = _copy_balls(base, max(e[5] + e[4] for e in events))
                apart = None
            else:
                shared = None
                apart = [_copy_balls(lib.pool_sim_event_states(p, byref(evs[i])), e[4])
                         for i, e in enumerate(events)]
        if shared is not None:
            states = _unpack_balls(shared)
            afters = [tuple(states[e[5]:e[5] + e[4]]) for e in events]
        else:
            afters = [tuple(_unpack_balls(raw)) for raw in apart]
        ev_name, rail_name, pocket_name, part_name = (_name_table("pool_event_type_name"),
                                                      _name_table("pool_rail_name"),
                                                      _name_table("pool_pocket_name"),
                                                      _name_table("pool_cushion_part_name"))
        return [EventRecord(t, ev_name(ty), tuple(b.id for b in after), rail_name(r),
                            pocket_name(pk), after, part_name(pt))
                for (t, ty, r, pk, _, _, pt), after in zip(events, afters)]

    def state_at(self, t):
        """Every ball at time t (exact, closed form between events), by insertion order; t must
        not exceed the processed time unless the shot is over."""
        t = _real(t, "t")
        with self._lock:
            lib, p = _lib(), self._p()
            n = lib.pool_sim_ball_count(p)
            if self._states is None or len(self._states) < max(n, 1):
                self._states = (CBallState * max(n, 16))()
            code = lib.pool_sim_state_at(p, t, self._states)
            if code < 0:
                raise PoolError(code, self._time_message("t", t))
            raw = _copy_balls(addressof(self._states), n)
        return _unpack_balls(raw)

    def _time_message(self, name, t):
        """Why pool_sim_state_at refused t, the argument named name (call with the lock held)."""
        if not (t >= 0.0):
            return f"{name}: must be a time >= 0 s, got {t!r}"
        # The library's pool_sim_last_error has the time processed (which a run_until may have
        # taken past the last event); it names its own call and argument ("state_at: t = ...").
        said = _lib().pool_sim_last_error(self._p()).decode("utf-8", "replace")
        detail = said.split(": ", 1)[-1]
        return f"{name} = {detail[4:] if detail.startswith('t = ') else detail}"

    def trajectory(self, times):
        """Every ball's exact state at each of the times (s), as NumPy arrays, in one C call
        (pool_sim_states_at): a Trajectory with t [k], ids [n], pos, vel, omega [k, n, 3] and
        motion [k, n] (codes of MOTION_NAMES). Times need no order; each must be >= 0 and at
        most the processed time (any once the shot is over). Needs NumPy."""
        from . import arrays
        return arrays.trajectory(self, times)

    def history(self):
        """The shot's events and their after-states as NumPy arrays (a History), copied in one
        pass. Needs NumPy."""
        from . import arrays
        return arrays.history(self)

    def layout(self, t=None):
        """A libpool-scenario/1 document (a dict) of this simulation at time t (default: the end
        of what has been processed, the final positions of a finished shot): the table, params,
        options and models, and every ball still in play with its state then; no strike. Feed it
        to libpool.batch.run, pool-sim (json.dump) or another Sim (Sim.from_layout)."""
        from . import documents
        return documents.layout(self, t)

    def result(self, sample_dt=None):
        """The libpool-result/1 document (a dict) of this simulation, as pool-sim writes it
        (events, final, initial, stats, table, params, models; samples every sample_dt s when
        given), for pool-plot and pool-view (libpool.write_result)."""
        from . import documents
        return documents.result(self, sample_dt)

    @classmethod
    def from_layout(cls, layout, strike=True):
        """A Sim set up from a libpool-scenario/1 document (path, JSON text or dict, read by
        libpool.batch.load_layout's rules): its table, params, options, models and balls, and its
        strike applied unless strike=False. Needs NumPy (libpool.batch)."""
        from . import documents
        return documents.sim_from_layout(cls, layout, strike)


def write_result(path, source, sample_dt=None, pretty=False):
    """Writes a libpool-result/1 file: source is a Sim (its result(sample_dt)) or a result dict.
    Written through a temporary file renamed over path (no partial file on failure); missing
    directories are created. For pool-plot and pool-view."""
    from . import documents
    documents.write_result(path, source, sample_dt, pretty)


def __getattr__(name):
    # libpool.batch (NumPy) is imported on first use, so `import libpool` needs nothing but the
    # standard library.
    if name in ("batch", "game", "gym", "aim", "arrays", "documents"):
        import importlib
        return importlib.import_module("." + name, __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
