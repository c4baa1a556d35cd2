"""End-to-end tests of pool-sim, pool-rack and pool-plot (ctest label "tools").

Usage: python test_commands.py --pool-sim PATH --pool-rack PATH --pool-plot PATH
                               --python PATH --work DIR [unittest arguments]
"""
import argparse
import json
import math
import os
import shutil
import stat
import subprocess
import sys
import unittest

ARGS = None
R = 0.028575
EVENT_TYPES = {"strike", "slide_roll", "roll_stop", "spin_stop", "ball_ball", "ball_cushion",
               "ball_table", "pocket", "off_table", "link_begin", "link_step", "link_end"}
STATES = {"stationary", "spinning", "sliding", "rolling", "airborne", "linked", "pocketed",
          "off_table"}
RAILS = {"south", "north", "west", "east"}
POCKETS = {"sw", "se", "nw", "ne", "s", "n"}


def run(cmd, stdin=None, timeout=120):
    return subprocess.run(cmd, input=stdin, capture_output=True, timeout=timeout)


def sim(*args, stdin=None):
    return run([ARGS.pool_sim, *args], stdin=stdin)


def write(name, doc):
    path = os.path.join(ARGS.work, name)
    with open(path, "w", encoding="utf-8") as f:
        f.write(doc if isinstance(doc, str) else json.dumps(doc))
    return path


def straight_shot(speed=1.0):
    """Cue ball on the head string aimed straight at an object ball on the same line."""
    return {
        "format": "libpool-scenario/1",
        "table": {"preset": "wpa-9ft"},
        "balls": [{"id": 0, "pos": [0.635, 0.635]}, {"id": 1, "pos": [1.905, 0.635]}],
        "strike": {"ball": 0, "speed": speed, "phi": 0.0, "theta": 0.0, "a": 0.0, "b": 0.0},
    }


class ResultChecks:
    def check_result(self, doc, ball_ids):
        self.assertEqual(doc["format"], "libpool-result/1")
        times = [e["t"] for e in doc["events"]]
        self.assertEqual(times, sorted(times), "event times must not decrease")
        for e in doc["events"]:
            self.assertIn(e["type"], EVENT_TYPES)
            self.assertTrue(math.isfinite(e["t"]) and e["t"] >= 0)
            self.assertEqual(len(e["after"]), len(e["balls"]))
            self.assertEqual([a["id"] for a in e["after"]], e["balls"])
            for a in e["after"]:
                self.assertIn(a["state"], STATES)
                for key in ("pos", "vel", "omega"):
                    self.assertEqual(len(a[key]), 3)
            if e["type"] == "ball_cushion":
                self.assertIn(e["rail"], RAILS)
            if e["type"] == "pocket":
                self.assertIn(e["pocket"], POCKETS)
        self.assertEqual(sorted(b["id"] for b in doc["final"]), sorted(ball_ids))
        for b in doc["final"]:
            self.assertIn(b["state"], STATES)
        self.assertEqual(doc["stats"]["events"], len(doc["events"]))
        if doc["events"]:
            self.assertLessEqual(times[-1], doc["stats"]["sim_time"] + 1e-12)
        # No two balls left on the table interpenetrate at the end.
        on = [b for b in doc["final"] if b["state"] not in ("pocketed", "off_table")]
        for i in range(len(on)):
            for j in range(i):
                d = math.dist(on[i]["pos"], on[j]["pos"])
                self.assertGreater(d, 2 * R - 1e-6, f"balls {on[i]['id']} and {on[j]['id']}")


class TestPoolSim(unittest.TestCase, ResultChecks):
    def test_help(self):
        r = sim("--help")
        self.assertEqual(r.returncode, 0)
        self.assertIn(b"usage: pool-sim", r.stdout)

    def test_usage_errors_name_the_option(self):
        for args, expect in [((), b"missing"), (("--bogus", "x.json"), b"--bogus"),
                             (("x.json", "--sample", "abc"), b"--sample"),
                             (("x.json", "--sample", "-1"), b"--sample"),
                             (("x.json", "-o"), b"-o"), (("a.json", "b.json"), b"b.json")]:
            r = sim(*args)
            self.assertEqual(r.returncode, 2, args)
            self.assertIn(expect, r.stderr, args)
            self.assertEqual(r.stdout, b"", args)

    def test_straight_shot_matches_closed_form(self):
        # Centre-ball level strike: v0 = 2 V / (1 + m/M), no spin, so the ball slides until
        # t = 2 v0 / (7 mu_slide g) and has then covered v0 t - mu_slide g t^2 / 2 (PHYSICS.md).
        path = write("straight.json", straight_shot(1.0))
        r = sim(path)
        self.assertEqual(r.returncode, 0, r.stderr)
        doc = json.loads(r.stdout)
        self.check_result(doc, [0, 1])
        m, M, mu, g = 0.17, 0.54, 0.2, 9.81
        v0 = 2 * 1.0 / (1 + m / M)
        strike = doc["events"][0]
        self.assertEqual(strike["type"], "strike")
        self.assertEqual(strike["t"], 0)
        self.assertAlmostEqual(strike["after"][0]["vel"][0], v0, delta=1e-12)
        self.assertEqual(strike["after"][0]["state"], "sliding")
        roll = [e for e in doc["events"] if e["type"] == "slide_roll" and e["balls"] == [0]][0]
        t_roll = 2 * v0 / (7 * mu * g)
        self.assertAlmostEqual(roll["t"], t_roll, delta=1e-12)
        self.assertAlmostEqual(roll["after"][0]["pos"][0], 0.635 + v0 * t_roll - mu * g * t_roll**2 / 2,
                               delta=1e-12)
        self.assertAlmostEqual(roll["after"][0]["vel"][0], 5 * v0 / 7, delta=1e-12)
        hits = [e for e in doc["events"] if e["type"] == "ball_ball"]
        self.assertTrue(hits, "the cue ball must reach ball 1")
        self.assertEqual(sorted(hits[0]["balls"]), [0, 1])
        self.assertEqual(doc["stats"]["stop_reason"], "rest")
        for b in doc["final"]:
            self.assertIn(b["state"], ("stationary", "pocketed"))

    def test_sampling_includes_event_times(self):
        path = write("sampled.json", straight_shot(1.5))
        r = sim(path, "--sample", "0.05")
        self.assertEqual(r.returncode, 0, r.stderr)
        doc = json.loads(r.stdout)
        self.assertEqual(doc["samples"]["dt"], 0.05)
        cue = [b for b in doc["samples"]["balls"] if b["id"] == 0][0]
        self.assertEqual(len(cue["t"]), len(cue["pos"]))
        self.assertEqual(cue["t"], sorted(cue["t"]))
        for e in doc["events"]:
            if 0 in e["balls"]:
                self.assertIn(e["t"], cue["t"])
                k = cue["t"].index(e["t"])
                after = e["after"][e["balls"].index(0)]
                self.assertLess(math.dist(cue["pos"][k], after["pos"]), 1e-9)

    def test_deterministic_and_pretty_is_same_document(self):
        path = write("det.json", straight_shot(2.5))
        a = sim(path, "--sample", "0.01")
        b = sim(path, "--sample", "0.01")
        self.assertEqual(a.returncode, 0, a.stderr)
        self.assertEqual(a.stdout, b.stdout)
        p = sim(path, "--sample", "0.01", "--pretty")
        self.assertEqual(json.loads(p.stdout), json.loads(a.stdout))
        self.assertGreater(p.stdout.count(b"\n"), a.stdout.count(b"\n"))

    def test_numbers_round_trip(self):
        # A ball nothing touches ends exactly where it started: numbers are written with enough
        # digits (up to 17) to read back to the same double.
        doc = straight_shot(1.0)
        doc["balls"].append({"id": 2, "pos": [1.9051234567890123, 1.0123456789012345]})
        r = sim(write("rt.json", doc))
        self.assertEqual(r.returncode, 0, r.stderr)
        final = {b["id"]: b for b in json.loads(r.stdout)["final"]}
        self.assertEqual(final[2]["pos"], [1.9051234567890123, 1.0123456789012345, R])
        self.assertEqual(final[2]["state"], "stationary")

    def test_stdin_and_output_file(self):
        doc = json.dumps(straight_shot(1.0)).encode()
        r = sim("-", stdin=doc)
        self.assertEqual(r.returncode, 0, r.stderr)
        out = os.path.join(ARGS.work, "out.json")
        if os.path.exists(out):
            os.unlink(out)
        r2 = sim("-", "-o", out, stdin=doc)
        self.assertEqual(r2.returncode, 0, r2.stderr)
        self.assertEqual(r2.stdout, b"")
        with open(out, "rb") as f:
            self.assertEqual(f.read(), r.stdout)

    def test_bad_input_leaves_no_file(self):
        directory = os.path.join(ARGS.work, "nofile")
        shutil.rmtree(directory, ignore_errors=True)
        os.makedirs(directory)
        bad = straight_shot()
        bad["balls"][1]["pos"] = [0.65, 0.635]
        out = os.path.join(directory, "result.json")
        r = sim(write("bad_overlap.json", bad), "-o", out)
        self.assertEqual(r.returncode, 2)
        self.assertEqual(os.listdir(directory), [])

    def test_output_through_symlink_and_fifo(self):
        # -o replaces the file a link points to (the link stays), and writes pipes in place.
        path = write("ok_link.json", straight_shot())
        expected = sim(path).stdout
        target = os.path.join(ARGS.work, "link_target.json")
        link = os.path.join(ARGS.work, "link.json")
        for p in (target, link):
            if os.path.lexists(p):
                os.unlink(p)
        os.symlink("link_target.json", link)
        for _ in range(2):  # dangling first, then an existing target
            r = sim(path, "-o", link)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertTrue(os.path.islink(link))
            with open(target, "rb") as f:
                self.assertEqual(f.read(), expected)
        fifo = os.path.join(ARGS.work, "result.fifo")
        if os.path.lexists(fifo):
            os.unlink(fifo)
        os.mkfifo(fifo)
        proc = subprocess.Popen([ARGS.pool_sim, path, "-o", fifo], stderr=subprocess.PIPE)
        with open(fifo, "rb") as f:
            data = f.read()
        self.assertEqual(proc.wait(timeout=60), 0)
        self.assertEqual(data, expected)
        self.assertTrue(stat.S_ISFIFO(os.lstat(fifo).st_mode))

    def test_unwritable_output_is_reported(self):
        r = sim(write("ok.json", straight_shot()), "-o", os.path.join(ARGS.work, "no", "such", "dir.json"))
        self.assertNotEqual(r.returncode, 0)
        self.assertIn(b"dir.json", r.stderr)

    def test_bad_inputs_exit_2_naming_the_field(self):
        def with_(change):
            doc = straight_shot()
            change(doc)
            return json.dumps(doc)

        def ball(i, **fields):
            return lambda d: d["balls"][i].update(fields)

        cases = [
            ("malformed", '{"format": "libpool-scenario/1", "balls": [', "line 1"),
            ("malformed2", '{"format": "libpool-scenario/1",\n "balls": [}', "line 2"),
            ("not_object", "[1, 2]", "(document)"),
            ("format", with_(lambda d: d.update(format="libpool-scenario/2")), "format"),
            ("no_format", with_(lambda d: d.pop("format")), "format"),
            ("unknown_top", with_(lambda d: d.update(bogus=1)), "bogus: unknown field"),
            ("unknown_ball", with_(ball(1, color="red")), "balls[1].color: unknown field"),
            ("unknown_strike", with_(lambda d: d["strike"].update(spin=1)), "strike.spin: unknown field"),
            ("unknown_param", with_(lambda d: d.update(params={"mu_sled": 0.2})), "params.mu_sled"),
            ("unknown_table", with_(lambda d: d["table"].update(colour="green")), "table.colour"),
            ("unknown_option", with_(lambda d: d.update(options={"dt": 0.1})), "options.dt"),
            ("duplicate_key", '{"format": "libpool-scenario/1", "format": "x", "balls": []}', "duplicate"),
            ("overlap", with_(ball(1, pos=[0.635 + 0.054150, 0.635])), "balls[1].pos: overlaps ball 0 by 0.003 m"),
            ("off_table", with_(ball(1, pos=[2.6, 0.5])), "balls[1]"),
            ("off_table_neg", with_(ball(0, pos=[-0.1, 0.5])), "balls[0]"),
            ("duplicate_id", with_(ball(1, id=0)), "balls[1].id"),
            ("id_float", with_(ball(1, id=1.5)), "balls[1].id"),
            ("id_string", with_(ball(1, id="1")), "balls[1].id"),
            ("no_id", with_(lambda d: d["balls"][1].pop("id")), "balls[1].id"),
            ("no_pos", with_(lambda d: d["balls"][1].pop("pos")), "balls[1].pos"),
            ("pos_short", with_(ball(1, pos=[1.0])), "balls[1].pos"),
            ("pos_string", with_(ball(1, pos=[1.0, "0.5"])), "balls[1].pos[1]"),
            ("vel_bool", with_(ball(1, vel=[True, 0, 0])), "balls[1].vel[0]"),
            ("no_balls", with_(lambda d: d.pop("balls")), "balls"),
            ("empty_balls", with_(lambda d: d.update(balls=[])), "balls"),
            ("tip_offset", with_(lambda d: d["strike"].update(a=0.02, b=0.021)), "strike"),
            ("speed_zero", with_(lambda d: d["strike"].update(speed=0)), "strike"),
            ("speed_negative", with_(lambda d: d["strike"].update(speed=-1)), "strike"),
            ("strike_ball", with_(lambda d: d["strike"].update(ball=7)), "strike.ball"),
            ("strike_no_speed", with_(lambda d: d["strike"].pop("speed")), "strike.speed"),
            ("negative_mu", with_(lambda d: d.update(params={"mu_ball": -0.1})), "params.mu_ball"),
            ("negative_mu_slide", with_(lambda d: d.update(params={"mu_slide": -1})), "params.mu_slide"),
            ("restitution", with_(lambda d: d.update(params={"e_ball": 1.5})), "params.e_ball"),
            ("param_string", with_(lambda d: d.update(params={"g": "9.81"})), "params.g"),
            ("nan_literal", json.dumps(straight_shot()).replace('"speed": 1.0', '"speed": NaN'), "line 1"),
            ("infinity", json.dumps(straight_shot()).replace('"speed": 1.0', '"speed": 1e999'), "(document)"),
            ("huge", with_(lambda d: d["strike"].update(speed=1e300)), "strike.speed"),
            ("huge_pos", with_(ball(1, pos=[1e200, 0.5])), "balls[1].pos[0]"),
            ("table_string", with_(lambda d: d.update(table="wpa-9ft")), "table"),
            ("preset", with_(lambda d: d.update(table={"preset": "snooker"})), "table.preset"),
            ("table_width", with_(lambda d: d.update(table={"width": -1})), "table.width"),
            ("airborne_type", with_(lambda d: d.update(options={"airborne": 1})), "options.airborne"),
            ("max_time", with_(lambda d: d.update(options={"max_time": 0})), "options.max_time"),
            ("max_events", with_(lambda d: d.update(options={"max_events": 2.5})), "options.max_events"),
            ("empty_file", "", "(document)"),
            ("theta_90", with_(lambda d: d["strike"].update(theta=90)), "strike.theta: must be in [0, 90) degrees"),
            ("theta_negative", with_(lambda d: d["strike"].update(theta=-5)), "strike.theta"),
            ("strike_moving", with_(ball(0, vel=[1.0, 0.0])), "strike.ball"),
            ("below_cloth", with_(ball(1, pos=[1.9, 0.6, 0.01])), "balls[1].pos"),
            ("vertical_velocity", with_(ball(1, vel=[0.0, 0.0, 0.5])), "balls[1].vel: vertical velocity 0.5 m/s"),
            ("radius_too_big", with_(lambda d: d.update(params={"ball_radius": 1.0})), "params.ball_radius"),
        ]
        for name, text, expect in cases:
            with self.subTest(name=name):
                r = sim(write(f"bad_{name}.json", text))
                self.assertEqual(r.returncode, 2, f"{name}: {r.stderr!r}")
                self.assertEqual(r.stdout, b"")
                message = r.stderr.decode()
                self.assertTrue(message.startswith("pool-sim: "), message)
                self.assertIn(expect, message, name)

    def test_missing_file(self):
        path = os.path.join(ARGS.work, "does-not-exist.json")
        r = sim(path)
        self.assertEqual(r.returncode, 2)
        self.assertIn(path.encode(), r.stderr)

    def test_unusual_input_files(self):
        # What cannot be tested in-process: a directory, a device and a 100 MB file as input.
        # Each exits 2 with one message naming the input or the document, and writes no file.
        directory = os.path.join(ARGS.work, "unusual")
        shutil.rmtree(directory, ignore_errors=True)
        os.makedirs(directory)
        out = os.path.join(directory, "result.json")
        big = os.path.join(ARGS.work, "big_nested.json")
        with open(big, "wb") as f:
            f.write(b"[" * (100 * 1024 * 1024))
        empty = write("empty.json", "")
        try:
            cases = [
                (directory, directory + ": read error: "),
                ("/dev/null", "(document): malformed JSON at line 1"),
                (empty, "(document): malformed JSON at line 1"),
                (big, "(document): malformed JSON at line 1"),
            ]
            for path, expect in cases:
                with self.subTest(path=path):
                    r = sim(path, "-o", out)
                    message = r.stderr.decode()
                    self.assertEqual(r.returncode, 2, message)
                    self.assertTrue(message.startswith("pool-sim: " + expect), message)
                    self.assertEqual(message.count("\n"), 1, message)
                    self.assertEqual(r.stdout, b"")
                    self.assertEqual(os.listdir(directory), [])
        finally:
            os.unlink(big)

    def test_valid_variants(self):
        # Explicit table fields over a preset, parameters, a moving ball without a strike, 3D pos.
        doc = {
            "format": "libpool-scenario/1",
            "name": "variants",
            "table": {"preset": "wpa-8ft", "corner_mouth": 0.12},
            "params": {"mu_ball": 0.05, "e_cushion": 0.8},
            "balls": [{"id": 5, "pos": [0.5, 0.5, R], "vel": [1.0, 0.3, 0.0], "omega": [0, 0, 0]},
                      {"id": -2, "pos": [1.2, 0.4]}],
            "options": {"airborne": False, "max_time": 60, "max_events": 5000},
        }
        r = sim(write("variants.json", doc))
        self.assertEqual(r.returncode, 0, r.stderr)
        out = json.loads(r.stdout)
        self.check_result(out, [5, -2])
        self.assertEqual(out["table"]["corner_mouth"], 0.12)
        self.assertNotIn("strike", {e["type"] for e in out["events"]})
        self.assertEqual(out["events"][0]["balls"], [5])  # only the moving ball has events first

    def test_max_time_cuts_the_shot(self):
        # "final" is taken at max_time when the shot is cut there, with balls still moving.
        doc = straight_shot(2.0)
        doc["options"] = {"max_time": 0.3}
        r = sim(write("max_time.json", doc), "--sample", "0.01")
        self.assertEqual(r.returncode, 0, r.stderr)
        out = json.loads(r.stdout)
        self.check_result(out, [0, 1])
        self.assertEqual(out["stats"]["stop_reason"], "max_time")
        self.assertEqual(out["stats"]["end_time"], 0.3)
        self.assertLessEqual(out["stats"]["sim_time"], 0.3)
        cue = [b for b in out["final"] if b["id"] == 0][0]
        self.assertEqual(cue["state"], "sliding")
        # Still sliding at 0.3 s (slide_roll comes at 2 v0 / (7 mu g) = 0.44 s): closed form.
        v0, a = 2 * 2.0 / (1 + 0.17 / 0.54), 0.2 * 9.81
        self.assertAlmostEqual(cue["pos"][0], 0.635 + v0 * 0.3 - a * 0.3**2 / 2, delta=1e-12)
        self.assertAlmostEqual(cue["vel"][0], v0 - a * 0.3, delta=1e-12)
        samples = [b for b in out["samples"]["balls"] if b["id"] == 0][0]
        self.assertEqual(samples["t"][-1], 0.3)
        self.assertIn(0.29, samples["t"])  # grid times are k / (1/dt), not k * dt

    def test_max_events_stops(self):
        doc = straight_shot(3.0)
        doc["options"] = {"max_events": 2}
        r = sim(write("max_events.json", doc))
        self.assertEqual(r.returncode, 0, r.stderr)
        out = json.loads(r.stdout)
        self.check_result(out, [0, 1])
        self.assertLessEqual(len(out["events"]), 3)  # the strike plus at most max_events
        self.assertEqual(out["stats"]["stop_reason"], "max_events")


class TestRack(unittest.TestCase, ResultChecks):
    def rack(self, *args):
        r = run([ARGS.pool_rack, *args])
        self.assertEqual(r.returncode, 0, r.stderr)
        return json.loads(r.stdout), r.stdout

    def test_help_and_usage(self):
        r = run([ARGS.pool_rack, "--help"])
        self.assertEqual(r.returncode, 0)
        self.assertIn(b"usage: pool-rack", r.stdout)
        for args, expect in [((), b"8ball"), (("10ball",), b"10ball"), (("8ball", "--speed", "-3"), b"--speed"),
                             (("8ball", "--spin", "1"), b"--spin"), (("8ball", "--table", "x"), b"--table"),
                             (("8ball", "--speed"), b"--speed"), (("8ball", "--frobnicate"), b"--frobnicate")]:
            r = run([ARGS.pool_rack, *args])
            self.assertEqual(r.returncode, 2, args)
            self.assertIn(expect, r.stderr, args)
        r = run([ARGS.pool_rack, "8ball", "--spin", "0.02,0.025"])
        self.assertEqual(r.returncode, 2)
        self.assertIn(b"strike", r.stderr)

    def test_racks_are_tight_and_on_the_table(self):
        for kind, n in (("8ball", 16), ("9ball", 10)):
            doc, _ = self.rack(kind, "--gap", "0")
            self.assertEqual(doc["format"], "libpool-scenario/1")
            self.assertEqual(sorted(b["id"] for b in doc["balls"]), list(range(n)))
            pos = {b["id"]: b["pos"] for b in doc["balls"]}
            self.assertEqual(pos[0], [2.54 / 4, 1.27 / 2])
            # Apex on the foot spot, every rack ball touching at least two neighbours.
            apex = min((p for i, p in pos.items() if i), key=lambda p: p[0])
            self.assertAlmostEqual(apex[0], 3 * 2.54 / 4, delta=1e-12)
            self.assertAlmostEqual(apex[1], 1.27 / 2, delta=1e-12)
            for i in pos:
                if i == 0:
                    continue
                touching = sum(1 for j in pos if j not in (0, i) and abs(math.dist(pos[i], pos[j]) - 2 * R) < 1e-9)
                self.assertGreaterEqual(touching, 2, (kind, i))
                for j in pos:
                    if j != i:
                        self.assertGreater(math.dist(pos[i], pos[j]), 2 * R - 1e-9)
            self.assertEqual(doc["strike"]["ball"], 0)

    def test_rack_round_trips_through_pool_sim(self):
        for args in (("8ball",), ("9ball", "--speed", "4", "--spin", "0,-0.01", "--table", "wpa-7ft")):
            _, text = self.rack(*args)
            path = write(f"rack_{args[0]}.json", text.decode())
            r = sim(path, "--sample", "0.02")
            self.assertEqual(r.returncode, 0, r.stderr)
            doc = json.loads(r.stdout)
            self.check_result(doc, [b["id"] for b in json.loads(text)["balls"]])
            self.assertIn("ball_ball", {e["type"] for e in doc["events"]})

    def test_output_file(self):
        out = os.path.join(ARGS.work, "rack-out.json")
        r = run([ARGS.pool_rack, "9ball", "-o", out])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stdout, b"")
        with open(out, encoding="utf-8") as f:
            self.assertEqual(len(json.load(f)["balls"]), 10)


class TestPlot(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rack = run([ARGS.pool_rack, "8ball"])
        scenario = write("plot_rack.json", rack.stdout.decode())
        cls.result = os.path.join(ARGS.work, "plot_result.json")
        r = sim(scenario, "--sample", "0.02", "-o", cls.result)
        assert r.returncode == 0, r.stderr

    def plot(self, *args):
        return run([ARGS.python, ARGS.pool_plot, *args], timeout=180)

    def test_png(self):
        out = os.path.join(ARGS.work, "break.png")
        r = self.plot(self.result, "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out, "rb") as f:
            data = f.read()
        self.assertEqual(data[:8], b"\x89PNG\r\n\x1a\n")
        self.assertGreater(len(data), 20000)
        width, height = int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")
        self.assertGreater(width, 1000)
        self.assertAlmostEqual(width / height, 1.65, delta=0.3)
        again = os.path.join(ARGS.work, "break2.png")
        self.assertEqual(self.plot(self.result, "-o", again).returncode, 0)
        with open(again, "rb") as f:
            self.assertEqual(f.read(), data, "the same result must give the same picture")

    def test_svg(self):
        out = os.path.join(ARGS.work, "break.svg")
        r = self.plot(self.result, "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out, encoding="utf-8") as f:
            text = f.read()
        self.assertIn("<svg", text)
        self.assertIn("</svg>", text)

    def test_pipe_output(self):
        fifo = os.path.join(ARGS.work, "plot.fifo.png")
        if os.path.lexists(fifo):
            os.unlink(fifo)
        os.mkfifo(fifo)
        proc = subprocess.Popen([ARGS.python, ARGS.pool_plot, self.result, "-o", fifo],
                                stderr=subprocess.PIPE)
        with open(fifo, "rb") as f:
            data = f.read()
        self.assertEqual(proc.wait(timeout=180), 0)
        self.assertEqual(data[:8], b"\x89PNG\r\n\x1a\n")
        self.assertTrue(stat.S_ISFIFO(os.lstat(fifo).st_mode))

    def test_bad_input(self):
        bad = write("not_a_result.json", json.dumps({"format": "libpool-scenario/1"}))
        for args, expect in [((bad,), "format"), ((os.path.join(ARGS.work, "nope.json"),), "nope.json"),
                             ((write("broken.json", "{"),), "malformed"),
                             ((self.result, "-o", os.path.join(ARGS.work, "x.gif")), "-o")]:
            r = self.plot(*args)
            self.assertEqual(r.returncode, 2, args)
            self.assertIn(expect, r.stderr.decode(), args)
        r = self.plot("--help")
        self.assertEqual(r.returncode, 0)
        self.assertIn(b"usage", r.stdout)


def main():
    global ARGS
    parser = argparse.ArgumentParser()
    for name in ("--pool-sim", "--pool-rack", "--pool-plot", "--python", "--work"):
        parser.add_argument(name, required=True)
    ARGS, rest = parser.parse_known_args()
    os.makedirs(ARGS.work, exist_ok=True)
    unittest.main(argv=[sys.argv[0], *rest], verbosity=2)


if __name__ == "__main__":
    main()
