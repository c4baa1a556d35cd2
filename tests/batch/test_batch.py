"""End-to-end tests of pool-batch (ctest label "tools").

Usage: python test_batch.py --pool-batch PATH --pool-sim PATH --pool-rack PATH --source DIR
                            --work DIR [unittest arguments]

Checks that the output is byte-identical on 1, 2, 4 and 7 threads, that every row is what pool-sim
gives for the same layout and strike (final positions compared as doubles, exactly), that grids
and random samples have the documented size, values and order and are reproducible from the seed,
that bad input exits 2 with a message naming the option, file, line and column or field, and that
a strike the library refuses gives a row with pool-sim's message while the other rows run.
Every subprocess has a timeout.
"""
import argparse
import csv
import io
import json
import os
import pty
import select
import subprocess
import sys
import time
import unittest

ARGS = None
THREADS = (1, 2, 4, 7)


def run(cmd, timeout=300, stdin=None):
    return subprocess.run(cmd, input=stdin, capture_output=True, timeout=timeout)


def work(name):
    return os.path.join(ARGS.work, name)


def write(name, text):
    path = work(name)
    with open(path, "w") as f:
        f.write(text)
    return path


def batch(*args, timeout=300):
    return run([ARGS.pool_batch, *args], timeout=timeout)


def batch_ok(test, *args):
    p = batch(*args)
    test.assertEqual(p.returncode, 0, p.stderr.decode(errors="replace"))
    return p.stdout


def jsonl(data):
    return [json.loads(line) for line in data.decode().splitlines()]


def first_hit(result, ball):
    """The first ball the struck ball hits, from a pool-sim result (ball_ball or link_begin)."""
    for e in result["events"]:
        if e["type"] in ("ball_ball", "link_begin") and ball in e["balls"]:
            others = [b for b in e["balls"] if b != ball]
            if others:
                return others[0]
    return None


RACK = None        # 8-ball rack with its break strike (pool-rack 8ball)
RACK_CUT = None    # the same rack cut at max_time 0.3 s: balls still move at the end
JUMP = None        # airborne layout: a jump over a blocking ball
NO_STRIKE = None   # two balls, no strike


def setUpModule():
    global RACK, RACK_CUT, JUMP, NO_STRIKE
    os.makedirs(ARGS.work, exist_ok=True)
    RACK = work("rack.json")
    p = run([ARGS.pool_rack, "8ball", "-o", RACK])
    assert p.returncode == 0, p.stderr
    with open(RACK) as f:
        doc = json.load(f)
    doc["options"] = {"max_time": 0.3}
    RACK_CUT = write("rack_cut.json", json.dumps(doc))
    JUMP = os.path.join(ARGS.source, "tests", "lcm", "data", "jump.json")
    NO_STRIKE = write("no_strike.json", json.dumps({
        "format": "libpool-scenario/1",
        "balls": [{"id": 3, "pos": [0.635, 0.635]}, {"id": 5, "pos": [1.905, 0.635]}]}))


class Determinism(unittest.TestCase):
    def check_threads(self, *args):
        outputs = {t: batch_ok(self, *args, "--threads", str(t)) for t in THREADS}
        for t in THREADS[1:]:
            self.assertEqual(outputs[t], outputs[1], "output on %d threads differs from 1 thread" % t)
        self.assertEqual(batch_ok(self, *args), outputs[1], "default thread count")
        return outputs[1]

    def test_grid_csv_and_jsonl_same_on_every_thread_count(self):
        grid = ["--grid", "speed=2:8:4,phi=-3:3:5,b=-0.01:0.01:3"]
        out = self.check_threads(RACK, *grid)
        self.assertEqual(len(out.decode().splitlines()), 1 + 60)
        out = self.check_threads(RACK, *grid, "--format", "jsonl")
        rows = jsonl(out)
        self.assertEqual([r["shot"] for r in rows], list(range(60)))
        # The shots differ from each other (a batch of identical rows would pass trivially).
        self.assertGreater(len({json.dumps(r["final"]) for r in rows}), 50)

    def test_random_same_on_every_thread_count(self):
        out = self.check_threads(RACK, "--random", "150", "--seed", "7", "--ranges",
                                 "speed=0.5:8,phi=-10:10,theta=0:20,a=-0.01:0.01,b=-0.01:0.01")
        self.assertEqual(len(out.decode().splitlines()), 151)

    def test_output_file_equals_standard_output(self):
        args = [RACK, "--grid", "speed=1:6:6", "--threads", "2"]
        out = batch_ok(self, *args)
        path = work("grid_out.csv")
        if os.path.exists(path):
            os.remove(path)
        p = batch(*args, "-o", path)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(p.stdout, b"")
        with open(path, "rb") as f:
            self.assertEqual(f.read(), out)
        # stderr is not a terminal here: no progress line.
        self.assertEqual(p.stderr, b"")


class EqualsPoolSim(unittest.TestCase):
    """Each row is what pool-sim gives for the layout with that one strike."""

    def compare(self, layout, rows, csv_rows=None):
        with open(layout) as f:
            doc = json.load(f)
        for k, row in enumerate(rows):
            scenario = dict(doc)
            scenario["strike"] = {key: row[key] for key in ("ball", "speed", "phi", "theta", "a", "b")}
            path = write("single.json", json.dumps(scenario))
            p = run([ARGS.pool_sim, path])
            if row["stop_reason"] == "error":
                self.assertEqual(p.returncode, 2, "row %d: %s" % (k, row))
                self.assertEqual(p.stderr.decode().strip(), "pool-sim: " + row["error"])
                continue
            self.assertEqual(p.returncode, 0, p.stderr)
            result = json.loads(p.stdout)
            stats = result["stats"]
            self.assertEqual(row["events"], stats["events"])
            self.assertEqual(row["stop_reason"], stats["stop_reason"])
            self.assertEqual(row["end_time"], stats["end_time"])
            self.assertEqual(row["pocketed"], stats["pocketed"])
            self.assertEqual(row["off_table"], stats["off_table"])
            self.assertEqual(row["first_hit"], first_hit(result, row["ball"]))
            self.assertEqual(len(row["final"]), len(result["final"]))
            for mine, theirs in zip(row["final"], result["final"]):
                self.assertEqual(mine["id"], theirs["id"])
                self.assertEqual(mine["pos"], theirs["pos"], "row %d ball %d" % (k, mine["id"]))
                self.assertEqual(mine["state"], theirs["state"])
            if csv_rows is not None:
                c = csv_rows[k]
                self.assertEqual(int(c["events"]), stats["events"])
                self.assertEqual(c["stop_reason"], stats["stop_reason"])
                self.assertEqual(c["pocketed"], " ".join(str(i) for i in stats["pocketed"]))
                self.assertEqual(c["first_hit"], "" if row["first_hit"] is None else str(row["first_hit"]))
                for theirs in result["final"]:
                    prefix = "ball_%d_" % theirs["id"]
                    self.assertEqual([float(c[prefix + a]) for a in "xyz"], theirs["pos"])
                    self.assertEqual(c[prefix + "state"], theirs["state"])

    def test_random_break_shots(self):
        args = [RACK, "--random", "24", "--seed", "3", "--threads", "2", "--ranges",
                "speed=1:8,phi=-4:4,theta=0:10,a=-0.012:0.012,b=-0.012:0.012"]
        rows = jsonl(batch_ok(self, *args, "--format", "jsonl"))
        csv_rows = list(csv.DictReader(io.StringIO(batch_ok(self, *args).decode())))
        self.assertEqual(len(rows), 24)
        self.assertTrue(any(r["pocketed"] for r in rows), "no shot pocketed a ball")
        self.compare(RACK, rows, csv_rows)

    def test_shots_cut_at_max_time(self):
        rows = jsonl(batch_ok(self, RACK_CUT, "--grid", "speed=3:7:3", "--format", "jsonl"))
        self.assertEqual({r["stop_reason"] for r in rows}, {"max_time"})
        self.assertTrue(any(b["state"] != "stationary" for r in rows for b in r["final"]))
        self.compare(RACK_CUT, rows)

    def test_airborne_jumps(self):
        rows = jsonl(batch_ok(self, JUMP, "--grid", "speed=3:6:4,theta=30:50:3", "--format", "jsonl"))
        self.assertEqual(len(rows), 12)
        self.compare(JUMP, rows)

    def test_base_strike_from_the_layout(self):
        # Parameters a strike does not give come from the layout's strike, with its angles as
        # written (58.64336754504867 deg does not survive a trip through radians and back).
        with open(RACK) as f:
            doc = json.load(f)
        doc["strike"] = {"ball": 0, "speed": 5, "phi": 58.64336754504867, "theta": 15.949013304472443,
                         "b": -0.004}
        layout = write("base_strike.json", json.dumps(doc))
        rows = jsonl(batch_ok(self, layout, "--grid", "speed=5,a=-0.01:0.01:3", "--format", "jsonl"))
        self.assertEqual([(r["phi"], r["theta"], r["b"], r["a"]) for r in rows],
                         [(58.64336754504867, 15.949013304472443, -0.004, a) for a in (-0.01, 0, 0.01)])
        self.compare(layout, rows)
        # The middle row is the layout's own strike: pool-sim on the layout file itself.
        result = json.loads(run([ARGS.pool_sim, layout]).stdout)
        self.assertEqual([b["pos"] for b in rows[1]["final"]], [b["pos"] for b in result["final"]])

    def test_refused_strikes_carry_the_library_message(self):
        strikes = write("refused.csv", "ball,speed,a,b,theta\n"
                        "0,3,0,0,0\n"        # fine
                        "0,3,0.03,0,0\n"     # a^2 + b^2 >= R^2
                        "0,200,0,0,0\n"      # above POOL_MAX_SPEED
                        "42,3,0,0,0\n"       # no such ball
                        "0,-1,0,0,0\n"       # speed <= 0
                        "0,3,0,0,90\n"       # theta out of range
                        "0,4,0,0,0\n")       # fine again: the run goes on
        rows = jsonl(batch_ok(self, RACK, "--strikes", strikes, "--format", "jsonl"))
        self.assertEqual([r["stop_reason"] == "error" for r in rows],
                         [False, True, True, True, True, True, False])
        self.assertIn("strike.a", rows[1]["error"])
        self.assertIn("strike.ball: no ball has id 42", rows[3]["error"])
        self.assertIn("strike.theta", rows[5]["error"])
        self.compare(RACK, rows)  # each message is pool-sim's for the same strike
        out = batch_ok(self, RACK, "--strikes", strikes).decode()
        c = list(csv.DictReader(io.StringIO(out)))
        self.assertEqual(c[1]["stop_reason"], "error")
        self.assertEqual(c[1]["error"], rows[1]["error"])
        self.assertEqual(c[1]["ball_0_x"], "")
        self.assertEqual(c[0]["error"], "")


class Modes(unittest.TestCase):
    def test_grid_count_values_and_order(self):
        out = batch_ok(self, RACK, "--grid", "speed=1:6:11,phi=0:350:36", "--threads", "2").decode()
        rows = list(csv.DictReader(io.StringIO(out)))
        self.assertEqual(len(rows), 11 * 36)
        self.assertEqual([int(r["shot"]) for r in rows], list(range(396)))
        # The first parameter varies slowest; values are evenly spaced, ends included, exactly.
        speeds = [1 + 0.5 * k for k in range(11)]
        phis = [10.0 * k for k in range(36)]
        expected = [(s, p) for s in speeds for p in phis]
        self.assertEqual([(float(r["speed"]), float(r["phi"])) for r in rows], expected)
        # The other parameters come from the layout's strike (pool-rack: straight, no spin).
        self.assertEqual({(r["ball"], r["theta"], r["a"], r["b"]) for r in rows}, {("0", "0", "0", "0")})

    def test_grid_single_values_and_ball(self):
        rows = jsonl(batch_ok(self, NO_STRIKE, "--grid", "speed=2,phi=0:180:3", "--ball", "5",
                              "--format", "jsonl"))
        self.assertEqual([(r["ball"], r["speed"], r["phi"]) for r in rows],
                         [(5, 2, 0), (5, 2, 90), (5, 2, 180)])
        rows = jsonl(batch_ok(self, NO_STRIKE, "--grid", "speed=2", "--format", "jsonl"))
        self.assertEqual(rows[0]["ball"], 3, "default ball: the layout's first")
        self.assertEqual(rows[0]["first_hit"], 5)

    def test_random_count_range_and_seed(self):
        ranges = ["--ranges", "speed=0.5:6,phi=0:360,b=-0.01:0.01"]
        a = batch_ok(self, RACK, "--random", "300", "--seed", "11", *ranges)
        rows = list(csv.DictReader(io.StringIO(a.decode())))
        self.assertEqual(len(rows), 300)
        for r in rows:
            self.assertTrue(0.5 <= float(r["speed"]) < 6)
            self.assertTrue(0 <= float(r["phi"]) < 360)
            self.assertTrue(-0.01 <= float(r["b"]) < 0.01)
            self.assertEqual((r["theta"], r["a"]), ("0", "0"))
        self.assertGreater(len({r["speed"] for r in rows}), 290)
        # Reproducible from the seed, on any thread count; another seed gives other shots.
        self.assertEqual(batch_ok(self, RACK, "--random", "300", "--seed", "11", *ranges,
                                  "--threads", "1"), a)
        other = batch_ok(self, RACK, "--random", "300", "--seed", "12", *ranges)
        self.assertNotEqual(other, a)
        # Shot i depends on the seed and i only: a shorter run is a prefix.
        short = batch_ok(self, RACK, "--random", "40", "--seed", "11", *ranges)
        self.assertEqual(short.decode().splitlines(), a.decode().splitlines()[:41])
        # The default seed is 1.
        self.assertEqual(batch_ok(self, RACK, "--random", "5", *ranges),
                         batch_ok(self, RACK, "--random", "5", "--seed", "1", *ranges))

    def test_strike_files_csv_and_json_agree(self):
        c = write("list.csv", "# a comment, then a blank line\n\n"
                  "speed, phi ,b,ball\r\n"
                  "3,2,,0\r\n"
                  "5,-1.5,-0.01,\r\n"
                  "2,0,0.005,7\n")
        j = write("list.json", json.dumps([{"speed": 3, "phi": 2, "ball": 0},
                                           {"speed": 5, "phi": -1.5, "b": -0.01},
                                           {"ball": 7, "speed": 2, "phi": 0, "b": 0.005}]))
        out_c = batch_ok(self, RACK, "--strikes", c)
        self.assertEqual(batch_ok(self, RACK, "--strikes", j), out_c)
        rows = list(csv.DictReader(io.StringIO(out_c.decode())))
        self.assertEqual([(r["ball"], r["speed"], r["phi"], r["b"]) for r in rows],
                         [("0", "3", "2", "0"), ("0", "5", "-1.5", "-0.01"), ("7", "2", "0", "0.005")])
        # The header names one column group per ball, in the layout's order.
        header = out_c.decode().splitlines()[0].split(",")
        self.assertEqual(header[:14], ["shot", "ball", "speed", "phi", "theta", "a", "b", "stop_reason",
                                       "events", "end_time", "first_hit", "pocketed", "off_table",
                                       "error"])
        self.assertEqual(header[14:18], ["ball_0_x", "ball_0_y", "ball_0_z", "ball_0_state"])
        self.assertEqual(len(header), 14 + 4 * 16)

    def test_progress_only_on_a_terminal(self):
        # A run of well over a second with standard error on a pseudo-terminal shows the progress
        # line there (and standard output stays the same as without it).
        args = [ARGS.pool_batch, RACK, "--random", "3000", "--ranges", "speed=1:8,phi=-3:3",
                "--threads", "2", "--format", "jsonl", "-o", work("progress.jsonl")]
        master, slave = pty.openpty()
        start = time.monotonic()
        proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=slave)
        os.close(slave)
        seen = b""
        while True:
            ready, _, _ = select.select([master], [], [], 1.0)
            if ready:
                try:
                    chunk = os.read(master, 4096)
                except OSError:
                    break
                if not chunk:
                    break
                seen += chunk
            elif proc.poll() is not None:
                break
            if time.monotonic() - start > 300:
                proc.kill()
                break
        proc.wait(timeout=60)
        os.close(master)
        elapsed = time.monotonic() - start
        self.assertEqual(proc.returncode, 0, seen)
        if elapsed < 1.5:
            self.skipTest("the run took %.2f s, too short for the progress line" % elapsed)
        self.assertIn(b"shots", seen)
        self.assertIn(b"3000 of 3000 shots (100%)", seen)


class BadInput(unittest.TestCase):
    def test_bad_inputs_exit_2_naming_the_field(self):
        files = {
            "bad_cell.csv": "ball,speed,phi\n0,3,0\n0,abc,1\n",
            "bad_column.csv": "ball,sped\n0,3\n",
            "dup_column.csv": "speed,phi,speed\n1,2,3\n",
            "cells.csv": "speed,phi\n1,2,3\n",
            "ball_id.csv": "ball,speed\n1.5,2\n",
            "huge.csv": "speed,a\n1,1e300\n",
            "nan.csv": "speed\nnan\n",
            "header_only.csv": "speed,phi\n",
            "empty.csv": "",
            "bad.json": '[{"speed": 1,}]',
            "type.json": '[{"speed": "fast"}]',
            "field.json": '[{"speed": 1, "spin": 2}]',
            "ball.json": '[{"speed": 1, "ball": 0.5}]',
            "object.json": '{"speed": 1}',
            "element.json": '[3]',
            "no_speed.csv": "phi\n10\n",
            "bad_layout.json": '{"format": "libpool-scenario/1", "balls": [{"id": 0, "pos": [0.5, 0.5]},'
                               ' {"id": 1, "pos": [0.51, 0.5]}]}',
        }
        paths = {name: write(name, text) for name, text in files.items()}
        cases = [
            ([RACK, "--strikes", paths["bad_cell.csv"]], "line 3 (strike 1), column speed: 'abc' is not a number"),
            ([RACK, "--strikes", paths["bad_column.csv"]], "line 1, column 2: 'sped' is not a column name"),
            ([RACK, "--strikes", paths["dup_column.csv"]], "line 1, column 3: speed is given twice"),
            ([RACK, "--strikes", paths["cells.csv"]], "line 2 (strike 0): 3 cells, the header has 2"),
            ([RACK, "--strikes", paths["ball_id.csv"]], "column ball: '1.5' is not a ball id"),
            ([RACK, "--strikes", paths["huge.csv"]], "column a: '1e300' is too large"),
            ([RACK, "--strikes", paths["nan.csv"]], "column speed: 'nan' is not a number"),
            ([RACK, "--strikes", paths["header_only.csv"]], "header_only.csv: no strikes"),
            ([RACK, "--strikes", paths["empty.csv"]], "empty.csv: no header line"),
            ([RACK, "--strikes", paths["bad.json"]], "bad.json: malformed JSON at line 1"),
            ([RACK, "--strikes", paths["type.json"]], "[0].speed: must be a number"),
            ([RACK, "--strikes", paths["field.json"]], "[0].spin: unknown field"),
            ([RACK, "--strikes", paths["ball.json"]], "[0].ball: must be a ball id"),
            ([RACK, "--strikes", paths["object.json"]], "must be a JSON array of strikes"),
            ([RACK, "--strikes", paths["element.json"]], "[0]: must be an object"),
            ([NO_STRIKE, "--strikes", paths["no_speed.csv"]], "no speed column"),
            ([NO_STRIKE, "--grid", "phi=0:10:2"], "--grid: no speed"),
            ([RACK, "--strikes", work("missing.csv")], "missing.csv: No such file or directory"),
            ([work("missing.json"), "--grid", "speed=1"], "missing.json: No such file or directory"),
            ([paths["bad_layout.json"], "--grid", "speed=1"], "balls[1].pos: overlaps ball 0"),
            ([RACK, "--strikes", "/dev/zero"], "/dev/zero: input is larger than the limit"),
            ([RACK, "--grid", "speed=1:x:3"], "--grid: speed: 'x' is not a number"),
            ([RACK, "--grid", "spin=1:2:3"], "--grid: 'spin': unknown parameter"),
            ([RACK, "--grid", "speed=1:2:0"], "--grid: speed: count '0'"),
            ([RACK, "--grid", "speed=1:2:2.5"], "--grid: speed: count '2.5'"),
            ([RACK, "--grid", "speed=1:2:3,speed=4"], "--grid: speed is given twice"),
            ([RACK, "--grid", "speed=1:2"], "--grid: speed: 'speed=1:2' is not LO:HI:COUNT"),
            ([RACK, "--grid", "speed"], "--grid: 'speed' is not NAME=LO:HI:COUNT"),
            ([RACK, "--grid", "speed=1:2:10000,phi=0:1:10000,a=0:0.01:10"], "--grid: more than"),
            ([RACK, "--grid", ""], "--grid: empty"),
            ([RACK, "--random", "0", "--ranges", "speed=1:2"], "--random: '0'"),
            ([RACK, "--random", "10"], "--random needs --ranges"),
            ([RACK, "--random", "10", "--ranges", "speed=1:2:3"], "--ranges: speed:"),
            ([RACK, "--random", "10", "--ranges", "speed=1:2", "--seed", "-4"], "--seed: '-4'"),
            ([RACK, "--grid", "speed=1", "--seed", "4"], "--seed goes with --random"),
            ([RACK, "--grid", "speed=1", "--threads", "0"], "--threads: '0'"),
            ([RACK, "--grid", "speed=1", "--threads", "x"], "--threads: 'x'"),
            ([RACK, "--grid", "speed=1", "--format", "xml"], "--format: 'xml'"),
            ([RACK, "--grid", "speed=1", "--ball", "99"], "--ball: no ball of the layout has id 99"),
            ([RACK, "--grid", "speed=1", "--strikes", paths["bad_cell.csv"]], "give one of --strikes, --grid"),
            ([RACK], "no strikes: give --strikes"),
            (["--grid", "speed=1"], "missing LAYOUT.json"),
            ([RACK, "--grid", "speed=1", "--bogus"], "unknown option '--bogus'"),
            ([RACK, "--grid"], "option --grid needs a value"),
            ([RACK, "--grid", "speed=1", "--max-input", "100"], "input is larger than the limit of 100 bytes"),
        ]
        out = work("never_written.csv")
        for args, expected in cases:
            with self.subTest(args=args):
                if os.path.exists(out):
                    os.remove(out)
                p = batch("-o", out, *args)
                err = p.stderr.decode(errors="replace")
                self.assertEqual(p.returncode, 2, err)
                self.assertIn(expected, err)
                self.assertEqual(p.stdout, b"")
                self.assertFalse(os.path.exists(out), "bad input left an output file")
                self.assertLess(len(err.splitlines()), 3, err)

    def test_help(self):
        p = batch("--help")
        self.assertEqual(p.returncode, 0)
        for word in (b"--strikes", b"--grid", b"--random", b"--ranges", b"--seed", b"--threads",
                     b"--format", b"Exit status"):
            self.assertIn(word, p.stdout)


def main():
    global ARGS
    parser = argparse.ArgumentParser()
    for option in ("--pool-batch", "--pool-sim", "--pool-rack", "--source", "--work"):
        parser.add_argument(option, required=True)
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
