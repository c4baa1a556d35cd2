#!/usr/bin/env python3
"""libpool.dask.run on a LocalCluster of two worker processes: the arrays equal
libpool.batch.run's on one machine bit for bit (post-break shots with refused strikes among them,
chunks that do not divide the strikes, structured strikes completed from the base strike, no
strikes), the chunks really run in the two worker processes, and bad input raises before any
task is sent.

Usage: test_dask.py --pool-rack PROG --pool-sim PROG --work DIR [unittest args]
(LIBPOOL_PATH names the shared library; PYTHONPATH holds python/; the worker processes inherit
both.) Exits 77 (skipped) with the reason when dask.distributed cannot be imported: the
project's setup script installs it into .venv, so CI runs this test.
"""

import argparse
import json
import os
import subprocess
import sys
import unittest

try:
    from dask.distributed import Client, LocalCluster
except ImportError as e:  # pragma: no cover - the setup script installs dask[distributed]
    print(f"SKIPPED: dask.distributed is not installed ({e}); run tools/setup.sh", file=sys.stderr)
    sys.exit(77)

import numpy as np

import libpool.batch as lb
import libpool.dask as ld

ARGS = None
CLUSTER = None
CLIENT = None
LAYOUT = None  # path of a post-break layout with a base strike
N_SHOTS = 700
CHUNK = 64     # 11 chunks, the last one short


def same_arrays(a, b):
    """The first field where two BatchResults differ (bit for bit, NaN rows included), or None."""
    for name in ("ball_ids", "ball", "strikes", "stop_reason", "events", "end_time", "first_hit",
                 "pos", "state", "pocketed", "off_table"):
        x, y = getattr(a, name), getattr(b, name)
        if x.dtype != y.dtype or x.shape != y.shape or x.tobytes() != y.tobytes():
            return name
    if a.error != b.error:
        return "error"
    return None


def post_break_layout(work):
    rack = os.path.join(work, "rack.json")
    subprocess.run([ARGS.pool_rack, "8ball", "-o", rack], check=True, timeout=60)
    result = json.loads(subprocess.run([ARGS.pool_sim, rack], check=True, capture_output=True,
                                       text=True, timeout=60).stdout)
    balls = [{"id": b["id"], "pos": b["pos"][:2]} for b in result["final"]
             if b["state"] == "stationary"]
    path = os.path.join(work, "post_break.json")
    with open(path, "w") as f:
        json.dump({"format": "libpool-scenario/1", "balls": balls,
                   "strike": {"ball": 0, "speed": 2, "phi": 10}}, f)
    return path


def random_strikes(n, seed):
    rng = np.random.default_rng(seed)
    rows = np.column_stack([np.zeros(n), rng.uniform(0.5, 6, n), rng.uniform(0, 360, n),
                            rng.uniform(0, 10, n), rng.uniform(-0.012, 0.012, n),
                            rng.uniform(-0.012, 0.012, n)])
    rows[::97, 4] = 0.03  # a > R: refused by the library, an error row
    return rows


def setUpModule():
    global CLUSTER, CLIENT, LAYOUT
    os.makedirs(ARGS.work, exist_ok=True)
    LAYOUT = post_break_layout(ARGS.work)
    CLUSTER = LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                           dashboard_address=None, local_directory=ARGS.work)
    CLIENT = Client(CLUSTER)


def tearDownModule():
    CLIENT.close()
    CLUSTER.close()


class EqualsLocalRun(unittest.TestCase):
    def test_random_post_break_shots_bit_for_bit(self):
        strikes = random_strikes(N_SHOTS, 5)
        local = lb.run(LAYOUT, strikes, workers=2)
        remote = ld.run(CLIENT, LAYOUT, strikes, chunk_size=CHUNK)
        self.assertIsNone(same_arrays(local, remote))
        self.assertEqual(len(remote), N_SHOTS)
        refused = int((remote.stop_reason == lb.STOP_ERROR).sum())
        self.assertEqual(refused, len(range(0, N_SHOTS, 97)))
        self.assertGreater(int(remote.pocketed.sum()), 0)  # real shots, not only errors

    def test_structured_strikes_and_the_layout_as_a_dict(self):
        with open(LAYOUT) as f:
            doc = json.load(f)
        rng = np.random.default_rng(9)
        strikes = np.zeros(150, dtype=[("speed", "f8"), ("phi", "f8")])
        strikes["speed"] = rng.uniform(1, 4, 150)
        strikes["phi"] = rng.uniform(0, 360, 150)
        local = lb.run(doc, strikes, workers=1)
        remote = ld.run(CLIENT, doc, strikes, chunk_size=7, threads=2)
        self.assertIsNone(same_arrays(local, remote))
        self.assertTrue((remote.strikes[:, 3] == 0.0).all())  # a from the base strike

    def test_chunk_sizes_do_not_matter(self):
        strikes = random_strikes(90, 11)
        results = [ld.run(CLIENT, LAYOUT, strikes, chunk_size=c) for c in (1, 13, 90, 1000)]
        for r in results[1:]:
            self.assertIsNone(same_arrays(results[0], r))

    def test_no_strikes(self):
        remote = ld.run(CLIENT, LAYOUT, np.zeros((0, 6)))
        self.assertEqual(len(remote), 0)
        self.assertEqual(remote.pos.shape[0], 0)


class RunsOnTheWorkers(unittest.TestCase):
    def test_two_worker_processes_share_the_chunks(self):
        pids = CLIENT.run(os.getpid)
        self.assertEqual(len(set(pids.values())), 2)
        self.assertNotIn(os.getpid(), pids.values())
        rows = random_strikes(400, 3)
        with open(LAYOUT) as f:
            text = f.read()
        futures = CLIENT.map(ld.run_chunk, [text] * 8, [rows[i::8] for i in range(8)], pure=False)
        CLIENT.gather(futures)
        who = CLIENT.who_has(futures)
        workers = {w for addresses in who.values() for w in addresses}
        self.assertEqual(len(workers), 2, who)


class BadInput(unittest.TestCase):
    def test_raises_before_sending_tasks(self):
        strikes = random_strikes(10, 1)
        cases = [
            (dict(chunk_size=0), "chunk_size"),
            (dict(threads=0), "threads"),
            (dict(ball=99), "ball: no ball"),
        ]
        for kwargs, text in cases:
            with self.assertRaises(ValueError) as e:
                ld.run(CLIENT, LAYOUT, strikes, **kwargs)
            self.assertIn(text, str(e.exception))
        with self.assertRaises(ValueError) as e:
            ld.run(CLIENT, LAYOUT, [[0, 1.0, 0, 0]])
        self.assertIn("rows of 6 numbers", str(e.exception))
        with self.assertRaises(ValueError) as e:
            ld.run(CLIENT, '{"format": "libpool-scenario/1", "balls": []', strikes)
        self.assertIn("malformed JSON", str(e.exception))
        with self.assertRaises(TypeError):
            ld.run(CLIENT, lb.load_layout(LAYOUT), strikes)


def main():
    global ARGS
    parser = argparse.ArgumentParser()
    parser.add_argument("--pool-rack", required=True)
    parser.add_argument("--pool-sim", required=True)
    parser.add_argument("--work", required=True)
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0], *rest], verbosity=2)


if __name__ == "__main__":
    main()
