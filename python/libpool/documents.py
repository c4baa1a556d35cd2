"""A Sim as the documents the commands read and write (docs/interfaces.md): its layout as a
libpool-scenario/1 dict, its shot as a libpool-result/1 dict (pool-sim's own writer, from
libpool_scenario), and the result file written for pool-plot and pool-view.
"""
import ctypes
import json
import math
import os
import tempfile

from . import PoolError, Sim, _ffi, _finite, models_dict

__all__ = ["layout", "result", "write_result", "sim_from_layout"]

_TABLE_FIELDS = ("length", "width", "cushion_height", "corner_mouth", "side_mouth")
_PARAM_FIELDS = tuple(n for n, _ in _ffi.Params._fields_)


_POCKETS_MODELS = ("mouth_lines", "jaws", "none")
# The geometry of pockets "jaws" as results and scenarios write it (cut angles in degrees).
_JAW_FIELDS = ("corner_cut_angle", "side_cut_angle", "corner_jaw_radius", "side_jaw_radius",
               "corner_shelf", "side_shelf", "corner_hole_radius", "side_hole_radius")


def _table(t):
    table = {k: getattr(t, k) for k in _TABLE_FIELDS}
    table["pockets"] = _POCKETS_MODELS[t.pockets] if 0 <= t.pockets < 3 else "unknown"
    if t.pockets == 1:
        for k in _JAW_FIELDS:
            v = getattr(t, k)
            table[k] = v * 180.0 / math.pi if k.endswith("cut_angle") else v
    return table


def _definition(sim):
    d = sim.definition
    return d, _table(d.table), {k: getattr(d.params, k) for k in _PARAM_FIELDS}


def _models(d):
    # Always: a document says which laws it means, whatever a reader's defaults are (a
    # zero-initialised pool_models is thesis, not the defaults).
    return models_dict(d.models)


def layout(sim, t=None):
    with sim.lock:
        if t is None:
            t = sim.end_time if sim.stop_reason is not None else sim.time
        t = _finite(t, "t")
        balls = sim.state_at(t)
        d, table, params = _definition(sim)
        R = d.params.ball_radius
        out = []
        for b in balls:
            if b.motion in ("pocketed", "off_table"):
                continue
            ball = {"id": b.id, "pos": [b.pos[0], b.pos[1]] if b.pos[2] == R else list(b.pos)}
            if any(b.vel):
                ball["vel"] = list(b.vel) if b.vel[2] != 0.0 else [b.vel[0], b.vel[1]]
            if any(b.omega):
                ball["omega"] = list(b.omega)
            out.append(ball)
        doc = {"format": "libpool-scenario/1", "table": table, "params": params, "balls": out,
               "options": {"airborne": bool(d.airborne), "max_time": d.max_time,
                           "max_events": d.max_events}}
        doc["models"] = _models(d)
    return doc


def sim_from_layout(cls, source, strike=True):
    from . import batch
    lay = batch.load_layout(source)
    d = lay.sim_def
    sim = cls(table=d.table, params=d.params, max_time=d.max_time, max_events=d.max_events,
              airborne=bool(d.airborne), models=d.models)
    try:
        sim._add_c(lay.balls)
        if strike and lay.strike is not None:
            sim.strike(lay.strike_ball, *lay.strike)
    except BaseException:
        sim.close()
        raise
    return sim


def result(sim, sample_dt=None):
    """pool-sim's result document of the simulation: written by the scenario library's writer
    (pool_result_json, the one pool-sim calls), read back as a dict."""
    if sample_dt is not None:
        sample_dt = _finite(sample_dt, "sample_dt")
        if not sample_dt > 0.0:
            raise PoolError(-1, f"sample_dt: must be > 0 s, got {sample_dt!r}")
    from . import _scenario
    lib = _scenario.load()
    with sim.lock:
        d = sim.definition
        options = _scenario.CResultOptions(sample_dt or 0.0, False, ctypes.pointer(d), None)
        text = lib.pool_result_json(sim._p(), ctypes.byref(options))
    if not text:
        raise MemoryError("result: out of memory writing the document")
    try:
        return json.loads(ctypes.string_at(text).decode("utf-8"))
    finally:
        lib.pool_scenario_text_free(text)


def write_result(path, source, sample_dt=None, pretty=False):
    if isinstance(source, Sim):
        doc = result(source, sample_dt)
    elif isinstance(source, dict):
        if sample_dt is not None:
            raise TypeError("sample_dt: only with a Sim (a result dict is written as it is)")
        doc = source
    else:
        raise TypeError(f"source: expected a Sim or a result dict, got {type(source).__name__}")
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path: expected a path, got {type(path).__name__}")
    text = json.dumps(doc, indent=2 if pretty else None, allow_nan=False) + "\n"
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=".libpool-result-", dir=directory)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
