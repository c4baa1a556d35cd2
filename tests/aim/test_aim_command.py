"""End-to-end tests of pool-aim (ctest label "tools").

Usage: python test_aim_command.py --pool-aim PATH --pool-sim PATH --work DIR [unittest arguments]

Every shot pool-aim prints is played again by pool-sim (a scenario with that strike, and the
position's "game" when it has one), and must do what the list says: drop that ball in that pocket
(legally under the rules), the cue ball staying on the table. Then the list's form, the picture,
determinism, and bad input (exit 2, the option or field named).
"""
import argparse
import json
import os
import subprocess
import sys
import unittest

ARGS = None


def run(cmd, timeout=600):
    return subprocess.run(cmd, capture_output=True, timeout=timeout, text=True)


def work(name):
    return os.path.join(ARGS.work, name)


def write(name, doc):
    path = work(name)
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


POSITION = {"format": "libpool-scenario/1",
            "balls": [{"id": 0, "pos": [1.0, 0.5]}, {"id": 1, "pos": [2.0, 0.3]}, {"id": 2, "pos": [0.6, 1.0]},
                      {"id": 3, "pos": [1.5, 0.95]}]}


def aim(*args):
    r = run([ARGS.pool_aim, *args])
    if r.returncode != 0:
        raise AssertionError("pool-aim %s: exit %d: %s" % (" ".join(args), r.returncode, r.stderr))
    return json.loads(r.stdout)


def replay(position, shot):
    """pool-sim on the position with the shot's strike; the result document."""
    doc = dict(position)
    doc["strike"] = shot["strike"]
    path = write("replay.json", doc)
    r = run([ARGS.pool_sim, path])
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def potted(result, ball, pocket):
    return any(e["type"] == "pocket" and e["balls"] == [ball] and e["pocket"] == pocket for e in result["events"])


def cue_on_table(result, cue=0):
    return [b for b in result["final"] if b["id"] == cue][0]["state"] not in ("pocketed", "off_table")


class Shots(unittest.TestCase):
    def test_shots_do_what_they_say(self):
        path = write("position.json", POSITION)
        shots = aim(path, "--top", "4", "-n", "100", "--position")
        self.assertGreaterEqual(len(shots), 1)
        for k, s in enumerate(shots):
            self.assertEqual(s["rank"], k + 1)
            self.assertEqual(set(s), {"rank", "strike", "ball", "pocket", "kind", "via", "rail", "p_success", "ci95",
                                      "samples", "cue_ball_final", "position"})
            self.assertIn(s["kind"], ("straight", "bank", "kick", "combination", "carom"))
            self.assertEqual(s["samples"], 100)
            self.assertLessEqual(s["ci95"][0], s["p_success"])
            self.assertLessEqual(s["p_success"], s["ci95"][1])
            result = replay(POSITION, s)
            self.assertTrue(potted(result, s["ball"], s["pocket"]), s)
            self.assertTrue(cue_on_table(result))
            cue = [b for b in result["final"] if b["id"] == 0][0]["pos"]
            self.assertAlmostEqual(cue[0], s["cue_ball_final"][0], places=9)
            self.assertAlmostEqual(cue[1], s["cue_ball_final"][1], places=9)
            if k:
                self.assertLessEqual(s["p_success"], shots[k - 1]["p_success"])

    def test_ball_pocket_and_noise(self):
        path = write("position.json", POSITION)
        shots = aim(path, "--ball", "1", "--pocket", "se", "--noise", "none", "-n", "50", "--kinds", "straight")
        self.assertGreaterEqual(len(shots), 1)
        for s in shots:
            self.assertEqual((s["ball"], s["pocket"], s["kind"]), (1, "se", "straight"))
            self.assertEqual(s["p_success"], 1.0)  # without noise, every repetition is the shot

    def test_game_rules(self):
        """A 9-ball position (no strike: pool-aim needs none): every shot hits the 1 first and is
        legal when pool-sim judges it with the same "game"."""
        doc = {"format": "libpool-scenario/1",
               "balls": [{"id": 0, "pos": [0.8, 0.6]}, {"id": 1, "pos": [1.6, 0.9]}, {"id": 2, "pos": [2.3, 0.25]},
                         {"id": 9, "pos": [1.9, 0.5]}],
               "game": {"rules": "9ball"}}
        shots = aim(write("nine.json", doc), "-n", "100")
        self.assertGreaterEqual(len(shots), 1)
        for s in shots:
            result = replay(doc, s)
            self.assertTrue(result["game"]["legal"], result["game"])
            self.assertEqual(result["game"]["first_hit"], 1)
            self.assertTrue(potted(result, s["ball"], s["pocket"]))

    def test_picture_output_and_determinism(self):
        path = write("position.json", POSITION)
        svg, out = work("shots.svg"), work("shots.json")
        for f in (svg, out):
            if os.path.exists(f):
                os.remove(f)
        one = run([ARGS.pool_aim, path, "-n", "60", "--threads", "1", "--svg", svg, "-o", out, "--summary"])
        two = run([ARGS.pool_aim, path, "-n", "60", "--threads", "2"])
        self.assertEqual(one.returncode, 0, one.stderr)
        with open(out) as f:
            self.assertEqual(f.read(), two.stdout)
        self.assertIn("candidates", one.stderr)
        with open(svg) as f:
            text = f.read()
        self.assertTrue(text.startswith("<?xml") and text.rstrip().endswith("</svg>"))
        self.assertIn("<polyline", text)
        self.assertIn("p_success", text)

    def test_strike_in_the_scenario_is_ignored(self):
        doc = dict(POSITION)
        doc["strike"] = {"ball": 0, "speed": 9.0, "phi": 123.0}
        a = aim(write("with_strike.json", doc), "-n", "40")
        b = aim(write("position.json", POSITION), "-n", "40")
        self.assertEqual(a, b)


class BadInput(unittest.TestCase):
    def expect(self, args, needle):
        r = run([ARGS.pool_aim, *args])
        self.assertEqual(r.returncode, 2, "%s: %s" % (args, r.stderr))
        self.assertIn(needle, r.stderr)
        self.assertEqual(r.stdout, "")

    def test_options_and_files(self):
        path = write("position.json", POSITION)
        self.expect([path, "--pocket", "middle"], "pocket: 'middle' is not a pocket")
        self.expect([path, "--noise", "loud"], "noise")
        self.expect([path, "--kinds", "straight,jump"], "kinds: 'jump' is not a kind of shot")
        self.expect([path, "--ball", "9"], "aim.ball: no object ball has id 9")
        self.expect([path, "--cue", "7"], "aim.cue_ball: no ball has id 7")
        self.expect([path, "-n", "0"], "-n")
        self.expect([path, "--top", "x"], "--top")
        self.expect([path, "--time-budget", "-1"], "--time-budget")
        self.expect([path, "--bogus"], "unknown option")
        self.expect([], "missing SCENARIO.json")
        bad = dict(POSITION)
        bad["balls"] = POSITION["balls"] + [{"id": 4, "pos": [2.0, 0.31]}]
        self.expect([write("overlap.json", bad)], "balls[4].pos: overlaps ball 1")
        game = dict(POSITION)
        game["game"] = {"rules": "three_cushion"}
        self.expect([write("carom.json", game)], "three_cushion")
        game["game"] = {"rules": "9ball", "state": {"fouls": 7}}
        self.expect([write("fouls.json", game)], "game.state.fouls")

    def test_help(self):
        r = run([ARGS.pool_aim, "--help"])
        self.assertEqual(r.returncode, 0)
        self.assertIn("usage: pool-aim", r.stdout)


def main():
    global ARGS
    parser = argparse.ArgumentParser()
    parser.add_argument("--pool-aim", required=True)
    parser.add_argument("--pool-sim", required=True)
    parser.add_argument("--work", required=True)
    ARGS, rest = parser.parse_known_args()
    os.makedirs(ARGS.work, exist_ok=True)
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
