#!/usr/bin/env python3
"""The examples of the README and docs/commands.md print what those pages say they print.

- The README's tour runs a one-line break in Python (`PYTHONPATH=python .venv/bin/python -c
  '...'`) and says what it prints under the default laws and under `Sim(models="thesis")`: the
  README's own line is run as written and with `libpool.Sim()` made
  `libpool.Sim(models="thesis")`.
- docs/commands.md runs `pool-rack 8ball` and `pool-sim --summary` on it and shows the summary:
  its events, simulated time, stop reason, events by type and pocketed balls (the CPU time
  varies and is not compared).
- docs/python.md's first example ("A break, pocketed balls") and the output it says it prints.
- The README runs `pool-sensitivity` on its draw shot with spin-blind collisions and says how far
  the means move, under the default laws and with `"models": "thesis"` in the scenario: the
  README's own command is run both ways and the distances compared at the digits the README
  gives.

A change of the laws or of the table (as the merge of real pockets was) changes these outputs;
the pages a newcomer reads first cannot then go stale unnoticed.

Usage: test_doc_examples.py --pool-rack PATH --pool-sim PATH [--pool-sensitivity PATH] --work DIR
[unittest args]
(LIBPOOL_PATH names the shared library; PYTHONPATH holds python/).
"""

import argparse
import json
import os
import re
import subprocess
import sys
import unittest

SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
ARGS = None


def page(name):
    with open(os.path.join(SOURCE, name), encoding="utf-8") as f:
        return f.read()


def python_example(text):
    """The code of the README's Python one-liner (between the single quotes of `-c '...'`)."""
    m = re.search(r"^PYTHONPATH=python \.venv/bin/python -c '([^']*)'$", text, re.M)
    if m is None:
        raise AssertionError("README.md: no line `PYTHONPATH=python .venv/bin/python -c '...'`")
    return m.group(1)


def claimed_python_outputs(text):
    """What the README says the Python example prints: (default laws, thesis laws)."""
    m = re.search(
        r"prints the stop reason and the pocketed balls \(`([^`]*)`;\s+`Sim\(models=\"thesis\"\)`,"
        r"\s+the 2012\s+laws, gives `([^`]*)`\)",
        text,
    )
    if m is None:
        raise AssertionError("README.md: the sentence saying what the Python example prints is not found")
    return m.group(1), m.group(2)


def claimed_summary(text):
    """docs/commands.md's example of `pool-sim --summary`: its lines, the CPU time cut off."""
    m = re.search(r"`--summary` prints on standard error, for example:\n\n```\n(.*?)\n```", text, re.S)
    if m is None:
        raise AssertionError("docs/commands.md: the example of pool-sim --summary is not found")
    return without_cpu(m.group(1))


def without_cpu(summary):
    return [re.sub(r", cpu [0-9.]+ ms$", "", line.rstrip()) for line in summary.strip().splitlines()]


def sensitivity_example(text):
    """The README's pool-sensitivity command: its arguments after the program, `-o` left out."""
    m = re.search(r"^build/release/tools/pool-sensitivity (.*?)  # writes", text, re.M | re.S)
    if m is None:
        raise AssertionError("README.md: the pool-sensitivity example is not found")
    args = m.group(1).replace("\\\n", " ").split()
    i = args.index("-o")
    return args[:i] + args[i + 2 :]


def claimed_spin_blind(text):
    """The README's distances of the means: (cue, object) under the defaults and under thesis."""
    m = re.search(
        r"spin-blind collisions move the mean final position of the cue ball by\s+([0-9.]+) m and"
        r"\s+of the object ball by\s+([0-9.]+) m\s+\(with\s+`\"models\": \"thesis\"`\s+in\s+the\s+scenario,"
        r"\s+([0-9.]+) m\s+and\s+([0-9.]+) m\)",
        text,
    )
    if m is None:
        raise AssertionError("README.md: the sentence giving the spin-blind distances is not found")
    return (m.group(1), m.group(2)), (m.group(3), m.group(4))


def at_digits_of(value, claimed):
    """value rounded to as many decimals as the claimed figure has, as text."""
    decimals = len(claimed.split(".")[1]) if "." in claimed else 0
    return f"{value:.{decimals}f}"


def example_and_output(text, heading):
    """The first ```python block under `heading` and the ``` block after the word "prints"."""
    start = text.find(heading)
    if start < 0:
        raise AssertionError(f"heading {heading!r} not found")
    m = re.compile(r"```python\n(.*?)\n```\s+prints\s+```\n(.*?)\n```", re.S).search(text, start)
    if m is None:
        raise AssertionError(f"under {heading!r}: no ```python block followed by 'prints' and its output")
    return m.group(1), m.group(2)


def run(argv):
    out = subprocess.run(argv, capture_output=True, text=True, timeout=120)
    if out.returncode != 0:
        raise AssertionError(f"{argv[0]} failed ({out.returncode}): {out.stderr.strip()}")
    return out


class ReadmePython(unittest.TestCase):
    def test_default_laws(self):
        text = page("README.md")
        default, _ = claimed_python_outputs(text)
        self.assertEqual(run([sys.executable, "-c", python_example(text)]).stdout.strip(), default)

    def test_thesis_laws(self):
        text = page("README.md")
        _, thesis = claimed_python_outputs(text)
        code = python_example(text)
        self.assertIn("libpool.Sim()", code)
        code = code.replace("libpool.Sim()", 'libpool.Sim(models="thesis")')
        self.assertEqual(run([sys.executable, "-c", code]).stdout.strip(), thesis)


class PythonManual(unittest.TestCase):
    def test_break_pocketed_balls(self):
        code, claimed = example_and_output(page("docs/python.md"), "## A break, pocketed balls")
        self.assertEqual(run([sys.executable, "-c", code]).stdout.rstrip("\n"), claimed)


class CommandsBreak(unittest.TestCase):
    def test_summary(self):
        claimed = claimed_summary(page("docs/commands.md"))
        os.makedirs(ARGS.work, exist_ok=True)
        scenario = os.path.join(ARGS.work, "break_scenario.json")
        result = os.path.join(ARGS.work, "break.json")
        run([ARGS.pool_rack, "8ball", "-o", scenario])
        out = run([ARGS.pool_sim, scenario, "--sample", "0.01", "--summary", "-o", result])
        self.assertEqual(without_cpu(out.stderr), claimed)


class ReadmeSensitivity(unittest.TestCase):
    def distances(self, scenario, args):
        out = run([ARGS.pool_sensitivity, scenario] + args).stdout
        found = re.findall(r"^distance between the means \(default to spin-blind\), ball ([01]): ([0-9.eE+-]+) m$", out, re.M)
        self.assertEqual([b for b, _ in found], ["0", "1"], out)
        return [float(d) for _, d in found]

    def test_spin_blind(self):
        if not ARGS.pool_sensitivity:
            self.skipTest("no pool-sensitivity")
        text = page("README.md")
        args = sensitivity_example(text)
        scenario = os.path.join(SOURCE, args[0])
        (cue, obj), (cue_t, obj_t) = claimed_spin_blind(text)
        got = self.distances(scenario, args[1:])
        self.assertEqual([at_digits_of(got[0], cue), at_digits_of(got[1], obj)], [cue, obj])
        with open(scenario, encoding="utf-8") as f:
            doc = json.load(f)
        doc["models"] = "thesis"
        os.makedirs(ARGS.work, exist_ok=True)
        thesis = os.path.join(ARGS.work, "example_draw_thesis.json")
        with open(thesis, "w", encoding="utf-8") as f:
            json.dump(doc, f)
        got = self.distances(thesis, args[1:])
        self.assertEqual([at_digits_of(got[0], cue_t), at_digits_of(got[1], obj_t)], [cue_t, obj_t])


def main():
    global ARGS
    p = argparse.ArgumentParser()
    p.add_argument("--pool-rack", required=True)
    p.add_argument("--pool-sim", required=True)
    p.add_argument("--pool-sensitivity")
    p.add_argument("--work", required=True)
    ARGS, rest = p.parse_known_args()
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False, verbosity=2)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
