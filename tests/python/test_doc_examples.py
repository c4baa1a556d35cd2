#!/usr/bin/env python3
"""The examples of the README and docs/commands.md print what those pages say they print.

- The README's tour runs a one-line break in Python (`PYTHONPATH=python .venv/bin/python -c
  '...'`) and says what it prints under the default laws and under `Sim(models="thesis")`: the
  README's own line is run as written and with `libpool.Sim()` made
  `libpool.Sim(models="thesis")`.
- docs/commands.md runs `pool-rack 8ball` and `pool-sim --summary` on it and shows the summary:
  its events, simulated time, stop reason, events by type and pocketed balls (the CPU time
  varies and is not compared).

A change of the laws or of the table (as the merge of real pockets was) changes these outputs;
the pages a newcomer reads first cannot then go stale unnoticed.

Usage: test_doc_examples.py --pool-rack PATH --pool-sim PATH --work DIR [unittest args]
(LIBPOOL_PATH names the shared library; PYTHONPATH holds python/).
"""

import argparse
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


class CommandsBreak(unittest.TestCase):
    def test_summary(self):
        claimed = claimed_summary(page("docs/commands.md"))
        os.makedirs(ARGS.work, exist_ok=True)
        scenario = os.path.join(ARGS.work, "break_scenario.json")
        result = os.path.join(ARGS.work, "break.json")
        run([ARGS.pool_rack, "8ball", "-o", scenario])
        out = run([ARGS.pool_sim, scenario, "--sample", "0.01", "--summary", "-o", result])
        self.assertEqual(without_cpu(out.stderr), claimed)


def main():
    global ARGS
    p = argparse.ArgumentParser()
    p.add_argument("--pool-rack", required=True)
    p.add_argument("--pool-sim", required=True)
    p.add_argument("--work", required=True)
    ARGS, rest = p.parse_known_args()
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False, verbosity=2)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
