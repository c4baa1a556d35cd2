#!/usr/bin/env python3
"""The pool-view page of a break: its size and its load time in headless Chromium (navigation
start to the end of the load event, the page drawn at t = 0), median and minimum of the runs.

    .venv/bin/python bench/bench_view.py [--runs N] [--bin-dir build/release/tools]
"""
import argparse
import os
import platform
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "view"))
from browser import Browser  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--runs", type=int, default=11)
    p.add_argument("--bin-dir", default=os.path.join(ROOT, "build", "release", "tools"))
    args = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        rack, result, page = (os.path.join(tmp, n) for n in ("rack.json", "break.json", "break.html"))
        subprocess.run([os.path.join(args.bin_dir, "pool-rack"), "8ball", "--gap", "0", "--speed",
                        "8", "-o", rack], check=True)
        subprocess.run([os.path.join(args.bin_dir, "pool-sim"), rack, "-o", result, "--view", page],
                       check=True)
        loads, draws = [], []
        with Browser() as b:
            version = b.call("Browser.getVersion")["product"]
            for _ in range(args.runs):
                b.open("file://" + page)
                nav = b.evaluate("(() => { const n = performance.getEntriesByType('navigation')[0];"
                                 " return [n.loadEventEnd, n.domContentLoadedEventEnd]; })()")
                loads.append(nav[0])
                draws.append(nav[1])
            events = b.evaluate("poolView.view.shot.events.length")
        size, data = os.path.getsize(page), os.path.getsize(result)
    model = platform.processor() or "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            model = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    print(f"machine: {model}, {os.cpu_count()} CPUs online, {version} headless")
    print(f"break page: {size} bytes ({data} of them the result, {events} events)")
    print(f"load (navigation to load event end): median {statistics.median(loads):.1f} ms, "
          f"min {min(loads):.1f} ms; script done (DOMContentLoaded end): median "
          f"{statistics.median(draws):.1f} ms, min {min(draws):.1f} ms ({args.runs} loads)")


if __name__ == "__main__":
    main()
