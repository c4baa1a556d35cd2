#!/usr/bin/env python3
"""Thread, lifetime and C-string safety of the Python binding (python/libpool).

One Sim used from several threads, close() during run() in another thread, __del__, results
outliving close(), and strings with NUL characters: none may crash the interpreter, and each
behaves as the Sim docstring says. Runs under unittest (ctest) or pytest.

Usage: test_safety.py [unittest args]  (LIBPOOL_PATH names the shared library; PYTHONPATH
holds python/.)
"""

import copy
import ctypes
import gc
import pickle
import random
import sys
import threading
import time
import unittest

import libpool
from libpool import PoolError, _ffi

THREADS = 6


def break_shot(sim):
    sim.rack("9ball", gap=1e-4)
    sim.break_strike(7.0)


def crowded_shot(sim, nx=20, ny=10):
    """nx * ny balls in a grid and a strike into them: a run() of about 20 ms (2000 events)."""
    t, R = sim.table, sim.params.ball_radius
    dx, dy = (t.length - 4 * R) / nx, (t.width - 4 * R) / ny
    for ix in range(nx):
        for iy in range(ny):
            sim.add_ball(ix * ny + iy, (2 * R + dx * (ix + 0.5), 2 * R + dy * (iy + 0.5)))
    sim.strike(0, 8.0, phi_deg=33.0)


class Watch:
    """Stands in for the loaded library (libpool._ffi._lib): forwards every call and counts the
    calls on one simulation handle that overlap in time with another call on it, and calls that
    reach a handle already destroyed. The binding's lock must keep both at zero. It also keeps
    when each pool_sim_run started and returned and when each pool_sim_destroy started (read
    inside the binding's lock, so their order is not blurred by thread scheduling)."""

    def __init__(self, real):
        self._real = real
        self._mu = threading.Lock()
        self._active = {}  # handle address -> calls in progress
        self._dead = set()  # handle addresses destroyed and not created again
        self.overlaps = 0
        self.after_destroy = 0
        self.calls = 0
        self.runs = []  # (start, end) of pool_sim_run
        self.destroys = []  # start of pool_sim_destroy
        self._wrapped = {}

    def __getattr__(self, name):
        fn = getattr(self._real, name)
        if not name.startswith("pool_sim_"):
            return fn
        if name not in self._wrapped:
            self._wrapped[name] = self._wrap(name, fn)
        return self._wrapped[name]

    def _wrap(self, name, fn):
        def call(handle, *args):
            if name == "pool_sim_create":
                out = fn(handle, *args)
                with self._mu:
                    self._dead.discard(args[0]._obj.value)
                return out
            key = handle.value if isinstance(handle, ctypes.c_void_p) else handle
            with self._mu:
                self.calls += 1
                if self._active.get(key, 0):
                    self.overlaps += 1
                if key in self._dead:
                    self.after_destroy += 1
                self._active[key] = self._active.get(key, 0) + 1
                if name == "pool_sim_destroy":
                    self.destroys.append(time.perf_counter())
                    self._dead.add(key)
            start = time.perf_counter()
            try:
                return fn(handle, *args)
            finally:
                end = time.perf_counter()
                with self._mu:
                    self._active[key] -= 1
                    if name == "pool_sim_run":
                        self.runs.append((start, end))

        return call

    def __enter__(self):
        _ffi.load()
        self._saved = _ffi._lib
        _ffi._lib = self
        return self

    def __exit__(self, *exc):
        _ffi._lib = self._saved


def hammer(sim, ref_events, ref_states, seconds, errors, barrier):
    """One thread's share: random run_until(t)/state_at(t), events, run(), balls, properties
    on the shared sim, each result checked against the single-threaded reference."""
    rng = random.Random(threading.get_ident())
    times = list(ref_states)
    barrier.wait()
    end = time.perf_counter() + seconds
    try:
        while time.perf_counter() < end:
            op = rng.randrange(5)
            if op == 0:
                t = rng.choice(times)
                sim.run_until(t)
                if sim.state_at(t) != ref_states[t]:
                    errors.append(f"state_at({t}) differs")
            elif op == 1:
                ev = sim.events
                if ev != ref_events[:len(ev)]:
                    errors.append(f"events (first {len(ev)}) are not a prefix of the reference")
            elif op == 2:
                if sim.run() != "rest":
                    errors.append("run() did not end at rest")
            elif op == 3:
                sim.balls, sim.pocketed, sim.event_count
            else:
                sim.time, sim.end_time, sim.stop_reason, sim.ball_count, sim.params
    except Exception as e:  # the test fails on any exception; none is expected
        errors.append(f"{type(e).__name__}: {e}")


class Threads(unittest.TestCase):
    def setUp(self):
        with libpool.Sim() as ref:
            break_shot(ref)
            self.ref_times = [0.0, 0.002, 0.01, 0.05, 0.2, 0.5, 1.0, 2.0, 4.0]
            self.ref_partial = {}
            for t in self.ref_times:  # state_at(t) right after run_until(t): the partial case
                ref.run_until(t)
                self.ref_partial[t] = ref.state_at(t)
            self.assertEqual(ref.run(), "rest")
            self.ref_events = ref.events
            self.ref_balls = ref.balls
            self.ref_states = {t: ref.state_at(t) for t in self.ref_times}
        self.assertEqual(self.ref_partial, self.ref_states)  # state_at does not depend on how far
        self.assertGreater(len(self.ref_events), 50)

    def hammer_rounds(self, rounds, seconds):
        for _ in range(rounds):
            with libpool.Sim() as sim:
                break_shot(sim)
                errors = []
                barrier = threading.Barrier(THREADS, timeout=10)
                threads = [threading.Thread(target=hammer, args=(
                    sim, self.ref_events, self.ref_states, seconds, errors, barrier))
                    for _ in range(THREADS)]
                for t in threads:
                    t.start()
                for t in threads:
                    t.join()
                self.assertEqual(errors[:5], [])
                self.assertEqual(sim.run(), "rest")
                self.assertEqual(sim.events, self.ref_events)
                self.assertEqual(sim.balls, self.ref_balls)

    def test_hammer_one_sim_equals_single_thread(self):
        # Six threads on one Sim: every result equals the single-threaded run's.
        self.hammer_rounds(rounds=20, seconds=0.05)

    def test_hammer_calls_never_overlap_in_c(self):
        # The same through Watch: no two C calls on the handle ever ran at once.
        with Watch(_ffi.load()) as w:
            self.hammer_rounds(rounds=10, seconds=0.05)
        self.assertGreater(w.calls, 1000)
        self.assertEqual(w.overlaps, 0)
        self.assertEqual(w.after_destroy, 0)

    def test_setup_sequences_atomic_with_lock(self):
        # Whole shots (reset, rack, strike, run, events) from several threads on one Sim, each
        # made atomic with `with sim.lock:`: every thread gets the reference events.
        errors = []
        sim = libpool.Sim()

        def shots():
            try:
                for _ in range(30):
                    with sim.lock:
                        sim.reset()
                        break_shot(sim)
                        sim.run()
                        if sim.events != self.ref_events:
                            errors.append("events differ")
            except Exception as e:
                errors.append(f"{type(e).__name__}: {e}")

        threads = [threading.Thread(target=shots) for _ in range(4)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        sim.close()
        self.assertEqual(errors, [])

    def test_library_loads_once_from_many_threads(self):
        # Eight threads' first calls at once: the library is loaded and set up once. Loading is
        # slowed down so that, without the loader's lock, they would all load it.
        saved, real_cdll, loads = _ffi._lib, _ffi.ctypes.CDLL, []

        def slow_cdll(*args, **kwargs):
            loads.append(1)
            time.sleep(0.005)
            return real_cdll(*args, **kwargs)

        _ffi.ctypes.CDLL = slow_cdll
        try:
            for _ in range(5):
                _ffi._lib = None
                loads.clear()
                got, barrier = [], threading.Barrier(8, timeout=10)

                def load():
                    barrier.wait()
                    got.append(_ffi.load())

                threads = [threading.Thread(target=load) for _ in range(8)]
                for t in threads:
                    t.start()
                for t in threads:
                    t.join()
                self.assertEqual(len(got), 8)
                self.assertTrue(all(lib is got[0] for lib in got))
                self.assertEqual(len(loads), 1)
        finally:
            _ffi.ctypes.CDLL = real_cdll
            _ffi._lib = saved


class Close(unittest.TestCase):
    def test_close_during_run_waits(self):
        # Documented: close() in another thread waits for run() to return; run() returns its
        # normal result; calls after close() raise PoolError "sim: closed". Timestamps from
        # Watch, taken inside the binding's lock, show the destroy began only after the run
        # ended, in every round where close() was called while run() was running.
        with libpool.Sim() as probe:
            crowded_shot(probe)
            t0 = time.perf_counter()
            self.assertEqual(probe.run(), "rest")
            run_s = time.perf_counter() - t0
        self.assertGreater(run_s, 0.002, "the crowded shot is too short to close during it")
        waited = 0
        with Watch(_ffi.load()) as w:
            for _ in range(8):
                sim = libpool.Sim()
                crowded_shot(sim)
                started, out = threading.Event(), {}

                def run():
                    started.set()
                    try:
                        out["result"] = sim.run()
                    except PoolError as e:
                        out["error"] = e

                th = threading.Thread(target=run)
                w.runs.clear()
                w.destroys.clear()
                th.start()
                self.assertTrue(started.wait(10))
                time.sleep(run_s / 4)
                close_called = time.perf_counter()
                sim.close()
                th.join()
                self.assertTrue(sim.closed)
                with self.assertRaises(PoolError) as cm:
                    sim.events
                self.assertEqual(cm.exception.name, "POOL_ERR_STATE")
                self.assertIn("closed", cm.exception.message)
                self.assertEqual(len(w.destroys), 1)
                if "result" in out:
                    self.assertEqual(out["result"], "rest")
                    (run_start, run_end), = w.runs
                    self.assertGreaterEqual(w.destroys[0], run_end)
                    if close_called < run_end:
                        waited += 1
                else:  # close() won the race before run() took the lock: documented too
                    self.assertEqual(out["error"].name, "POOL_ERR_STATE")
                    self.assertEqual(w.runs, [])
        self.assertEqual(w.overlaps, 0)
        self.assertEqual(w.after_destroy, 0)
        self.assertGreater(waited, 0, "close() never ran during run(): the test proved nothing")

    def test_close_while_threads_hammer(self):
        # close() while six threads call everything: each call either completes (and is right)
        # or raises PoolError "sim: closed"; nothing else, no crash.
        with libpool.Sim() as ref:
            break_shot(ref)
            ref.run()
            ref_events = ref.events
        for _ in range(20):
            sim = libpool.Sim()
            break_shot(sim)
            errors, barrier = [], threading.Barrier(THREADS + 1, timeout=10)

            def work():
                barrier.wait()
                try:
                    while True:
                        sim.run_until(0.5)
                        sim.state_at(0.5)
                        ev = sim.events
                        if ev != ref_events[:len(ev)]:
                            errors.append("events differ")
                        sim.run()
                except PoolError as e:
                    if e.name != "POOL_ERR_STATE" or "closed" not in e.message:
                        errors.append(repr(e))
                except Exception as e:
                    errors.append(repr(e))

            threads = [threading.Thread(target=work) for _ in range(THREADS)]
            for t in threads:
                t.start()
            barrier.wait()
            time.sleep(0.002)
            sim.close()
            for t in threads:
                t.join()
            self.assertEqual(errors, [])

    def test_close_waits_for_lock_holder(self):
        sim = libpool.Sim()
        held, released = threading.Event(), []

        def hold():
            with sim.lock:
                held.set()
                time.sleep(0.05)
                released.append(time.perf_counter())  # before the release, so before close ends

        th = threading.Thread(target=hold)
        th.start()
        self.assertTrue(held.wait(10))
        sim.close()
        closed_at = time.perf_counter()
        th.join()
        self.assertGreater(closed_at, released[0])

    def test_results_outlive_close(self):
        # What the methods return is copied: closing the sim and reusing its memory for other
        # shots changes nothing in it.
        sim = libpool.Sim()
        break_shot(sim)
        sim.run()
        got = (sim.events, sim.balls, sim.state_at(0.5), sim.pocketed, sim.definition, sim.table)
        text = repr(got)
        sim.close()
        for _ in range(20):
            with libpool.Sim() as other:
                crowded_shot(other, 8, 4)
                other.run()
        self.assertEqual(repr(got), text)

    def test_del_is_safe(self):
        unraisable = []
        old_hook = sys.unraisablehook
        sys.unraisablehook = lambda u: unraisable.append(u)
        try:
            # A Sim whose __init__ raised is finalized without error.
            for bad in (dict(max_time=float("nan")), dict(table="wpa-9ft\x00"),
                        dict(table="billiards")):
                with self.assertRaises((PoolError, ValueError)):
                    libpool.Sim(**bad)
            # Sims in reference cycles, dropped from several threads at once.
            def churn():
                for _ in range(50):
                    s = libpool.Sim()
                    break_shot(s)
                    s.self_ref = s
                    del s
                gc.collect()

            threads = [threading.Thread(target=churn) for _ in range(4)]
            for t in threads:
                t.start()
            for t in threads:
                t.join()
            # A Sim dropped while another thread holds its lock: __del__ does not block on it.
            sim = libpool.Sim()
            lock, held, done = sim.lock, threading.Event(), threading.Event()

            def hold():
                with lock:
                    held.set()
                    done.wait(10)

            th = threading.Thread(target=hold)
            th.start()
            self.assertTrue(held.wait(10))
            t0 = time.perf_counter()
            del sim
            gc.collect()
            dt = time.perf_counter() - t0
            done.set()
            th.join()
            self.assertLess(dt, 1.0)
        finally:
            sys.unraisablehook = old_hook
        self.assertEqual([repr(u.exc_value) for u in unraisable], [])

    def test_copy_and_pickle_refused(self):
        # A copy would share the C simulation and free it a second time (a crash before).
        with libpool.Sim() as sim:
            sim.rack("8ball")
            for fn in (copy.copy, copy.deepcopy, pickle.dumps):
                with self.assertRaises(TypeError):
                    fn(sim)
            self.assertEqual(sim.ball_count, 16)


class Strings(unittest.TestCase):
    def test_nul_refused(self):
        for name in ("wpa-9ft\x00x", "wpa-9ft\x00", "\x00"):
            with self.assertRaises(ValueError) as cm:
                libpool.table_preset(name)
            self.assertIn("name", str(cm.exception))
            self.assertIn("NUL", str(cm.exception))
            with self.assertRaises(ValueError) as cm:
                libpool.Sim(table=name)
            self.assertTrue(str(cm.exception).startswith("table:"), str(cm.exception))
        with libpool.Sim(table="wpa-8ft") as sim:
            with self.assertRaises(ValueError) as cm:
                sim.reset(table="wpa-7ft\x00")
            self.assertTrue(str(cm.exception).startswith("table:"), str(cm.exception))
            self.assertEqual(sim.table.length, libpool.table_preset("wpa-8ft").length)

    def test_invalid_text_and_types_refused(self):
        with self.assertRaises(ValueError) as cm:
            libpool.table_preset("wpa-9ft\udcff")  # a lone surrogate: no UTF-8 form
        self.assertIn("name", str(cm.exception))
        for bad in (b"wpa-9ft", 9, None):
            with self.assertRaises(TypeError) as cm:
                libpool.table_preset(bad)
            self.assertIn("name", str(cm.exception))

    def test_valid_names_still_work(self):
        self.assertEqual(libpool.table_preset("wpa-7ft").length,
                         libpool.Sim(table="wpa-7ft").table.length)
        with self.assertRaises(PoolError) as cm:
            libpool.table_preset("wpa-10ft")
        self.assertEqual(cm.exception.name, "POOL_ERR_UNKNOWN_PRESET")


if __name__ == "__main__":
    unittest.main(verbosity=2)
