#!/usr/bin/env python3
"""The rules everywhere a command user meets them (docs/games.md, docs/interfaces.md "Games"):

- pool-sim: a scenario's "game" judged in the result; what the rules read equals the independent
  recount from the result's own events (recount.py); the rules' verdicts on shots built for them;
  the next state fed back; bad "game" input exits 2 naming the field; no "game", no change.
- pool-batch: the game columns equal pool-sim's "game" for the same strike; --noise: rows
  reproducible from the seed, the strikes equal libpool.game.noisy_strike bit for bit, each row
  equal to pool-sim with its strike; bad options exit 2.
- pool-sensitivity: with a game, the probabilities equal the counts of its samples' CSV, and its
  samples are pool-batch --noise's strikes.
- pool-game: a record whose every shot pool-sim reproduces from the shot's table, strike and
  state, states chained shot to shot, balls spotted by the rules; a ghost-ball strategy plays a
  9-ball rack to its end; bad answers exit 2 naming the shot and the field.
"""

import argparse
import csv
import io
import json
import math
import os
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from recount import recount  # noqa: E402

ARGS = None
R = 0.028575
L, W = 2.54, 1.27


def run(cmd, stdin=None, timeout=600):
    return subprocess.run(cmd, input=stdin, capture_output=True, text=True, timeout=timeout)


def work(name):
    return os.path.join(ARGS.work, name)


def write(name, doc):
    path = work(name)
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


def scenario(balls, strike, game=None, **extra):
    doc = {"format": "libpool-scenario/1", "balls": [{"id": i, "pos": list(p)} for i, p in balls],
           "strike": strike}
    if game is not None:
        doc["game"] = game
    doc.update(extra)
    return doc


def sim(doc, name="shot.json"):
    p = run([ARGS.pool_sim, write(name, doc)])
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


def toward(p, q, d):
    n = math.dist(p, q)
    return (p[0] + d * (q[0] - p[0]) / n, p[1] + d * (q[1] - p[1]) / n)


def aim(p, q):
    return math.degrees(math.atan2(q[1] - p[1], q[0] - p[0]))


def nine_rack():
    """pool-rack's 9-ball layout (ids 0..9) and its break strike, as a scenario dict."""
    p = run([ARGS.pool_rack, "9ball"])
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


class PoolSimGame(unittest.TestCase):
    def test_what_the_rules_read_equals_the_recount(self):
        """30 breaks and 30 cut shots: first_hit, rails_after_contact, pocketed (and pockets),
        off_table, the cue ball's cushions before the second ball, from the result's events."""
        rack = nine_rack()
        docs = []
        for k in range(30):
            d = dict(rack, strike={"ball": 0, "speed": 3.0 + 0.2 * k, "phi": -2.0 + 0.13 * k,
                                   "b": 0.001 * (k % 5 - 2)},
                     game={"rules": "9ball", "state": {"break": True, "ball_in_hand": True,
                                                       "behind_head_string": True}})
            docs.append(d)
        for k in range(30):
            balls = [(0, (0.6 + 0.03 * k, 0.5)), (1, (1.6, 0.7)), (2, (2.0, 0.4)), (9, (1.9, 1.0))]
            docs.append(scenario(balls, {"ball": 0, "speed": 1.0 + 0.1 * k, "phi": 8.0 + 1.7 * k},
                                 {"rules": "9ball"}))
        for k, doc in enumerate(docs):
            res = sim(doc)
            g, rc = res["game"], recount(res)
            for key in ("first_hit", "rails_after_contact", "pocketed", "pockets", "off_table"):
                self.assertEqual(g[key], rc[key], (k, key))
            if rc["second_hit"] is not None:
                self.assertEqual(g["cue_cushions"], rc["cue_cushions"], k)
            # The fouls the recount alone decides (9-ball: lowest first, scratch, no rail).
            lowest = min(b["id"] for b in doc["balls"] if b["id"] != 0)
            self.assertEqual("wrong_ball_first" in g["fouls"],
                             rc["first_hit"] is not None and rc["first_hit"] != lowest, k)
            self.assertEqual("no_contact" in g["fouls"], rc["first_hit"] is None, k)
            self.assertEqual("scratch" in g["fouls"], 0 in rc["pocketed"] or 0 in rc["off_table"], k)
            self.assertEqual(g["legal"], not g["fouls"])

    def test_verdicts_on_built_shots(self):
        """The 9-ball cases of the unit tests, through pool-sim: the 3 first with the 1 on the
        table (WPA 6.2) is a foul though the 3 drops; the 9 by a combination wins (2.5)."""
        pocket = (L, W)
        cue = (2.1, 0.95)
        obj = toward(pocket, cue, 0.3)
        wrong = sim(scenario([(0, cue), (3, obj), (1, (0.3, 0.3))],
                             {"ball": 0, "speed": 1.5, "phi": aim(cue, obj), "b": -0.3 * R},
                             {"rules": "9ball", "state": {"fouls": 1}}))
        self.assertEqual(recount(wrong)["first_hit"], 3)
        self.assertEqual(recount(wrong)["pocketed"], [3])
        g = wrong["game"]
        self.assertEqual((g["legal"], g["fouls"], g["outcome"], g["ball_in_hand"]),
                         (False, ["wrong_ball_first"], "turn_over", True))
        self.assertEqual(g["state"]["player"], 1)
        self.assertEqual(g["state"]["opponent_fouls"], 2)
        cue = (0.9, 0.35)
        nine = toward(pocket, cue, 0.25)
        one = toward(nine, cue, 2 * R + 0.005)
        win = sim(scenario([(0, cue), (1, one), (9, nine), (5, (0.3, 1.0))],
                           {"ball": 0, "speed": 2.0, "phi": aim(cue, one), "b": -0.4 * R},
                           {"rules": "9ball"}))
        self.assertIn(9, recount(win)["pocketed"])
        self.assertEqual((win["game"]["outcome"], win["game"]["reason"]), ("win", "nine_pocketed"))

    def test_the_next_state_reads_back(self):
        rack = nine_rack()
        res = sim(dict(rack, game={"rules": "9ball", "state": {"break": True, "ball_in_hand": True,
                                                               "behind_head_string": True}}))
        state = res["game"]["state"]
        # Fed back as the next shot's state, pool-sim reads it and writes it unchanged when the
        # next shot passes nothing on (the same state keys come back).
        balls = [(b["id"], b["pos"][:2]) for b in res["final"] if b["state"] == "stationary"]
        if all(b != 0 for b, _ in balls):
            balls.append((0, (0.3, 0.3)))
        again = sim(scenario(balls, {"ball": 0, "speed": 0.3, "phi": 180.0},
                             {"rules": "9ball", "state": state}))
        self.assertEqual(set(again["game"]["state"]), set(state))

    def test_three_cushion_and_eight_ball_objects(self):
        res = sim(scenario([(0, (0.71, 0.528)), (1, (0.71, 0.71)), (2, (2.13, 0.71))],
                           {"ball": 0, "speed": 4.0, "phi": 20.0},
                           {"rules": "three_cushion", "state": {"points": 3, "target": 5}},
                           table="carom"))
        g = res["game"]
        self.assertEqual(g["points"], 1 if g["outcome"] in ("continue", "win") else 0)
        self.assertIn("target", g["state"])
        self.assertNotIn("group", g["state"])
        res = sim(scenario([(0, (0.6, 0.6)), (3, (1.2, 0.6)), (8, (2.0, 1.0))], {"ball": 0, "speed": 2.0},
                           {"rules": "8ball", "state": {"called": {"ball": 3, "pocket": "ne"}}}))
        self.assertIn("group", res["game"]["state"])
        self.assertNotIn("called", res["game"]["state"])  # a call is for one shot

    def test_no_game_no_change(self):
        doc = scenario([(0, (0.6, 0.6)), (1, (1.2, 0.6))], {"ball": 0, "speed": 2.0})
        res = sim(doc)
        self.assertNotIn("game", res)

    def test_bad_game_exits_2_naming_the_field(self):
        base = [(0, (0.6, 0.6)), (1, (1.2, 0.6))]
        strike = {"ball": 0, "speed": 2.0}
        cases = [
            ({"rules": "snooker"}, 'game.rules: unknown rules "snooker"'),
            ({"rules": 9}, "game.rules: must be a string"),
            ({}, "game.rules: missing"),
            ({"rules": "9ball", "extra": 1}, "game.extra: unknown field"),
            ({"rules": "9ball", "state": {"fouls": -1}}, "game.state.fouls: must be a whole number"),
            ({"rules": "9ball", "state": {"fouls": 3}}, "game.state.fouls: must be 0, 1 or 2"),
            ({"rules": "9ball", "state": {"colour": 1}}, "game.state.colour: unknown field"),
            ({"rules": "9ball", "state": {"break": 1}}, "game.state.break: must be true or false"),
            ({"rules": "9ball", "state": {"group": "solids"}}, "game.state.group: only in 8ball"),
            ({"rules": "8ball", "state": {"called": {"pocket": "xx"}}}, "game.state.called.pocket:"),
            ({"rules": "8ball", "state": {"called": {"ball": 16}}}, "game.state.called.ball:"),
            ({"rules": "9ball", "state": {"push_out": True}}, "game.state.push_out:"),
            ({"rules": "three_cushion"}, "balls: three_cushion is played with three balls, not 2"),
            ({"rules": "9ball", "state": []}, "game.state: must be an object"),
            ("9ball", "game: must be an object"),
        ]
        for game, message in cases:
            p = run([ARGS.pool_sim, write("bad.json", scenario(base, strike, game))])
            self.assertEqual(p.returncode, 2, (game, p.stderr))
            self.assertIn("pool-sim: " + message, p.stderr, game)
            self.assertEqual(p.stdout, "")
        p = run([ARGS.pool_sim, write("bad.json", scenario([(0, (0.6, 0.6)), (16, (1.2, 0.6))], strike,
                                                           {"rules": "8ball"}))])
        self.assertEqual(p.returncode, 2)
        self.assertIn("balls: id 16 is not a ball of 8ball (0 to 15)", p.stderr)
        doc = scenario(base, strike, {"rules": "9ball"})
        del doc["strike"]
        p = run([ARGS.pool_sim, write("bad.json", doc)])
        self.assertEqual(p.returncode, 2)
        self.assertIn("game: the rules judge a struck shot: the scenario needs a strike", p.stderr)


def batch(layout_path, *args):
    p = run([ARGS.pool_batch, layout_path, "--no-progress", *args])
    assert p.returncode == 0, p.stderr
    return list(csv.DictReader(io.StringIO(p.stdout))), p.stdout


class PoolBatchGame(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        balls = [(0, (0.6, 0.5)), (1, (1.6, 0.7)), (2, (2.0, 0.4)), (9, (1.9, 1.0))]
        cls.doc = scenario(balls, {"ball": 0, "speed": 2.0, "phi": 10.0}, {"rules": "9ball"})
        cls.layout = write("batch_layout.json", cls.doc)

    def test_game_columns_equal_pool_sim(self):
        rows, _ = batch(self.layout, "--grid", "speed=1:4:4,phi=0:30:5")
        self.assertEqual(len(rows), 20)
        for row in rows:
            d = dict(self.doc, strike={"ball": 0, "speed": float(row["speed"]), "phi": float(row["phi"])})
            g = sim(d)["game"]
            self.assertEqual(row["legal"], "true" if g["legal"] else "false")
            self.assertEqual(row["fouls"], " ".join(g["fouls"]))
            self.assertEqual((row["outcome"], row["reason"], int(row["points"])),
                             (g["outcome"], g["reason"], g["points"]))

    def test_noise_is_reproducible_and_the_strikes_are_libpool_game_s(self):
        rows, text = batch(self.layout, "--grid", "speed=2:2:6", "--noise", "fastfiz", "--seed", "7")
        _, again = batch(self.layout, "--grid", "speed=2:2:6", "--noise", "fastfiz", "--seed", "7",
                         "--threads", "1")
        self.assertEqual(text, again)
        _, other = batch(self.layout, "--grid", "speed=2:2:6", "--noise", "fastfiz", "--seed", "8")
        self.assertNotEqual(text, other)
        _, none = batch(self.layout, "--grid", "speed=2:2:6", "--noise", "none", "--seed", "7")
        _, plain = batch(self.layout, "--grid", "speed=2:2:6")
        self.assertEqual(none, plain)
        for i, row in enumerate(rows):
            got = tuple(float(row[k]) for k in ("speed", "phi", "theta", "a", "b"))
            if not ARGS.no_binding:
                sys.path.insert(0, os.path.join(ARGS.source, "python"))
                from libpool import game
                self.assertEqual(got, game.noisy_strike((2.0, 10.0, 0.0, 0.0, 0.0), "fastfiz", 7, i), i)
            res = sim(dict(self.doc, strike={"ball": 0, **dict(zip(("speed", "phi", "theta", "a", "b"), got))}))
            self.assertEqual(int(row["events"]), res["stats"]["events"])
            self.assertEqual(row["outcome"], res["game"]["outcome"])
        # The sample spreads as the preset says: speed sd 0.075 m/s over 2000 shots.
        rows, _ = batch(self.layout, "--grid", "speed=2:2:2000", "--noise", "speed=0.075", "--seed", "1")
        v = [float(r["speed"]) for r in rows]
        mean = sum(v) / len(v)
        sd = math.sqrt(sum((x - mean) ** 2 for x in v) / (len(v) - 1))
        self.assertLess(abs(mean - 2.0), 4 * 0.075 / math.sqrt(len(v)))
        self.assertLess(abs(sd - 0.075), 4 * 0.075 / math.sqrt(2 * len(v)))
        self.assertTrue(all(float(r["phi"]) == 10.0 for r in rows))

    def test_bad_options(self):
        if ARGS.pool_sensitivity:
            p = run([ARGS.pool_sensitivity, self.layout, "--sd", "speed=0.1", "--noise", "fastfiz"])
            self.assertEqual(p.returncode, 2)
            self.assertIn("--noise: give --sd or --noise, not both", p.stderr)
            p = run([ARGS.pool_sensitivity, self.layout, "--noise", "fast"])
            self.assertEqual(p.returncode, 2)
            self.assertIn("--noise: 'fast' is not a preset (none, fastfiz) or NAME=SD", p.stderr)
        for args, message in ((["--noise", "spin=1"], "--noise: 'spin': unknown parameter"),
                              (["--noise", "phi=-1"], "--noise: phi: '-1' is not a standard deviation"),
                              (["--seed", "3"], "--seed goes with --random or --noise")):
            p = run([ARGS.pool_batch, self.layout, "--grid", "speed=1:2:2", *args])
            self.assertEqual(p.returncode, 2, args)
            self.assertIn("pool-batch: " + message, p.stderr)


class SensitivityGame(unittest.TestCase):
    def test_probabilities_and_samples(self):
        if not ARGS.pool_sensitivity:
            self.skipTest("pool-sensitivity not built")
        cue = (2.1, 0.95)
        obj = toward((L, W), cue, 0.3)
        doc = scenario([(0, cue), (1, obj), (9, (0.4, 0.3))],
                       {"ball": 0, "speed": 1.5, "phi": aim(cue, obj), "b": -0.008}, {"rules": "9ball"})
        path = write("sens.json", doc)
        prefix = work("sens_out")
        p = run([ARGS.pool_sensitivity, path, "--noise", "phi=1.5,speed=0.1", "-n", "400", "--seed", "5",
                 "-o", prefix, "--no-progress"])
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("game 9ball: legal", p.stdout)
        with open(prefix + ".json") as f:
            g = json.load(f)["model_sets"][0]["game"]
        with open(prefix + ".samples.csv") as f:
            samples = list(csv.DictReader(f))
        n = len(samples)
        legal = sum(r["legal"] == "true" for r in samples)
        pots = sum(r["legal"] == "true" and r["outcome"] in ("continue", "win") for r in samples)
        self.assertEqual((g["legal"]["count"], g["legal_pot"]["count"]), (legal, pots))
        for name in ("continue", "turn_over", "win", "loss"):
            self.assertEqual(g["outcomes"][name]["count"], sum(r["outcome"] == name for r in samples))
        self.assertTrue(0 < pots < n, pots)  # the noise makes this pot uncertain
        self.assertLessEqual(g["legal_pot"]["low"], g["legal_pot"]["p"])
        # Sample i is pool-batch --noise's strike i (same spec and seed).
        rows, _ = batch(path, "--grid", "speed=1.5:1.5:10", "--noise", "phi=1.5,speed=0.1", "--seed", "5")
        for i in range(10):
            for k in ("speed", "phi", "theta", "a", "b"):
                self.assertEqual(float(rows[i][k]), float(samples[i][k]), (i, k))
            self.assertEqual(rows[i]["outcome"], samples[i]["outcome"])


class PoolGame(unittest.TestCase):
    def play(self, rules, answers, *args, expect=0):
        p = run([ARGS.pool_game, rules, *args], stdin="".join(json.dumps(a) + "\n" for a in answers))
        self.assertEqual(p.returncode, expect, p.stderr)
        return p

    def test_every_shot_replays_in_pool_sim(self):
        answers = [{"strike": {"speed": 8.0, "phi": 0.0}}] + \
                  [{"strike": {"speed": 1.0 + 0.37 * k, "phi": 23.0 * k, "b": -0.003}, "cue_pos": [0.4, 0.3]}
                   for k in range(1, 25)]
        # Answers give cue_pos only when the cue ball is in hand: play one at a time.
        record = None
        sent = []
        for a in answers:
            trial = sent + [a]
            p = run([ARGS.pool_game, "9ball", "--noise", "fastfiz", "--seed", "3"],
                    stdin="".join(json.dumps(x) + "\n" for x in trial))
            if p.returncode == 2 and "cue ball is not in hand" in p.stderr:
                trial = sent + [{"strike": a["strike"]}]
                p = run([ARGS.pool_game, "9ball", "--noise", "fastfiz", "--seed", "3"],
                        stdin="".join(json.dumps(x) + "\n" for x in trial))
            self.assertEqual(p.returncode, 0, p.stderr)
            sent = trial
            record = json.loads(p.stdout)
            if record["end"] in ("win", "loss"):
                break
        shots = record["shots"]
        self.assertGreaterEqual(len(shots), 5)
        table = record["start"]
        for k, shot in enumerate(shots):
            balls = [(b["id"], tuple(b["pos"])) for b in table]
            if shot["cue_pos"] is not None:
                balls = [(i, p) for i, p in balls if i != 0] + [(0, tuple(shot["cue_pos"]))]
            s = shot["strike"]
            res = sim(scenario(balls, {k2: s[k2] for k2 in ("ball", "speed", "phi", "theta", "a", "b")},
                               {"rules": "9ball", "state": shot["state"]}))
            self.assertEqual(res["game"], shot["result"], k)
            # The table after the shot: the balls at rest, the pocketed ones gone, the spotted back.
            on = {b["id"] for b in res["final"] if b["state"] not in ("pocketed", "off_table")}
            self.assertEqual({b["id"] for b in shot["balls"]}, on | set(shot["result"]["spot"]), k)
            for b in shot["balls"]:
                if b["id"] in shot["result"]["spot"]:
                    self.assertEqual(b["pos"], [0.75 * L, 0.5 * W])  # the foot spot was free
            if k + 1 < len(shots):
                self.assertEqual(shots[k + 1]["state"]["player"], shot["result"]["state"]["player"])
                self.assertEqual(shots[k + 1]["state"]["fouls"], shot["result"]["state"]["fouls"])
            table = shot["balls"]
            self.assertEqual(shot["nominal"]["speed"], sent[k]["strike"]["speed"])

    def test_ghost_ball_strategy_plays_a_rack_to_its_end(self):
        strategy = f"{sys.executable} {os.path.join(ARGS.source, 'tools', 'game', 'ghost_ball_strategy.py')}"
        for rules in ("9ball", "8ball"):
            p = run([ARGS.pool_game, rules, "--strategy", strategy, "--max-shots", "150", "-o",
                     work(f"ghost_{rules}.json")])
            self.assertEqual(p.returncode, 0, p.stderr)
            with open(work(f"ghost_{rules}.json")) as f:
                record = json.load(f)
            self.assertIn(record["end"], ("win", "loss"), rules)
            self.assertIn(record["winner"], (0, 1))
            legal = sum(s["result"]["legal"] for s in record["shots"])
            print(f"\nghost-ball {rules}: {len(record['shots'])} shots, {legal} legal, {record['end']} "
                  f"for player {record['shots'][-1]['player']}", file=sys.stderr)

    def test_bad_answers_exit_2_naming_the_shot(self):
        cases = [
            ([{"strike": {"phi": 3}}], "shot 0: strike.speed: missing"),
            ([{"strike": {"speed": "x"}}], "shot 0: strike.speed: must be a number"),
            ([{"strike": {"speed": 2, "spin": 1}}], "shot 0: strike.spin: unknown field"),
            ([{"strike": {"speed": 2}, "cue": 1}], "shot 0: cue: unknown field"),
            ([{"strike": {"speed": 2, "a": 0.03}}], "shot 0: strike.a: a^2 + b^2 must be < R^2"),
            ([{"strike": {"speed": 2}, "push_out": True}], "shot 0: answer.push_out:"),
            ([{"strike": {"speed": 8}}, {"strike": {"speed": 2}, "cue_pos": [0.5, 0.5]}],
             "shot 1: cue_pos: the cue ball is not in hand"),
            ([{"strike": {"speed": 2}, "cue_pos": [1.905, 0.635]}], "shot 0: cue_pos: overlaps ball 1"),
        ]
        for answers, message in cases:
            p = self.play("9ball", answers, expect=2)
            self.assertIn("pool-game: " + message, p.stderr, answers)
            self.assertEqual(p.stdout, "")
        p = run([ARGS.pool_game, "snooker"])
        self.assertEqual(p.returncode, 2)
        p = run([ARGS.pool_game, "9ball", "--target", "3"])
        self.assertEqual(p.returncode, 2)
        self.assertIn("--target: only in three_cushion", p.stderr)

    def test_layout_and_table(self):
        """--layout: the scenario's table, balls and game state are the start; --table: a preset."""
        doc = scenario([(0, (0.6, 0.6)), (3, (1.2, 0.6)), (8, (2.0, 1.0)), (12, (1.5, 0.3))],
                       {"ball": 0, "speed": 1.0},
                       {"rules": "8ball", "state": {"group": "solids", "fouls": 1, "player": 1}},
                       table={"preset": "wpa-8ft"})
        path = write("layout.json", doc)
        p = self.play("8ball", [{"strike": {"speed": 1.5, "phi": 0.0}, "call": {"ball": 3, "pocket": "e"}}],
                      "--layout", path, expect=2)
        self.assertIn("shot 0: answer.called.pocket:", p.stderr)
        p = self.play("8ball", [{"strike": {"speed": 1.5, "phi": 0.0}, "call": {"ball": 3, "pocket": "ne"}}],
                      "--layout", path)
        record = json.loads(p.stdout)
        self.assertEqual(record["table"]["length"], 92 * 0.0254)
        self.assertEqual([b["id"] for b in record["start"]], [0, 3, 8, 12])
        st = record["shots"][0]["state"]
        self.assertEqual((st["group"], st["fouls"], st["player"], st["called"]),
                         ("solids", 1, 1, {"ball": 3, "pocket": "ne"}))
        self.assertEqual(record["shots"][0]["result"]["first_hit"], 3)
        p = self.play("9ball", [{"strike": {"speed": 8.0}}], "--layout", path, expect=2)
        self.assertIn("--layout: game.rules: 8ball, not 9ball", p.stderr)
        p = self.play("9ball", [{"strike": {"speed": 8.0}}], "--table", "wpa-7ft")
        self.assertEqual(json.loads(p.stdout)["table"]["length"], 78 * 0.0254)
        p = self.play("9ball", [], "--table", "wpa-10ft", expect=2)
        self.assertIn("--table: unknown preset", p.stderr)

    def test_strikes_ending_keep_the_record(self):
        p = self.play("three_cushion", [{"strike": {"speed": 4, "phi": 10}}], "--target", "2")
        record = json.loads(p.stdout)
        self.assertEqual(record["end"], "no_more_strikes")
        self.assertEqual(len(record["shots"]), 1)
        self.assertEqual(record["rules"], "three_cushion")
        self.assertEqual(record["table"]["corner_mouth"], 0.0)
        self.assertEqual(record["table"]["pockets"], "none")  # the carom preset
        self.assertEqual(record["ball_radius"], 0.03075)      # with its balls


def main():
    global ARGS
    parser = argparse.ArgumentParser()
    for name in ("--pool-sim", "--pool-batch", "--pool-rack", "--pool-game", "--source", "--work"):
        parser.add_argument(name, required=True)
    parser.add_argument("--pool-sensitivity", default="")
    parser.add_argument("--no-binding", action="store_true",
                        help="do not import libpool.game (a sanitizer build without a preloadable runtime)")
    ARGS, rest = parser.parse_known_args()
    os.makedirs(ARGS.work, exist_ok=True)
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
