"""Helpers shared by the LCM end-to-end tests (run inside netns_run.sh)."""
import argparse
import json
import os
import queue
import select
import subprocess
import sys
import threading
import time

URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608"
STATE_NAMES = ["stationary", "spinning", "sliding", "rolling", "airborne", "linked",
               "pocketed", "off_table"]


def parse_args(extra=()):
    """Paths every test needs: the build's tools, the generated Python types, the data."""
    p = argparse.ArgumentParser()
    p.add_argument("--bin-dir", required=True, help="directory holding pool-sim, pool-shot-server")
    p.add_argument("--types-dir", required=True, help="generated Python types (pool_lcm)")
    p.add_argument("--data-dir", required=True, help="tests/lcm/data")
    p.add_argument("--subscriber", required=True, help="tools/pool_lcm_subscribe.py")
    p.add_argument("--work-dir", required=True, help="scratch directory")
    for name, kw in extra:
        p.add_argument(name, **kw)
    args = p.parse_args()
    sys.path.insert(0, args.types_dir)
    os.makedirs(args.work_dir, exist_ok=True)
    return args


failures = []


def check(condition, message):
    """Records a failed expectation (and prints it) without stopping the test."""
    if not condition:
        failures.append(message)
        print("FAIL: " + message, flush=True)
    return condition


def finish():
    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)
    print("all checks passed")
    sys.exit(0)


def pool_sim_json(bin_dir, scenario, work_dir, extra=()):
    """pool-sim's result document for a scenario file (-o FILE), parsed."""
    out = os.path.join(work_dir, os.path.basename(scenario) + ".result.json")
    subprocess.run([os.path.join(bin_dir, "pool-sim"), scenario, "-o", out, *extra], check=True,
                   timeout=60)
    with open(out) as f:
        return json.load(f)


def wait_for_line(proc, needle, timeout=10.0):
    """Reads proc.stderr until a line containing needle; returns the lines read."""
    lines = []
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        ready, _, _ = select.select([proc.stderr], [], [], 0.1)
        if ready:
            line = proc.stderr.readline()
            if not line:
                break
            lines.append(line)
            if needle in line:
                return lines
    raise RuntimeError("no '%s' from %s within %g s: %r" % (needle, proc.args, timeout, lines))


def ball_json(b):
    return {"id": b.id, "pos": list(b.pos), "vel": list(b.vel), "omega": list(b.omega),
            "state": STATE_NAMES[b.state]}


def event_json(e):
    out = {"t": e.t, "type": e.type, "balls": [b.id for b in e.balls]}
    if e.rail:
        out["rail"] = e.rail
    if e.pocket:
        out["pocket"] = e.pocket
    out["after"] = [ball_json(b) for b in e.balls]
    return out


def compare_result(got, want, label):
    """Event for event, to full double precision: types, times, ball ids, rail/pocket, states;
    then the final states and the stats both documents carry."""
    ok = check(len(got["events"]) == len(want["events"]),
               "%s: %d events, pool-sim has %d" % (label, len(got["events"]), len(want["events"])))
    if ok:
        for i, (g, w) in enumerate(zip(got["events"], want["events"])):
            for key in ("t", "type", "balls", "rail", "pocket", "after"):
                if not check(g.get(key) == w.get(key), "%s: event %d %s: %r != pool-sim %r" % (
                        label, i, key, g.get(key), w.get(key))):
                    return False
    check(got["final"] == want["final"], "%s: final states differ from pool-sim's" % label)
    for key in ("events", "sim_time", "stop_reason"):
        check(got["stats"][key] == want["stats"][key], "%s: stats.%s %r != pool-sim %r" % (
            label, key, got["stats"][key], want["stats"][key]))
    return not failures


class Collector:
    """Receives messages on some channels in a background thread, raw bytes and arrival order."""

    def __init__(self, url, channels):
        import lcm
        self.lc = lcm.LCM(url)
        self.messages = queue.Queue()
        self.subs = []
        for ch in channels:
            sub = self.lc.subscribe(ch, self._on)
            sub.set_queue_capacity(100000)
            self.subs.append(sub)
        self.stop = False
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _on(self, channel, data):
        self.messages.put((channel, data))

    def _run(self):
        while not self.stop:
            self.lc.handle_timeout(50)

    def get(self, timeout):
        return self.messages.get(timeout=timeout)

    def collect_until(self, predicate, timeout):
        """All messages until predicate(list) is true or the timeout passes."""
        got = []
        deadline = time.monotonic() + timeout
        while not predicate(got):
            left = deadline - time.monotonic()
            if left <= 0:
                break
            try:
                got.append(self.get(left))
            except queue.Empty:
                break
        return got

    def close(self):
        self.stop = True
        self.thread.join(2)
        for sub in self.subs:
            self.lc.unsubscribe(sub)
