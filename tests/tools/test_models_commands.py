"""The models (issues 12 and 25) through the commands: pool-sim, pool-batch and pool-rack refuse
bad "models" with exit status 2 and the field named, write nothing then; pool-rack --model and
--models write them into a scenario, pool-sim's result always carries them (so they round-trip),
and pool-batch runs every shot of a layout with the layout's models, or with --models (its rows
are pool-sim's results).

Usage: python test_models_commands.py --pool-sim PATH --pool-rack PATH [--pool-batch PATH]
                                      --work DIR [unittest arguments]
"""
import argparse
import json
import os
import subprocess
import sys
import unittest

ARGS = None
ALL_MODELS = {"cushion": "mathavan2010", "ball_ball_friction": "alciatore", "squirt": "endmass"}
DEFAULTS = {"cushion": "mathavan2010", "ball_ball_friction": "alciatore", "squirt": "none"}
THESIS = {"cushion": "petit", "ball_ball_friction": "constant", "squirt": "none"}
SPEC_NAMES = ("no model set (default, thesis) nor model (petit, mathavan2010, constant, alciatore, "
              "none, endmass)")


def run(cmd, timeout=120):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)


def scenario(models=None, params=None, strike=None):
    """A rail shot: the cue ball sent into the east cushion with side, past one object ball."""
    doc = {"format": "libpool-scenario/1",
           "balls": [{"id": 0, "pos": [1.2, 0.6]}, {"id": 1, "pos": [1.8, 0.7]}],
           "strike": strike or {"ball": 0, "speed": 2.5, "phi": 8.0, "a": 0.012, "b": 0.005}}
    if models is not None:
        doc["models"] = models
    if params is not None:
        doc["params"] = params
    return doc


def write(name, doc):
    path = os.path.join(ARGS.work, name)
    with open(path, "w") as f:
        f.write(doc if isinstance(doc, str) else json.dumps(doc))
    return path


# Bad "models" (and model parameters) and the message each must give, whole or its start.
BAD = [
    ({"cushion": "foo"}, None, 'models.cushion: unknown model "foo" (petit, mathavan2010)'),
    ({"ball_ball_friction": "speedy"}, None,
     'models.ball_ball_friction: unknown model "speedy" (constant, alciatore)'),
    ({"squirt": "lots"}, None, 'models.squirt: unknown model "lots" (none, endmass)'),
    ({"swerve": "none"}, None, "models.swerve: unknown field"),
    ({"cushion": 2}, None, "models.cushion: must be a string"),
    ("petit", None, 'models: unknown model set "petit" (default, thesis)'),
    (["thesis"], None, "models: must be a model set name or an object"),
    ({"set": "2012"}, None, 'models.set: unknown model set "2012" (default, thesis)'),
    (None, {"throw_d": 1.0}, "params.throw_d: unknown field"),
    (None, {"cue_end_mass": 0.0}, "params.cue_end_mass"),
    (None, {"throw_b": -0.1}, "params.throw_b"),
]


class Commands(unittest.TestCase):
    def test_pool_sim_refuses_bad_models_naming_the_field(self):
        for i, (models, params, message) in enumerate(BAD):
            path = write(f"bad_{i}.json", scenario(models, params))
            out = os.path.join(ARGS.work, f"bad_{i}.result.json")
            if os.path.exists(out):
                os.remove(out)
            r = run([ARGS.pool_sim, path, "-o", out])
            self.assertEqual(r.returncode, 2, f"{message}: {r.stderr!r}")
            self.assertTrue(r.stderr.startswith(f"pool-sim: {message}"), r.stderr)
            self.assertFalse(os.path.exists(out), "a refused scenario left an output file")

    def test_pool_batch_refuses_bad_models_naming_the_field(self):
        if not ARGS.pool_batch:
            self.skipTest("no pool-batch")
        for i, (models, params, message) in enumerate(BAD):
            path = write(f"bad_layout_{i}.json", scenario(models, params))
            r = run([ARGS.pool_batch, path, "--grid", "speed=1:2:2", "--no-progress"])
            self.assertEqual(r.returncode, 2, f"{message}: {r.stderr!r}")
            self.assertTrue(r.stderr.startswith(f"pool-batch: {message}"), r.stderr)
            self.assertEqual(r.stdout, "", "rows written for a refused layout")

    def test_pool_rack_refuses_bad_model_options(self):
        cases = [
            (["--model", "cushion=rubber"], "--model: unknown cushion model 'rubber' "
                                            "(petit, mathavan2010)"),
            (["--model", "spin=none"], "--model: 'spin=none' is not KIND=NAME (KIND among "
                                       "cushion, ball_ball_friction, squirt)"),
            (["--model", "mathavan2010"], "--model: 'mathavan2010' is not KIND=NAME"),
            (["--model"], "option --model needs a value"),
            (["--models", "rubber"], f"--models: 'rubber' is {SPEC_NAMES}"),
            (["--models", "thesis+"], f"--models: '' is {SPEC_NAMES}"),
            (["--models"], "option --models needs a value"),
        ]
        for extra, message in cases:
            r = run([ARGS.pool_rack, "8ball", *extra])
            self.assertEqual(r.returncode, 2, f"{extra}: {r.stderr!r}")
            self.assertTrue(r.stderr.startswith(f"pool-rack: {message}"), r.stderr)
            self.assertEqual(r.stdout, "")
        self.assertIn("--model KIND=NAME", run([ARGS.pool_rack, "--help"]).stdout)
        self.assertIn("--models SET", run([ARGS.pool_rack, "--help"]).stdout)

    def test_models_round_trip_through_rack_sim_and_result(self):
        rack = os.path.join(ARGS.work, "rack_models.json")
        r = run([ARGS.pool_rack, "9ball", "--model", "cushion=mathavan2010", "--model",
                 "ball_ball_friction=alciatore", "--model", "squirt=endmass", "-o", rack])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(rack) as f:
            doc = json.load(f)
        self.assertEqual(doc["models"], ALL_MODELS)
        # The later --model of a kind wins; the default names are written as such.
        r = run([ARGS.pool_rack, "9ball", "--model", "cushion=mathavan2010", "--model",
                 "cushion=petit", "--model", "squirt=endmass"])
        self.assertEqual(json.loads(r.stdout)["models"], dict(DEFAULTS, cushion="petit", squirt="endmass"))
        # Without --model the scenario has no "models" (the defaults).
        self.assertNotIn("models", json.loads(run([ARGS.pool_rack, "9ball"]).stdout))
        # --models: a set, then --model kinds on it.
        r = run([ARGS.pool_rack, "9ball", "--models", "thesis"])
        self.assertEqual(json.loads(r.stdout)["models"], THESIS)
        r = run([ARGS.pool_rack, "9ball", "--models", "thesis", "--model", "squirt=endmass"])
        self.assertEqual(json.loads(r.stdout)["models"], dict(THESIS, squirt="endmass"))
        r = run([ARGS.pool_rack, "9ball", "--models", "thesis+mathavan2010"])
        self.assertEqual(json.loads(r.stdout)["models"], dict(THESIS, cushion="mathavan2010"))

        out = os.path.join(ARGS.work, "rack_models.result.json")
        r = run([ARGS.pool_sim, rack, "-o", out])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out) as f:
            result = json.load(f)
        self.assertEqual(result["models"], ALL_MODELS)
        # The result's models, put back into a scenario, select the same models again: the
        # simulation is the same one, bit for bit.
        doc2 = dict(doc, models=result["models"])
        out2 = os.path.join(ARGS.work, "rack_models_again.result.json")
        r = run([ARGS.pool_sim, write("rack_models_again.json", doc2), "-o", out2])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out2) as f:
            self.assertEqual(json.load(f), result)
        # Every result says which laws made it: a default shot's, and a "thesis" one's.
        default_out = os.path.join(ARGS.work, "default.result.json")
        run([ARGS.pool_sim, write("default.json", scenario()), "-o", default_out])
        with open(default_out) as f:
            default_result = json.load(f)
        self.assertEqual(default_result["models"], DEFAULTS)
        thesis_out = os.path.join(ARGS.work, "thesis.result.json")
        run([ARGS.pool_sim, write("thesis.json", scenario("thesis")), "-o", thesis_out])
        with open(thesis_out) as f:
            thesis_result = json.load(f)
        self.assertEqual(thesis_result["models"], THESIS)
        # The laws differ on this rail shot: the final positions do too.
        self.assertNotEqual([b["pos"] for b in thesis_result["final"]],
                            [b["pos"] for b in default_result["final"]])

    def test_pool_batch_rows_are_pool_sims_with_the_layouts_models(self):
        if not ARGS.pool_batch:
            self.skipTest("no pool-batch")
        layout = scenario(ALL_MODELS, {"throw_a": 0.012, "cue_end_mass": 0.1})
        path = write("batch_layout.json", layout)
        strikes = [{"ball": 0, "speed": 2.5, "phi": 8.0, "a": 0.012, "b": 0.005},
                   {"ball": 0, "speed": 1.7, "phi": 5.0, "a": -0.01, "b": -0.008}]
        strikes_path = write("batch_strikes.json", strikes)
        r = run([ARGS.pool_batch, path, "--strikes", strikes_path, "--format", "jsonl",
                 "--threads", "2", "--no-progress"])
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = [json.loads(line) for line in r.stdout.splitlines()]
        self.assertEqual(len(rows), len(strikes))
        for k, (row, strike) in enumerate(zip(rows, strikes)):
            out = os.path.join(ARGS.work, f"batch_shot_{k}.result.json")
            r = run([ARGS.pool_sim, write(f"batch_shot_{k}.json", dict(layout, strike=strike)),
                     "-o", out])
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out) as f:
                want = json.load(f)
            self.assertEqual(want["models"], ALL_MODELS)
            self.assertEqual(row["events"], want["stats"]["events"], f"shot {k}")
            self.assertEqual(row["end_time"], want["stats"]["end_time"], f"shot {k}")
            self.assertEqual([b["pos"] for b in row["final"]], [b["pos"] for b in want["final"]],
                             f"shot {k}")


    def test_pool_batch_models_option(self):
        """--models replaces the layout's laws (applied to them): the rows are pool-sim's on the
        layout with those models; a bad value is refused before anything runs."""
        if not ARGS.pool_batch:
            self.skipTest("no pool-batch")
        layout = scenario(ALL_MODELS)
        path = write("batch_models_layout.json", layout)
        for spec, models in (("thesis", THESIS), ("thesis+endmass", dict(THESIS, squirt="endmass")),
                             ("default", DEFAULTS)):
            r = run([ARGS.pool_batch, path, "--grid", "speed=2.5", "--models", spec, "--format",
                     "jsonl", "--no-progress"])
            self.assertEqual(r.returncode, 0, r.stderr)
            row = json.loads(r.stdout)
            out = os.path.join(ARGS.work, "batch_models_want.result.json")
            r = run([ARGS.pool_sim, write("batch_models_want.json", dict(layout, models=models)),
                     "-o", out])
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out) as f:
                want = json.load(f)
            self.assertEqual(row["events"], want["stats"]["events"], spec)
            self.assertEqual([b["pos"] for b in row["final"]], [b["pos"] for b in want["final"]], spec)
        r = run([ARGS.pool_batch, path, "--grid", "speed=2.5", "--models", "thesis+rubber"])
        self.assertEqual(r.returncode, 2)
        self.assertTrue(r.stderr.startswith(f"pool-batch: --models: 'rubber' is {SPEC_NAMES}"), r.stderr)
        self.assertEqual(r.stdout, "")


def main():
    global ARGS
    p = argparse.ArgumentParser()
    p.add_argument("--pool-sim", required=True)
    p.add_argument("--pool-rack", required=True)
    p.add_argument("--pool-batch", default="")
    p.add_argument("--work", required=True)
    ARGS, rest = p.parse_known_args()
    os.makedirs(ARGS.work, exist_ok=True)
    unittest.main(argv=[sys.argv[0], *rest], verbosity=2)


if __name__ == "__main__":
    main()
