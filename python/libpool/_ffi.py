"""ctypes mirrors of the public C structures of libpool and the prototypes of its functions.

Layouts follow libpool/include/pool/*.h field by field; tests/python checks every size and offset
against a C program compiled from those headers, so a change on either side fails the tests.
"""

import ctypes
import ctypes.util
import os
import threading
from ctypes import POINTER, c_bool, c_char, c_char_p, c_double, c_int, c_int32, c_void_p

__all__ = [
    "Vec3", "TableDef", "Params", "BallState", "Strike", "Event", "Allocator", "Models", "SimDef",
    "Error",
    "STRUCTS", "load", "library_path", "companion_path", "Companion",
]


class _Struct(ctypes.Structure):
    """Structure with a readable repr and a dict view (names as in the C header)."""

    def as_dict(self):
        """Fields as a dict; nested structures as dicts too."""
        out = {}
        for name, _ in self._fields_:
            v = getattr(self, name)
            out[name] = v.as_dict() if isinstance(v, _Struct) else v
        return out

    def __repr__(self):
        body = ", ".join(f"{n}={getattr(self, n)!r}" for n, _ in self._fields_)
        return f"{type(self).__name__}({body})"


class Vec3(_Struct):
    """pool_vec3: x, y, z (m, m/s or rad/s)."""
    _fields_ = [("x", c_double), ("y", c_double), ("z", c_double)]

    def __iter__(self):
        return iter((self.x, self.y, self.z))

    def __repr__(self):
        return f"Vec3({self.x!r}, {self.y!r}, {self.z!r})"


class TableDef(_Struct):
    """pool_table_def: table geometry in metres, cut angles in RADIANS, pockets a
    pool_pockets_model value (0 mouth_lines, 1 jaws, 2 none)."""
    _fields_ = [("length", c_double), ("width", c_double), ("cushion_height", c_double),
                ("corner_mouth", c_double), ("side_mouth", c_double), ("pockets", c_int),
                ("corner_cut_angle", c_double), ("side_cut_angle", c_double),
                ("corner_jaw_radius", c_double), ("side_jaw_radius", c_double),
                ("corner_shelf", c_double), ("side_shelf", c_double),
                ("corner_hole_radius", c_double), ("side_hole_radius", c_double)]


class Params(_Struct):
    """pool_params: physical parameters, names and units as in docs/physics.md."""
    _fields_ = [(n, c_double) for n in (
        "g", "mu_slide", "mu_roll", "mu_spin", "mu_ball", "e_ball", "mu_cushion", "e_cushion",
        "mu_table", "e_table", "ball_radius", "ball_mass", "cue_mass",
        "throw_a", "throw_b", "throw_c", "cue_end_mass", "e_cushion_mathavan",
        "mu_cushion_mathavan")]


class BallState(_Struct):
    """pool_ball_state: id, motion (pool_motion value), pos, vel, omega."""
    _fields_ = [("id", c_int32), ("motion", c_int), ("pos", Vec3), ("vel", Vec3), ("omega", Vec3)]


class Strike(_Struct):
    """pool_strike: speed m/s, phi and theta in RADIANS (the C convention), a and b in m."""
    _fields_ = [("speed", c_double), ("phi", c_double), ("theta", c_double),
                ("a", c_double), ("b", c_double)]


class Event(_Struct):
    """pool_event: time, type, rail, pocket, ball_count, first_state, part (pool_cushion_part)."""
    _fields_ = [("time", c_double), ("type", c_int), ("rail", c_int), ("pocket", c_int),
                ("ball_count", c_int), ("first_state", c_int), ("part", c_int)]


class Allocator(_Struct):
    """pool_allocator as three pointers (alloc, free, context); leave zero for malloc/free."""
    _fields_ = [("alloc", c_void_p), ("free", c_void_p), ("context", c_void_p)]


class Models(_Struct):
    """pool_models: cushion, ball_ball_friction, squirt (C enum values; all 0 is the "thesis" set)."""
    _fields_ = [("cushion", c_int), ("ball_ball_friction", c_int), ("squirt", c_int)]


class SimDef(_Struct):
    """pool_sim_def: table, params, airborne, max_time, max_events, allocator, models."""
    _fields_ = [("table", TableDef), ("params", Params), ("airborne", c_bool),
                ("max_time", c_double), ("max_events", c_int), ("allocator", Allocator),
                ("models", Models)]


class Error(_Struct):
    """pool_error: the field-naming message of a failed validating call."""
    _fields_ = [("message", c_char * 256)]


# C name -> mirror; the layout test walks this.
STRUCTS = {
    "pool_vec3": Vec3, "pool_table_def": TableDef, "pool_params": Params,
    "pool_ball_state": BallState, "pool_strike": Strike, "pool_event": Event,
    "pool_allocator": Allocator, "pool_models": Models, "pool_sim_def": SimDef, "pool_error": Error,
}

_sim_p = c_void_p  # pool_sim * (opaque)
_E = POINTER(Error)

# name: (restype, argtypes) for every public function of pool/*.h.
_PROTOTYPES = {
    "pool_version": (c_int, []),
    "pool_result_str": (c_char_p, [c_int]),
    "pool_motion_name": (c_char_p, [c_int]),
    "pool_motion_from_name": (c_int, [c_char_p]),
    "pool_event_type_name": (c_char_p, [c_int]),
    "pool_rail_name": (c_char_p, [c_int]),
    "pool_pocket_name": (c_char_p, [c_int]),
    "pool_cushion_part_name": (c_char_p, [c_int]),
    "pool_pockets_model_name": (c_char_p, [c_int]),
    "pool_pockets_model_from_name": (c_int, [c_char_p]),
    "pool_params_preset": (c_int, [c_char_p, POINTER(Params)]),
    "pool_quartic_real_roots": (c_int, [POINTER(c_double), POINTER(c_double)]),
    "pool_quartic_smallest_root_in": (c_int, [POINTER(c_double), c_double, c_double,
                                              POINTER(c_double)]),
    "pool_default_table_def": (TableDef, []),
    "pool_table_preset": (c_int, [c_char_p, POINTER(TableDef)]),
    "pool_default_params": (Params, []),
    "pool_table_def_validate": (c_int, [POINTER(TableDef), _E]),
    "pool_params_validate": (c_int, [POINTER(Params), _E]),
    "pool_strike_velocities": (c_int, [POINTER(Params), POINTER(Strike), POINTER(Vec3),
                                       POINTER(Vec3), _E]),
    "pool_rack": (c_int, [c_int, POINTER(TableDef), POINTER(Params), c_double,
                          POINTER(BallState), c_int]),
    "pool_break_strike": (Strike, [c_double]),
    "pool_rack_break_strike": (Strike, [POINTER(BallState), c_int, c_double]),
    "pool_default_sim_def": (SimDef, []),
    "pool_cushion_model_name": (c_char_p, [c_int]),
    "pool_ball_friction_model_name": (c_char_p, [c_int]),
    "pool_squirt_model_name": (c_char_p, [c_int]),
    "pool_cushion_model_from_name": (c_int, [c_char_p]),
    "pool_ball_friction_model_from_name": (c_int, [c_char_p]),
    "pool_squirt_model_from_name": (c_int, [c_char_p]),
    "pool_default_models": (Models, []),
    "pool_thesis_models": (Models, []),
    "pool_models_preset": (c_int, [c_char_p, POINTER(Models)]),
    "pool_models_preset_name": (c_char_p, [c_int]),
    "pool_stop_reason_name": (c_char_p, [c_int]),
    "pool_ball_on_cloth": (BallState, [c_int32, c_double, c_double, POINTER(Params)]),
    "pool_sim_create": (c_int, [POINTER(SimDef), POINTER(_sim_p), _E]),
    "pool_sim_destroy": (None, [_sim_p]),
    "pool_sim_reset": (c_int, [_sim_p, POINTER(SimDef), _E]),
    "pool_sim_add_ball": (c_int, [_sim_p, POINTER(BallState), _E]),
    "pool_sim_strike": (c_int, [_sim_p, c_int32, POINTER(Strike), _E]),
    "pool_sim_step": (c_int, [_sim_p]),
    "pool_sim_run": (c_int, [_sim_p]),
    "pool_sim_run_until": (c_int, [_sim_p, c_double]),
    "pool_sim_last_error": (c_char_p, [_sim_p]),
    "pool_sim_stop_reason": (c_int, [_sim_p]),
    "pool_sim_time": (c_double, [_sim_p]),
    "pool_sim_end_time": (c_double, [_sim_p]),
    "pool_sim_ball_count": (c_int, [_sim_p]),
    "pool_sim_balls": (POINTER(BallState), [_sim_p]),
    "pool_sim_state_at": (c_int, [_sim_p, c_double, POINTER(BallState)]),
    "pool_sim_states_at": (c_int, [_sim_p, POINTER(c_double), c_int, POINTER(BallState),
                                   POINTER(c_int)]),
    "pool_sim_events": (POINTER(Event), [_sim_p, POINTER(c_int)]),
    "pool_sim_event_states": (POINTER(BallState), [_sim_p, POINTER(Event)]),
}


def library_path():
    """Where libpool.so is: the one bundled in the package (pip install ./python puts it next to
    this file), else $LIBPOOL_PATH, else the repository's build/release tree, else the system's
    library search (ctypes.util.find_library). None when nothing is found."""
    bundled = os.path.join(os.path.dirname(os.path.abspath(__file__)), "libpool.so")
    if os.path.exists(bundled):
        return bundled
    env = os.environ.get("LIBPOOL_PATH")
    if env:
        return env
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    built = os.path.join(repo, "build", "release", "libpool", "libpool.so")
    if os.path.exists(built):
        return built
    return ctypes.util.find_library("pool")


def companion_path(file_name, env, folder):
    """Where a library of the project beside libpool is (libpool_games.so in games/,
    libpool_scenario.so in scenario/): bundled next to this file (pip install ./python), else
    $env, else beside the libpool.so in use when that is a build tree's (build/X/libpool/libpool.so
    -> build/X/folder/file_name), else the repository's build/release tree, else the system's
    library search. None when nothing is found."""
    here = os.path.dirname(os.path.abspath(__file__))
    bundled = os.path.join(here, file_name)
    if os.path.exists(bundled):
        return bundled
    if os.environ.get(env):
        return os.environ[env]
    pool = library_path()
    if pool:
        beside = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(pool))), folder,
                              file_name)
        if os.path.exists(beside):
            return beside
    built = os.path.join(os.path.dirname(os.path.dirname(here)), "build", "release", folder,
                         file_name)
    if os.path.exists(built):
        return built
    return ctypes.util.find_library(file_name[3:-3])  # libNAME.so -> NAME


class Companion:
    """A library of the project beside libpool (libpool_games.so, libpool_scenario.so): found by
    companion_path, loaded on first use after libpool.so and the libraries it needs, with its
    prototypes ({name: (restype, argtypes)}) set; once, safely from several threads."""

    def __init__(self, file_name, env, folder, prototypes, needs=(), hint=""):
        self.file_name, self.env, self.folder = file_name, env, folder
        self.prototypes, self.needs, self.hint = prototypes, needs, hint
        self._lib = None
        self._lock = threading.Lock()

    def path(self):
        return companion_path(self.file_name, self.env, self.folder)

    def load(self):
        lib = self._lib
        if lib is not None:
            return lib
        with self._lock:
            if self._lib is None:
                load()  # libpool.so first, then what this one needs: it links them
                for library in self.needs:
                    library.load()
                path = self.path()
                if path is None:
                    raise OSError(f"{self.file_name} not found: set {self.env}, build the repository "
                                  f"into build/release, or pip install ./python{self.hint}")
                lib = ctypes.CDLL(path)
                for name, (restype, argtypes) in self.prototypes.items():
                    fn = getattr(lib, name)
                    fn.restype, fn.argtypes = restype, argtypes
                self._lib = lib
        return self._lib


_lib = None
_load_lock = threading.Lock()  # two threads' first calls load and set up the library once


def load():
    """The loaded library with every prototype set (loaded once; safe from several threads)."""
    lib = _lib
    if lib is not None:
        return lib
    with _load_lock:
        return _load_locked()


def _load_locked():
    global _lib
    if _lib is None:
        path = library_path()
        if path is None:
            raise OSError("libpool.so not found: set LIBPOOL_PATH, build the repository into "
                          "build/release, or install libpool")
        lib = ctypes.CDLL(path)
        for name, (restype, argtypes) in _PROTOTYPES.items():
            fn = getattr(lib, name)
            fn.restype = restype
            fn.argtypes = argtypes
        _lib = lib
    return _lib
