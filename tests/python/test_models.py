#!/usr/bin/env python3
"""The models (issues 12 and 25) in the Python binding: chosen by name or model set on a Sim
(models=...), refused with the field named, read back by name; the defaults are the measured laws
and "thesis" the 2012 work's; a Sim with models simulates exactly what pool-sim simulates for the
same scenario; libpool.batch's layout parser reads "models" and the model parameters as pool-sim's
parser does (same values, same messages).

Usage: test_models.py [--pool-sim PROG] [--work DIR] [unittest args]
(LIBPOOL_PATH names the shared library; PYTHONPATH holds python/.)
"""

import argparse
import json
import os
import subprocess
import sys
import unittest

import libpool
from libpool import PoolError

ARGS = None
ALL = {"cushion": "mathavan2010", "ball_ball_friction": "alciatore", "squirt": "endmass"}
DEFAULTS = {"cushion": "mathavan2010", "ball_ball_friction": "alciatore", "squirt": "none"}
THESIS = {"cushion": "petit", "ball_ball_friction": "constant", "squirt": "none"}
# Each kind's model that is not the default one.
OTHERS = {"cushion": "petit", "ball_ball_friction": "constant", "squirt": "endmass"}
INVALID_ARGUMENT = -1

# A cut into the rail: the cue ball struck with side hits ball 1, both reach cushions.
BALLS = [(0, (1.0, 0.5)), (1, (1.5, 0.62))]
STRIKE = (0, 2.2, 12.0, 0.0, 0.011, -0.004)  # ball, speed, phi deg, theta deg, a, b


def scenario(models=None, params=None):
    doc = {"format": "libpool-scenario/1",
           "balls": [{"id": i, "pos": list(p)} for i, p in BALLS],
           "strike": dict(zip(("ball", "speed", "phi", "theta", "a", "b"), STRIKE))}
    if models is not None:
        doc["models"] = models
    if params is not None:
        doc["params"] = params
    return doc


def run_sim(models=None, params=None):
    with libpool.Sim(params=params, models=models) as sim:
        for i, p in BALLS:
            sim.add_ball(i, p)
        sim.strike(*STRIKE)
        sim.run()
        return sim.events, sim.state_at(sim.end_time)


class Names(unittest.TestCase):
    def test_kinds_and_names(self):
        self.assertEqual(libpool.MODEL_KINDS, ("cushion", "ball_ball_friction", "squirt"))
        self.assertEqual(libpool.model_names("cushion"), ["petit", "mathavan2010"])
        self.assertEqual(libpool.model_names("ball_ball_friction"), ["constant", "alciatore"])
        self.assertEqual(libpool.model_names("squirt"), ["none", "endmass"])
        with self.assertRaises(PoolError):
            libpool.model_names("swerve")

    def test_make_models(self):
        self.assertEqual(libpool.models_dict(libpool.make_models()), DEFAULTS)
        self.assertEqual(libpool.models_dict(libpool.make_models(ALL)), ALL)
        m = libpool.make_models({"cushion": "mathavan2010"}, squirt="endmass")
        self.assertEqual(libpool.models_dict(m), dict(DEFAULTS, cushion="mathavan2010",
                                                      squirt="endmass"))
        # A Models is copied, keywords applied on top.
        copy = libpool.make_models(m, cushion="petit")
        self.assertEqual(copy.cushion, 0)
        self.assertEqual(m.cushion, 1)
        self.assertEqual(libpool.models_dict(libpool.default_sim_def().models), DEFAULTS)

    def test_model_sets(self):
        self.assertEqual(libpool.model_sets(), ["default", "thesis"])
        self.assertEqual(libpool.models_dict(libpool.default_models()), DEFAULTS)
        self.assertEqual(libpool.models_dict(libpool.thesis_models()), THESIS)
        self.assertEqual(bytes(libpool.thesis_models()), bytes(libpool.Models()))  # all zero
        self.assertEqual(libpool.models_dict(libpool.make_models("thesis")), THESIS)
        self.assertEqual(libpool.models_dict(libpool.make_models("default")), DEFAULTS)
        self.assertEqual(libpool.models_dict(libpool.make_models({"set": "thesis", "squirt": "endmass"})),
                         dict(THESIS, squirt="endmass"))
        self.assertEqual(libpool.models_dict(libpool.make_models({"set": "thesis"}, cushion="mathavan2010")),
                         dict(THESIS, cushion="mathavan2010"))
        self.assertEqual(libpool.models_dict(libpool.make_models({"ball_ball_friction": "constant"})),
                         dict(DEFAULTS, ball_ball_friction="constant"))

    def test_refusals_name_the_field(self):
        cases = [
            ({"cushion": "foo"}, 'models.cushion: unknown model "foo" (petit, mathavan2010)'),
            ({"squirt": "Endmass"}, 'models.squirt: unknown model "Endmass" (none, endmass)'),
            ({"ball_ball_friction": 1},
             'models.ball_ball_friction: unknown model "1" (constant, alciatore)'),
            ({"cushion": "petit\0mathavan2010"}, "models.cushion: unknown model"),
            ({"swerve": "none"}, "models.swerve: unknown field"),
            ("mathavan2010", 'models: unknown model set "mathavan2010" (default, thesis)'),
            ("thesis\0", 'models: unknown model set'),
            ({"set": "2012"}, 'models.set: unknown model set "2012" (default, thesis)'),
            ({"set": 2012}, "models.set: must be a string"),
        ]
        for models, message in cases:
            with self.subTest(models=models):
                with self.assertRaises(PoolError) as cm:
                    libpool.Sim(models=models)
                self.assertEqual(cm.exception.code, INVALID_ARGUMENT)
                self.assertTrue(cm.exception.message.startswith(message), cm.exception.message)
        with self.assertRaises(TypeError):
            libpool.Sim(models=["thesis"])


class OnTheSim(unittest.TestCase):
    def test_sim_keeps_and_reports_its_models(self):
        with libpool.Sim(models={"cushion": "mathavan2010"}) as sim:
            self.assertEqual(sim.models, dict(DEFAULTS, cushion="mathavan2010"))
            self.assertEqual(sim.definition.models.cushion, 1)
            # reset without models keeps them; with models replaces them as a whole.
            sim.reset(max_time=30.0)
            self.assertEqual(sim.models["cushion"], "mathavan2010")
            sim.reset(models={"squirt": "endmass"})
            self.assertEqual(sim.models, dict(DEFAULTS, squirt="endmass"))
            sim.reset(models={})
            self.assertEqual(sim.models, DEFAULTS)
        with libpool.Sim() as sim:
            self.assertEqual(sim.models, DEFAULTS)
            sim.reset(models="thesis")
            self.assertEqual(sim.models, THESIS)

    def test_model_parameters_are_params(self):
        p = libpool.default_params()
        self.assertEqual((p.throw_a, p.throw_b, p.throw_c), (9.951e-3, 0.108, 1.088))
        self.assertGreater(p.cue_end_mass, 0.0)
        p.cue_end_mass = 0.0
        with self.assertRaises(PoolError) as cm:
            libpool.validate_params(p)
        self.assertTrue(cm.exception.message.startswith("params.cue_end_mass"),
                        cm.exception.message)

    def test_same_shot_as_pool_sim(self):
        """The binding hands the models to the library as the scenario parser does: the events
        and final states of pool-sim's result, to the last bit, for every combination tried."""
        if not ARGS.pool_sim:
            self.skipTest("no --pool-sim")
        params = libpool.default_params()
        params.throw_a, params.cue_end_mass = 0.012, 0.09
        for k, models in enumerate((ALL, {"cushion": "petit"}, {"squirt": "endmass"}, {}, "thesis",
                                    {"set": "thesis", "squirt": "endmass"})):
            with self.subTest(models=models):
                path = os.path.join(ARGS.work, "models_%d.json" % k)
                with open(path, "w") as f:
                    json.dump(scenario(models, {"throw_a": 0.012, "cue_end_mass": 0.09}), f)
                out = subprocess.run([ARGS.pool_sim, path], check=True, capture_output=True,
                                     text=True).stdout
                want = json.loads(out)
                events, final = run_sim(models, params)
                self.assertEqual(len(events), len(want["events"]))
                for e, w in zip(events, want["events"]):
                    self.assertEqual((e.time, e.type), (w["t"], w["type"]))
                    self.assertEqual([list(b.pos) for b in e.after], [b["pos"] for b in w["after"]])
                    self.assertEqual([list(b.vel) for b in e.after], [b["vel"] for b in w["after"]])
                self.assertEqual([list(b.pos) for b in final], [b["pos"] for b in want["final"]])
                self.assertEqual(want["models"], libpool.models_dict(libpool.make_models(models)))


class ModelsMatter(unittest.TestCase):
    def test_each_model_changes_the_shot(self):
        """Each kind, chosen alone, changes this shot's final positions (the cut with side goes
        into cushions): the binding did not drop it on the way to the library."""
        _, default = run_sim({})
        for kind, name in OTHERS.items():
            with self.subTest(kind=kind):
                _, final = run_sim({kind: name})
                self.assertNotEqual([b.pos for b in final], [b.pos for b in default])
        _, thesis = run_sim("thesis")
        self.assertNotEqual([b.pos for b in thesis], [b.pos for b in default])


class BatchLayout(unittest.TestCase):
    """libpool.batch reads models with pool-sim's own parser (libpool_scenario)."""

    def setUp(self):
        try:
            import libpool.batch  # noqa: F401  (needs NumPy)
        except ImportError as e:
            self.skipTest(f"libpool.batch unavailable: {e}")

    def test_layout_reads_models_and_parameters(self):
        import libpool.batch as batch
        layout = batch.load_layout(scenario(ALL, {"throw_c": 2.0, "cue_end_mass": 0.11}))
        self.assertEqual(libpool.models_dict(layout.sim_def.models), ALL)
        self.assertEqual(layout.sim_def.params.throw_c, 2.0)
        self.assertEqual(layout.sim_def.params.cue_end_mass, 0.11)
        self.assertEqual(libpool.models_dict(batch.load_layout(scenario()).sim_def.models),
                         DEFAULTS)
        self.assertEqual(libpool.models_dict(batch.load_layout(scenario("thesis")).sim_def.models),
                         THESIS)
        layout = batch.load_layout(scenario({"set": "thesis", "cushion": "mathavan2010"}))
        self.assertEqual(libpool.models_dict(layout.sim_def.models), dict(THESIS, cushion="mathavan2010"))

    def test_layout_refusals_are_pool_sims(self):
        import libpool.batch as batch
        bad = [({"cushion": "foo"}, None), ({"squirt": 3}, None), ("petit", None), (["thesis"], None),
               ({"set": "x"}, None), ({"set": None}, None),
               ({"cushions": "petit"}, None), ({"": "x"}, None), (None, {"throw_q": 1.0}),
               (None, {"cue_end_mass": -1.0}), (None, {"throw_b": "big"})]
        for models, params in bad:
            with self.subTest(models=models, params=params):
                doc = scenario(models, params)
                with self.assertRaises(ValueError) as cm:
                    batch.load_layout(doc)
                got = str(cm.exception)
                self.assertTrue(got.startswith("layout: models") or got.startswith("layout: params"),
                                got)
                if ARGS.pool_sim:
                    path = os.path.join(ARGS.work, "bad_layout.json")
                    with open(path, "w") as f:
                        json.dump(doc, f)
                    r = subprocess.run([ARGS.pool_sim, path], capture_output=True, text=True)
                    self.assertEqual(r.returncode, 2)
                    self.assertEqual(got[len("layout: "):], r.stderr.strip()[len("pool-sim: "):])

    def test_batch_run_uses_the_layouts_models(self):
        """libpool.batch.run with a models layout gives pool-sim's final positions."""
        import libpool.batch as batch
        if not ARGS.pool_sim:
            self.skipTest("no --pool-sim")
        doc = scenario(ALL)
        res = batch.run(doc, [STRIKE], workers=1)
        path = os.path.join(ARGS.work, "batch_models.json")
        with open(path, "w") as f:
            json.dump(doc, f)
        want = json.loads(subprocess.run([ARGS.pool_sim, path], check=True, capture_output=True,
                                         text=True).stdout)
        self.assertEqual(res.pos[0].tolist(), [b["pos"] for b in want["final"]])
        self.assertEqual(int(res.events[0]), want["stats"]["events"])


def main():
    global ARGS
    p = argparse.ArgumentParser()
    p.add_argument("--pool-sim", default="")
    p.add_argument("--work", default="work_models")
    ARGS, rest = p.parse_known_args()
    os.makedirs(ARGS.work, exist_ok=True)
    unittest.main(argv=[sys.argv[0], *rest], verbosity=2)


if __name__ == "__main__":
    main()
