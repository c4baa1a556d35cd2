"""pool-bench-breaks, pool-break-plot and bench/breaks/pooltool_breaks.py (issue 25).

pool-bench-breaks: its printed statistics are recomputed here from its --json (the median rack
ball's distance, the means per break, the share of breaks pocketing a ball); the same seed gives
the same breaks; every model set runs the same aims; a gentle break (0.5 m/s) moves no ball far,
sends none to a rail or a pocket; bad arguments exit 2 with a message. pool-break-plot draws
valid PNG and SVG files from that JSON (when the tools' Python has matplotlib) and exits 2 on bad
input. pooltool_breaks.py, run by a Python without pooltool, says so and exits 3.

Usage: python test_breaks.py --bench PATH --plot PATH --pooltool-script PATH --python PATH
                             --work DIR [--require-matplotlib] [unittest arguments]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import unittest

ARGS = None
RACK_BALLS = 15
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def bench(*args):
    return subprocess.run([ARGS.bench, *args], capture_output=True, text=True, timeout=300)


def python(script, *args):
    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run([ARGS.python, script, *args], capture_output=True, text=True,
                          timeout=300, env=env)


def work(name):
    return os.path.join(ARGS.work, name)


def has_module(name):
    r = subprocess.run([ARGS.python, "-c", f"import {name}"], capture_output=True, timeout=120)
    return r.returncode == 0


def rows(stdout):
    """{set name: [printed fields]} from the statistics table."""
    lines = stdout.splitlines()
    head = next(i for i, line in enumerate(lines) if line.startswith("models"))
    out = {}
    for line in lines[head + 1:]:
        if line.strip():
            fields = line.split()
            out[fields[0]] = fields[1:]
    return out


class BenchBreaks(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.json_path = work("breaks.json")
        cls.result = bench("--breaks", "6", "--seed", "3", "--models", "thesis,default,thesis+alciatore",
                        "--json", cls.json_path)
        with open(cls.json_path) as f:
            cls.doc = json.load(f)

    def test_runs_and_writes_the_format(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        self.assertIn("machine:", self.result.stdout)
        self.assertEqual(self.doc["format"], "libpool-breaks/1")
        self.assertEqual(self.doc["breaks"], 6)
        self.assertEqual(self.doc["seed"], 3)
        self.assertEqual([s["name"] for s in self.doc["sets"]],
                         ["thesis", "default", "thesis+alciatore"])
        self.assertEqual(self.doc["sets"][0]["models"],
                         {"cushion": "petit", "ball_ball_friction": "constant", "squirt": "none"})
        self.assertEqual(self.doc["sets"][1]["models"],
                         {"cushion": "mathavan2010", "ball_ball_friction": "alciatore",
                          "squirt": "none"})
        self.assertEqual(self.doc["sets"][2]["models"]["ball_ball_friction"], "alciatore")
        self.assertEqual(self.doc["sets"][2]["models"]["cushion"], "petit")

    def test_figures_are_in_range(self):
        for s in self.doc["sets"]:
            self.assertEqual(len(s["displacement"]), RACK_BALLS * 6, s["name"])
            for key in ("moved", "cushion", "pocketed"):
                self.assertEqual(len(s[key]), 6)
                self.assertTrue(all(0 <= x <= RACK_BALLS for x in s[key]), (s["name"], key))
            self.assertTrue(all(x >= 0 for x in s["displacement"] + s["cue_distance"]))
            self.assertTrue(all(x in (0, 1) for x in s["scratch"]))
            self.assertTrue(all(x > 0 for x in s["events"]))

    def test_printed_statistics_are_the_json_s(self):
        printed = rows(self.result.stdout)
        for s in self.doc["sets"]:
            p = printed[s["name"]]
            n = len(s["moved"])
            self.assertAlmostEqual(float(p[0]), statistics.median(s["displacement"]), delta=5e-4)
            self.assertEqual(p[1], "m")
            self.assertAlmostEqual(float(p[2]), sum(s["moved"]) / n, delta=5e-3)
            self.assertAlmostEqual(float(p[3]), sum(s["cushion"]) / n, delta=5e-3)
            self.assertAlmostEqual(float(p[4]), sum(s["pocketed"]) / n, delta=5e-3)
            share = 100.0 * sum(1 for x in s["pocketed"] if x > 0) / n
            self.assertAlmostEqual(float(p[5]), share, delta=0.5)
            self.assertAlmostEqual(float(p[7]), statistics.median(s["cue_distance"]), delta=5e-4)

    def test_the_same_seed_gives_the_same_breaks(self):
        again = work("breaks_again.json")
        r = bench("--breaks", "6", "--seed", "3", "--models", "thesis,default,thesis+alciatore",
                  "--json", again)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(again) as f:
            self.assertEqual(json.load(f)["sets"], self.doc["sets"])
        other = work("breaks_seed4.json")
        r = bench("--breaks", "6", "--seed", "4", "--models", "thesis", "--json", other)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(other) as f:
            self.assertNotEqual(json.load(f)["sets"][0]["displacement"],
                                self.doc["sets"][0]["displacement"])

    def test_the_sets_differ(self):
        thesis, default = self.doc["sets"][0], self.doc["sets"][1]
        self.assertNotEqual(thesis["displacement"], default["displacement"])

    def test_a_gentle_break_hardly_moves_the_rack(self):
        path = work("gentle.json")
        r = bench("--breaks", "3", "--speed", "0.5", "--json", path)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(path) as f:
            doc = json.load(f)
        self.assertEqual([s["name"] for s in doc["sets"]], ["thesis", "default"])
        for s in doc["sets"]:
            self.assertEqual(s["moved"], [0, 0, 0])
            self.assertEqual(s["cushion"], [0, 0, 0])
            self.assertEqual(s["pocketed"], [0, 0, 0])
            self.assertLess(max(s["displacement"]), 0.3)

    def test_bad_arguments_exit_2(self):
        for args in (["--breaks", "0"], ["--breaks", "x"], ["--speed", "-1"], ["--speed", "60"],
                     ["--seed", "-2"], ["--models", "nonsense"], ["--models", ""],
                     ["--models", "thesis+petit+foo"], ["--bogus"], ["--json"]):
            r = bench(*args)
            self.assertEqual(r.returncode, 2, (args, r.stdout, r.stderr))
            self.assertIn("pool-bench-breaks", r.stderr, args)

    def test_help(self):
        r = bench("--help")
        self.assertEqual(r.returncode, 0)
        self.assertIn("usage: pool-bench-breaks", r.stdout)


class BreakPlot(unittest.TestCase):
    def setUp(self):
        self.json_path = work("plot_input.json")
        r = bench("--breaks", "4", "--json", self.json_path)
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_draws_png_and_svg(self):
        if not has_module("matplotlib"):
            if ARGS.require_matplotlib:
                self.fail(f"{ARGS.python} has no matplotlib")
            self.skipTest("no matplotlib")
        png, svg = work("breaks.png"), work("breaks.svg")
        for out in (png, svg):
            if os.path.exists(out):
                os.remove(out)
            r = python(ARGS.plot, self.json_path, "-o", out)
            self.assertEqual(r.returncode, 0, r.stderr)
        with open(png, "rb") as f:
            self.assertEqual(f.read(8), PNG_SIGNATURE)
        with open(svg) as f:
            self.assertIn("<svg", f.read())

    def test_bad_input_exits_2(self):
        bad = work("bad_breaks.json")
        with open(bad, "w") as f:
            json.dump({"format": "libpool-breaks/1", "sets": [{"name": "x"}]}, f)
        not_json = work("not_json.json")
        with open(not_json, "w") as f:
            f.write("{")
        for args in ([bad, "-o", work("x.png")], [not_json, "-o", work("x.png")],
                     [work("missing.json"), "-o", work("x.png")], [self.json_path]):
            r = python(ARGS.plot, *args)
            self.assertEqual(r.returncode, 2, (args, r.stderr))
            self.assertTrue(r.stderr.strip(), args)
        self.assertFalse(os.path.exists(work("x.png")))


class PooltoolScript(unittest.TestCase):
    def test_without_pooltool_says_so_and_exits_3(self):
        if has_module("pooltool"):
            self.skipTest("pooltool is installed in the tools' Python")
        r = python(ARGS.pooltool_script, "--breaks", "1", "-o", work("pooltool.json"))
        self.assertEqual(r.returncode, 3, r.stderr)
        self.assertIn("pooltool", r.stderr)
        self.assertFalse(os.path.exists(work("pooltool.json")))


def main():
    global ARGS
    p = argparse.ArgumentParser()
    p.add_argument("--bench", required=True)
    p.add_argument("--plot", required=True)
    p.add_argument("--pooltool-script", required=True)
    p.add_argument("--python", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--require-matplotlib", action="store_true")
    ARGS, rest = p.parse_known_args()
    os.makedirs(ARGS.work, exist_ok=True)
    unittest.main(argv=[sys.argv[0], *rest], verbosity=2)


if __name__ == "__main__":
    main()
