#!/usr/bin/env python3
"""Benchmark of libpool.batch.run against pool-batch: shots per second on post-break random shots.

Usage: PYTHONPATH=python LIBPOOL_PATH=build/release/libpool/libpool.so \
       .venv/bin/python bench/batch/bench_pybatch.py [--bin DIR] [--runs R] [--shots N]
                                                    [--threads T] [--work DIR] [--ranges SPEC]

The post-break table and the strikes of bench/batch/bench_batch.py (pool-batch --random N --seed 1
with its ranges). pool-batch is timed as there (wall time of the whole process, CSV to /dev/null);
libpool.batch.run on the same strikes (read from pool-batch's rows) is timed from the call to its
return (layout parse, simulation, the NumPy arrays), on 1 and T workers. Median and best of R
runs; prints figures and the ratio pool-batch / libpool.batch, asserts nothing.
"""
import argparse
import csv
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import bench_batch  # noqa: E402  (post_break_layout, time_run, machine, load)

RANGES = "speed=0.5:6,phi=0:360,theta=0:10,a=-0.012:0.012,b=-0.012:0.012"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--bin", default=os.path.join(HERE, "..", "..", "build", "release", "tools"))
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--shots", type=int, default=40000)
    parser.add_argument("--threads", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--work", default="/tmp")
    parser.add_argument("--ranges", default=RANGES,
                        help="pool-batch --ranges of the strikes (default: %(default)s); slow "
                             "strikes (speed=0.1:0.3) leave mostly the cost around each shot")
    a = parser.parse_args()
    import libpool.batch
    batch = os.path.join(a.bin, "pool-batch")
    _, post, nballs = bench_batch.post_break_layout(a.bin, a.work)
    rows_path = os.path.join(a.work, "bench_pybatch.csv")
    base = [batch, post, "--random", str(a.shots), "--seed", "1", "--ranges", a.ranges,
            "--no-progress"]
    subprocess.run(base + ["-o", rows_path], check=True)
    with open(rows_path) as f:
        strikes = [(int(r["ball"]), float(r["speed"]), float(r["phi"]), float(r["theta"]),
                    float(r["a"]), float(r["b"])) for r in csv.DictReader(f)]
    print("machine: %s; load average before: %s" % (bench_batch.machine(), bench_batch.load()))
    print("post-break table (%d balls), %d random shots (%s), %d runs each; library %s"
          % (nballs, a.shots, a.ranges, a.runs, libpool.library_path()))
    for t in sorted({1, a.threads}):
        c_times, py_times = [], []
        for _ in range(a.runs):  # alternated, so a change of load hits both alike
            c_times.append(bench_batch.time_run(base + ["--threads", str(t)]))
            start = time.perf_counter()
            libpool.batch.run(post, strikes, workers=t)
            py_times.append(time.perf_counter() - start)
        for name, times in (("pool-batch", c_times), ("libpool.batch", py_times)):
            med, best = statistics.median(times), min(times)
            print("%-14s threads %2d  median %8.0f shots/s  max %8.0f shots/s  (median %.3f s, "
                  "min %.3f s)" % (name, t, a.shots / med, a.shots / best, med, best))
        print("%-14s threads %2d  pool-batch / libpool.batch: %.2fx (medians), %.2fx (best)"
              % ("ratio", t, statistics.median(py_times) / statistics.median(c_times),
                 min(py_times) / min(c_times)))
    print("load average after: %s" % bench_batch.load())


if __name__ == "__main__":
    main()
