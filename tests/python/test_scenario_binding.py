#!/usr/bin/env python3
"""libpool.batch on libpool_scenario: the ctypes mirrors of pool/scenario.h and pool/batch.h
against the C layouts, load_layout's refusals word for word pool-sim's (the same parser), the
strike as the file writes it, and a layout dict holding what JSON cannot carry.

Usage: test_scenario_binding.py --struct-sizes PROG --pool-sim PROG --work DIR [unittest args]
(LIBPOOL_PATH names libpool.so; PYTHONPATH holds python/.)
"""

import argparse
import copy
import ctypes
import json
import os
import subprocess
import sys
import unittest

import numpy as np

import libpool.batch as lb
from libpool import _scenario

ARGS = None
BASE = {"format": "libpool-scenario/1",
        "balls": [{"id": 0, "pos": [0.5, 0.5]}, {"id": 1, "pos": [1.0, 0.5]}],
        "strike": {"ball": 0, "speed": 1.5, "phi": 12.3, "theta": 4.5, "a": 0.002, "b": -0.004}}


def changed(f):
    doc = copy.deepcopy(BASE)
    f(doc)
    return doc


# Refused layouts, one per kind of check: JSON, fields, ranges, the library's rules, airborne, game.
BAD = [
    changed(lambda d: d.pop("format")),
    changed(lambda d: d.update(table="snooker-12ft")),
    changed(lambda d: d.update(table={"length": -1})),
    changed(lambda d: d.update(params={"mu_slide": -1})),
    changed(lambda d: d.update(params={"g": True})),
    changed(lambda d: d.update(options={"max_events": 0})),
    changed(lambda d: d.update(models={"cushion": "x"})),
    changed(lambda d: d["balls"].append({"id": 0, "pos": [2, 1]})),
    changed(lambda d: d["balls"].append({"id": 2, "pos": [1.01, 0.5]})),
    changed(lambda d: d["balls"].append({"id": 2, "pos": [5, 0.5]})),
    changed(lambda d: d["balls"].append({"id": 2, "pos": [1, 1, 0.05]})),
    changed(lambda d: d["strike"].update(theta=95)),
    changed(lambda d: d["strike"].update(a=0.03)),
    changed(lambda d: d.update(game={"rules": "9ball", "state": {"fouls": 7}})),
    changed(lambda d: d.update(options={"airborne": True}) or
            d["balls"].append({"id": 2, "pos": [1, 1, 0.01]})),
]


class Mirrors(unittest.TestCase):
    def test_layouts_match_the_headers(self):
        c = json.loads(subprocess.run([ARGS.struct_sizes], check=True, capture_output=True,
                                      text=True).stdout)
        constants = c.pop("constants")
        self.assertEqual(set(c), set(_scenario.STRUCTS))
        for name, (mirror, renamed) in _scenario.STRUCTS.items():
            with self.subTest(struct=name):
                self.assertEqual(ctypes.sizeof(mirror), c[name]["size"])
                want = {renamed.get(f, f): off for f, off in c[name]["fields"].items()}
                self.assertEqual({f: getattr(mirror, f).offset for f, _ in mirror._fields_}, want)
        self.assertEqual(constants["POOL_SCENARIO_MESSAGE_SIZE"], _scenario.MESSAGE_SIZE)
        self.assertEqual(constants["POOL_BATCH_MESSAGE_SIZE"], _scenario.BATCH_MESSAGE_SIZE)
        self.assertEqual(constants["POOL_SCENARIO_MAX_ABS"], lb._MAX_ABS)


class Parser(unittest.TestCase):
    def test_refusals_are_pool_sims(self):
        os.makedirs(ARGS.work, exist_ok=True)
        path = os.path.join(ARGS.work, "bad.json")
        for doc in BAD:
            with self.subTest(doc=doc):
                with open(path, "w") as f:
                    json.dump(doc, f)
                p = subprocess.run([ARGS.pool_sim, path], capture_output=True, text=True)
                self.assertEqual(p.returncode, 2)
                with self.assertRaises(ValueError) as cm:
                    lb.load_layout(doc)
                self.assertEqual("layout: " + p.stderr.strip()[len("pool-sim: "):],
                                 str(cm.exception))

    def test_strike_is_kept_as_written(self):
        lay = lb.load_layout(BASE)
        self.assertEqual(lay.strike_ball, 0)
        self.assertEqual(lay.strike, (1.5, 12.3, 4.5, 0.002, -0.004))
        self.assertEqual(lay.ball_ids, [0, 1])
        self.assertEqual([tuple(b.pos) for b in lay.balls],
                         [(0.5, 0.5, lay.sim_def.params.ball_radius),
                          (1.0, 0.5, lay.sim_def.params.ball_radius)])

    def test_what_json_cannot_carry_is_named(self):
        cases = [(changed(lambda d: d["balls"][1]["pos"].__setitem__(1, float("nan"))),
                  "layout: balls[1].pos[1]: must be a finite number"),
                 (changed(lambda d: d["strike"].update(speed=float("inf"))),
                  "layout: strike.speed: must be a finite number"),
                 (changed(lambda d: d["balls"][0].update(id=np.int64(0))),
                  "layout: balls[0].id: must be a JSON value")]
        for doc, message in cases:
            with self.subTest(message=message):
                with self.assertRaises(ValueError) as cm:
                    lb.load_layout(doc)
                self.assertTrue(str(cm.exception).startswith(message), str(cm.exception))
        # A tuple is an array, NumPy's float64 a float.
        lay = lb.load_layout(changed(lambda d: d["balls"][1].update(pos=(np.float64(1.0), 0.5))))
        self.assertEqual(tuple(lay.balls[1].pos)[:2], (1.0, 0.5))


def main():
    global ARGS
    parser = argparse.ArgumentParser()
    parser.add_argument("--struct-sizes", required=True)
    parser.add_argument("--pool-sim", required=True)
    parser.add_argument("--work", required=True)
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
