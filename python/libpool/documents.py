"""A Sim as the documents the commands read and write (docs/interfaces.md): its layout as a
libpool-scenario/1 dict, its shot as a libpool-result/1 dict (pool-sim's), and the result file
written for pool-plot and pool-view.
"""
import json
import math
import os
import tempfile

from . import (EVENT_TYPES, MOTION_NAMES, STOP_REASONS, PoolError, Sim, _ffi, _finite, _lib,
               models_dict)

__all__ = ["layout", "result", "write_result", "sim_from_layout"]

_TABLE_FIELDS = ("length", "width", "cushion_height", "corner_mouth", "side_mouth")
_PARAM_FIELDS = tuple(n for n, _ in _ffi.Params._fields_)
_RAILS = ("south", "north", "west", "east")
_POCKETS = ("sw", "se", "nw", "ne", "s", "n")
_MAX_SAMPLES = 20000  # as pool-sim: a longer grid widens dt


def _state(b):
    return {"id": b.id, "pos": list(b.pos), "vel": list(b.vel), "omega": list(b.omega),
            "state": b.motion}


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


def _samples(sim, events, end, dt):
    """pool-sim --sample DT: the multiples of dt up to end plus every event time; per ball, the
    inside of runs where it does not move dropped, ending where it leaves play."""
    steps = math.floor(end / dt)
    if steps > _MAX_SAMPLES:
        dt = end / _MAX_SAMPLES
        steps = _MAX_SAMPLES
    rate = 1.0 / dt
    whole = rate == math.floor(rate) and rate < 1e15
    times = [(k / rate if whole else k * dt) for k in range(int(steps) + 1)]
    times = [t for t in times if t <= end]
    times += [e.time for e in events if 0.0 <= e.time <= end] + [end]
    times = sorted(set(times))
    traj = sim.trajectory(times)
    pos, motion, ids = traj.pos, traj.motion, traj.ids
    gone = {MOTION_NAMES.index("pocketed"), MOTION_NAMES.index("off_table")}
    balls = []
    n = len(times)
    for b in range(len(ids)):
        last = n - 1
        for k in range(n):
            if int(motion[k, b]) in gone:
                last = k
                break
        keep = []
        for k in range(last + 1):
            if 0 < k < last:
                same_prev = motion[k - 1, b] == motion[k, b] and (pos[k - 1, b] == pos[k, b]).all()
                same_next = motion[k + 1, b] == motion[k, b] and (pos[k + 1, b] == pos[k, b]).all()
                if same_prev and same_next:
                    continue
            keep.append(k)
        balls.append({"id": int(ids[b]), "t": [times[k] for k in keep],
                      "pos": [pos[k, b].tolist() for k in keep]})
    return {"dt": dt, "balls": balls}


def result(sim, sample_dt=None):
    if sample_dt is not None:
        sample_dt = _finite(sample_dt, "sample_dt")
        if not sample_dt > 0.0:
            raise PoolError(-1, f"sample_dt: must be > 0 s, got {sample_dt!r}")
    with sim.lock:
        d, table, params = _definition(sim)
        events = sim.events
        end = sim.end_time
        final = sim.state_at(end)
        doc = {"format": "libpool-result/1", "table": table, "ball_radius": d.params.ball_radius,
               "params": params}
        doc["models"] = _models(d)
        doc["initial"] = [_state(b) for b in sim.state_at(0.0)]
        out_events = []
        for e in events:
            ev = {"t": e.time, "type": e.type, "balls": list(e.balls)}
            if e.rail is not None:
                ev["rail"] = e.rail
            if e.part is not None:
                ev["part"] = e.part
            if e.pocket is not None:
                ev["pocket"] = e.pocket
            ev["after"] = [_state(b) for b in e.after]
            out_events.append(ev)
        doc["events"] = out_events
        doc["final"] = [_state(b) for b in final]
        counts = {}
        for e in events:
            counts[e.type] = counts.get(e.type, 0) + 1
        stop = sim.stop_reason
        doc["stats"] = {
            "events": len(events), "sim_time": sim.time, "end_time": end,
            "stop_reason": stop if stop is not None else STOP_REASONS[0],
            "balls": len(final),
            "event_counts": {t: counts[t] for t in EVENT_TYPES if t in counts},
            "pocketed": [b.id for b in final if b.motion == "pocketed"],
            "off_table": [b.id for b in final if b.motion == "off_table"],
        }
        if sample_dt is not None and final:
            doc["samples"] = _samples(sim, events, end, sample_dt)
    return doc


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
