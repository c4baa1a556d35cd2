#!/usr/bin/env python3
"""Benchmark of libpool.dask.run on a 2-worker LocalCluster against local libpool.batch.run and
pool-batch: shots per second on post-break random shots, and the cluster's overhead per chunk.

Usage: PYTHONPATH=python LIBPOOL_PATH=build/release/libpool/libpool.so \
       .venv/bin/python bench/batch/bench_dask.py [--bin DIR] [--runs R] [--shots N]
                                                  [--chunks C1,C2,...] [--work DIR]

The post-break table and strikes of bench/batch/bench_batch.py (pool-batch --random N --seed 1).
Timed, alternating so that a change of load hits all alike: pool-batch --threads 2 (the whole
process, CSV to /dev/null), libpool.batch.run(workers=2) and libpool.dask.run on a LocalCluster
of 2 worker processes with one thread each (the cluster started once, outside the timing; each
run from the call to the concatenated arrays) for each chunk size. Median and best of R runs.
Overhead per chunk = (median Dask time - median local time) / number of chunks: what a task
costs beyond its shots (scheduling, pickling strikes and arrays, the layout parse per task).
Checks that the Dask arrays equal the local ones; asserts nothing about speed.
"""
import argparse
import csv
import logging
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import bench_batch  # noqa: E402  (post_break_layout, time_run, machine, load)

RANGES = "speed=0.5:6,phi=0:360,theta=0:10,a=-0.012:0.012,b=-0.012:0.012"
WORKERS = 2


def same(a, b):
    names = ("ball", "strikes", "stop_reason", "events", "end_time", "first_hit", "pos", "state")
    return all(getattr(a, n).tobytes() == getattr(b, n).tobytes() for n in names) and a.error == b.error


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--bin", default=os.path.join(HERE, "..", "..", "build", "release", "tools"))
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--shots", type=int, default=40000)
    parser.add_argument("--chunks", default="500,2000,10000")
    parser.add_argument("--work", default="/tmp")
    a = parser.parse_args()
    import libpool.batch
    import libpool.dask
    from dask.distributed import Client, LocalCluster

    batch = os.path.join(a.bin, "pool-batch")
    _, post, nballs = bench_batch.post_break_layout(a.bin, a.work)
    rows_path = os.path.join(a.work, "bench_dask.csv")
    base = [batch, post, "--random", str(a.shots), "--seed", "1", "--ranges", RANGES,
            "--no-progress", "--threads", str(WORKERS)]
    subprocess.run(base + ["-o", rows_path], check=True)
    with open(rows_path) as f:
        strikes = [(int(r["ball"]), float(r["speed"]), float(r["phi"]), float(r["theta"]),
                    float(r["a"]), float(r["b"])) for r in csv.DictReader(f)]
    chunks = [int(c) for c in a.chunks.split(",")]
    print("machine: %s; load average before: %s" % (bench_batch.machine(), bench_batch.load()))
    print("post-break table (%d balls), %d random shots, %d runs each; library %s"
          % (nballs, a.shots, a.runs, libpool.library_path()))
    with LocalCluster(n_workers=WORKERS, processes=True, threads_per_worker=1,
                      dashboard_address=None, local_directory=a.work) as cluster, \
            Client(cluster) as client:
        local_ref = libpool.batch.run(post, strikes, workers=WORKERS)
        for c in chunks:  # warm the workers (imports, libpool loaded) and check the arrays
            assert same(local_ref, libpool.dask.run(client, post, strikes, chunk_size=c)), c
        times = {"pool-batch": [], "libpool.batch": []}
        times.update({("dask", c): [] for c in chunks})
        for _ in range(a.runs):
            times["pool-batch"].append(bench_batch.time_run(base))
            start = time.perf_counter()
            libpool.batch.run(post, strikes, workers=WORKERS)
            times["libpool.batch"].append(time.perf_counter() - start)
            for c in chunks:
                start = time.perf_counter()
                libpool.dask.run(client, post, strikes, chunk_size=c)
                times[("dask", c)].append(time.perf_counter() - start)
        # The workers' connections closing at shutdown are logged as errors: not ours to report.
        logging.getLogger("distributed").setLevel(logging.CRITICAL)
    local_med = statistics.median(times["libpool.batch"])
    for key, ts in times.items():
        med, best = statistics.median(ts), min(ts)
        name = key if isinstance(key, str) else "dask chunk %d" % key[1]
        line = "%-17s %d workers  median %8.0f shots/s  max %8.0f shots/s  (median %.3f s, min %.3f s)" % (
            name, WORKERS, a.shots / med, a.shots / best, med, best)
        if not isinstance(key, str):
            n_chunks = -(-a.shots // key[1])
            line += "  %d chunks, overhead per chunk %.1f ms, %.0f %% of local" % (
                n_chunks, 1000 * (med - local_med) / n_chunks, 100 * local_med / med)
        print(line)
    print("load average after: %s" % bench_batch.load())


if __name__ == "__main__":
    main()
