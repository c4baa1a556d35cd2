"""End-to-end tests of pool-fit and pool-tracks (ctest label "tools").

Usage: python test_fit.py --pool-fit PATH --pool-tracks PATH --work DIR [unittest arguments]

Oracles, in order of independence:
- closed forms written here, not by libpool: a centre-ball (stun) shot along a line slides with
  r(t) = v0 t - mu_slide g t^2 / 2 until t1 = 2 v0 / (7 mu_slide g), then rolls at 5/7 of v0,
  slowing by mu_roll g, with v0 = 2 V / (1 + m/M) (docs/physics.md, docs/validation.md 1).
  Tracks sampled from them at 100 Hz with Gaussian noise from Python's own generator; pool-fit
  must find V, phi, mu_slide and mu_roll from a wrong start, each inside its 95 % interval, with
  the residual at the noise and the standard errors of the size the linear theory gives;
- several shots together: one table (mu_slide, mu_roll) shared by three such shots of different
  speeds and directions, each with its own strike;
- a libpool shot with collisions (pool-tracks, no noise): the strike is found to 1e-6;
- determinism: the same output on 1 and 2 threads, and twice.
Bad input exits 2 and names the file, line, column or option. Every subprocess has a timeout.
"""
import argparse
import json
import math
import os
import random
import subprocess
import sys
import unittest

ARGS = None

R, M_BALL, M_CUE, G = 0.028575, 0.17, 0.54, 9.81
# Each estimate must lie within Z_CHECK standard errors of the truth: a correct fit fails one such
# check with probability 0.1 % (the seeds are fixed, so the outcome is deterministic). How often
# the 95 % intervals hold the truth is pool-fit-trials' test (fit_trials_coverage).
Z_CHECK = 3.2905


def near(test, p, truth, name):
    test.assertLessEqual(abs(p["value"] - truth), Z_CHECK * p["se"], "%s: %r, truth %r" % (name, p, truth))


def run(cmd, timeout=300):
    return subprocess.run(cmd, capture_output=True, timeout=timeout, text=True)


def work(name):
    return os.path.join(ARGS.work, name)


def write(name, text):
    path = work(name)
    with open(path, "w") as f:
        f.write(text)
    return path


def scenario(balls, strike=None, params=None, models=None):
    doc = {"format": "libpool-scenario/1", "balls": balls}
    if models:
        doc["models"] = models
    if strike:
        doc["strike"] = strike
    if params:
        doc["params"] = params
    return json.dumps(doc)


L, W = 2.54, 1.27  # the default table (wpa-9ft)


def stun_track(x0, y0, speed, phi_deg, mu_slide, mu_roll, t_end, rate=100.0):
    """Closed-form positions of a centre-ball strike (docs/physics.md), never libpool, until
    t_end or until the ball comes within 5 cm of a cushion (the forms know no cushions)."""
    v0 = 2.0 * speed / (1.0 + M_BALL / M_CUE)
    ux, uy = math.cos(math.radians(phi_deg)), math.sin(math.radians(phi_deg))
    t1 = 2.0 * v0 / (7.0 * mu_slide * G)
    d1 = v0 * t1 - 0.5 * mu_slide * G * t1 * t1
    v1 = 5.0 * v0 / 7.0
    t2 = v1 / (mu_roll * G)
    out = []
    for k in range(int(t_end * rate) + 1):
        t = k / rate
        if t <= t1:
            d = v0 * t - 0.5 * mu_slide * G * t * t
        else:
            s = min(t - t1, t2)
            d = d1 + v1 * s - 0.5 * mu_roll * G * s * s
        x, y = x0 + d * ux, y0 + d * uy
        if min(x, y, L - x, W - y) < 0.05:
            break
        out.append((t, x, y))
    return out


def tracks_csv(rows, sigma, rng, ball=0):
    lines = ["t,id,x,y"]
    for t, x, y in rows:
        lines.append("%.10g,%d,%.10g,%.10g" % (t, ball, x + rng.gauss(0.0, sigma), y + rng.gauss(0.0, sigma)))
    return "\n".join(lines) + "\n"


def fit(*args, timeout=600):
    r = run([ARGS.pool_fit, "--quiet", *args], timeout)
    if r.returncode != 0:
        raise AssertionError("pool-fit %s: exit %d: %s" % (" ".join(args), r.returncode, r.stderr))
    return json.loads(r.stdout)


def param(doc, name, shot):
    for p in doc["parameters"]:
        if p["name"] == name and p["shot"] == shot:
            return p
    raise KeyError(name)


class ClosedForm(unittest.TestCase):
    """Tracks from the closed forms; pool-fit recovers what made them."""

    def test_one_stun_shot(self):
        truth = dict(speed=0.9, phi=13.0, mu_slide=0.23, mu_roll=0.012)
        rows = stun_track(0.4, 0.3, truth["speed"], truth["phi"], truth["mu_slide"], truth["mu_roll"], 4.0)
        self.assertGreater(len(rows), 150)
        rng = random.Random(7)
        tracks = write("stun.csv", tracks_csv(rows, 0.001, rng))
        start = write("stun.json", scenario([{"id": 0, "pos": [0.4, 0.3]}],
                                            {"ball": 0, "speed": 1.5, "phi": 21.0}))
        doc = fit(start, tracks, "--fit", "speed,phi,mu_slide,mu_roll", "--summary")
        self.assertEqual(doc["format"], "libpool-fit/1")
        self.assertTrue(doc["solver"]["converged"])
        # The residual is the noise: rms of N(0, 1 mm) per coordinate within 10 %.
        self.assertAlmostEqual(doc["residual"]["rms"], 0.001, delta=1e-4)
        for name in ("speed", "phi"):
            near(self, param(doc, name, 0), truth[name], name)
        for name in ("mu_slide", "mu_roll"):
            p = param(doc, name, "all")
            near(self, p, truth[name], name)
            self.assertLess(p["ci95"][0], p["value"])
            self.assertGreater(p["ci95"][1], p["value"])
            self.assertAlmostEqual(doc["params"][name], p["value"])
        # Linear theory for the direction: the ball's lateral offset at distance d is d * dphi,
        # so 1 mm of noise on n points spread along the path gives se(phi) of order
        # sigma / sqrt(sum d^2); within a factor 2 of that.
        ds = [math.hypot(x - 0.4, y - 0.3) for _, x, y in rows]
        expected = math.degrees(0.001 / math.sqrt(sum(d * d for d in ds)))
        self.assertLess(param(doc, "phi", 0)["se"], 2 * expected)
        self.assertGreater(param(doc, "phi", 0)["se"], expected / 2)
        self.assertEqual(doc["shots"][0]["strike"]["ball"], 0)

    def test_three_shots_share_the_cloth(self):
        rng = random.Random(11)
        mu_slide, mu_roll = 0.18, 0.009
        shots = [(0.3, 0.3, 0.8, 10.0), (2.2, 1.0, 0.9, 190.0), (1.2, 0.15, 0.5, 80.0)]
        paths = []
        for k, (x, y, speed, phi) in enumerate(shots):
            rows = stun_track(x, y, speed, phi, mu_slide, mu_roll, 2.0)
            paths.append(write("shot%d.json" % k, scenario([{"id": 0, "pos": [x, y]}],
                                                           {"ball": 0, "speed": speed * 0.9, "phi": phi + 1.5})))
            paths.append(write("shot%d.csv" % k, tracks_csv(rows, 0.001, rng)))
        doc = fit(*paths, "--fit", "speed,phi,mu_slide,mu_roll")
        self.assertEqual(len(doc["shots"]), 3)
        self.assertEqual(len(doc["parameters"]), 2 + 3 * 2)
        for name, value in (("mu_slide", mu_slide), ("mu_roll", mu_roll)):
            near(self, param(doc, name, "all"), value, name)
        for k, (_, _, speed, phi) in enumerate(shots):
            near(self, param(doc, "speed", k), speed, "speed")
            self.assertAlmostEqual(doc["shots"][k]["strike"]["speed"], param(doc, "speed", k)["value"])
            wrapped = (phi + 180.0) % 360.0 - 180.0  # pool-fit reports phi in (-180, 180]
            near(self, param(doc, "phi", k), wrapped, "phi")
        # The normal equations built shot by shot (what fits of more than 16 parameters use) reach
        # the same minimum, standard errors and intervals as the dense QR: the same problem solved
        # by other linear algebra, so they differ by the solver's tolerance, not by a noise's worth.
        blocks = fit(*paths, "--fit", "speed,phi,mu_slide,mu_roll", "--linear", "blocks")
        for p, q in zip(doc["parameters"], blocks["parameters"]):
            self.assertEqual((p["name"], p["shot"]), (q["name"], q["shot"]))
            for a, b in ((p["value"], q["value"]), (p["ci95"][0], q["ci95"][0]), (p["ci95"][1], q["ci95"][1])):
                self.assertLessEqual(abs(a - b), 1e-3 * p["se"], "%s: %r %r" % (p["name"], p, q))
            self.assertAlmostEqual(q["se"] / p["se"], 1.0, delta=1e-4)

    def test_exact_tracks_give_the_truth(self):
        """Without noise the closed forms and libpool agree to rounding: the fit finds the values
        that made the tracks to 1e-7."""
        truth = dict(speed=0.8, phi=10.0, mu_slide=0.18, mu_roll=0.009)
        rows = stun_track(0.3, 0.3, truth["speed"], truth["phi"], truth["mu_slide"], truth["mu_roll"], 2.0)
        tracks = write("exact.csv", tracks_csv(rows, 0.0, random.Random(1)))
        start = write("exact.json", scenario([{"id": 0, "pos": [0.3, 0.3]}], {"ball": 0, "speed": 0.7, "phi": 11.0}))
        doc = fit(start, tracks, "--fit", "speed,phi,mu_slide,mu_roll")
        self.assertLess(doc["residual"]["rms"], 1e-8)
        self.assertAlmostEqual(param(doc, "speed", 0)["value"], truth["speed"], delta=1e-7)
        self.assertAlmostEqual(param(doc, "phi", 0)["value"], truth["phi"], delta=1e-6)
        self.assertAlmostEqual(param(doc, "mu_slide", "all")["value"], truth["mu_slide"], delta=1e-7)
        self.assertAlmostEqual(param(doc, "mu_roll", "all")["value"], truth["mu_roll"], delta=1e-8)

    def test_table_alone(self):
        """Only a table parameter free (the strike known): mu_roll from one stun shot's tracks."""
        truth = dict(speed=0.9, phi=13.0, mu_slide=0.2, mu_roll=0.011)
        rows = stun_track(0.4, 0.3, truth["speed"], truth["phi"], truth["mu_slide"], truth["mu_roll"], 4.0)
        tracks = write("table_alone.csv", tracks_csv(rows, 0.001, random.Random(17)))
        start = write("table_alone.json", scenario([{"id": 0, "pos": [0.4, 0.3]}],
                                                   {"ball": 0, "speed": truth["speed"], "phi": truth["phi"]},
                                                   {"mu_slide": truth["mu_slide"], "mu_roll": 0.02}))
        doc = fit(start, tracks, "--fit", "mu_roll")
        self.assertEqual(len(doc["parameters"]), 1)
        near(self, param(doc, "mu_roll", "all"), truth["mu_roll"], "mu_roll")

    def test_guess_from_the_tracks(self):
        """No strike in the scenario: --ball, and the start comes from the first frames."""
        rows = stun_track(1.0, 0.9, 1.0, -35.0, 0.2, 0.01, 2.0)
        tracks = write("guess.csv", tracks_csv(rows, 0.0005, random.Random(3)))
        start = write("guess.json", scenario([{"id": 0, "pos": [1.0, 0.9]}]))
        doc = fit(start, tracks, "--ball", "0", "--fit", "speed,phi")
        self.assertAlmostEqual(param(doc, "speed", 0)["value"], 1.0, delta=0.01)
        self.assertAlmostEqual(param(doc, "phi", 0)["value"], -35.0, delta=0.05)


class LibpoolTracks(unittest.TestCase):
    """Tracks of a shot with collisions and cushions, made by pool-tracks."""

    @classmethod
    def setUpClass(cls):
        balls = [{"id": 0, "pos": [0.7, 0.5]}, {"id": 1, "pos": [1.5, 0.7]}, {"id": 2, "pos": [2.0, 0.3]}]
        cls.truth = {"ball": 0, "speed": 2.2, "phi": 12.0, "a": 0.005, "b": 0.008}
        cls.shot = write("cut.json", scenario(balls, cls.truth))
        cls.start = write("cut_start.json", scenario(balls, {"ball": 0, "speed": 2.0, "phi": 11.0}))
        cls.tracks = work("cut.csv")
        r = run([ARGS.pool_tracks, cls.shot, "-o", cls.tracks])
        assert r.returncode == 0, r.stderr

    def test_exact_tracks_give_the_strike(self):
        # The 2012 laws are closed forms: the fit reaches the tracks' printed digits. The default
        # cushion (mathavan2010) integrates each impact in 128 steps, and a contact changing between
        # stick and slip inside a step leaves kinks of about 1e-7 m in the tracks as functions of
        # the strike: the least squares end there (measured 1.1e-7 m on this shot).
        for models, rms in (("thesis", 1e-8), (None, 1e-6)):
            with self.subTest(models=models):
                start, tracks = self.start, self.tracks
                if models:
                    balls = json.load(open(self.shot))["balls"]
                    shot = write("cut_%s.json" % models, scenario(balls, self.truth, models=models))
                    start = write("cut_start_%s.json" % models,
                                  scenario(balls, {"ball": 0, "speed": 2.0, "phi": 11.0}, models=models))
                    tracks = work("cut_%s.csv" % models)
                    r = run([ARGS.pool_tracks, shot, "-o", tracks])
                    self.assertEqual(r.returncode, 0, r.stderr)
                doc = fit(start, tracks)
                self.assertLess(doc["residual"]["rms"], rms)
                for name in ("speed", "phi", "a", "b"):
                    self.assertAlmostEqual(param(doc, name, 0)["value"], self.truth[name], delta=1e-6, msg=name)

    def test_cushion_parameters(self):
        """A shot off three cushions (the thesis laws, Petit's impulse): the cushion's restitution and
        friction from 1 mm tracks, each within Z_CHECK standard errors of the values that made them."""
        truth = {"e_cushion": 0.75, "mu_cushion": 0.15}
        balls = [{"id": 0, "pos": [0.6, 0.4]}, {"id": 1, "pos": [1.8, 0.9]}]
        shot = write("cushion.json", scenario(balls, {"ball": 0, "speed": 2.0, "phi": 75.0, "b": 0.005}, truth,
                                              models="thesis"))
        start = write("cushion_start.json", scenario(balls, {"ball": 0, "speed": 1.9, "phi": 75.5}, models="thesis"))
        tracks = work("cushion.csv")
        r = run([ARGS.pool_tracks, shot, "--noise", "0.001", "--seed", "3", "-o", tracks])
        self.assertEqual(r.returncode, 0, r.stderr)
        doc = fit(start, tracks, "--fit", "strike,e_cushion,mu_cushion")
        self.assertAlmostEqual(doc["residual"]["rms"], 0.001, delta=1e-4)
        for name, value in truth.items():
            near(self, param(doc, name, "all"), value, name)
        for p in doc["parameters"]:  # no interval beyond what the parameter can be
            if p["name"] in ("a", "b"):
                self.assertGreaterEqual(p["ci95"][0], -0.9 * R - 1e-12)
                self.assertLessEqual(p["ci95"][1], 0.9 * R + 1e-12)
            if p["name"] == "speed":
                self.assertGreater(p["ci95"][0], 0.0)

    def test_deterministic_whatever_the_threads(self):
        one = run([ARGS.pool_fit, "--quiet", "--threads", "1", self.start, self.tracks])
        two = run([ARGS.pool_fit, "--quiet", "--threads", "2", self.start, self.tracks])
        again = run([ARGS.pool_fit, "--quiet", "--threads", "2", self.start, self.tracks])
        self.assertEqual(one.returncode, 0, one.stderr)
        self.assertEqual(one.stdout, two.stdout)
        self.assertEqual(two.stdout, again.stdout)

    def test_outputs(self):
        prefix = work("out")
        for suffix in (".json", ".svg"):
            if os.path.exists(prefix + suffix):
                os.remove(prefix + suffix)
        r = run([ARGS.pool_fit, "--quiet", "--starts", "1", self.start, self.tracks, "-o", prefix, "--summary"])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(prefix + ".json") as f:
            self.assertEqual(json.load(f), json.loads(r.stdout))
        with open(prefix + ".svg") as f:
            svg = f.read()
        self.assertTrue(svg.startswith("<?xml") and svg.rstrip().endswith("</svg>"))
        self.assertIn("<polyline", svg)
        self.assertIn("parameter", r.stderr)  # the --summary table

    def test_tracks_noise_and_rate(self):
        noisy = work("noisy.csv")
        r = run([ARGS.pool_tracks, self.shot, "--noise", "0.002", "--rate", "50", "--seed", "5", "-o", noisy])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(self.tracks) as f:
            exact = [line.split(",") for line in f.read().split()[1:]]
        with open(noisy) as f:
            rows = [line.split(",") for line in f.read().split()[1:]]
        exact_at = {(float(t), i): (float(x), float(y)) for t, i, x, y in exact}
        errors = [float(x) - exact_at[(float(t), i)][0] for t, i, x, y in rows]
        # 50 Hz: every other frame of 100 Hz, for each ball as long as it is seen.
        every_other = sorted((round(float(t) * 100), i) for t, i, _, _ in exact if round(float(t) * 100) % 2 == 0)
        self.assertEqual(sorted((round(float(t) * 100), i) for t, i, _, _ in rows), every_other)
        sd = math.sqrt(sum(e * e for e in errors) / len(errors))
        self.assertAlmostEqual(sd, 0.002, delta=0.0003)


class BadInput(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.scenario = write("bad.json", scenario([{"id": 0, "pos": [0.5, 0.5]}, {"id": 1, "pos": [1.5, 0.5]}],
                                                  {"ball": 0, "speed": 1.0, "phi": 0.0}))
        rows = stun_track(0.5, 0.5, 1.0, 0.0, 0.2, 0.01, 0.5)
        cls.tracks = write("good.csv", tracks_csv(rows, 0.0, random.Random(1)))

    def expect(self, args, needle):
        r = run([ARGS.pool_fit, "--quiet", *args])
        self.assertEqual(r.returncode, 2, "%s: %s" % (args, r.stderr))
        self.assertIn(needle, r.stderr)
        self.assertEqual(r.stdout, "")

    def test_tracks_files(self):
        cases = [
            ("x,y,t\n", "no column id"),
            ("t,id,x,y,id\n0,0,1,1,0\n", "id is given twice"),
            ("t,id,x,y\n0,0,0.5,abc\n", "line 2, column y: 'abc' is not a position in metres"),
            ("t,id,x,y\n0,7,0.5,0.5\n", "line 2, column id: no ball of the scenario has id 7"),
            ("t,id,x,y\n0,0,0.5\n", "line 2: 3 cells, the header has 4"),
            ("t,id,x,y\n0,0,,0.5\n", "line 2: x and y must both be given or both be empty"),
            ("t,id,x,y\nnan,0,0.5,0.5\n", "column t: 'nan' is not a time in seconds"),
            ("t,id,x,y\n", "no observations"),
            ("", "no header"),
        ]
        for text, needle in cases:
            with self.subTest(text=text):
                self.expect([self.scenario, write("bad.csv", text)], needle)

    def test_options(self):
        self.expect([self.scenario], "has no tracks file")
        self.expect([], "missing SCENARIO.json TRACKS.csv")
        self.expect([self.scenario, self.tracks, "--fit", "mu_sliding"], "--fit: 'mu_sliding' is not a parameter")
        thesis = write("thesis.json", scenario([{"id": 0, "pos": [0.5, 0.5]}, {"id": 1, "pos": [1.5, 0.5]}],
                                               {"ball": 0, "speed": 1.0, "phi": 0.0}, models="thesis"))
        # A parameter the shot's laws never read is refused, naming the laws that read it.
        for path, name, needs in ((thesis, "throw_a", '"ball_ball_friction": "alciatore"'),
                                  (thesis, "e_cushion_mathavan", '"cushion": "mathavan2010"'),
                                  (self.scenario, "e_cushion", '"cushion": "petit"'),
                                  (self.scenario, "mu_ball", '"ball_ball_friction": "constant"'),
                                  (self.scenario, "cue_end_mass", '"squirt": "endmass"')):
            self.expect([path, self.tracks, "--fit", name], "%s is not used by the laws of" % name)
            self.expect([path, self.tracks, "--fit", name], "it needs \"models\": {%s}" % needs)
        self.expect([self.scenario, self.tracks, "--sigma", "-1"], "--sigma")
        self.expect([self.scenario, self.tracks, "--starts", "0"], "--starts")
        self.expect([self.scenario, self.tracks, "--intervals", "exact"], "--intervals")
        self.expect([self.scenario, self.tracks, "--linear", "sparse"], "--linear: 'sparse' is not auto, dense or blocks")
        self.expect([self.scenario, self.tracks, "--bogus"], "unknown option '--bogus'")
        self.expect([self.scenario, self.tracks, "--threads"], "needs a value")
        nostrike = write("nostrike.json", scenario([{"id": 0, "pos": [0.5, 0.5]}]))
        self.expect([nostrike, self.tracks], "no strike: give one")
        self.expect([nostrike, self.tracks, "--ball", "9"], "--ball")
        self.expect([write("broken.json", "{"), self.tracks], "broken.json")
        # More parameters than coordinates.
        self.expect([self.scenario, write("one.csv", "t,id,x,y\n0,0,0.5,0.5\n"), "--fit", "cue,t0"],
                    "more observations than there are parameters")

    def test_help(self):
        for tool in (ARGS.pool_fit, ARGS.pool_tracks):
            r = run([tool, "--help"])
            self.assertEqual(r.returncode, 0)
            self.assertIn("usage:", r.stdout)
        r = run([ARGS.pool_tracks, self.scenario, "--rate", "0"])
        self.assertEqual(r.returncode, 2)
        self.assertIn("--rate", r.stderr)


def main():
    global ARGS
    parser = argparse.ArgumentParser()
    parser.add_argument("--pool-fit", required=True)
    parser.add_argument("--pool-tracks", required=True)
    parser.add_argument("--work", required=True)
    ARGS, rest = parser.parse_known_args()
    os.makedirs(ARGS.work, exist_ok=True)
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
