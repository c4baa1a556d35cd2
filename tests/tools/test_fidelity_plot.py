"""pool-fidelity-plot (issue 12) headless (MPLBACKEND=Agg): it writes its three figures as valid
PNG and SVG files into the directory given, answers --help, and exits 2 with a message for bad
arguments and bad published files (writing nothing then).

Usage: python test_fidelity_plot.py --tool PATH --python PATH --libpool PATH --work DIR
                                    [unittest arguments]
"""
import argparse
import json
import os
import shutil
import struct
import subprocess
import sys
import unittest
import xml.etree.ElementTree as ET

ARGS = None
FIGURES = ("cushion_speed_ratio", "cushion_rebound_angle", "throw")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
# Published values quoted in issue 12 (Alciatore TP A.14's 30 degree stun cut; Mathavan 2010's
# model for a rolling ball at 1 m/s, 45 degrees in, leaving 52.7 degrees from the rail).
PUBLISHED = {"series": [
    {"source": "Alciatore TP A.14", "quantity": "throw_angle", "x_name": "speed",
     "x": [0.45, 1.34, 3.13], "y": [4.7, 3.6, 1.7], "conditions": {"spin": "stun", "cut_angle": 30}},
    {"source": "Mathavan et al. 2010 (model)", "quantity": "cushion_rebound_angle",
     "x_name": "incidence_angle", "x": [45], "y": [52.7],
     "conditions": {"spin": "rolling", "speed": 1.0, "angles_from": "rail"}},
]}


def run(args, env_extra=None):
    env = dict(os.environ, MPLBACKEND="Agg", **(env_extra or {}))
    return subprocess.run([ARGS.python, ARGS.tool, *args], capture_output=True, text=True,
                          timeout=300, env=env)


def write_json(name, doc):
    path = os.path.join(ARGS.work, name)
    with open(path, "w") as f:
        f.write(doc if isinstance(doc, str) else json.dumps(doc))
    return path


def png_size(path):
    """(width, height) from a PNG's IHDR chunk, after checking the signature and chunk type."""
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != PNG_SIGNATURE or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


class FidelityPlot(unittest.TestCase):
    def test_writes_valid_png_and_svg(self):
        out = os.path.join(ARGS.work, "figures")
        shutil.rmtree(out, ignore_errors=True)
        published = write_json("published.json", PUBLISHED)
        r = run([out, "--published", published, "--libpool", ARGS.libpool])
        self.assertEqual(r.returncode, 0, r.stderr)
        listed = r.stdout.split()
        for name in FIGURES:
            png, svg = os.path.join(out, name + ".png"), os.path.join(out, name + ".svg")
            self.assertIn(png, listed)
            self.assertIn(svg, listed)
            size = png_size(png)
            self.assertIsNotNone(size, f"{png}: not a PNG")
            self.assertTrue(size[0] >= 300 and size[1] >= 200, f"{png}: {size}")
            root = ET.parse(svg).getroot()  # well-formed XML
            self.assertTrue(root.tag.endswith("svg"), root.tag)
        self.assertEqual(sorted(os.listdir(out)),
                         sorted(f"{n}.{e}" for n in FIGURES for e in ("png", "svg")))
        # --format png writes only the PNGs.
        only = os.path.join(ARGS.work, "png_only")
        shutil.rmtree(only, ignore_errors=True)
        r = run([only, "--published", published, "--libpool", ARGS.libpool, "--format", "png"])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(sorted(os.listdir(only)), sorted(f"{n}.png" for n in FIGURES))

    def test_block_form_and_the_trees_file(self):
        """The block form of the published file (the one the models' own tests read) is drawn
        too, and tests/data/published_fidelity.json (the default) is readable."""
        blocks = {"cushion": {"source": "Mathavan 2010",
                              "rows": [{"spin": "rolling", "speed": 1.0, "incidence_deg": 0.0,
                                        "speed_ratio": 0.91},
                                       {"spin": "rolling", "speed": 1.0, "incidence_deg": 45.0,
                                        "rebound_from_rail_deg": 52.7}],
                              "measured": {"speed_ratio_min": 0.9, "speed_ratio_max": 0.95,
                                           "speed_min": 0.5, "speed_max": 2.0}},
                  "throw": {"source": "Alciatore TP A.14",
                            "rows": [{"cue": "stun", "cut_deg": 30.0, "speed": v, "throw_deg": t}
                                     for v, t in ((0.447, 4.7), (1.341, 3.6), (3.129, 1.7))]}}
        for name, args in (("blocks", ["--published", write_json("blocks.json", blocks)]),
                           ("default", [])):
            with self.subTest(name):
                out = os.path.join(ARGS.work, "figures_" + name)
                shutil.rmtree(out, ignore_errors=True)
                r = run([out, "--libpool", ARGS.libpool, "--format", "png", *args])
                self.assertEqual(r.returncode, 0, r.stderr)
                self.assertEqual(sorted(os.listdir(out)), sorted(f"{n}.png" for n in FIGURES))
        bad = dict(blocks, throw={"rows": [{"cue": "stun", "cut_deg": 30.0, "speed": "fast",
                                            "throw_deg": 1.0}]})
        r = run([os.path.join(ARGS.work, "x"), "--published", write_json("bad_blocks.json", bad)])
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("throw.rows[0].speed: must be a finite number", r.stderr)

    def test_help(self):
        r = run(["--help"])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("usage: pool-fidelity-plot", r.stdout)
        self.assertIn("--published", r.stdout)

    def test_bad_arguments_exit_2(self):
        good = write_json("published_ok.json", PUBLISHED)
        a_file = write_json("not_a_dir", "x")
        series = PUBLISHED["series"][0]
        bad_published = {
            "missing_y": ({"series": [{k: v for k, v in series.items() if k != "y"}]},
                          "series[0].y: missing"),
            "quantity": ({"series": [dict(series, quantity="spin_decay")]},
                         "series[0].quantity: unknown 'spin_decay'"),
            "x_name": ({"series": [dict(series, x_name="time")]}, "series[0].x_name: unknown"),
            "lengths": ({"series": [dict(series, y=[1.0])]}, "x and y must have the same"),
            "numbers": ({"series": [dict(series, x=[0.5, "fast", 3.0])]},
                        "series[0].x: must be a list of finite numbers"),
            "not_list": ({"series": 3}, "expected a list of series"),
            "not_json": ("{", "is not JSON"),
        }
        cases = [
            ([], "the following arguments are required: outdir"),
            ([os.path.join(ARGS.work, "x"), "--format", "jpg", "--published", good],
             "--format: 'jpg'"),
            ([os.path.join(ARGS.work, "x"), "--bogus"], "unrecognized arguments: --bogus"),
            ([a_file, "--published", good], "exists and is not a directory"),
            ([os.path.join(ARGS.work, "x"), "--published", os.path.join(ARGS.work, "none.json")],
             "--published: cannot read"),
            ([os.path.join(ARGS.work, "x"), "--published", good, "--libpool",
              os.path.join(ARGS.work, "nolib.so")], "--libpool:"),
        ]
        for name, (doc, message) in bad_published.items():
            cases.append(([os.path.join(ARGS.work, "x"), "--published",
                           write_json(f"bad_{name}.json", doc)], message))
        for args, message in cases:
            with self.subTest(args=args):
                r = run(args)
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertIn(message, r.stderr)
                self.assertTrue(r.stderr.startswith("pool-fidelity-plot: ")
                                or r.stderr.startswith("usage:"), r.stderr)
        self.assertFalse(os.path.exists(os.path.join(ARGS.work, "x")), "bad arguments wrote")


def main():
    global ARGS
    p = argparse.ArgumentParser()
    p.add_argument("--tool", required=True)
    p.add_argument("--python", required=True)
    p.add_argument("--libpool", required=True)
    p.add_argument("--work", required=True)
    ARGS, rest = p.parse_known_args()
    os.makedirs(ARGS.work, exist_ok=True)
    unittest.main(argv=[sys.argv[0], *rest], verbosity=2)


if __name__ == "__main__":
    main()
