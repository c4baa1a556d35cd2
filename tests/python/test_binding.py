#!/usr/bin/env python3
"""Tests of the Python binding (python/libpool) against libpool.so.

Usage: test_binding.py --struct-sizes PROG [--pool-sim PROG] [--work DIR] [unittest args]
(LIBPOOL_PATH names the shared library; PYTHONPATH holds python/.)
"""

import argparse
import ctypes
import json
import math
import os
import subprocess
import sys
import unittest

import libpool
from libpool import PoolError, _ffi

ARGS = None


def stun_sim(speed=0.3):
    sim = libpool.Sim()
    sim.add_ball(0, (0.635, 0.635))
    sim.strike(0, speed)
    sim.run()
    return sim


class StructLayout(unittest.TestCase):
    """Every ctypes mirror has the size and field offsets of the C structure."""

    def test_layouts_match_c(self):
        out = subprocess.run([ARGS.struct_sizes], check=True, capture_output=True, text=True).stdout
        c = json.loads(out)
        enums = c.pop("enum_sizes")
        self.assertEqual(set(c), set(_ffi.STRUCTS))
        for name, mirror in _ffi.STRUCTS.items():
            with self.subTest(struct=name):
                self.assertEqual(ctypes.sizeof(mirror), c[name]["size"])
                py = {f: getattr(mirror, f).offset for f, _ in mirror._fields_}
                self.assertEqual(py, c[name]["fields"])
        for name, size in enums.items():
            self.assertEqual(size, ctypes.sizeof(ctypes.c_int), name)


class ClosedForms(unittest.TestCase):
    def test_stun(self):
        # docs/validation.md 1: rolling starts at 2 v0/(7 mu g), after 12 v0^2/(49 mu g), at 5 v0/7.
        with stun_sim() as sim:
            p = sim.params
            ev = sim.events
            self.assertEqual(ev[0].type, "strike")
            v0 = ev[0].after[0].vel[0]
            self.assertGreater(v0, 0.0)
            self.assertEqual(ev[0].after[0].vel[1], 0.0)
            self.assertEqual([e.type for e in ev], ["strike", "slide_roll", "roll_stop"])
            roll = [e for e in ev if e.type == "slide_roll"]
            mu_g = p.mu_slide * p.g
            t1, b1 = roll[0].time, roll[0].after[0]
            self.assertAlmostEqual(t1 / (2 * v0 / (7 * mu_g)), 1.0, delta=1e-9)
            self.assertAlmostEqual(b1.vel[0] / (5 * v0 / 7), 1.0, delta=1e-9)
            self.assertAlmostEqual((b1.pos[0] - 0.635) / (12 * v0 * v0 / (49 * mu_g)), 1.0, delta=1e-9)
            self.assertEqual(b1.motion, "rolling")
            self.assertEqual(sim.stop_reason, "rest")

    def test_state_at_between_events(self):
        # Rolling after slide_roll: v = v1 - mu_roll g dt, x = x1 + v1 dt - mu_roll g dt^2 / 2.
        with stun_sim() as sim:
            p = sim.params
            roll = next(e for e in sim.events if e.type == "slide_roll")
            stop = next(e for e in sim.events if e.type == "roll_stop")
            b1 = roll.after[0]
            for frac in (0.1, 0.5, 0.9):
                t = roll.time + frac * (stop.time - roll.time)
                dt = t - roll.time
                s = sim.state_at(t)[0]
                a = p.mu_roll * p.g
                self.assertAlmostEqual(s.vel[0], b1.vel[0] - a * dt, delta=1e-12)
                self.assertAlmostEqual(s.pos[0], b1.pos[0] + b1.vel[0] * dt - 0.5 * a * dt * dt,
                                       delta=1e-12)
                self.assertEqual(s.motion, "rolling")
            # At an event time the state is the event's after-state.
            self.assertEqual(sim.state_at(roll.time)[0].pos, b1.pos)

    def test_state_at_beyond_processed_time(self):
        sim = libpool.Sim()
        sim.add_ball(0, (0.635, 0.635))
        sim.strike(0, 2.0)
        sim.run_until(0.05)
        self.assertTrue(all(e.time <= 0.05 for e in sim.events))
        with self.assertRaises(PoolError) as cm:
            sim.state_at(10.0)
        self.assertEqual(cm.exception.name, "POOL_ERR_STATE")
        sim.close()
        sim.close()  # idempotent
        with self.assertRaises(PoolError):
            sim.run()

    def test_strike_velocities(self):
        p = libpool.default_params()
        vel, omega = libpool.strike_velocities(2.0, phi_deg=90.0)
        self.assertAlmostEqual(vel[0], 0.0, delta=1e-15)
        self.assertAlmostEqual(vel[1], 2 * 2.0 / (1 + p.ball_mass / p.cue_mass), delta=1e-12)
        self.assertEqual(omega, (0.0, 0.0, 0.0))


class AgainstPoolSim(unittest.TestCase):
    """Python and pool-sim give the same event list, bit for bit, for the same scenario."""

    def compare(self, kind, gap, speed, phi=0.0, theta=0.0, a=0.0, b=0.0, use_break=False, airborne=False):
        if not ARGS.pool_sim:
            self.skipTest("pool-sim not built")
        with libpool.Sim(airborne=airborne) as sim:
            balls = sim.rack(kind, gap=gap)
            if use_break:
                sim.break_strike(speed)
            else:
                sim.strike(0, speed, phi_deg=phi, theta_deg=theta, a=a, b=b)
            self.assertEqual(sim.run(), "rest")
            events = sim.events
        scenario = {
            "format": "libpool-scenario/1",
            "balls": [{"id": x.id, "pos": list(x.pos)} for x in balls],
            "strike": {"ball": 0, "speed": speed, "phi": phi, "theta": theta, "a": a, "b": b},
        }
        if airborne:
            scenario["options"] = {"airborne": True}
        os.makedirs(ARGS.work, exist_ok=True)
        path = os.path.join(ARGS.work, f"{kind}_{speed}_{int(airborne)}.json")
        with open(path, "w") as f:
            json.dump(scenario, f)
        res = json.loads(subprocess.run([ARGS.pool_sim, path], check=True, capture_output=True,
                                        text=True).stdout)
        self.assertEqual(len(events), len(res["events"]))
        self.assertGreater(len(events), 50)
        for mine, theirs in zip(events, res["events"]):
            self.assertEqual(mine.type, theirs["type"])
            self.assertEqual(repr(mine.time), repr(float(theirs["t"])))
            self.assertEqual(list(mine.balls), theirs["balls"])
            self.assertEqual(mine.rail, theirs.get("rail"))
            self.assertEqual(mine.pocket, theirs.get("pocket"))
            for b, tb in zip(mine.after, theirs["after"]):
                self.assertEqual((b.id, b.motion), (tb["id"], tb["state"]))
                self.assertEqual(list(b.pos), tb["pos"])
                self.assertEqual(list(b.vel), tb["vel"])
                self.assertEqual(list(b.omega), tb["omega"])

    def test_frozen_8ball_break(self):
        self.compare("8ball", 0.0, 8.0, use_break=True)

    def test_9ball_with_spin_and_angles(self):
        # Degrees convert exactly as the scenario parser converts them.
        self.compare("9ball", 1e-4, 6.5, phi=1.3, theta=4.0, a=0.004, b=-0.006)

    def test_airborne_break(self):
        # Sim(airborne=True): an elevated break (the cue ball driven into the cloth hops into the
        # rack) gives pool-sim's airborne event list, ball_table events and airborne states included.
        self.compare("9ball", 1e-4, 7.0, theta=12.0, b=0.005, airborne=True)


class Errors(unittest.TestCase):
    def check(self, fn, name, field):
        with self.assertRaises(PoolError) as cm:
            fn()
        e = cm.exception
        self.assertEqual(e.name, name)
        self.assertTrue(e.message.startswith(field), e.message)
        self.assertEqual(e.reason, libpool._lib().pool_result_str(e.code).decode())
        self.assertIn(e.message, str(e))
        return e

    def test_overlap(self):
        sim = libpool.Sim()
        sim.add_ball(0, (1.0, 0.6))
        e = self.check(lambda: sim.add_ball(1, (1.0 + 0.05, 0.6)), "POOL_ERR_OVERLAP", "balls[1].pos")
        self.assertIn("overlaps ball 0", e.message)
        sim.add_ball(1, (1.2, 0.6))  # the sim stays usable
        self.assertEqual(sim.ball_count, 2)

    def test_python_side_checks(self):
        # What ctypes would silently truncate or zero-fill is rejected before the C call.
        sim = libpool.Sim()
        self.check(lambda: sim.add_ball(0, (1.0,)), "POOL_ERR_INVALID_ARGUMENT", "ball.pos")
        self.check(lambda: sim.add_ball(0, (1.0, 0.5), vel=(1.0, 0.0)), "POOL_ERR_INVALID_ARGUMENT",
                   "ball.vel")
        self.check(lambda: sim.add_ball(2**32, (1.0, 0.5)), "POOL_ERR_INVALID_ARGUMENT", "ball.id")
        with self.assertRaisesRegex(TypeError, "ball.id: expected an int, got float 1.5"):
            sim.add_ball(1.5, (1.0, 0.5))
        self.assertEqual(sim.ball_count, 0)

    def test_duplicate_id(self):
        sim = libpool.Sim()
        sim.add_ball(4, (1.0, 0.6))
        self.check(lambda: sim.add_ball(4, (1.5, 0.6)), "POOL_ERR_DUPLICATE_ID", "balls[1].id")

    def test_bad_strike(self):
        sim = libpool.Sim()
        sim.add_ball(0, (1.0, 0.6))
        R = sim.params.ball_radius
        self.check(lambda: sim.strike(0, 2.0, a=0.8 * R, b=0.6 * R), "POOL_ERR_BAD_STRIKE", "strike.a")
        self.check(lambda: sim.strike(7, 2.0), "POOL_ERR_UNKNOWN_BALL", "strike.ball")
        self.check(lambda: sim.strike(2**31, 2.0), "POOL_ERR_INVALID_ARGUMENT", "strike.ball")

    def test_bad_definition(self):
        p = libpool.default_params()
        p.mu_slide = -0.1
        self.check(lambda: libpool.Sim(params=p), "POOL_ERR_INVALID_ARGUMENT", "params.mu_slide")
        self.check(lambda: libpool.Sim(table="snooker-12ft"), "POOL_ERR_UNKNOWN_PRESET", "table.preset")
        self.check(lambda: libpool.Sim(max_time=float("nan")), "POOL_ERR_NON_FINITE", "")
        self.check(lambda: libpool.Sim().add_ball(0, (-1.0, 0.5)), "POOL_ERR_OFF_TABLE", "balls[0].pos")
        self.check(lambda: libpool.rack("10ball"), "POOL_ERR_INVALID_ARGUMENT", "rack")


class Reuse(unittest.TestCase):
    def test_reset_reuses(self):
        with libpool.Sim() as sim:
            sim.rack("8ball")
            sim.break_strike(8.0)
            sim.run()
            first = sim.events
            sim.reset()
            self.assertEqual(sim.ball_count, 0)
            self.assertEqual(sim.event_count, 0)
            for _ in range(3):
                sim.rack("8ball")
                sim.break_strike(8.0)
                sim.run()
                self.assertEqual(sim.events, first)
                sim.reset()
            # A new definition through reset: a 7 ft table gives a different shot.
            sim.reset(table="wpa-7ft")
            self.assertEqual(sim.table.length, libpool.table_preset("wpa-7ft").length)
            sim.rack("8ball")
            sim.break_strike(8.0)
            sim.run()
            self.assertNotEqual(sim.events, first)

    def test_step_equals_run(self):
        with libpool.Sim() as a, libpool.Sim() as b:
            for s in (a, b):
                s.rack("9ball", gap=1e-4)
                s.break_strike(7.0)
            n = 0
            while a.step():
                n += 1
            b.run()
            self.assertEqual(a.events, b.events)
            self.assertEqual(n + 1, len(a.events))  # + the strike event
            self.assertEqual(a.stop_reason, "rest")
            self.assertEqual(a.balls, b.balls)
            self.assertEqual(a.state_at(a.time), a.state_at(a.time + 5.0))

    def test_limits(self):
        with libpool.Sim(max_events=10) as sim:
            sim.rack("8ball")
            sim.break_strike(8.0)
            self.assertEqual(sim.run(), "max_events")
            self.assertEqual(sim.event_count, 10)
        with libpool.Sim(max_time=0.5) as sim:
            sim.rack("8ball")
            sim.break_strike(8.0)
            self.assertEqual(sim.run(), "max_time")
            self.assertLessEqual(sim.time, 0.5)
            self.assertEqual(sim.end_time, 0.5)
            self.assertNotEqual(sim.state_at(sim.end_time), sim.state_at(sim.time))  # still moving


class Tables(unittest.TestCase):
    """Pockets "jaws" (docs/physics.md "Table geometry") through the binding: presets with their
    balls, the snooker rack, the part of a cushion event, the thesis model by its enum value."""

    def test_presets_and_parts(self):
        with libpool.Sim(table="snooker") as sim:
            self.assertEqual(sim.params.ball_radius, 0.02625)
            self.assertEqual(sim.table.pockets, 1)  # POOL_POCKETS_JAWS
            balls = sim.rack("snooker")
            self.assertEqual(len(balls), 22)
            sim.break_strike(6.0)
            self.assertEqual(sim.run(), "rest")
        self.assertEqual(libpool.params_preset("carom").ball_radius, 0.03075)
        # A ball rolling steeply into the side pocket's east facing: a facing contact (part,
        # and the pocket it belongs to), not a pocketing.
        with libpool.Sim() as sim:
            t, R = sim.table, sim.params.ball_radius
            x0 = t.length / 2 + t.side_mouth / 2 - 0.03
            v = 0.6
            sim.add_ball(0, (x0 - 0.2, 0.2), (v, -v, 0.0), (v / R, v / R, 0.0))
            sim.run()
            first = [e for e in sim.events if e.type == "ball_cushion"][0]
            self.assertIn(first.part, ("facing", "jaw"))
            self.assertEqual(first.pocket, "s")
            self.assertEqual(first.rail, "south")
        # The thesis model: a cushion event names no part.
        table = libpool.default_table()
        table.pockets = 0
        with libpool.Sim(table=table) as sim:
            sim.add_ball(0, (1.0, 0.5), (0.0, -1.0, 0.0), (1.0 / sim.params.ball_radius, 0.0, 0.0))
            sim.run()
            self.assertIsNone([e for e in sim.events if e.type == "ball_cushion"][0].part)


class Quartic(unittest.TestCase):
    def test_roots(self):
        r = libpool.quartic_real_roots([1, -10, 35, -50, 24])  # (x-1)(x-2)(x-3)(x-4)
        self.assertEqual(len(r), 4)
        for got, want in zip(r, (1, 2, 3, 4)):
            self.assertAlmostEqual(got, want, delta=1e-12)
        self.assertEqual(libpool.quartic_real_roots([1, 0, 0, 0, 1]), [])  # x^4 + 1
        r = libpool.quartic_real_roots([0, 0, 1, -3, 2])  # quadratic (x-1)(x-2)
        self.assertEqual(len(r), 2)
        self.assertAlmostEqual(r[0], 1.0, delta=1e-14)
        self.assertAlmostEqual(r[1], 2.0, delta=1e-14)
        r = libpool.quartic_real_roots([1, -4, 6, -4, 1])  # (x-1)^4
        self.assertEqual(len(r), 4)
        self.assertTrue(all(abs(x - 1.0) < 1e-3 for x in r))
        self.assertEqual(libpool.quartic_real_roots([float("nan"), 1, 1, 1, 1]), [])
        self.assertAlmostEqual(libpool.quartic_smallest_root_in([1, -10, 35, -50, 24], 2.5, 10), 3.0,
                               delta=1e-12)
        self.assertIsNone(libpool.quartic_smallest_root_in([1, -10, 35, -50, 24], 4.5, 10))
        with self.assertRaises(PoolError):
            libpool.quartic_real_roots([1, 2, 3])


def main():
    global ARGS
    ap = argparse.ArgumentParser()
    ap.add_argument("--struct-sizes", required=True)
    ap.add_argument("--pool-sim")
    ap.add_argument("--work", default="/tmp/libpool-python-test")
    ARGS, rest = ap.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
