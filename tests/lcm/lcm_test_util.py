"""Helpers shared by the LCM end-to-end tests (run inside netns_run.sh)."""
import argparse
import importlib.util
import json
import os
import queue
import select
import subprocess
import sys
import threading
import time

URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608"

# Message-to-result conversions (ball_json, event_json, shot_json) are the shipped subscriber's
# (tools/pool_lcm_subscribe.py, given by --subscriber): parse_args loads them, so the tests check
# the code users run rather than a copy of it.
ball_json = event_json = shot_json = None


def ball_grid(n, frictionless=True, max_events=2 ** 31 - 1):
    """A libpool-scenario/1 text: n small balls (R = 5 mm) on a grid, every one moving. Frictionless
    (the default), with perfectly elastic impacts, tiny pockets and no time limit of its own, the
    shot practically never ends: it stops at its own max_events (by default none that matters) or
    at the server's budget. With friction: an ordinary shot of n balls (the --max-balls test)."""
    r, balls, i, y = 0.005, [], 0, 0.05
    while i < n:
        x = 0.05
        while x < 2.49 and i < n:
            balls.append({"id": i, "pos": [round(x, 6), round(y, 6)],
                          "vel": [0.3 if i % 2 else -0.2, 0.25 if i % 3 else -0.1, 0.0]})
            i, x = i + 1, x + 2.5 * r
        y += 2.5 * r
    # The thesis model's pockets: mouths of 10 mm on the rail lines (jaws for 5 mm balls would
    # need a table of their own).
    doc = {"format": "libpool-scenario/1",
           "table": {"preset": "wpa-9ft", "cushion_height": 0.0065, "pockets": "mouth_lines"},
           "params": {"ball_radius": r}, "balls": balls}
    if frictionless:
        doc["table"].update({"corner_mouth": 0.0101, "side_mouth": 0.0101})
        doc["params"].update({"mu_slide": 0.0, "mu_roll": 0.0, "mu_spin": 0.0, "e_ball": 1.0,
                              "e_cushion": 1.0})
        doc["options"] = {"max_time": 1e9, "max_events": max_events}
    return json.dumps(doc)


def lcm_events(events):
    """A result's events as the released event_t carries them: without the cushion "part"
    (pockets "jaws"), which that type has no field for (docs/lcm.md)."""
    return [{k: v for k, v in e.items() if k != "part"} for e in events]


def publish_request(client, request_id, text):
    """Publishes a shot_request_t for the scenario text on POOL_SHOT_REQUEST (after parse_args,
    which puts the generated types on the path)."""
    from pool_lcm import shot_request_t
    msg = shot_request_t()
    msg.utime = int(time.time() * 1e6)
    msg.request_id = request_id
    msg.scenario_json = text
    client.publish("POOL_SHOT_REQUEST", msg.encode())


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
    load_subscriber(args.subscriber)
    return args


def load_subscriber(path):
    """Imports the subscriber script as a module and takes its conversion functions."""
    global ball_json, event_json, shot_json
    spec = importlib.util.spec_from_file_location("pool_lcm_subscribe", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    ball_json, event_json, shot_json = module.ball_json, module.event_json, module.shot_json
    return module


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


def compare_result(got, want, label):
    """Event for event, to full double precision: types, times, ball ids, rail/pocket, states;
    then the final states and the stats both documents carry."""
    ok = check(len(got["events"]) == len(want["events"]),
               "%s: %d events, pool-sim has %d" % (label, len(got["events"]), len(want["events"])))
    if ok:
        for i, (g, w) in enumerate(zip(got["events"], want["events"])):
            # The cushion's part only where the message carries it (shot2_t, whose document has
            # the table too); shot_t has no field for it.
            keys = ("t", "type", "balls", "rail", "pocket", "after") + (("part",) if "table" in got else ())
            for key in keys:
                if not check(g.get(key) == w.get(key), "%s: event %d %s: %r != pool-sim %r" % (
                        label, i, key, g.get(key), w.get(key))):
                    return False
    check(got["final"] == want["final"], "%s: final states differ from pool-sim's" % label)
    for key in ("events", "sim_time", "stop_reason"):
        check(got["stats"][key] == want["stats"][key], "%s: stats.%s %r != pool-sim %r" % (
            label, key, got["stats"][key], want["stats"][key]))
    return not failures


LCM_PORT = 7667


def udp_sockets(port=LCM_PORT):
    """(local address, rx_queue bytes) of every UDP socket bound to port in this namespace."""
    found = []
    for table in ("/proc/net/udp", "/proc/net/udp6"):
        try:
            with open(table) as f:
                next(f)
                for line in f:
                    fields = line.split()
                    local, queues = fields[1], fields[4]
                    if int(local.rsplit(":", 1)[1], 16) == port:
                        found.append((local, int(queues.split(":")[1], 16)))
        except OSError:
            pass
    return found


def wait_for_listeners(count, timeout=10.0, port=LCM_PORT):
    """Waits until at least count sockets listen on port: a program such as lcm-logger, which
    prints nothing when ready, has joined the multicast group once its socket exists."""
    deadline = time.monotonic() + timeout
    while len(udp_sockets(port)) < count:
        if time.monotonic() > deadline:
            check(False, "%d listeners on port %d after %.0f s, expected %d" % (
                len(udp_sockets(port)), port, timeout, count))
            return
        time.sleep(0.02)


def wait_until_drained(timeout=10.0, port=LCM_PORT):
    """Waits until every socket on port has read all its datagrams (rx_queue 0, twice in a row):
    a listener under load may not have read the last message when a fixed sleep ends."""
    deadline = time.monotonic() + timeout
    quiet = 0
    while quiet < 2:
        if time.monotonic() > deadline:
            check(False, "datagrams still queued on port %d after %.0f s" % (port, timeout))
            return
        quiet = quiet + 1 if all(q == 0 for _, q in udp_sockets(port)) else 0
        time.sleep(0.05)


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
