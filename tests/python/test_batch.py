#!/usr/bin/env python3
"""Tests of libpool.batch.run: equal to pool-batch's rows value for value, identical whatever the
number of workers, the layout forms and the strike forms, refused strikes and bad input.

Usage: test_batch.py --pool-batch PROG --pool-rack PROG --pool-sim PROG --work DIR [unittest args]
(LIBPOOL_PATH names the shared library; PYTHONPATH holds python/.)
"""

import argparse
import csv
import io
import json
import os
import subprocess
import sys
import unittest

import numpy as np

import libpool
import libpool.batch as lb

ARGS = None
RANDOM_RANGES = "speed=0.5:6,phi=0:360,theta=0:10,a=-0.012:0.012,b=-0.012:0.012"


def pool_batch(layout, *args):
    """pool-batch's CSV rows (dicts) for the layout file and options."""
    out = subprocess.run([ARGS.pool_batch, layout, "--no-progress", *args], check=True,
                         capture_output=True, text=True).stdout
    return list(csv.DictReader(io.StringIO(out)))


def strikes_of(rows):
    """The strikes of pool-batch's rows (its numbers read back to the same doubles)."""
    return [(int(r["ball"]), float(r["speed"]), float(r["phi"]), float(r["theta"]),
             float(r["a"]), float(r["b"])) for r in rows]


def same_arrays(a, b):
    """Bit-for-bit equality of two BatchResults (NaN rows included)."""
    for name in ("ball_ids", "ball", "strikes", "stop_reason", "events", "end_time", "first_hit",
                 "pos", "state", "pocketed", "off_table"):
        x, y = getattr(a, name), getattr(b, name)
        if x.dtype != y.dtype or x.shape != y.shape or x.tobytes() != y.tobytes():
            return name
    if a.error != b.error:
        return "error"
    return None


def post_break_layout(work):
    rack = os.path.join(work, "rack.json")
    subprocess.run([ARGS.pool_rack, "8ball", "-o", rack], check=True)
    result = json.loads(subprocess.run([ARGS.pool_sim, rack], check=True, capture_output=True,
                                       text=True).stdout)
    balls = [{"id": b["id"], "pos": b["pos"][:2]} for b in result["final"]
             if b["state"] == "stationary"]
    doc = {"format": "libpool-scenario/1", "balls": balls, "strike": {"ball": 0, "speed": 2}}
    path = os.path.join(work, "post_break.json")
    with open(path, "w") as f:
        json.dump(doc, f)
    return rack, path, doc


class Batch(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(ARGS.work, exist_ok=True)
        cls.rack, cls.post, cls.post_doc = post_break_layout(ARGS.work)

    def assert_rows_equal(self, res, rows):
        """Every value of every pool-batch row equals the BatchResult's, exactly."""
        self.assertEqual(len(res), len(rows))
        ids = res.ball_ids.tolist()
        for i, r in enumerate(rows):
            with self.subTest(shot=i):
                self.assertEqual(int(r["shot"]), i)
                self.assertEqual(int(r["ball"]), res.ball[i])
                for j, k in enumerate(("speed", "phi", "theta", "a", "b")):
                    self.assertEqual(float(r[k]), res.strikes[i, j])
                self.assertEqual(r["stop_reason"], lb.STOP_NAMES[int(res.stop_reason[i])])
                if r["stop_reason"] == "error":
                    self.assertEqual(r["error"], res.error[i])
                    self.assertTrue(np.isnan(res.pos[i]).all())
                    self.assertTrue((res.state[i] == -1).all())
                    continue
                self.assertEqual(res.error[i], "")
                self.assertEqual(int(r["events"]), res.events[i])
                self.assertEqual(float(r["end_time"]), res.end_time[i])
                hit = int(r["first_hit"]) if r["first_hit"] else lb.NO_HIT
                self.assertEqual(hit, res.first_hit[i])
                self.assertEqual([int(x) for x in r["pocketed"].split()],
                                 [ids[k] for k in np.flatnonzero(res.pocketed[i])])
                self.assertEqual([int(x) for x in r["off_table"].split()],
                                 [ids[k] for k in np.flatnonzero(res.off_table[i])])
                for k, bid in enumerate(ids):
                    for c, axis in enumerate("xyz"):
                        self.assertEqual(float(r[f"ball_{bid}_{axis}"]), res.pos[i, k, c])
                    self.assertEqual(r[f"ball_{bid}_state"],
                                     lb.MOTION_NAMES[int(res.state[i, k])])

    def test_post_break_random_equals_pool_batch(self):
        rows = pool_batch(self.post, "--random", "2000", "--seed", "3", "--ranges", RANDOM_RANGES,
                          "--threads", "2")
        strikes = strikes_of(rows)
        results = {w: lb.run(self.post, strikes, workers=w) for w in (1, 2, 3, 8)}
        self.assert_rows_equal(results[1], rows)
        self.assertTrue(any(h != lb.NO_HIT for h in results[1].first_hit))
        self.assertTrue(results[1].pocketed.any())
        for w in (2, 3, 8):
            self.assertIsNone(same_arrays(results[1], results[w]), f"workers={w}")
        # Small chunks: another split of the shots between the threads, the same arrays.
        self.assertIsNone(same_arrays(results[1], lb.run(self.post, strikes, workers=4, chunk=1)))

    def test_breaks_equal_pool_batch(self):
        rows = pool_batch(self.rack, "--random", "12", "--seed", "5", "--ranges",
                          "speed=6:9,phi=-1:1,a=-0.005:0.005,b=-0.005:0.005")
        strikes = np.array(strikes_of(rows))
        res = lb.run(self.rack, strikes, workers=2)
        self.assert_rows_equal(res, rows)
        self.assertIsNone(same_arrays(res, lb.run(self.rack, strikes, workers=1)))

    def test_refused_strikes_give_pool_batch_error_rows(self):
        path = os.path.join(ARGS.work, "strikes.csv")
        strikes = [(0, 3, 10, 0, 0, 0), (0, 3, 10, 0, 0.03, 0), (0, 3, 10, 95, 0, 0),
                   (0, 3, 10, -1, 0, 0), (99, 3, 10, 0, 0, 0), (1, 2, 45, 5, 0.01, -0.01),
                   (0, 200, 0, 0, 0, 0), (0, -1, 0, 0, 0, 0), (0, 2, 0, 0, 0, 0)]
        with open(path, "w") as f:
            f.write("ball,speed,phi,theta,a,b\n")
            for s in strikes:
                f.write(",".join(repr(float(x)) if k else str(x) for k, x in enumerate(s)) + "\n")
        rows = pool_batch(self.post, "--strikes", path)
        self.assertGreaterEqual(sum(r["stop_reason"] == "error" for r in rows), 5)
        for w in (1, 2):
            res = lb.run(self.post, strikes, workers=w)
            self.assert_rows_equal(res, rows)
            self.assertIn(lb.STOP_ERROR, res.stop_reason.tolist())

    def test_structured_strikes_take_base_values(self):
        # Fields absent from the array come from the layout's strike, as pool-batch's absent
        # columns do; --ball / ball= names the struck ball.
        path = os.path.join(ARGS.work, "speed_phi.csv")
        with open(path, "w") as f:
            f.write("speed,phi\n1.5,30\n2.5,-60\n4,179.5\n")
        rows = pool_batch(self.post, "--strikes", path)
        arr = np.array([(1.5, 30.0), (2.5, -60.0), (4.0, 179.5)],
                       dtype=[("speed", "f8"), ("phi", "f8")])
        self.assert_rows_equal(lb.run(self.post, arr, workers=2), rows)
        rows = pool_batch(self.post, "--strikes", path, "--ball", "1")
        self.assert_rows_equal(lb.run(self.post, arr, workers=2, ball=1), rows)

    def test_airborne_layout_equals_pool_batch(self):
        # options.airborne: a ball in flight at the start, jump shots of the cue ball.
        doc = {"format": "libpool-scenario/1", "options": {"airborne": True, "max_time": 30},
               "balls": [{"id": 0, "pos": [0.635, 0.635]}, {"id": 1, "pos": [1.2, 0.64]},
                         {"id": 2, "pos": [1.6, 0.9, 0.08], "vel": [0.3, 0.1, 0.5]}],
               "strike": {"ball": 0, "speed": 4, "theta": 30}}
        path = os.path.join(ARGS.work, "airborne.json")
        with open(path, "w") as f:
            json.dump(doc, f)
        rows = pool_batch(path, "--random", "150", "--seed", "2", "--ranges",
                          "speed=2:7,phi=-10:10,theta=0:60,b=-0.01:0.01")
        res = lb.run(doc, strikes_of(rows), workers=2)
        self.assert_rows_equal(res, rows)
        self.assertIsNone(same_arrays(res, lb.run(path, strikes_of(rows), workers=1)))
        low = json.loads(json.dumps(doc))
        low["balls"][2]["pos"][2] = 0.01
        with self.assertRaisesRegex(ValueError, r"balls\[2\]\.pos: below the cloth"):
            lb.run(low, [(0, 1, 0, 0, 0, 0)])

    def test_layout_forms(self):
        strikes = [(0, 2.0, 12.5, 0.0, 0.0, 0.0), (0, 4.0, 200.0, 3.0, 0.001, 0.002)]
        ref = lb.run(self.post, strikes, workers=1)
        with open(self.post) as f:
            text = f.read()
        import pathlib
        for layout in (text, self.post_doc, pathlib.Path(self.post), lb.load_layout(self.post)):
            self.assertIsNone(same_arrays(ref, lb.run(layout, strikes, workers=2)))
        self.assertEqual(ref.ball_ids.tolist(), [b["id"] for b in self.post_doc["balls"]])
        self.assertEqual(ref.pos.shape, (2, len(self.post_doc["balls"]), 3))

    def test_matches_sim(self):
        # A row is the shot Sim gives for the layout and that one strike.
        res = lb.run(self.post, [(0, 3.0, 33.0, 4.0, 0.005, -0.004)], workers=1)
        with libpool.Sim() as sim:
            for b in self.post_doc["balls"]:
                sim.add_ball(b["id"], b["pos"])
            sim.strike(0, 3.0, 33.0, 4.0, 0.005, -0.004)
            sim.run()
            self.assertEqual(res.events[0], sim.event_count)
            self.assertEqual(res.end_time[0], sim.end_time)
            final = sim.state_at(sim.end_time)
        self.assertEqual([b.pos for b in final], [tuple(p) for p in res.pos[0].tolist()])

    def test_bad_input(self):
        with self.assertRaisesRegex(ValueError, r"strikes\[1\]\.speed: must be a finite number, got nan"):
            lb.run(self.post, [(0, 1, 0, 0, 0, 0), (0, float("nan"), 0, 0, 0, 0)])
        with self.assertRaisesRegex(ValueError, r"strikes\[0\]\.ball"):
            lb.run(self.post, [(0.5, 1, 0, 0, 0, 0)])
        with self.assertRaisesRegex(ValueError, "rows of 6 numbers"):
            lb.run(self.post, [(0, 1, 0)])
        with self.assertRaisesRegex(ValueError, "unknown field"):
            lb.run(self.post, np.zeros(2, dtype=[("speed", "f8"), ("spin", "f8")]))
        with self.assertRaisesRegex(ValueError, "workers"):
            lb.run(self.post, [(0, 1, 0, 0, 0, 0)], workers=0)
        with self.assertRaisesRegex(ValueError, "ball: no ball of the layout"):
            lb.run(self.post, [(0, 1, 0, 0, 0, 0)], ball=77)
        doc = dict(self.post_doc)
        doc.pop("strike")
        with self.assertRaisesRegex(ValueError, "no speed"):
            lb.run(doc, np.zeros(1, dtype=[("phi", "f8")]))
        bad = dict(self.post_doc, balls=self.post_doc["balls"] + [self.post_doc["balls"][0]])
        with self.assertRaisesRegex(ValueError, r"balls\[\d+\]\.id: duplicate id 0"):
            lb.run(bad, [(0, 1, 0, 0, 0, 0)])
        with self.assertRaisesRegex(ValueError, "format"):
            lb.run({"balls": []}, [(0, 1, 0, 0, 0, 0)])
        with self.assertRaisesRegex(ValueError, "params.nope: unknown field"):
            lb.run(dict(self.post_doc, params={"nope": 1}), [(0, 1, 0, 0, 0, 0)])
        self.assertEqual(len(lb.run(self.post, np.zeros((0, 6)))), 0)


def main():
    global ARGS
    parser = argparse.ArgumentParser()
    parser.add_argument("--pool-batch", required=True)
    parser.add_argument("--pool-rack", required=True)
    parser.add_argument("--pool-sim", required=True)
    parser.add_argument("--work", required=True)
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
