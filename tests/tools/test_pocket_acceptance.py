"""pool-pocket-acceptance (issue 20): Alciatore's pocket model as the tool computes it reproduces the
numbers TP 3.6 prints (its critical angles and the target's parts there), and libpool's sweep on
Alciatore's pocket geometry under his assumptions (no spin, mirror reflections, walls touching the
ball at its equator) gives his effective target sizes, corner (TP 3.6) and side (TP 3.5), to within
the sweep's line spacing; the tool writes its CSV and picture and refuses bad arguments.

Usage: python test_pocket_acceptance.py --tool PATH --python PATH --libpool PATH --work DIR
                                        [unittest arguments]
"""
import argparse
import csv
import importlib.machinery
import importlib.util
import os
import subprocess
import sys
import unittest

ARGS = None
RAD = 3.141592653589793 / 180


def load_tool():
    loader = importlib.machinery.SourceFileLoader("pocket_acceptance", ARGS.tool)
    spec = importlib.util.spec_from_loader("pocket_acceptance", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


class AlciatoreModel(unittest.TestCase):
    def test_tp36_printed_numbers(self):
        """TP 3.6 prints, for its pocket (p 4.5875 in, walls at 7 deg, hole 2.75 in, shelf 1.125 in,
        L = 96 in): theta_critical_C 38.558 deg where rail-point-wall and rail-wall-wall both give
        1.829 in at a rail distance of 10.275 in; theta_critical_D 28.167 deg where rail-wall-wall
        and point-wall-wall give 0.945 in; theta_max_long 44.058 deg at d_max 87.262 in; and 0.841
        in from wall-wall and point-wall at theta_critical = theta_critical_C - 90 deg."""
        tool = load_tool()
        tp = tool.tp36_corner()
        self.assertAlmostEqual(tp.th_c / RAD, 38.558, places=3)
        self.assertAlmostEqual(tp.th_d / RAD, 28.167, places=3)
        self.assertAlmostEqual(tp.th_max / RAD, 44.058, places=3)
        self.assertAlmostEqual(tp.d_max, 87.262, places=3)
        d = tp.d_rail(tp.s_point_wall, tp.th_c)
        self.assertAlmostEqual(d, 10.275, delta=2e-3)
        self.assertAlmostEqual(tp.s_rail(d, tp.th_c), 1.829, delta=1e-3)
        self.assertAlmostEqual(tp.s_rail(tp.d_rail(tp.s_wall_wall, tp.th_d), tp.th_d), 0.945, delta=1e-3)
        self.assertAlmostEqual(tp.s_point_wall_wall(tp.th_d), 0.945, delta=1e-3)
        crit = tp.th_c - 90 * RAD
        self.assertAlmostEqual(tp.s_wall_wall(crit), 0.841, delta=1e-3)
        self.assertAlmostEqual(tp.s_point_wall(crit), 0.841, delta=1e-3)

    def test_sweep_under_tp_assumptions_gives_tp(self):
        """The whole model (nose curve, contacts, Petit's law at e = 1, pocketing at the hole's
        edge) against the published analysis: lines 1 mm apart, so within 2 mm of target."""
        tool = load_tool()
        spacing = 1e-3
        for pocket, thetas, tp in (("sw", (0, 20, -30, 35), tool.tp36_corner()),
                                   ("s", (0, 40, -55), tool.tp35_side())):
            for theta, target in tool.sweep(pocket, 0.5, thetas, "specular", "tp", spacing=spacing):
                with self.subTest(pocket=pocket, theta=theta):
                    want = tp.target(theta) * tool.INCH
                    print(f"{pocket} {theta:+} deg: libpool {target / tool.INCH:.3f} in, "
                          f"Alciatore {want / tool.INCH:.3f} in")
                    self.assertLess(abs(target - want), 2 * spacing)


class Command(unittest.TestCase):
    def run_tool(self, *args):
        env = dict(os.environ, MPLBACKEND="Agg", LIBPOOL_PATH=ARGS.libpool,
                   PYTHONPATH=os.path.join(os.path.dirname(os.path.dirname(ARGS.tool)), "python"))
        return subprocess.run([ARGS.python, ARGS.tool, *args], capture_output=True, text=True,
                              timeout=600, env=env)

    def test_csv_and_picture(self):
        os.makedirs(ARGS.work, exist_ok=True)
        out, table = os.path.join(ARGS.work, "side.png"), os.path.join(ARGS.work, "side.csv")
        p = self.run_tool("--pocket", "s", "--step", "35", "--runs", "rolling:wpa,specular:tp",
                          "-o", out, "--csv", table)
        self.assertEqual(p.returncode, 0, p.stderr)
        with open(out, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        with open(table) as f:
            rows = list(csv.DictReader(f))
        self.assertEqual([float(r["theta_deg"]) for r in rows], [-70, -35, 0, 35, 70])
        for r in rows:  # nothing enters beyond +-70 deg; straight in, about 3.3 in
            self.assertGreaterEqual(float(r["rolling_wpa_in"]), 0.0)
        self.assertEqual(float(rows[0]["rolling_wpa_in"]), 0.0)
        self.assertGreater(float(rows[2]["rolling_wpa_in"]), 3.0)

    def test_bad_arguments(self):
        for args, message in ((["--runs", "rolling:snooker"], "--runs:"), (["--speed", "0"], "--speed:"),
                              (["--step", "90"], "--step:")):
            p = self.run_tool(*args)
            self.assertEqual(p.returncode, 2, p.stderr)
            self.assertIn(message, p.stderr)


def main():
    global ARGS
    p = argparse.ArgumentParser()
    p.add_argument("--tool", required=True)
    p.add_argument("--python", required=True)
    p.add_argument("--libpool", required=True)
    p.add_argument("--work", required=True)
    ARGS, rest = p.parse_known_args()
    os.environ["LIBPOOL_PATH"] = ARGS.libpool
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(ARGS.tool)), "python"))
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
