"""End-to-end tests of pool-sim, pool-rack and pool-plot (ctest label "tools").

Usage: python test_commands.py --pool-sim PATH --pool-rack PATH --pool-plot PATH
                               --python PATH --work DIR [--require-matplotlib]
                               [unittest arguments]

Every wait is bounded: subprocesses run with timeouts, and FIFOs are read and written by helpers
that give up (and unblock themselves) when the other side dies or the deadline passes. The plot
tests need matplotlib in --python: without it they are skipped with a message (or fail, with
--require-matplotlib), and pool-plot's own message for a missing matplotlib is tested instead.
"""
import argparse
import functools
import json
import math
import os
import select
import shutil
import stat
import subprocess
import tempfile
import sys
import threading
import time
import unittest

ARGS = None
HAS_MATPLOTLIB = False
LIMIT = 64 << 20  # the commands' default --max-input, bytes
R = 0.028575
EVENT_TYPES = {"strike", "slide_roll", "roll_stop", "spin_stop", "ball_ball", "ball_cushion",
               "ball_table", "pocket", "off_table", "link_begin", "link_step", "link_end"}
STATES = {"stationary", "spinning", "sliding", "rolling", "airborne", "linked", "pocketed",
          "off_table"}
RAILS = {"south", "north", "west", "east"}
POCKETS = {"sw", "se", "nw", "ne", "s", "n"}


def run(cmd, stdin=None, timeout=120, env=None):
    return subprocess.run(cmd, input=stdin, capture_output=True, timeout=timeout, env=env)


def finish(proc, timeout=60):
    """Waits for proc (killing it at the deadline); returns (returncode, stderr bytes)."""
    try:
        _, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        _, err = proc.communicate(timeout=30)
        return "killed after %s s" % timeout, err
    return proc.returncode, err


def read_fifo(path, proc, timeout=60):
    """Reads the FIFO path, which proc writes, to its end. Bounded: when proc exits without ever
    opening the FIFO (pool-plot without matplotlib did), the reader blocked in open() is released
    by opening the FIFO for writing for a moment; at the deadline proc is killed.
    Returns (data, returncode, stderr)."""
    result = {"data": b""}

    def reader():
        try:
            with open(path, "rb") as f:
                result["data"] = f.read()
        except OSError as e:
            result["error"] = e

    thread = threading.Thread(target=reader, daemon=True)
    thread.start()
    deadline = time.monotonic() + timeout
    while thread.is_alive() and proc.poll() is None and time.monotonic() < deadline:
        thread.join(0.05)
    if proc.poll() is None and thread.is_alive():
        proc.kill()
    thread.join(2)  # a writer that has exited leaves at most a pipe buffer to read
    if thread.is_alive():
        try:
            os.close(os.open(path, os.O_WRONLY | os.O_NONBLOCK))
        except OSError:
            pass
        thread.join(10)
    rc, err = finish(proc, 30)
    return result["data"], rc, err


def pump(fd, chunk, total, deadline):
    """Writes chunk to fd (made non-blocking) until total bytes, EPIPE or the deadline; returns the
    bytes written. Never blocks past the deadline, even when the reader hangs."""
    os.set_blocking(fd, False)
    written = 0
    while written < total and time.monotonic() < deadline:
        if not select.select([], [fd], [], 0.1)[1]:
            continue
        try:
            written += os.write(fd, chunk[:total - written])
        except BlockingIOError:
            continue
        except (BrokenPipeError, ConnectionResetError):
            break
    return written


def write_fifo(path, proc, chunk, total, timeout=60):
    """Writes chunk to the FIFO path, which proc reads, until proc stops reading (EPIPE) or total
    bytes are written; bounded like read_fifo. Returns (bytes written, returncode, stderr)."""
    deadline = time.monotonic() + timeout
    fd = None
    while fd is None and proc.poll() is None and time.monotonic() < deadline:
        try:  # non-blocking open: ENXIO until proc has opened its end
            fd = os.open(path, os.O_WRONLY | os.O_NONBLOCK)
        except OSError:
            time.sleep(0.01)
    written = 0
    if fd is not None:
        try:
            written = pump(fd, chunk, total, deadline)
        finally:
            os.close(fd)
    rc, err = finish(proc, max(1, deadline - time.monotonic()))
    return written, rc, err


def stream_stdin(cmd, chunk, total, timeout=60):
    """Runs cmd with a pipe of up to total bytes on its standard input, written until it stops
    reading; bounded. Returns (bytes written, returncode, stderr)."""
    proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE)
    deadline = time.monotonic() + timeout
    try:
        written = pump(proc.stdin.fileno(), chunk, total, deadline)
    finally:
        proc.stdin.close()
        proc.stdin = None  # so that communicate() leaves it alone
    rc, err = finish(proc, max(1, deadline - time.monotonic()))
    return written, rc, err


def assert_printable(test, text, what):
    """text (bytes from a command's standard error) holds no control character but the newline
    ending each line, no DEL and no C1 control."""
    for i, c in enumerate(text):
        if (c < 0x20 and c != 0x0A) or c == 0x7F:
            test.fail(f"{what}: raw control byte 0x{c:02x} at {i} in {text[:300]!r}")
    decoded = text.decode("utf-8", errors="replace")
    for ch in decoded:
        if 0x80 <= ord(ch) <= 0x9F or ord(ch) in (0x202E, 0x2066, 0x2067):
            test.fail(f"{what}: raw U+{ord(ch):04X} in {decoded[:300]!r}")


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
                             (("x.json", "-o"), b"-o"), (("a.json", "b.json"), b"b.json"),
                             (("x.json", "--max-input"), b"--max-input")]:
            r = sim(*args)
            self.assertEqual(r.returncode, 2, args)
            self.assertIn(expect, r.stderr, args)
            self.assertEqual(r.stdout, b"", args)

    def test_straight_shot_matches_closed_form(self):
        # Centre-ball level strike: v0 = 2 V / (1 + m/M), no spin, so the ball slides until
        # t = 2 v0 / (7 mu_slide g) and has then covered v0 t - mu_slide g t^2 / 2 (docs/physics.md).
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
        data, rc, err = read_fifo(fifo, proc)
        self.assertEqual(rc, 0, err)
        self.assertEqual(data, expected)
        self.assertTrue(stat.S_ISFIFO(os.lstat(fifo).st_mode))

    def test_unwritable_output_is_reported(self):
        # Missing directories are created (a fresh clone's out/); a path through a regular file
        # cannot be written and is reported.
        fresh = os.path.join(ARGS.work, "fresh_out", "no", "such")
        shutil.rmtree(os.path.join(ARGS.work, "fresh_out"), ignore_errors=True)
        r = sim(write("ok.json", straight_shot()), "-o", os.path.join(fresh, "dir.json"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertTrue(os.path.isfile(os.path.join(fresh, "dir.json")))
        blocker = write("blocker", "x")
        r = sim(write("ok.json", straight_shot()), "-o", os.path.join(blocker, "such", "dir.json"))
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
            ("table_number", with_(lambda d: d.update(table=9)), "table: must be a preset name"),
            ("table_string", with_(lambda d: d.update(table="wpa-10ft")), "table: unknown preset"),
            ("preset", with_(lambda d: d.update(table={"preset": "billiards"})), "table.preset"),
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
            # 0.4 m R^2 underflows: the radius is named, not ball_mass (issue 9).
            ("radius_tiny", with_(lambda d: d.update(params={"ball_radius": 1e-300})),
             "params.ball_radius: 1e-300 m is out of range"),
            ("radius_subnormal_inertia", with_(lambda d: d.update(params={"ball_radius": 1e-160})),
             "params.ball_radius: 1e-160 m"),
            ("mass_subnormal", with_(lambda d: d.update(params={"ball_mass": 4.9e-324})),
             "params.ball_mass: 4.94066e-324 kg with ball_radius 0.028575 m is out of range"),
            ("mass_and_radius", with_(lambda d: d.update(params={"ball_mass": 1e-200, "ball_radius": 1e-100})),
             "params.ball_mass: 1e-200 kg"),
        ]
        for name, text, expect in cases:
            with self.subTest(name=name):
                r = sim(write(f"bad_{name}.json", text))
                self.assertEqual(r.returncode, 2, f"{name}: {r.stderr!r}")
                self.assertEqual(r.stdout, b"")
                message = r.stderr.decode()
                self.assertTrue(message.startswith("pool-sim: "), message)
                self.assertIn(expect, message, name)

    def test_airborne_inputs_exit_2_naming_the_field(self):
        # options.airborne = true: 3D positions and vertical velocities are accepted by the
        # parser; what it refuses exits 2 with the field named. A valid airborne scenario is
        # simulated.
        def air(change=None):
            doc = straight_shot()
            doc["options"] = {"airborne": True}
            if change:
                change(doc)
            return json.dumps(doc)

        def ball(i, **fields):
            return lambda d: d["balls"][i].update(fields)

        cases = [
            ("air_below_cloth", air(ball(1, pos=[1.9, 0.6, 0.01])), "balls[1].pos: below the cloth"),
            ("air_overlap_3d", air(lambda d: d["balls"].append({"id": 5, "pos": [1.905, 0.635, 0.07]})),
             "balls[2].pos: overlaps ball 1 by"),
            ("air_duplicate", air(lambda d: d["balls"].append({"id": 1, "pos": [1.0, 0.3, 0.2]})),
             "balls[2].id: duplicate id 1"),
            ("air_off_table", air(ball(1, pos=[2.6, 0.5, 0.3])), "balls[1].pos: off the table"),
            ("air_theta_90", air(lambda d: d["strike"].update(theta=90)), "strike.theta: must be in [0, 90) degrees"),
            ("air_strike_flying", air(ball(0, pos=[0.635, 0.635, 0.2])), "strike.ball: ball 0 must be at rest"),
            ("air_fast", air(ball(1, vel=[0.0, 0.0, 200.0])), "balls[1].vel: speed above"),
        ]
        for name, text, expect in cases:
            with self.subTest(name=name):
                r = sim(write(f"bad_{name}.json", text))
                self.assertEqual(r.returncode, 2, f"{name}: {r.stderr!r}")
                self.assertEqual(r.stdout, b"")
                message = r.stderr.decode()
                self.assertTrue(message.startswith("pool-sim: "), message)
                self.assertIn(expect, message, name)
        ok = air(lambda d: (d["balls"][1].update(pos=[1.905, 0.635, 0.2], vel=[0.0, 0.0, 1.0]),
                            d["strike"].update(theta=60)))
        r = sim(write("air_ok.json", ok))
        # libpool simulates airborne motion: the shot runs, the thrown ball lands, the elevated
        # cue drives the cue ball into the cloth at t = 0.
        self.assertEqual(r.returncode, 0, r.stderr)
        events = json.loads(r.stdout)["events"]
        self.assertIn("ball_table", [e["type"] for e in events])
        self.assertEqual([e["type"] for e in events[:2]], ["strike", "ball_table"])
        self.assertEqual(events[1]["t"], 0)

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
                (directory, (), directory + ": read error: "),
                ("/dev/null", (), "(document): malformed JSON at line 1"),
                (empty, (), "(document): malformed JSON at line 1"),
                # Over the 64 MiB input limit: refused from its size, unread.
                (big, (), big + ": input is larger than the limit of 67108864 bytes (104857600 bytes)"),
                # Read with a higher limit, jansson refuses the nesting.
                (big, ("--max-input", "200M"), "(document): malformed JSON at line 1"),
            ]
            for path, options, expect in cases:
                with self.subTest(path=path, options=options):
                    r = sim(path, "-o", out, *options)
                    message = r.stderr.decode()
                    self.assertEqual(r.returncode, 2, message)
                    self.assertTrue(message.startswith("pool-sim: " + expect), message)
                    self.assertEqual(message.count("\n"), 1, message)
                    self.assertEqual(r.stdout, b"")
                    self.assertEqual(os.listdir(directory), [])
        finally:
            os.unlink(big)

    def test_input_limit(self):
        # Every input is read up to the limit (64 MiB unless --max-input): a device, a pipe on
        # standard input and a FIFO that never end are refused, exit 2, naming the input.
        message = b": input is larger than the limit of 67108864 bytes\n"
        start = time.monotonic()
        r = run([ARGS.pool_sim, "/dev/zero"], timeout=60)
        self.assertEqual((r.returncode, r.stdout), (2, b""), r.stderr)
        self.assertEqual(r.stderr, b"pool-sim: /dev/zero" + message)

        chunk = b" " * (1 << 20)  # JSON whitespace: a parser reading it all would find no end
        written, rc, err = stream_stdin([ARGS.pool_sim, "-"], chunk, 1 << 30)
        self.assertEqual(rc, 2, err)
        self.assertEqual(err, b"pool-sim: standard input" + message)
        self.assertGreater(written, LIMIT)  # it read the limit, then stopped
        self.assertLess(written, 1 << 30)

        fifo = os.path.join(ARGS.work, "input.fifo")
        if os.path.lexists(fifo):
            os.unlink(fifo)
        os.mkfifo(fifo)
        proc = subprocess.Popen([ARGS.pool_sim, fifo], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        written, rc, err = write_fifo(fifo, proc, chunk, 1 << 30)
        self.assertEqual(rc, 2, err)
        self.assertEqual(err, b"pool-sim: " + fifo.encode() + message)
        self.assertGreater(written, LIMIT)
        self.assertLess(time.monotonic() - start, 60, "the three refusals must be quick")

        # --max-input N: a document of N bytes passes, N + 1 bytes do not (file and pipe alike).
        text = json.dumps(straight_shot()).encode()
        path = write("limit.json", text.decode())
        n = len(text)
        for source, stdin, name in ((path, None, path), ("-", text, "standard input")):
            with self.subTest(source=source):
                ok = sim(source, "--max-input", str(n), stdin=stdin)
                self.assertEqual(ok.returncode, 0, ok.stderr)
                over = sim(source, "--max-input", str(n - 1), stdin=stdin)
                self.assertEqual((over.returncode, over.stdout), (2, b""))
                expect = f"pool-sim: {name}: input is larger than the limit of {n - 1} bytes"
                self.assertTrue(over.stderr.decode().startswith(expect), over.stderr)
        self.assertEqual(sim(path, "--max-input", "1k").returncode, 0)
        over = sim(path, "--max-input", "0k")
        self.assertEqual(over.returncode, 2)
        for bad in ("0", "-1", "1.5", "12q", "", "1kk", "99999999999999999999999", "1e6"):
            with self.subTest(value=bad):
                r = sim(path, "--max-input", bad)
                self.assertEqual((r.returncode, r.stdout), (2, b""), r.stderr)
                self.assertIn(b"--max-input: '", r.stderr)
        r = sim("--help")
        self.assertIn(b"--max-input BYTES", r.stdout)

    def test_echoed_input_is_escaped(self):
        # Unknown keys, a preset name, jansson's quote of bad input, file names and options are
        # echoed with control and other invisible characters escaped, and cut when long; the
        # message still names the field and stays on one line.
        def doc_with(**parts):
            doc = straight_shot()
            for where, value in parts.items():
                if where == "top":
                    doc.update(value)
                else:
                    doc.setdefault(where, {}).update(value)
            return json.dumps(doc)

        long_key = "k" * 10240
        cases = [
            ("esc_top", doc_with(top={"bo\x1b[31mgus": 1}), "pool-sim: bo\\u001b[31mgus: unknown field\n"),
            ("newline_param", doc_with(params={"mu\nslide": 1}), "pool-sim: params.mu\\u000aslide: unknown field\n"),
            ("esc_ball", json.dumps(straight_shot()).replace('"id": 1,', '"id": 1, "c\\u001b]0;x\\u0007": 1,'),
             "pool-sim: balls[1].c\\u001b]0;x\\u0007: unknown field\n"),
            ("bidi_table", doc_with(table={"w\u202eidth": 1}), "pool-sim: table.w\\u202eidth: unknown field\n"),
            ("c1_option", doc_with(options={"x\u009by": 1}), "pool-sim: options.x\\u009by: unknown field\n"),
            ("preset", doc_with(table={"preset": "\x1b[2Jwpa"}),
             'pool-sim: table.preset: unknown preset "\\u001b[2Jwpa" (wpa-9ft, wpa-8ft, wpa-7ft, snooker, carom)\n'),
            # jansson refuses a NUL in a key; its message quotes the source text, escapes and all.
            ("nul_key", doc_with(params={"a\u0000b": 1}), "pool-sim: (document): malformed JSON at line 1"),
            # Raw control bytes in a string are not JSON: jansson's quote of them is escaped.
            ("raw_esc", '{"format": "libpool-scenario/1", "\x1b[2J": 1}', "pool-sim: (document): malformed JSON at line 1"),
            ("bad_utf8", b'{"format": "libpool-scenario/1", "x\xff\x9b": 1}', "pool-sim: (document): malformed JSON at line 1"),
            ("long_key", doc_with(params={long_key: 1}),
             "pool-sim: params." + "k" * 79 + "...(10240 bytes): unknown field\n"),
        ]
        for name, text, expect in cases:
            with self.subTest(name=name):
                path = os.path.join(ARGS.work, f"escape_{name}.json")
                with open(path, "wb") as f:
                    f.write(text if isinstance(text, bytes) else text.encode())
                r = sim(path)
                self.assertEqual((r.returncode, r.stdout), (2, b""), r.stderr)
                assert_printable(self, r.stderr, name)
                message = r.stderr.decode()
                self.assertTrue(message.startswith(expect) if not expect.endswith("\n") else message == expect,
                                f"{name}: {message!r}")
                self.assertEqual(message.count("\n"), 1, message)
                self.assertLess(len(r.stderr), 400, name)
        # File names and command-line arguments.
        odd = os.path.join(ARGS.work, "no\x1b[2Jsuch\nfile.json")
        r = sim(odd)
        self.assertEqual(r.returncode, 2)
        assert_printable(self, r.stderr, "file name")
        self.assertIn(b"no\\u001b[2Jsuch\\u000afile.json: No such file or directory", r.stderr)
        for args in (("--bogus\x1b[2J",), ("x.json", "y\x07.json"), ("x.json", "--sample", "\x1b"),
                     ("x.json", "--max-input", "\x1b[1m")):
            with self.subTest(args=args):
                r = sim(*args)
                self.assertEqual(r.returncode, 2, args)
                assert_printable(self, r.stderr, repr(args))
                self.assertTrue(b"\\u001b" in r.stderr or b"\\u0007" in r.stderr, r.stderr)
        # Missing directories are created; one under a regular file cannot be.
        write("not_a_directory", "x")
        r = sim(write("ok_escape.json", straight_shot()), "-o",
                os.path.join(ARGS.work, "not_a_directory", "\x1b.json"))
        self.assertNotEqual(r.returncode, 0)
        assert_printable(self, r.stderr, "output name")
        self.assertIn(b"\\u001b.json: Not a directory", r.stderr)

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
        # Echoed arguments are escaped and cut.
        for args, expect in [(("8ball", "--table", "\x1b[2J"), b"--table: unknown preset '\\u001b[2J'"),
                             (("8ball", "--speed", "1\n2"), b"--speed: '1\\u000a2'"),
                             (("x\x9b\x07",), b"unknown argument 'x\\u009b\\u0007'"),
                             (("8ball", "--gap", "9" * 5000), b"...(5000 bytes)' is not a gap")]:
            r = run([ARGS.pool_rack, *args])
            self.assertEqual(r.returncode, 2, args)
            assert_printable(self, r.stderr, repr(args))
            self.assertIn(expect, r.stderr, args)
            self.assertLess(len(r.stderr), 400, args)

    def test_snooker_and_carom(self):
        # Snooker: 15 reds behind the pink, the colours on the WPBSA spots (ids 20 + value), the
        # cue ball in the D; the snooker table's own balls; the break goes through pool-sim.
        doc, text = self.rack("snooker")
        self.assertEqual(doc["table"], {"preset": "snooker"})
        ids = sorted(b["id"] for b in doc["balls"])
        self.assertEqual(ids, [0] + list(range(1, 16)) + list(range(22, 28)))
        pos = {b["id"]: b["pos"] for b in doc["balls"]}
        L, W, R = 3.569, 1.778, 0.02625
        self.assertAlmostEqual(pos[27][0], L - 0.324, places=12)       # black on its spot
        self.assertAlmostEqual(pos[26][0], 0.75 * L, places=12)        # pink: the pyramid spot
        self.assertAlmostEqual(pos[25][0], 0.5 * L, places=12)         # blue: the centre
        self.assertAlmostEqual(pos[22][1], W / 2 - 0.292, places=12)   # yellow: the D's corner
        self.assertGreater(min(pos[k][0] for k in range(1, 16)), pos[26][0] + 2 * R)
        self.assertEqual(run([ARGS.pool_rack, "--table", "snooker"]).stdout, text)
        res = self.sim_result(text)
        self.assertEqual(res["stats"]["stop_reason"], "rest")
        self.assertEqual(res["ball_radius"], R)
        # Carom: three balls, red on the foot spot, the cue ball beside the yellow.
        doc, text = self.rack("carom")
        self.assertEqual(sorted(b["id"] for b in doc["balls"]), [0, 1, 2])
        res = self.sim_result(text)
        self.assertEqual(res["table"]["pockets"], "none")
        parts = {e.get("part") for e in res["events"] if e["type"] == "ball_cushion"}
        self.assertLessEqual(parts, {"nose"})

    def sim_result(self, scenario_text):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "s.json")
            with open(path, "wb") as f:
                f.write(scenario_text)
            r = run([ARGS.pool_sim, path])
            self.assertEqual(r.returncode, 0, r.stderr)
            return json.loads(r.stdout)

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


# The pool-plot whose planar pictures are the reference: without airborne data the picture must
# stay its very bytes (test_planar_picture_unchanged). It was the last one before the airborne
# side panel (5f22ca5) until the tables' pockets were drawn to scale (issue 20, f9beb63).
PLANAR_REFERENCE = "f9beb63c6f0a829fc6aecf6cee46737e925bac2f"
TABLE_9FT = {"length": 2.54, "width": 1.27, "cushion_height": 0.03629, "corner_mouth": 0.1143,
             "side_mouth": 0.127}


def airborne_result(dt=0.01):
    """A synthetic libpool-result/1 with flights, as the library will write them once it flies
    balls (it does not yet): cue ball 0 jumps over ball 1 (15 cm at the top, right above it),
    lands, bounces twice (e_table 0.5) and slides to a stop; ball 2 hops off the north cushion
    and leaves the table (state off_table, beyond the rail). Motions follow docs/physics.md: parabolas
    (g 9.81) in flight, constant deceleration on the cloth; samples every dt plus every event
    time, ending where a ball leaves the table."""
    g, W = 9.81, TABLE_9FT["width"]
    # Per ball, pieces (t_start, p0, v0, a, state after the event that starts the piece).
    def piece(t, p, v, a, state):
        return {"t": t, "p": list(p), "v": list(v), "a": list(a), "state": state}

    def at(pc, t):
        tau = t - pc["t"]
        return ([pc["p"][k] + pc["v"][k] * tau + pc["a"][k] * tau * tau / 2 for k in range(3)],
                [pc["v"][k] + pc["a"][k] * tau for k in range(3)])

    fly = [0.0, 0.0, -g]
    events = []
    # Ball 0: a jump (vz 1.72 m/s) along +x over ball 1, two bounces, then sliding to rest.
    cue = [piece(0.0, [0.635, 0.635, R], [1.5, 0.0, 1.72], fly, "airborne")]
    events.append((0.0, "strike", 0))
    vx, vz = 1.5, 1.72
    for n, (vx_after, state) in enumerate([(1.35, "airborne"), (1.25, "airborne"),
                                          (1.2, "sliding")]):
        last = cue[-1]
        t = last["t"] + 2 * vz / g  # back on the cloth
        p, _ = at(last, t)
        p[2] = R
        vz = 0.5 * vz if state == "airborne" else 0.0
        slide = [-1.5, 0.0, 0.0] if state == "sliding" else fly
        cue.append(piece(t, p, [vx_after, 0.0, vz], slide, state))
        events.append((t, "ball_table", 0))
    last = cue[-1]
    t_stop = last["t"] + 1.2 / 1.5
    p, _ = at(last, t_stop)
    cue.append(piece(t_stop, p, [0, 0, 0], [0, 0, 0], "stationary"))
    events.append((t_stop, "roll_stop", 0))
    # Ball 2: rolling north, hops at the cushion (y = W - R) and clears the rail.
    hop = [piece(0.0, [1.9, 0.9, R], [0.3, 1.6, 0.0], [0, 0, 0], "rolling")]
    t_c = (W - R - 0.9) / 1.6
    p, _ = at(hop[0], t_c)
    hop.append(piece(t_c, p, [0.3, 0.9, 1.1], fly, "airborne"))
    events.append((t_c, "ball_cushion", 2))
    t_off = t_c + (W + 0.05 - p[1]) / 0.9
    p, _ = at(hop[1], t_off)
    hop.append(piece(t_off, p, [0, 0, 0], [0, 0, 0], "off_table"))
    events.append((t_off, "off_table", 2))
    pieces = {0: cue, 1: [piece(0.0, [1.0, 0.635, R], [0, 0, 0], [0, 0, 0], "stationary")],
              2: hop}

    def state(ball_id, t):
        pcs = [pc for pc in pieces[ball_id] if pc["t"] <= t]
        pc = pcs[-1]
        pos, vel = at(pc, t)
        if pc["state"] in ("stationary", "off_table"):
            vel = [0.0, 0.0, 0.0]
        return {"id": ball_id, "pos": pos, "vel": vel, "omega": [0.0, 0.0, 0.0],
                "state": pc["state"]}

    events.sort()
    doc_events = []
    for t, kind, ball_id in events:
        ev = {"t": t, "type": kind, "balls": [ball_id], "after": [state(ball_id, t)]}
        if kind == "ball_cushion":
            ev["rail"] = "north"
        doc_events.append(ev)
    end = t_stop
    grid = [k / round(1 / dt) for k in range(int(end / dt) + 1)]
    balls = []
    for ball_id in sorted(pieces):
        stop = t_off if ball_id == 2 else end
        if ball_id == 1:
            ts = [0.0, end]
        else:
            ts = sorted({t for t in grid if t <= stop} | {t for t, _, _ in events if t <= stop}
                        | {stop})
        balls.append({"id": ball_id, "t": ts, "pos": [state(ball_id, t)["pos"] for t in ts]})
    return {
        "format": "libpool-result/1", "name": "jump over a ball, hop off the table",
        "table": dict(TABLE_9FT), "ball_radius": R, "events": doc_events,
        "final": [state(b, end) for b in sorted(pieces)],
        "stats": {"events": len(doc_events), "sim_time": end, "end_time": end,
                  "stop_reason": "rest", "pocketed": [], "off_table": [2]},
        "samples": {"dt": dt, "balls": balls},
    }


def needs_matplotlib(test):
    """Skips the test when --python has no matplotlib (fails instead with --require-matplotlib)."""
    @functools.wraps(test)
    def wrapper(self):
        if not HAS_MATPLOTLIB:
            if ARGS.require_matplotlib:
                self.fail(f"{ARGS.python} cannot import matplotlib, which --require-matplotlib "
                          "demands (it could at configure time)")
            self.skipTest(f"{ARGS.python} has no matplotlib (tools/setup.sh installs it)")
        return test(self)
    return wrapper


class TestPlot(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rack = run([ARGS.pool_rack, "8ball"])
        scenario = write("plot_rack.json", rack.stdout.decode())
        cls.result = os.path.join(ARGS.work, "plot_result.json")
        r = sim(scenario, "--sample", "0.02", "-o", cls.result)
        assert r.returncode == 0, r.stderr
        # A matplotlib that fails to import, first on the path: pool-plot as on a Python
        # without matplotlib, whatever --python has. Its exit status tells whether pool-plot
        # accepted the input (1: it got as far as drawing) or refused it (2).
        stub = os.path.join(ARGS.work, "no_matplotlib", "matplotlib")
        os.makedirs(stub, exist_ok=True)
        with open(os.path.join(stub, "__init__.py"), "w", encoding="utf-8") as f:
            f.write('raise ImportError("No module named \'matplotlib\' (test stub)")\n')
        cls.no_mpl_env = dict(os.environ, PYTHONPATH=os.path.dirname(stub))

    def plot(self, *args, env=None, stdin=None):
        return run([ARGS.python, ARGS.pool_plot, *args], timeout=180, env=env, stdin=stdin)

    @needs_matplotlib
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

    @needs_matplotlib
    def test_svg(self):
        out = os.path.join(ARGS.work, "break.svg")
        r = self.plot(self.result, "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out, encoding="utf-8") as f:
            text = f.read()
        self.assertIn("<svg", text)
        self.assertIn("</svg>", text)

    def fifo(self, name):
        fifo = os.path.join(ARGS.work, name)
        if os.path.lexists(fifo):
            os.unlink(fifo)
        os.mkfifo(fifo)
        return fifo

    @needs_matplotlib
    def test_pipe_output(self):
        fifo = self.fifo("plot.fifo.png")
        proc = subprocess.Popen([ARGS.python, ARGS.pool_plot, self.result, "-o", fifo],
                                stderr=subprocess.PIPE)
        data, rc, err = read_fifo(fifo, proc, timeout=180)
        self.assertEqual(rc, 0, err)
        self.assertEqual(data[:8], b"\x89PNG\r\n\x1a\n")
        self.assertTrue(stat.S_ISFIFO(os.lstat(fifo).st_mode))

    def test_without_matplotlib(self):
        # One message and exit 1, no output file, and a FIFO reader that does not wait forever
        # for the picture (this test hung when pool-plot died before opening the FIFO).
        out = os.path.join(ARGS.work, "no_mpl.png")
        if os.path.exists(out):
            os.unlink(out)
        r = self.plot(self.result, "-o", out, env=self.no_mpl_env)
        self.assertEqual(r.returncode, 1, r.stderr)
        message = r.stderr.decode()
        self.assertTrue(message.startswith("pool-plot: matplotlib is not installed for "), message)
        self.assertIn(".venv/bin/python", message)
        self.assertEqual(message.count("\n"), 1, message)
        self.assertFalse(os.path.exists(out))
        fifo = self.fifo("no_mpl.fifo.png")
        start = time.monotonic()
        proc = subprocess.Popen([ARGS.python, ARGS.pool_plot, self.result, "-o", fifo],
                                stderr=subprocess.PIPE, env=self.no_mpl_env)
        data, rc, err = read_fifo(fifo, proc, timeout=120)
        self.assertEqual((rc, data), (1, b""), err)
        self.assertIn(b"matplotlib is not installed", err)
        self.assertLess(time.monotonic() - start, 60)

    def test_input_limit(self):
        # Inputs over the limit (64 MiB unless --max-input) exit 2 naming the input, from a
        # device, a pipe or a file; input within it gets as far as drawing (exit 1 here: the
        # matplotlib stub).
        out = os.path.join(ARGS.work, "limit.png")
        env = self.no_mpl_env
        message = b": input is larger than the limit of 67108864 bytes\n"
        r = run([ARGS.python, ARGS.pool_plot, "/dev/zero", "-o", out], timeout=120, env=env)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertEqual(r.stderr, b"pool-plot: /dev/zero" + message)
        written, rc, err = stream_stdin([ARGS.python, ARGS.pool_plot, "-", "-o", out],
                                        b" " * (1 << 20), 1 << 30, timeout=120)
        self.assertEqual(rc, 2, err)
        self.assertEqual(err, b"pool-plot: standard input" + message)
        self.assertGreater(written, LIMIT)
        size = os.path.getsize(self.result)
        for limit, status in ((str(size), 1), (str(size - 1), 2), ("1M", 1), ("1k", 2)):
            with self.subTest(limit=limit):
                r = self.plot(self.result, "-o", out, "--max-input", limit, env=env)
                self.assertEqual(r.returncode, status, r.stderr)
                if status == 2:
                    self.assertIn(f"plot_result.json: input is larger than the limit of".encode(), r.stderr)
        with open(self.result, "rb") as f:
            text = f.read()
        r = self.plot("-", "-o", out, "--max-input", str(size - 1), env=env, stdin=text)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertTrue(r.stderr.startswith(b"pool-plot: standard input: input is larger"), r.stderr)
        for bad in ("0", "-1", "1.5", "12q", "", "1kk"):
            with self.subTest(value=bad):
                r = self.plot(self.result, "-o", out, "--max-input", bad, env=env)
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertIn(b"--max-input", r.stderr)

    def test_echoed_input_is_escaped(self):
        with open(self.result, encoding="utf-8") as f:
            doc = json.load(f)
        doc["events"][1]["type"] = "\x1b]0;owned\x07" + "x" * 3000
        bad_type = write("plot_bad_type.json", json.dumps(doc))
        out = os.path.join(ARGS.work, "escape.png")
        cases = [
            ((bad_type, "-o", out), b"events[1].type: unknown event type '\\u001b]0;owned\\u0007xxx"),
            ((os.path.join(ARGS.work, "no\x1b[2Jfile\n.json"), "-o", out), b"no\\u001b[2Jfile\\u000a.json: "),
            ((self.result, "-o", os.path.join(ARGS.work, "x\x1b[2J.gif")), b"x\\u001b[2J.gif' must end in .png"),
            ((self.result, "--bogus\x1b[2J"), b"--bogus\\u001b[2J"),
        ]
        for args, expect in cases:
            with self.subTest(args=args[:1]):
                r = self.plot(*args, env=self.no_mpl_env)
                self.assertEqual(r.returncode, 2, r.stderr)
                assert_printable(self, r.stderr, repr(args))
                self.assertIn(expect, r.stderr)
                self.assertLess(len(r.stderr), 800)

    def test_bad_input(self):
        bad = write("not_a_result.json", json.dumps({"format": "libpool-scenario/1"}))
        for args, expect in [((bad,), "format"), ((os.path.join(ARGS.work, "nope.json"),), "nope.json"),
                             ((write("broken.json", "{"),), "malformed"),
                             ((write("deep.json", "[" * 100000),), "malformed"),
                             ((self.result, "-o", os.path.join(ARGS.work, "x.gif")), "-o")]:
            r = self.plot(*args)
            self.assertEqual(r.returncode, 2, args)
            self.assertIn(expect, r.stderr.decode(), args)
        r = self.plot("--help")
        self.assertEqual(r.returncode, 0)
        self.assertIn(b"usage", r.stdout)
        self.assertIn(b"--max-input", r.stdout)

    def svg_of(self, result, name):
        out = os.path.join(ARGS.work, name)
        r = self.plot(result, "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out, encoding="utf-8") as f:
            return f.read()

    @needs_matplotlib
    def test_airborne_png_and_svg(self):
        # A jump over a ball and a ball leaving the table: a second axes below the table view,
        # the heights against time; dashed flights with their greatest height; landings and the
        # ball off the table marked. Deterministic, PNG and SVG.
        result = write("airborne.json", json.dumps(airborne_result()))
        out = os.path.join(ARGS.work, "airborne.png")
        r = self.plot(result, "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out, "rb") as f:
            data = f.read()
        self.assertEqual(data[:8], b"\x89PNG\r\n\x1a\n")
        width, height = int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")
        self.assertGreater(width, 1000)
        self.assertLess(width / height, 1.3, "the panel below makes the picture taller")
        self.assertEqual(self.plot(result, "-o", out).returncode, 0)
        with open(out, "rb") as f:
            self.assertEqual(f.read(), data, "the same result must give the same picture")
        svg = self.svg_of(result, "airborne.svg")
        self.assertTrue(svg == self.svg_of(result, "airborne.svg"), "the same SVG twice")
        self.assertTrue('id="axes_2"' in svg, "the side panel")
        self.assertFalse('id="axes_3"' in svg)
        for text in ("height above cloth (cm)", "time (s)", "ball 0", "ball 2",
                     "landing (ball_table)", "left the table", "ball 2 off the table",
                     "airborne (tag: greatest height)", "off table: 2", "pocketed: none",
                     "15.1 cm", "3.8 cm", "5.9 cm", "top of a ball on the cloth (2R)"):
            self.assertTrue(text in svg, text)
        self.assertFalse("<!-- ball 1 -->" in svg, "ball 1 never leaves the cloth")

    @needs_matplotlib
    def test_airborne_without_samples(self):
        # Only events: the heights are parabolas from the events' velocities, and the flight's
        # top is still written in the table view.
        doc = airborne_result()
        del doc["samples"]
        svg = self.svg_of(write("airborne_events.json", json.dumps(doc)), "airborne_events.svg")
        for text in ("height above cloth (cm)", "15.1 cm", "3.8 cm",
                     "flights from the events' velocities"):
            self.assertTrue(text in svg, text)

    @needs_matplotlib
    def test_off_table_balls(self):
        # A ball off the table is not drawn as a ball at rest: it is listed in the title, marked
        # where it left, and a position under the cloth is accepted for it (it may have fallen
        # to the floor, far from the table). Small hops are drawn in mm.
        doc = airborne_result()
        doc["final"][2]["pos"] = [2.2, 1.9, -0.7]
        for b in doc["samples"]["balls"]:  # ball 0 stays on the cloth: ball 2 alone flies
            if b["id"] == 0:
                b["pos"] = [[p[0], p[1], R] for p in b["pos"]]
            if b["id"] == 2:
                b["pos"] = [[p[0], p[1], R + (p[2] - R) / 20] for p in b["pos"]]
        for ev in doc["events"]:
            for a in ev["after"]:
                a["pos"][2] = R if a["id"] == 0 else R + (a["pos"][2] - R) / 20
                if a["state"] == "airborne" and a["id"] == 0:
                    a["state"] = "sliding"
        svg = self.svg_of(write("off_table.json", json.dumps(doc)), "off_table.svg")
        self.assertTrue('id="axes_2"' in svg, "the side panel")
        for text in ("height above cloth (mm)", "off table: 2", "ball 2 off the table"):
            self.assertTrue(text in svg, text)
        self.assertFalse("<!-- ball 0 -->" in svg, "ball 0 stays on the cloth")
        # Off the table by its state alone, every z on the cloth: still the panel.
        for b in doc["samples"]["balls"]:
            b["pos"] = [[p[0], p[1], R] for p in b["pos"]]
        for ev in doc["events"]:
            for a in ev["after"]:
                a["pos"][2] = R
        doc["final"][2]["pos"] = [1.99, 1.32, R]
        svg = self.svg_of(write("off_table_flat.json", json.dumps(doc)), "off_table_flat.svg")
        self.assertTrue('id="axes_2"' in svg, "the side panel")
        self.assertTrue("<!-- ball 2 off the table" in svg)

    @needs_matplotlib
    def test_planar_picture_unchanged(self):
        # Without airborne data the picture is the planar one of before the side panel: one
        # axes, nothing about heights, and the very bytes of the pool-plot of commit
        # PLANAR_REFERENCE (taken from git when the source tree is a checkout; change that
        # commit when the planar picture is changed on purpose).
        svg = self.svg_of(self.result, "planar.svg")
        self.assertTrue('id="axes_1"' in svg)
        self.assertFalse('id="axes_2"' in svg, "a planar result has no side panel")
        for text in ("height above", "airborne", "off table", "landing"):
            self.assertFalse(text in svg, text)
        source = os.path.dirname(os.path.dirname(os.path.abspath(ARGS.pool_plot)))
        git = shutil.which("git")
        shown = run([git, "-C", source, "show", f"{PLANAR_REFERENCE}:tools/pool-plot"]) \
            if git else None
        if shown is None or shown.returncode != 0:
            self.skipTest(f"no git checkout with commit {PLANAR_REFERENCE} at {source}: the "
                          "byte comparison with the planar pool-plot is skipped")
        old = write("pool-plot-planar-reference", shown.stdout.decode())
        with open(self.result, encoding="utf-8") as f:
            doc = json.load(f)
        del doc["samples"]
        events_only = write("planar_events.json", json.dumps(doc))
        for result in (self.result, events_only):
            for ext in ("png", "svg"):
                with self.subTest(result=os.path.basename(result), ext=ext):
                    pictures = []
                    for script in (old, ARGS.pool_plot):
                        out = os.path.join(ARGS.work, f"planar_ref.{ext}")
                        r = run([ARGS.python, script, result, "-o", out, "--title", "break"],
                                timeout=180)
                        self.assertEqual(r.returncode, 0, r.stderr)
                        with open(out, "rb") as f:
                            pictures.append(f.read())
                    self.assertTrue(pictures[0] == pictures[1], "the planar picture changed")

    def test_bad_heights_exit_2_naming_the_field(self):
        # Non-finite coordinates and balls under the cloth are refused before anything is drawn
        # (exit 2 whatever the Python: here the matplotlib stub, which would exit 1 on a good
        # input).
        nan, inf = float("nan"), float("inf")

        def case(change):
            doc = airborne_result()
            change(doc)
            return write("bad_height.json", json.dumps(doc))

        def sample(ball, k, z):
            return lambda d: d["samples"]["balls"][ball]["pos"][k].__setitem__(2, z)

        def after(i, z):
            return lambda d: d["events"][i]["after"][0]["pos"].__setitem__(2, z)

        cases = [
            (sample(0, 5, nan), "samples.balls[0].pos[5][2]: must be a finite number"),
            (sample(2, 3, -inf), "samples.balls[2].pos[3][2]: must be a finite number"),
            (lambda d: d["samples"]["balls"][0]["pos"][2].__setitem__(0, inf),
             "samples.balls[0].pos[2][0]: must be a finite number"),
            (sample(0, 7, 0.01), "samples.balls[0].pos[7][2]: z = 0.01 m is below the cloth"),
            (sample(1, 0, R - 2e-6), "samples.balls[1].pos[0][2]: z = 0.028573 m is below"),
            (after(3, nan), "events[3].after[0].pos[2]: must be a finite number"),
            (after(3, 0.0), "events[3].after[0].pos[2]: z = 0 m is below the cloth"),
            (lambda d: d["final"][0]["pos"].__setitem__(2, -0.5),
             "final[0].pos[2]: z = -0.5 m is below the cloth"),
            (lambda d: d["final"][1]["pos"].__setitem__(2, nan),
             "final[1].pos[2]: must be a finite number"),
            (lambda d: d["events"][0]["after"][0]["vel"].__setitem__(2, nan),
             "events[0].after[0].vel[2]: must be a finite number"),
            (lambda d: d["samples"]["balls"][0]["t"].pop(),
             "samples.balls[0].t: must be an array of"),
            (lambda d: d["samples"]["balls"][0]["t"].__setitem__(1, nan),
             "samples.balls[0].t[1]: must be a finite number"),
            (lambda d: d.__setitem__("ball_radius", 0), "ball_radius: must be > 0"),
        ]
        out = os.path.join(ARGS.work, "bad_height.png")
        for change, expect in cases:
            with self.subTest(expect=expect):
                r = self.plot(case(change), "-o", out, env=self.no_mpl_env)
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertTrue(r.stderr.decode().startswith("pool-plot: " + expect), r.stderr)
                self.assertEqual(r.stderr.count(b"\n"), 1, r.stderr)
        # Accepted: z a hair under R (rounding), and under the cloth for a ball off the table.
        for change in (sample(0, 7, R - 1e-12), after(2, -0.7),
                       lambda d: d["final"][2]["pos"].__setitem__(2, -0.7)):
            r = self.plot(case(change), "-o", out, env=self.no_mpl_env)
            self.assertEqual(r.returncode, 1, r.stderr)  # as far as drawing: the stub


def main():
    global ARGS
    parser = argparse.ArgumentParser()
    for name in ("--pool-sim", "--pool-rack", "--pool-plot", "--python", "--work"):
        parser.add_argument(name, required=True)
    parser.add_argument("--require-matplotlib", action="store_true",
                        help="fail, rather than skip, the plot tests when --python has no matplotlib")
    ARGS, rest = parser.parse_known_args()
    os.makedirs(ARGS.work, exist_ok=True)
    global HAS_MATPLOTLIB
    probe = run([ARGS.python, "-c", "import matplotlib"], timeout=120)
    HAS_MATPLOTLIB = probe.returncode == 0
    if not HAS_MATPLOTLIB:
        print(f"test_commands: {ARGS.python} cannot import matplotlib: the plot tests are "
              f"{'failed (--require-matplotlib)' if ARGS.require_matplotlib else 'skipped'}",
              file=sys.stderr)
    unittest.main(argv=[sys.argv[0], *rest], verbosity=2)


if __name__ == "__main__":
    main()
