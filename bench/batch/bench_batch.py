#!/usr/bin/env python3
"""Benchmark of pool-batch: shots per second on 1 thread and on every core, parallel efficiency.

Usage: python3 bench/batch/bench_batch.py [--bin DIR] [--runs R] [--shots N] [--breaks M]
                                         [--threads T] [--work DIR]

Two scenes, both simulated by pool-batch --random (fixed seed) with the output to /dev/null:
  post-break  the table a default 8-ball break leaves (pool-rack 8ball, pool-sim), random strikes
              of the cue ball: speed 0.5-6 m/s, any direction, elevation 0-10 deg, tip offsets
              within +-12 mm
  break       the 15-ball rack (gap 0.1 mm), break strikes: 6-9 m/s, aim +-1 deg, offsets +-5 mm
For each scene and thread count it prints the median and minimum over R runs of the wall time
(whole process: parse, simulate, format, write) as shots per second, the parallel efficiency
(rate on T threads / (T x rate on 1 thread), from the medians and from the best runs), the
machine and the load average before and after. As a control it also times T single-threaded
pool-batch processes run at once: on a shared machine that, not T times one process, is what T
threads can reach. Prints figures, asserts nothing.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time


def machine():
    model = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return "%s, %d cores online" % (model, os.cpu_count() or 0)


def load():
    try:
        return " ".join(open("/proc/loadavg").read().split()[:3])
    except OSError:
        return "unknown"


def check(cmd):
    p = subprocess.run(cmd, capture_output=True)
    if p.returncode != 0:
        sys.exit("bench_batch: %s failed: %s" % (cmd[0], p.stderr.decode(errors="replace")))
    return p.stdout


def post_break_layout(bins, work):
    rack = os.path.join(work, "bench_rack.json")
    check([os.path.join(bins, "pool-rack"), "8ball", "-o", rack])
    result = json.loads(check([os.path.join(bins, "pool-sim"), rack]))
    balls = [{"id": b["id"], "pos": b["pos"][:2]} for b in result["final"]
             if b["state"] == "stationary"]
    if not any(b["id"] == 0 for b in balls):
        sys.exit("bench_batch: the break pocketed the cue ball")
    path = os.path.join(work, "bench_post_break.json")
    with open(path, "w") as f:
        json.dump({"format": "libpool-scenario/1", "balls": balls,
                   "strike": {"ball": 0, "speed": 2}}, f)
    return rack, path, len(balls)


def time_run(cmd):
    start = time.perf_counter()
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    elapsed = time.perf_counter() - start
    if p.returncode != 0:
        sys.exit("bench_batch: %s" % p.stderr.decode(errors="replace"))
    return elapsed


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser()
    parser.add_argument("--bin", default=os.path.join(here, "..", "..", "build", "release", "tools"))
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--shots", type=int, default=40000, help="post-break shots per run")
    parser.add_argument("--breaks", type=int, default=4000, help="breaks per run")
    parser.add_argument("--threads", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--work", default="/tmp")
    a = parser.parse_args()
    batch = os.path.join(a.bin, "pool-batch")
    rack, post, nballs = post_break_layout(a.bin, a.work)
    scenes = [
        ("post-break (%d balls)" % nballs, post, a.shots,
         "speed=0.5:6,phi=0:360,theta=0:10,a=-0.012:0.012,b=-0.012:0.012"),
        ("break (16 balls)", rack, a.breaks, "speed=6:9,phi=-1:1,a=-0.005:0.005,b=-0.005:0.005"),
    ]
    print("machine: %s; load average before: %s" % (machine(), load()))
    print("pool-batch --random N --seed 1, output csv to /dev/null, %d runs each, wall time of the "
          "whole process" % a.runs)
    counts = sorted({1, a.threads})
    for name, layout, n, ranges in scenes:
        rates = {}
        for t in counts:
            cmd = [batch, layout, "--random", str(n), "--seed", "1", "--ranges", ranges,
                   "--threads", str(t), "--no-progress"]
            times = []
            for _ in range(a.runs):  # alternate would be fairer under load; runs are short
                times.append(time_run(cmd))
            med, best = statistics.median(times), min(times)
            rates[t] = (n / med, n / best)
            print("%-22s threads %2d  shots %6d  median %8.0f shots/s  max %8.0f shots/s  "
                  "(median %.3f s, min %.3f s)" % (name, t, n, n / med, n / best, med, best))
        for t in counts:
            if t == 1:
                continue
            eff_med = rates[t][0] / (t * rates[1][0])
            eff_best = rates[t][1] / (t * rates[1][1])
            print("%-22s parallel efficiency on %d threads: %.0f %% (medians), %.0f %% (best runs)"
                  % (name, t, 100 * eff_med, 100 * eff_best))
            # Control: what the machine gives t independent single-threaded processes at once (on
            # a shared machine this, not t times one process, is the most t threads can reach).
            cmd = [batch, layout, "--random", str(n), "--seed", "1", "--ranges", ranges,
                   "--threads", "1", "--no-progress"]
            times = []
            for _ in range(a.runs):
                start = time.perf_counter()
                procs = [subprocess.Popen(cmd, stdout=subprocess.DEVNULL) for _ in range(t)]
                for p in procs:
                    p.wait()
                times.append(time.perf_counter() - start)
            med, best = statistics.median(times), min(times)
            print("%-22s control: %d single-thread processes at once: median %8.0f shots/s, max "
                  "%8.0f shots/s in all; threads reach %.0f %% (medians), %.0f %% (best) of it"
                  % (name, t, t * n / med, t * n / best, 100 * rates[t][0] / (t * n / med),
                     100 * rates[t][1] / (t * n / best)))
    print("load average after: %s" % load())


if __name__ == "__main__":
    main()
