"""A shot as NumPy arrays: Sim.trajectory(times) and Sim.history(), each one C call.

    traj = sim.trajectory(np.linspace(0, sim.end_time, 1000))
    traj.pos[:, 0, :2]          # the cue ball's (x, y) at every time, m
    hist = sim.history()
    hist.time[hist.type == libpool.EVENT_TYPES.index("ball_ball")]
"""
from ctypes import byref, c_int, c_void_p, cast, string_at

import numpy as np

from . import EVENT_TYPES, MOTION_NAMES, PoolError, _lib, _type_name

__all__ = ["Trajectory", "History", "BALL_DTYPE", "EVENT_DTYPE", "trajectory", "history"]

# pool_ball_state and pool_event as NumPy records (the layouts of pool/ball.h and pool/event.h;
# tests/python checks them against the C structures).
BALL_DTYPE = np.dtype([("id", "<i4"), ("motion", "<i4"), ("pos", "<f8", 3), ("vel", "<f8", 3),
                       ("omega", "<f8", 3)])
EVENT_DTYPE = np.dtype([("time", "<f8"), ("type", "<i4"), ("rail", "<i4"), ("pocket", "<i4"),
                        ("ball_count", "<i4"), ("first_state", "<i4"), ("part", "<i4")])
assert BALL_DTYPE.itemsize == 80 and EVENT_DTYPE.itemsize == 32


class Trajectory:
    """Every ball at k times (n balls, insertion order):

    t       float64 [k]        s, the times asked for, in their order
    ids     int32 [n]          ball ids
    pos     float64 [k, n, 3]  m, centres
    vel     float64 [k, n, 3]  m/s
    omega   float64 [k, n, 3]  rad/s
    motion  int8 [k, n]        pool_motion codes (MOTION_NAMES[code])
    states  the raw pool_ball_state records [k, n] (BALL_DTYPE) the arrays are views of
    """
    __slots__ = ("t", "ids", "pos", "vel", "omega", "motion", "states")

    def __init__(self, t, states):
        self.t = t
        self.states = states
        self.ids = states["id"][0].copy() if len(states) else np.zeros(states.shape[1], "<i4")
        self.pos, self.vel, self.omega = states["pos"], states["vel"], states["omega"]
        self.motion = states["motion"].astype(np.int8)

    def motion_names(self):
        """motion as names ("rolling", "pocketed", ...), a list of lists."""
        return [[MOTION_NAMES[m] for m in row] for row in self.motion.tolist()]

    def __repr__(self):
        return f"Trajectory({len(self.t)} times, {len(self.ids)} balls)"


class History:
    """The events of a shot and their after-states (E events, S states):

    time         float64 [E]      s
    type         int8 [E]         EVENT_TYPES[code]
    rail         int8 [E]         pool_rail (0 south, 1 north, 2 west, 3 east; -1 none)
    pocket       int8 [E]         pool_pocket (sw, se, nw, ne, s, n; -1 none)
    part         int8 [E]         pool_cushion_part of a cushion event (0 nose, 1 facing, 2 jaw; -1 none)
    ball_count   int32 [E]        balls the event involved
    first        int32 [E]        index of its first after-state in the arrays below
    event        int32 [S]        the event each state follows
    ids          int32 [S]        ball id
    pos, vel, omega float64 [S, 3], motion int8 [S]: the state just after the event
    """
    __slots__ = ("time", "type", "rail", "pocket", "part", "ball_count", "first", "event", "ids",
                 "pos", "vel", "omega", "motion")

    def type_names(self):
        return [EVENT_TYPES[t] for t in self.type.tolist()]

    def after(self, i):
        """The slice of the state arrays holding event i's after-states."""
        return slice(int(self.first[i]), int(self.first[i] + self.ball_count[i]))

    def __repr__(self):
        return f"History({len(self.time)} events, {len(self.ids)} states)"


def _times(times):
    """times as a contiguous float64 array: numbers only (a string or a bool is not a time)."""
    if isinstance(times, (str, bytes)):
        raise TypeError(f"times: expected numbers, got {_type_name(times)}")
    a = np.asarray(times)
    if a.dtype.kind not in "iuf":
        raise TypeError(f"times: expected numbers, got an array of {a.dtype}")
    a = np.ascontiguousarray(a, dtype=np.float64)
    if a.ndim > 1:
        raise PoolError(-1, f"times: expected a sequence of times, got an array of shape {a.shape}")
    return a.reshape(-1)


def trajectory(sim, times):
    t = _times(times)
    lib = _lib()
    bad = c_int(-1)
    with sim.lock:
        p = sim._p()
        n = lib.pool_sim_ball_count(p)
        out = np.empty((len(t), n), dtype=BALL_DTYPE)
        code = lib.pool_sim_states_at(p, t.ctypes.data_as(lib.pool_sim_states_at.argtypes[1]),
                                      len(t), out.ctypes.data_as(lib.pool_sim_states_at.argtypes[3]),
                                      byref(bad))
        if code < 0:
            i = bad.value
            raise PoolError(code, sim._time_message(f"times[{i}]", float(t[i])) if i >= 0 else "")
    return Trajectory(t, out)


def history(sim):
    lib = _lib()
    count = c_int()
    with sim.lock:
        p = sim._p()
        evs = lib.pool_sim_events(p, byref(count))
        n = count.value
        events = np.frombuffer(string_at(evs, n * EVENT_DTYPE.itemsize), dtype=EVENT_DTYPE) \
            if n else np.zeros(0, EVENT_DTYPE)
        if n:
            # Every event's after-states lie in one array, indexed by first_state (pool/event.h).
            first = cast(lib.pool_sim_event_states(p, evs), c_void_p).value
            base = first - int(events["first_state"][0]) * BALL_DTYPE.itemsize
            total = int((events["first_state"] + events["ball_count"]).max())
            states = np.frombuffer(string_at(base, total * BALL_DTYPE.itemsize), dtype=BALL_DTYPE)
        else:
            states = np.zeros(0, BALL_DTYPE)
    h = History()
    h.time = events["time"].copy()
    h.type = events["type"].astype(np.int8)
    h.rail = events["rail"].astype(np.int8)
    h.pocket = events["pocket"].astype(np.int8)
    h.part = events["part"].astype(np.int8)  # pool_cushion_part: -1, nose 0, facing 1, jaw 2
    h.ball_count = events["ball_count"].copy()
    h.first = events["first_state"].copy()
    # Only the states that follow an event (the history also keeps the balls' initial states).
    index = np.concatenate([np.arange(f, f + c) for f, c in zip(h.first, h.ball_count)]) \
        if n else np.zeros(0, np.int64)
    picked = states[index]
    h.event = np.repeat(np.arange(n, dtype=np.int32), h.ball_count)
    h.first = (np.cumsum(h.ball_count) - h.ball_count).astype(np.int32)
    h.ids = picked["id"].copy()
    h.pos, h.vel, h.omega = picked["pos"].copy(), picked["vel"].copy(), picked["omega"].copy()
    h.motion = picked["motion"].astype(np.int8)
    return h
