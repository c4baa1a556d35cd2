"""ctypes mirrors and prototypes of libpool_scenario (scenario/include/pool/scenario.h and
pool/batch.h): the scenario parser, the result writer and the batch shot the commands use, so
libpool.batch reads a layout and shoots exactly as pool-sim and pool-batch do, and Sim.result is
the document pool-sim writes. tests/python checks every size and
offset against a C program compiled from those headers.
"""

import ctypes
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


LIBRARY = _ffi.Companion("libpool_scenario.so", "LIBPOOL_SCENARIO_PATH", "scenario", _PROTOTYPES,
                         needs=(game.LIBRARY,),
                         hint=" (which builds it when jansson is installed: libjansson-dev)")


def library_path():
    """Where libpool_scenario.so is: bundled next to this file (pip install ./python), else
    $LIBPOOL_SCENARIO_PATH, else beside the libpool.so in use when that is a build tree's, else
    the repository's build/release tree, else the system's library search."""
    return LIBRARY.path()


def load():
    """The loaded libpool_scenario with its prototypes set (once; safe from several threads)."""
    return LIBRARY.load()
