#!/usr/bin/env python3
"""libpool.game (the rules and the noise from Python) against the C library and the commands:

- the ctypes mirrors match the C structures field by field (game_struct_sizes.c);
- judge() equals pool-sim's "game" for the same shots, and reads what the independent recount
  reads from the events;
- State round-trips through its dict (the JSON state), refusals name the field as pool-sim does;
- the noise: presets, specs, noisy_strike equal to pool-batch --noise's strikes;
- libpool.batch with a "game" layout: legal, fouls, outcome, points equal pool-batch's columns;
- rack() and spot_position() as the C library places balls.
"""

import argparse
import csv
import ctypes
import io
import json
import math
import os
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from recount import recount  # noqa: E402

import libpool  # noqa: E402
from libpool import game  # noqa: E402

ARGS = None


def run(cmd, stdin=None):
    return subprocess.run(cmd, input=stdin, capture_output=True, text=True, timeout=300)


def write(name, doc):
    path = os.path.join(ARGS.work, name)
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


class Mirrors(unittest.TestCase):
    def test_struct_layouts(self):
        c = json.loads(run([ARGS.struct_sizes]).stdout)
        self.assertEqual(set(c), set(game.STRUCTS))
        for name, mirror in game.STRUCTS.items():
            with self.subTest(struct=name):
                self.assertEqual(ctypes.sizeof(mirror), c[name]["size"])
                self.assertEqual({f: getattr(mirror, f).offset for f, _ in mirror._fields_}, c[name]["fields"])


def shot_doc(k):
    balls = [(0, (0.5 + 0.02 * k, 0.4)), (1, (1.5, 0.7)), (3, (1.9, 0.3)), (9, (2.2, 1.0))]
    return {"format": "libpool-scenario/1", "balls": [{"id": i, "pos": list(p)} for i, p in balls],
            "strike": {"ball": 0, "speed": 1.2 + 0.15 * k, "phi": 5.0 + 2.3 * k, "b": -0.002},
            "game": {"rules": "9ball", "state": {"fouls": k % 3}}}


class Judge(unittest.TestCase):
    def test_equals_pool_sim_and_the_recount(self):
        for k in range(25):
            doc = shot_doc(k)
            p = run([ARGS.pool_sim, write("shot.json", doc)])
            self.assertEqual(p.returncode, 0, p.stderr)
            res = json.loads(p.stdout)
            with libpool.Sim() as sim:
                for b in doc["balls"]:
                    sim.add_ball(b["id"], b["pos"])
                s = doc["strike"]
                sim.strike(0, s["speed"], s["phi"], 0.0, 0.0, s["b"])
                sim.run()
                got = game.judge(sim, ("9ball", doc["game"]["state"]))
            self.assertEqual(got.to_dict(), res["game"], k)
            rc = recount(res)
            self.assertEqual((got.first_hit, got.rails_after_contact, got.pocketed),
                             (rc["first_hit"], rc["rails_after_contact"], rc["pocketed"]))

    def test_break_and_refusals(self):
        with libpool.Sim() as sim:
            sim.rack("9ball")
            sim.break_strike(8.0)
            sim.run()
            r = game.judge(sim, game.State.default("9ball"))
            self.assertEqual(r.first_hit, 1)
            self.assertIn(r.state.push_out_available, (True, False))
            self.assertEqual(r.state.break_shot, False)
            with self.assertRaises(libpool.PoolError) as e:
                game.judge(sim, game.State.default("three_cushion"))
            self.assertIn("balls: three_cushion is played with three balls, not 10", str(e.exception))
        with libpool.Sim() as sim:  # no strike: balls set rolling
            sim.add_ball(0, (1.0, 0.6), vel=(1.0, 0.0, 0.0))
            sim.run()
            with self.assertRaises(libpool.PoolError) as e:
                game.judge(sim, game.State("9ball"))
            self.assertIn("events: a shot judged by the rules starts with a strike", str(e.exception))


class States(unittest.TestCase):
    def test_round_trip_and_defaults(self):
        for rules in game.RULES:
            s = game.State.default(rules)
            self.assertEqual(game.State.from_dict(rules, s.to_dict()), s)
            self.assertTrue(s.break_shot)
        s = game.State.from_dict("8ball", {"group": "stripes", "called": {"ball": 12, "pocket": "s"}, "fouls": 4})
        self.assertEqual((s.group, s.called_ball, s.called_pocket, s.fouls), ("stripes", 12, "s", 4))
        self.assertEqual(game.State.from_dict("8ball", s.to_dict()), s)
        self.assertEqual(game.State.from_dict("9ball"), game.State("9ball"))

    def test_refusals_name_the_field(self):
        for rules, d, message in (
                ("9ball", {"fouls": 3}, "game.state.fouls: must be 0, 1 or 2"),
                ("9ball", {"fouls": -1}, "game.state.fouls: must be a whole number"),
                ("9ball", {"group": "solids"}, "game.state.group: only in 8ball"),
                ("8ball", {"called": {"pocket": "x"}}, "game.state.called.pocket"),
                ("8ball", {"called": {"ball": 0}}, "game.state.called.ball"),
                ("9ball", {"push_out": True}, "game.state.push_out"),
                ("9ball", {"break": "yes"}, "game.state.break: must be true or false"),
                ("9ball", {"colour": 1}, "game.state.colour: unknown field"),
                ("snooker", {}, "game.rules: unknown rules")):
            with self.assertRaises(ValueError) as e:
                game.State.from_dict(rules, d)
            self.assertIn(message, str(e.exception), d)


class Noise(unittest.TestCase):
    def test_presets_and_specs(self):
        self.assertEqual(game.noise("fastfiz"), game.Noise(0.075, 0.125, 0.1, 0.0005, 0.0005))
        self.assertTrue(game.noise("none").is_zero())
        self.assertEqual(game.noise("phi=0.3,b=0.001"), game.Noise(0.0, 0.3, 0.0, 0.0, 0.001))
        with self.assertRaises(ValueError) as e:
            game.noise("phi=x")
        self.assertIn("noise: phi: 'x' is not a standard deviation >= 0", str(e.exception))
        self.assertEqual(game.noisy_strike((2, 10, 0, 0, 0), "none", 1, 5), (2.0, 10.0, 0.0, 0.0, 0.0))
        a = game.noisy_strike((2, 10, 0, 0, 0), "fastfiz", 1, 5)
        self.assertEqual(a, game.noisy_strike((2, 10, 0, 0, 0), "fastfiz", 1, 5))
        self.assertNotEqual(a, game.noisy_strike((2, 10, 0, 0, 0), "fastfiz", 2, 5))
        self.assertGreaterEqual(a[2], 0.0)

    def test_equal_to_pool_batch(self):
        layout = write("noise_layout.json", shot_doc(0))
        p = run([ARGS.pool_batch, layout, "--grid", "speed=1.5:1.5:20", "--noise", "fastfiz", "--seed", "11",
                 "--no-progress"])
        self.assertEqual(p.returncode, 0, p.stderr)
        for i, row in enumerate(csv.DictReader(io.StringIO(p.stdout))):
            want = game.noisy_strike((1.5, 5.0, 0.0, 0.0, -0.002), "fastfiz", 11, i)
            self.assertEqual(tuple(float(row[k]) for k in ("speed", "phi", "theta", "a", "b")), want, i)


class Batch(unittest.TestCase):
    def test_game_arrays_equal_pool_batch(self):
        import libpool.batch
        doc = shot_doc(3)
        layout = write("batch_layout.json", doc)
        p = run([ARGS.pool_batch, layout, "--grid", "speed=1:4:4,phi=0:40:6", "--no-progress"])
        rows = list(csv.DictReader(io.StringIO(p.stdout)))
        strikes = [(0, float(r["speed"]), float(r["phi"]), 0.0, 0.0, -0.002) for r in rows]
        res = libpool.batch.run(layout, strikes, workers=2)
        for i, r in enumerate(rows):
            self.assertEqual(bool(res.legal[i]), r["legal"] == "true")
            self.assertEqual(game.OUTCOMES[res.outcome[i]], r["outcome"])
            self.assertEqual(int(res.points[i]), int(r["points"]))
            names = [game.FOULS[k] for k in range(len(game.FOULS)) if int(res.fouls[i]) >> k & 1]
            self.assertEqual(" ".join(names), r["fouls"])
        bad = dict(doc, game={"rules": "9ball", "state": {"fouls": 7}})
        with self.assertRaises(ValueError) as e:
            libpool.batch.load_layout(bad)
        self.assertIn("game.state.fouls", str(e.exception))
        del bad["strike"]
        bad["game"] = {"rules": "9ball"}
        with self.assertRaises(ValueError) as e:
            libpool.batch.load_layout(bad)
        self.assertIn("needs a strike", str(e.exception))


class Tables(unittest.TestCase):
    def test_rack_and_spots(self):
        nine = game.rack("9ball")
        self.assertEqual(sorted(i for i, _ in nine), list(range(10)))
        carom = game.rack("three_cushion")
        self.assertEqual(carom[2][1], (0.75 * 2.84, 0.71))
        s = game.State("9ball")
        self.assertEqual(game.spot_position(s, 9, []), (0.75 * 2.54, 0.635))
        x, y = game.spot_position(s, 9, [(3, (0.75 * 2.54, 0.635))])
        self.assertAlmostEqual(x - 0.75 * 2.54, 2 * 0.028575, delta=1e-8)
        self.assertEqual(y, 0.635)


def main():
    global ARGS
    parser = argparse.ArgumentParser()
    for name in ("--pool-sim", "--pool-batch", "--struct-sizes", "--work"):
        parser.add_argument(name, required=True)
    ARGS, rest = parser.parse_known_args()
    os.makedirs(ARGS.work, exist_ok=True)
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
