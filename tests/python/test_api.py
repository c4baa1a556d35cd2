#!/usr/bin/env python3
"""The Python API of issue 26: trajectories and the history as NumPy arrays, a Sim as layout and
result documents, strict argument types with messages naming the argument, degrees reported in
degrees, presets named by a string, version and ball_on_cloth.

Usage: test_api.py --struct-sizes PROG --pool-sim PROG --pool-rack PROG --work DIR
"""
import argparse
import inspect
import json
import math
import os
import subprocess
import sys
import unittest

import numpy as np

import libpool
import libpool.arrays
import libpool.batch
from libpool import PoolError

ARGS = None


def work(name):
    os.makedirs(ARGS.work, exist_ok=True)
    return os.path.join(ARGS.work, name)


def rack_file(gap="0", speed="8"):
    path = work(f"rack_{gap}_{speed}.json")
    subprocess.run([ARGS.pool_rack, "8ball", "--gap", gap, "--speed", speed, "-o", path],
                   check=True, timeout=60)
    return path


def pool_sim_result(scenario, *extra):
    out = subprocess.run([ARGS.pool_sim, scenario, *extra], check=True, capture_output=True,
                         timeout=60).stdout
    return json.loads(out)


class Arrays(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.rack = rack_file()
        cls.sim = libpool.Sim.from_layout(cls.rack)
        cls.sim.run()

    def test_dtypes_match_c(self):
        out = subprocess.run([ARGS.struct_sizes], check=True, capture_output=True, text=True).stdout
        c = json.loads(out)
        for dtype, name in ((libpool.arrays.BALL_DTYPE, "pool_ball_state"),
                            (libpool.arrays.EVENT_DTYPE, "pool_event")):
            self.assertEqual(dtype.itemsize, c[name]["size"], name)
            for field, offset in c[name]["fields"].items():
                self.assertEqual(dtype.fields[field][1], offset, f"{name}.{field}")

    def test_trajectory_is_state_at_bit_for_bit(self):
        sim = self.sim
        rng = np.random.default_rng(3)
        times = np.concatenate([[0.0, sim.end_time, sim.end_time + 3.0],
                                [e.time for e in sim.events],
                                rng.uniform(0, sim.end_time, 500)])
        traj = sim.trajectory(times)
        n = sim.ball_count
        self.assertEqual(traj.pos.shape, (len(times), n, 3))
        self.assertEqual(traj.motion.shape, (len(times), n))
        self.assertEqual(traj.ids.tolist(), [b.id for b in sim.balls])
        for k, t in enumerate(times.tolist()):
            for i, b in enumerate(sim.state_at(t)):
                self.assertEqual(tuple(traj.pos[k, i]), b.pos)
                self.assertEqual(tuple(traj.vel[k, i]), b.vel)
                self.assertEqual(tuple(traj.omega[k, i]), b.omega)
                self.assertEqual(libpool.MOTION_NAMES[traj.motion[k, i]], b.motion)
        # Any sequence of numbers; NumPy integer times too.
        self.assertEqual(sim.trajectory([1, 2]).pos.shape, (2, n, 3))
        self.assertEqual(sim.trajectory(np.arange(3)).pos.shape, (3, n, 3))
        self.assertEqual(sim.trajectory([]).pos.shape, (0, n, 3))

    def test_trajectory_errors_name_the_time(self):
        with libpool.Sim.from_layout(self.rack) as sim:
            sim.run_until(0.5)
            with self.assertRaises(PoolError) as cm:
                sim.trajectory([0.1, 0.2, math.nan])
            self.assertTrue(cm.exception.message.startswith("times[2]: must be a time >= 0 s"),
                            cm.exception.message)
            with self.assertRaises(PoolError) as cm:
                sim.trajectory([0.1, 30.0])
            self.assertEqual(cm.exception.name, "POOL_ERR_STATE")
            # the time processed is the one run_until reached, not the last event's
            self.assertEqual(cm.exception.message,
                             "times[1] = 30 s is past the time processed, 0.5 s: run the shot there first")
            for bad in (["0.1"], "0.1", [True, False], [[0.1, 0.2]]):
                with self.subTest(times=bad):
                    with self.assertRaises((TypeError, PoolError)) as cm:
                        sim.trajectory(bad)
                    self.assertIn("times", str(cm.exception))

    def test_history_is_the_event_list(self):
        sim = self.sim
        h = sim.history()
        events = sim.events
        self.assertEqual(len(h.time), len(events))
        self.assertEqual(h.type_names(), [e.type for e in events])
        self.assertEqual(h.time.tolist(), [e.time for e in events])
        rails = ("south", "north", "west", "east")
        for i, e in enumerate(events):
            self.assertEqual(rails[h.rail[i]] if h.rail[i] >= 0 else None, e.rail)
            s = h.after(i)
            self.assertEqual(h.ids[s].tolist(), list(e.balls))
            self.assertTrue((h.event[s] == i).all())
            for k, b in zip(range(s.start, s.stop), e.after):
                self.assertEqual(tuple(h.pos[k]), b.pos)
                self.assertEqual(tuple(h.vel[k]), b.vel)
                self.assertEqual(tuple(h.omega[k]), b.omega)
                self.assertEqual(libpool.MOTION_NAMES[h.motion[k]], b.motion)
        with libpool.Sim() as empty:
            self.assertEqual(len(empty.history().time), 0)


class Documents(unittest.TestCase):
    def test_result_is_pool_sims(self):
        for scenario in (rack_file(),
                         os.path.join(ARGS.source, "compare/scenarios/link/rest_on_two.json"),
                         os.path.join(ARGS.source, "compare/scenarios/airborne/jump.json")):
            with self.subTest(scenario=os.path.basename(scenario)):
                with libpool.Sim.from_layout(scenario) as sim:
                    sim.run()
                    self.assertEqual(sim.result(), pool_sim_result(scenario))
                    self.assertEqual(sim.result(sample_dt=0.01),
                                     pool_sim_result(scenario, "--sample", "0.01"))
                    path = work("written/" + os.path.basename(scenario))
                    libpool.write_result(path, sim)
                    with open(path, encoding="utf-8") as f:
                        self.assertEqual(json.load(f), sim.result())
                    # pool-view draws it.
                    r = subprocess.run([sys.executable, os.path.join(ARGS.source, "tools/pool-view"),
                                        path, "-o", path + ".html"], capture_output=True, timeout=60)
                    self.assertEqual(r.returncode, 0, r.stderr)

    def test_layout_round_trip_and_batch(self):
        rack = rack_file()
        with libpool.Sim.from_layout(rack) as sim:
            before = sim.layout(0.0)
            sim.run()
            after = sim.layout()
            end = sim.state_at(sim.end_time)
        # The balls at rest after the break, pocketed ones left out.
        in_play = [b for b in end if b.motion not in ("pocketed", "off_table")]
        self.assertEqual([b["id"] for b in after["balls"]], [b.id for b in in_play])
        for d, b in zip(after["balls"], in_play):
            self.assertEqual(d["pos"], list(b.pos[:2]))
            self.assertNotIn("vel", d)
        # At t = 0 the cue ball is already struck: it carries its velocity and spin.
        self.assertIn("vel", before["balls"][0])
        # The next shot from the layout: a Sim and libpool.batch give the same final states.
        with libpool.Sim.from_layout(after) as nxt:
            nxt.strike(0, 3.0, phi_deg=30.0)
            nxt.run()
            final = nxt.state_at(nxt.end_time)
        res = libpool.batch.run(after, [(0, 3.0, 30.0, 0.0, 0.0, 0.0)], workers=1)
        self.assertEqual(res.pos[0].tolist(), [list(b.pos) for b in final])
        # pool-sim reads it too.
        path = work("after_break.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(dict(after, strike={"ball": 0, "speed": 3.0, "phi": 30.0}), f)
        self.assertEqual(pool_sim_result(path)["final"],
                         [{"id": b.id, "pos": list(b.pos), "vel": list(b.vel),
                           "omega": list(b.omega), "state": b.motion} for b in final])

    def test_preset_by_name(self):
        doc = {"format": "libpool-scenario/1", "table": "wpa-8ft",
               "balls": [{"id": 0, "pos": [0.5, 0.5]}], "strike": {"ball": 0, "speed": 1.0}}
        lay = libpool.batch.load_layout(doc)
        self.assertEqual(lay.sim_def.table.length, libpool.table_preset("wpa-8ft").length)
        path = work("preset_string.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(doc, f)
        self.assertEqual(pool_sim_result(path)["table"]["length"],
                         libpool.table_preset("wpa-8ft").length)
        doc["table"] = "snooker-12ft"
        with self.assertRaisesRegex(ValueError, 'layout: table: unknown preset "snooker-12ft"'):
            libpool.batch.load_layout(doc)
        doc["table"] = 3
        with self.assertRaisesRegex(ValueError, "table: must be a preset name or an object"):
            libpool.batch.load_layout(doc)


class StrictArguments(unittest.TestCase):
    def test_types_are_refused_naming_the_argument(self):
        sim = libpool.Sim()
        sim.add_ball(0, (0.6, 0.6))
        cases = [
            (lambda: sim.strike(0, "2"), TypeError, "strike.speed: expected a number, got str"),
            (lambda: sim.strike(0, True), TypeError, "strike.speed: expected a number, got bool"),
            (lambda: sim.strike("0", 1.0), TypeError, "strike.ball: expected an int, got str"),
            (lambda: sim.strike(0.0, 1.0), TypeError, "strike.ball: expected an int, got float"),
            (lambda: sim.strike(0, 1.0, phi_deg="10"), TypeError, "strike.phi_deg"),
            (lambda: sim.strike(0, 1.0, a=None), TypeError, "strike.a"),
            (lambda: sim.add_ball(3.0, (1.0, 0.5)), TypeError, "ball.id: expected an int, got float"),
            (lambda: sim.add_ball(True, (1.0, 0.5)), TypeError, "ball.id: expected an int, got bool"),
            (lambda: sim.add_ball(1, "1.0"), TypeError, "ball.pos: expected a sequence of numbers"),
            (lambda: sim.add_ball(1, (1.0, "0.5")), TypeError, "ball.pos[1]: expected a number"),
            (lambda: sim.add_ball(1, (1.0, 0.5), vel=(True, 0, 0)), TypeError, "ball.vel[0]"),
            (lambda: libpool.Sim(airborne="yes"), TypeError, "airborne: expected True or False"),
            (lambda: libpool.Sim(airborne=1), TypeError, "airborne: expected True or False"),
            (lambda: libpool.Sim(max_time="5"), TypeError, "max_time: expected a number"),
            (lambda: libpool.Sim(max_events=10.0), TypeError, "max_events: expected an int"),
            (lambda: libpool.Sim(table=2.54), TypeError, "table: expected a preset name"),
            (lambda: libpool.Sim(params={"mu_slide": 0.2}), TypeError, "params: expected a Params"),
            (lambda: sim.state_at("1"), TypeError, "t: expected a number"),
            (lambda: sim.run_until(None), TypeError, "t: expected a number"),
            (lambda: libpool.rack("8ball", gap="0"), TypeError, "rack.gap"),
            (lambda: libpool.break_strike(False), TypeError, "break_strike.speed"),
            (lambda: libpool.batch.run(rack_file(), [(0, True, 0, 0, 0, 0)]), TypeError,
             "strikes[0].speed: expected a number, got bool"),
            (lambda: libpool.batch.run(rack_file(), [(0, "8", 0, 0, 0, 0)]), TypeError,
             "strikes[0].speed: expected a number, got str"),
        ]
        for fn, exc, text in cases:
            with self.subTest(expected=text):
                with self.assertRaises(exc) as cm:
                    fn()
                self.assertIn(text, str(cm.exception))
        # NumPy numbers are numbers.
        sim.strike(np.int32(0), np.float64(1.0), phi_deg=np.float32(5.0))
        self.assertEqual(sim.run(), "rest")

    def test_values_are_refused_naming_the_argument_in_its_unit(self):
        sim = libpool.Sim()
        sim.add_ball(0, (0.6, 0.6))
        for fn, name, text in [
            (lambda: sim.strike(0, 1.0, theta_deg=95), "POOL_ERR_INVALID_ARGUMENT",
             "strike.theta_deg: must be in [0, 90) degrees, got 95"),
            (lambda: sim.strike(0, 1.0, theta_deg=-1), "POOL_ERR_INVALID_ARGUMENT",
             "strike.theta_deg: must be in [0, 90) degrees, got -1"),
            (lambda: sim.strike(0, math.nan), "POOL_ERR_NON_FINITE",
             "strike.speed: must be a finite number, got nan"),
            (lambda: sim.state_at(math.nan), "POOL_ERR_INVALID_ARGUMENT",
             "t: must be a time >= 0 s, got nan"),
            (lambda: sim.state_at(-1), "POOL_ERR_INVALID_ARGUMENT", "t: must be a time >= 0 s"),
            (lambda: sim.add_ball(1, (1.0, math.inf)), "POOL_ERR_NON_FINITE", "ball.pos[1]"),
            (lambda: libpool.Sim(max_time=math.nan), "POOL_ERR_NON_FINITE", "max_time"),
        ]:
            with self.subTest(expected=text):
                with self.assertRaises(PoolError) as cm:
                    fn()
                self.assertEqual(cm.exception.name, name)
                self.assertTrue(cm.exception.message.startswith(text), cm.exception.message)
        with self.assertRaisesRegex(ValueError, r"strikes\[0\]\.speed: must be a finite number, got nan"):
            libpool.batch.run(rack_file(), [(0, math.nan, 0, 0, 0, 0)])


class Module(unittest.TestCase):
    def test_all_names_exist_and_help_is_current(self):
        for name in libpool.__all__:
            self.assertTrue(hasattr(libpool, name), name)
        for name in libpool.arrays.__all__ + libpool.batch.__all__:
            self.assertTrue(hasattr(libpool.arrays, name) or hasattr(libpool.batch, name), name)
        doc = inspect.getdoc(libpool.Sim)
        self.assertNotIn("rejected", doc)
        self.assertIn("airborne: True", doc)

    def test_version_and_ball_on_cloth(self):
        self.assertEqual(libpool.version(), (0, 1, 0))
        p = libpool.default_params()
        p.ball_radius = 0.03
        b = libpool.ball_on_cloth(5, 1.0, 0.5, p)
        self.assertEqual((b.id, b.motion, b.pos, b.vel, b.omega),
                         (5, "stationary", (1.0, 0.5, 0.03), (0.0,) * 3, (0.0,) * 3))
        with libpool.Sim(params=p) as sim:
            sim.add_balls([b])
            self.assertEqual(sim.balls[0].pos, (1.0, 0.5, 0.03))


def main():
    global ARGS
    p = argparse.ArgumentParser()
    p.add_argument("--struct-sizes", required=True)
    p.add_argument("--pool-sim", required=True)
    p.add_argument("--pool-rack", required=True)
    p.add_argument("--source", required=True)
    p.add_argument("--work", required=True)
    ARGS, rest = p.parse_known_args()
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False, verbosity=2)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
