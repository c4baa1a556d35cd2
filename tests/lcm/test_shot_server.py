"""pool-shot-server answers interleaved requests of two clients with the right request_id and
exactly pool-sim's result; a bad scenario gets `error` set; undecodable datagrams (garbage, or a
shot_request_t whose string length lies) neither crash nor stall it; SIGTERM stops it cleanly with
a report of what it served."""
import json
import os
import signal
import struct
import subprocess
import time

import lcm_test_util as u

args = u.parse_args()
import lcm  # noqa: E402
from pool_lcm import shot_request_t, shot_t  # noqa: E402

names = ["short", "cut", "bank", "break"]
scenarios = {n: open(os.path.join(args.data_dir, n + ".json")).read() for n in names}
want = {n: u.pool_sim_json(args.bin_dir, os.path.join(args.data_dir, n + ".json"), args.work_dir)
        for n in names}

# The server takes its URL from LCM_DEFAULT_URL here (no --lcm-url): the variable is honoured.
server = subprocess.Popen([os.path.join(args.bin_dir, "pool-shot-server")],
                          stderr=subprocess.PIPE, text=True,
                          env=dict(os.environ, LCM_DEFAULT_URL=u.URL))
u.wait_for_line(server, "ready")

answers = u.Collector(u.URL, ["POOL_SHOT"])
client_a = lcm.LCM(u.URL)
client_b = lcm.LCM(u.URL)


def request(client, request_id, text):
    msg = shot_request_t()
    msg.utime = int(time.time() * 1e6)
    msg.request_id = request_id
    msg.scenario_json = text
    client.publish("POOL_SHOT_REQUEST", msg.encode())


def wait_answers(ids, timeout=30):
    got = answers.collect_until(lambda m: len(m) >= len(ids), timeout)
    by_id = {}
    for _, data in got:
        s = shot_t.decode(data)
        u.check(s.request_id not in by_id, "request %d answered twice" % s.request_id)
        by_id[s.request_id] = s
    u.check(sorted(by_id) == sorted(ids), "answered %r, asked %r" % (sorted(by_id), sorted(ids)))
    return by_id


# Two clients, interleaved, without waiting for answers in between (ids from both clients).
plan = []
for round_ in range(3):
    for k, n in enumerate(names):
        client, base = (client_a, 1000) if (round_ + k) % 2 == 0 else (client_b, 2000)
        plan.append((client, base + 10 * round_ + k, n))
for client, rid, n in plan:
    request(client, rid, scenarios[n])
got = wait_answers([rid for _, rid, _ in plan])
for _, rid, n in plan:
    if rid in got:
        s = got[rid]
        u.check(s.error == "", "request %d (%s): error %r" % (rid, n, s.error))
        u.compare_result(u.shot_json(s), want[n], "request %d (%s)" % (rid, n))
shot_ids = [got[rid].shot_id for _, rid, _ in plan if rid in got]
u.check(len(set(shot_ids)) == len(shot_ids), "shot ids are not unique")
print("%d interleaved requests from two clients answered and matched" % len(plan), flush=True)

# Bad scenarios: answered with error set, naming the problem; nothing else in the message.
bad = {
    3001: "{not json",
    3002: json.dumps({"format": "libpool-scenario/1",
                      "balls": [{"id": 0, "pos": [0.5, 0.5]}, {"id": 1, "pos": [0.51, 0.5]}]}),
    3003: json.dumps({"format": "libpool-scenario/1", "balls": [{"id": 0, "pos": [0.5, 0.5]}],
                      "strike": {"ball": 0, "speed": 2.0, "phi": 0, "theta": 0, "a": 0.03,
                                 "b": 0.0}}),
    3004: "",
}
for rid, text in bad.items():
    request(client_a, rid, text)
got = wait_answers(list(bad))
for rid in bad:
    if rid in got:
        s = got[rid]
        u.check(s.error != "" and s.num_events == 0 and s.num_balls == 0,
                "bad request %d: error %r, %d events" % (rid, s.error, s.num_events))
u.check("balls[1]" in getattr(got.get(3002), "error", ""),
        "overlap error does not name balls[1]: %r" % getattr(got.get(3002), "error", None))
u.check("strike" in getattr(got.get(3003), "error", ""),
        "miscue error does not name the strike: %r" % getattr(got.get(3003), "error", None))

# Undecodable datagrams: garbage; a valid fingerprint whose string length runs past the end; a
# truncated message. Then a good request must still be answered.
good = shot_request_t()
good.request_id = 4242
good.scenario_json = scenarios["short"]
encoded = good.encode()
lying = encoded[:24] + struct.pack(">i", 10 ** 6) + encoded[28:]
unterminated = encoded[:-1] + b"x"
for datagram in (b"garbage", b"", os.urandom(300), lying, encoded[:30], unterminated):
    client_b.publish("POOL_SHOT_REQUEST", datagram)
request(client_b, 4243, scenarios["cut"])
got = wait_answers([4243])
if 4243 in got:
    u.compare_result(u.shot_json(got[4243]), want["cut"], "request after garbage")
u.check(server.poll() is None, "server died after garbage (exit %r)" % server.poll())

# Clean shutdown on SIGTERM, with the report.
answers.close()
server.send_signal(signal.SIGTERM)
try:
    _, err = server.communicate(timeout=5)
except subprocess.TimeoutExpired:
    server.kill()
    _, err = server.communicate()
    u.check(False, "server ignored SIGTERM")
u.check(server.returncode == 0, "server exit status %r" % server.returncode)
answered = len(plan) + len(bad) + 1
u.check("answered %d requests (%d with an error), skipped 6 undecodable" % (answered, len(bad))
        in err, "server report: %r" % err[-400:])
print(err.strip().splitlines()[-1])

# --max-requests: exits by itself after N answers.
server = subprocess.Popen([os.path.join(args.bin_dir, "pool-shot-server"), "--lcm-url", u.URL,
                           "--max-requests", "2"], stderr=subprocess.PIPE, text=True)
u.wait_for_line(server, "ready")
request(client_a, 1, scenarios["short"])
request(client_a, 2, scenarios["short"])
try:
    server.communicate(timeout=10)
    u.check(server.returncode == 0, "--max-requests: exit %r" % server.returncode)
except subprocess.TimeoutExpired:
    server.kill()
    u.check(False, "--max-requests 2: server still running after two requests")
u.finish()
