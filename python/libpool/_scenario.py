"""ctypes mirrors and prototypes of libpool_scenario (scenario/include/pool/scenario.h and
pool/batch.h): the scenario parser, the result writer and the batch shot the commands use, so
libpool.batch reads a layout and shoots exactly as pool-sim and pool-batch do, and Sim.result is
the document pool-sim writes. tests/python checks every size and
offset against a C program compiled from those headers.
"""

import ctypes
import threading
from ctypes import POINTER, c_bool, c_char, c_char_p, c_double, c_int, c_int32, c_size_t, c_void_p

from . import _ffi, game
from ._ffi import BallState, SimDef, Strike

__all__ = ["CBatchStrike", "CScenario", "CBatchShot", "CResultOptions", "STRUCTS", "MESSAGE_SIZE",
           "load", "library_path"]

MESSAGE_SIZE = 512        # POOL_SCENARIO_MESSAGE_SIZE
BATCH_MESSAGE_SIZE = 400  # POOL_BATCH_MESSAGE_SIZE


class CBatchStrike(ctypes.Structure):
    """pool_batch_strike: ball, speed m/s, phi and theta in DEGREES, a and b in m."""
    _fields_ = [("ball", c_int32), ("speed", c_double), ("phi", c_double), ("theta", c_double),
                ("a", c_double), ("b", c_double)]


class CScenario(ctypes.Structure):
    """pool_scenario (its C field "def" is sim_def here, a Python keyword otherwise)."""
    _fields_ = [("sim_def", SimDef), ("ball_count", c_int), ("balls", POINTER(BallState)),
                ("has_strike", c_bool), ("strike_ball", c_int), ("strike", Strike),
                ("written", CBatchStrike), ("has_game", c_bool), ("game", game.CState)]


class CBatchShot(ctypes.Structure):
    """pool_batch_shot: one shot's record."""
    _fields_ = [("result", c_int), ("failed", c_bool), ("stop_reason", c_int), ("events", c_int),
                ("end_time", c_double), ("hit", c_bool), ("first_hit", c_int32),
                ("judged", c_bool), ("game", game.CResult),
                ("message", c_char * BATCH_MESSAGE_SIZE)]


class CResultOptions(ctypes.Structure):
    """pool_result_options (its C field "def" is sim_def here)."""
    _fields_ = [("sample_dt", c_double), ("pretty", c_bool), ("sim_def", POINTER(SimDef)),
                ("game", POINTER(game.CState))]


# C name -> (mirror, {C field: mirror field} where they differ); the layout test walks this.
STRUCTS = {"pool_batch_strike": (CBatchStrike, {}), "pool_scenario": (CScenario, {"def": "sim_def"}),
           "pool_batch_shot": (CBatchShot, {}),
           "pool_result_options": (CResultOptions, {"def": "sim_def"})}

_sim_p = c_void_p
_PROTOTYPES = {
    "pool_scenario_parse": (c_int, [c_char_p, c_size_t, POINTER(CScenario), c_char_p, c_size_t]),
    "pool_scenario_free": (None, [POINTER(CScenario)]),
    "pool_batch_run": (c_int, [POINTER(CScenario), POINTER(CBatchStrike), c_int, POINTER(_sim_p),
                               POINTER(CBatchShot), POINTER(BallState)]),
    # The text is freed by pool_scenario_text_free: a c_void_p, not a c_char_p ctypes would copy.
    "pool_result_json": (c_void_p, [_sim_p, POINTER(CResultOptions)]),
    "pool_scenario_text_free": (None, [c_void_p]),
}


def library_path():
    """Where libpool_scenario.so is: bundled next to this file (pip install ./python), else
    $LIBPOOL_SCENARIO_PATH, else beside the libpool.so in use when that is a build tree's, else
    the repository's build/release tree, else the system's library search."""
    return _ffi.companion_path("libpool_scenario.so", "LIBPOOL_SCENARIO_PATH", "scenario")


_lib = None
_lock = threading.Lock()


def load():
    """The loaded libpool_scenario with its prototypes set (once; safe from several threads)."""
    global _lib
    if _lib is not None:
        return _lib
    with _lock:
        if _lib is None:
            _ffi.load()  # libpool.so and libpool_games.so first: libpool_scenario.so needs them
            game._load()
            path = library_path()
            if path is None:
                raise OSError("libpool_scenario.so not found: set LIBPOOL_SCENARIO_PATH, build the "
                              "repository into build/release, or pip install ./python (which "
                              "builds it when jansson is installed: libjansson-dev)")
            lib = ctypes.CDLL(path)
            for name, (restype, argtypes) in _PROTOTYPES.items():
                fn = getattr(lib, name)
                fn.restype, fn.argtypes = restype, argtypes
            _lib = lib
    return _lib
