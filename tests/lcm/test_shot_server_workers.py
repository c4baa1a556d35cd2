"""pool-shot-server --workers N: requests simulated on N worker threads at once, each with its own
simulation. With --workers 2, a long request (a 1000-ball frictionless shot that ends at its own
options.max_events after a fraction of a second), an endless one (cut by --max-shot-seconds) and a
short one sent right after them: both long ones run at once (the endless one is cut by its own
budget, not expired in the queue), and the short one is answered right after the first long one,
before the endless one ends (with the default single worker, the same three requests answer the
short one only after both); answers are matched by request_id and come in completion order;
the queue bound (--max-queue-requests) is shared by the workers; SIGTERM abandons every running
shot and answers the queued requests; a burst of 120 requests of four kinds on 3 workers, every
answer equal to pool-sim's; the exit report's counts match the answers; bad --workers values exit
2 naming the option. Every wait is bounded; the long requests
are calibrated on this machine (and build), so the test also runs under a sanitizer."""
import os
import re
import signal
import subprocess
import time

import lcm_test_util as u

args = u.parse_args(extra=[("--server", {"default": None,
                                         "help": "pool-shot-server to test (default: the build's)"})])
import lcm  # noqa: E402
from pool_lcm import shot_t  # noqa: E402

SERVER = args.server or os.path.join(args.bin_dir, "pool-shot-server")
SLACK = 1.0  # s allowed past a deadline on a loaded 2-core machine
names = ["short", "cut", "bank", "break"]
scenarios = {n: open(os.path.join(args.data_dir, n + ".json")).read() for n in names}
want = {n: u.pool_sim_json(args.bin_dir, os.path.join(args.data_dir, n + ".json"), args.work_dir)
        for n in names}


# The long request: 3000 events of 1000 balls (about 0.5 s in a Release build, a few hundred KB of
# answer); the endless one: the same balls without an event limit of their own.
LONG_EVENTS = 3000
long_text = u.ball_grid(1000, max_events=LONG_EVENTS)
long_path = os.path.join(args.work_dir, "long.json")
with open(long_path, "w") as f:
    f.write(long_text)
want_long = u.pool_sim_json(args.bin_dir, long_path, args.work_dir)
endless = u.ball_grid(1000)

answers = u.Collector(u.URL, ["POOL_SHOT"])
client = lcm.LCM(u.URL)


def request(request_id, text):
    u.publish_request(client, request_id, text)


got = {}    # request_id -> (shot_t, monotonic time this test received the answer)
order = []  # request ids in the order their answers came


def collect(ids, timeout):
    """Waits until every request in ids is answered or timeout seconds pass; returns the ids still
    unanswered. Answers are timed as they are taken off the collector, every 20 ms at most."""
    deadline = time.monotonic() + timeout
    while True:
        missing = [i for i in ids if i not in got]
        left = deadline - time.monotonic()
        if not missing or left <= 0:
            return missing
        for _, data in answers.collect_until(lambda m: len(m) >= 1, min(left, 0.02)):
            s = shot_t.decode(data)
            u.check(s.request_id not in got, "request %d answered twice" % s.request_id)
            got[s.request_id] = (s, time.monotonic())
            order.append(s.request_id)


def start(*options):
    server = subprocess.Popen([SERVER, "--lcm-url", u.URL, *options], stderr=subprocess.PIPE,
                              text=True)
    u.wait_for_line(server, "ready")
    return server


REPORT = re.compile(
    r"answered (\d+) requests \((\d+) with an error\), skipped (\d+) undecodable datagrams, "
    r"(\d+) publish failures; (\d+) over budget, (\d+) answers over --max-answer-bytes, (\d+) "
    r"shots abandoned on stop; (\d+) refused as busy \(queue full\), (\d+) expired in the queue, "
    r"(\d+) queued requests abandoned on stop; queue peak (\d+) requests, (\d+) bytes")
KEYS = ("answered", "errors", "undecodable", "publish_failures", "over_budget", "oversized",
        "abandoned", "busy", "expired", "abandoned_queued", "peak_requests", "peak_bytes")


def report_counts(err, label):
    """The exit report's counts as a dict (empty when there is no report)."""
    m = None
    for line in err.splitlines():
        m = REPORT.search(line) or m
    if not u.check(m is not None, "%s: no report in %r" % (label, err[-400:])):
        return {}
    print(m.group(0), flush=True)
    return dict(zip(KEYS, (int(g) for g in m.groups())))


def stop(server, label, timeout=3):
    """SIGTERM; returns the report's counts (checks exit 0 within timeout seconds)."""
    server.send_signal(signal.SIGTERM)
    return wait_exit(server, label, timeout)


def wait_exit(server, label, timeout):
    try:
        _, err = server.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        server.kill()
        _, err = server.communicate()
        u.check(False, "%s: server still running after %g s" % (label, timeout))
    u.check(server.returncode == 0, "%s: exit status %r" % (label, server.returncode))
    return report_counts(err, label)


def expect_counts(counts, label, **want_counts):
    for key, value in want_counts.items():
        u.check(counts.get(key) == value, "%s: report %s = %r, expected %r" % (
            label, key, counts.get(key), value))


def queued_seconds(error):
    """The time a request cut by --max-shot-seconds spent queued, from its error."""
    m = re.search(r"; ([0-9.]+) s of it spent queued", error)
    return float(m.group(1)) if m else None


# 0. Calibration: the long request alone, on this machine and build, so the budget of part 1
# leaves it room whatever the build's speed.
# (its own budget far above the default 10 s: a sanitizer build on a loaded machine takes that long)
server = start("--workers", "2", "--max-shot-seconds", "300")
t0 = time.monotonic()
request(1, long_text)
missing = collect([1], 120)
u.check(not missing, "calibration: the long request got no answer")
t_long = got[1][1] - t0 if 1 in got else 10.0
if 1 in got:
    u.check(got[1][0].error == "", "calibration: error %r" % got[1][0].error)
    u.compare_result(u.shot_json(got[1][0]), want_long, "calibration: long request")
counts = stop(server, "calibration")
expect_counts(counts, "calibration", answered=1, errors=0)
# Two workers on two cores beside other tests (ctest -j2) run the long request up to about three
# times slower than alone; five times leaves the short one's answer well before the endless one's.
BUDGET = round(max(3.0, 5.0 * t_long + 2.0), 1)
print("long request alone (%d events of 1000 balls): answered after %.2f s; budget for part 1: "
      "%g s" % (LONG_EVENTS, t_long, BUDGET), flush=True)


def long_endless_short(workers_option):
    """Sends the long request (1), the endless one (2) and the short one (3), in that order and at
    once; returns {id: seconds from sending to the answer} and the answer order."""
    got.clear()
    del order[:]
    server = start("--max-shot-seconds", str(BUDGET), *workers_option)
    t0 = time.monotonic()
    request(1, long_text)
    request(2, endless)
    request(3, scenarios["short"])
    missing = collect([1, 2, 3], BUDGET + SLACK + 5)
    label = "workers %s" % (workers_option[1] if workers_option else "default")
    u.check(not missing, "%s: requests %r unanswered" % (label, missing))
    took = {rid: got[rid][1] - t0 for rid in got}
    for rid, name in ((1, "long"), (2, "endless"), (3, "short")):
        if rid in got:
            s = got[rid][0]
            print("%s: %s request answered after %.2f s: %s" % (
                label, name, took[rid], s.error or "its shot (%d events)" % s.num_events),
                flush=True)
    return server, took, list(order)


# 1. --workers 2: the long and the endless request run at once, one per worker; the short one
# waits for the first worker to be free, i.e. for the long request, and is answered right after
# it, long before the endless one is cut; answers come in completion order (1, 3, 2), not arrival
# order.
server, took, answer_order = long_endless_short(["--workers", "2"])
if 3 in got:
    s = got[3][0]
    if u.check(s.error == "", "workers 2: short request error %r" % s.error):
        u.compare_result(u.shot_json(s), want["short"], "workers 2: short request")
if 1 in got:
    s = got[1][0]
    if u.check(s.error == "", "workers 2: long request error %r" % s.error):
        u.compare_result(u.shot_json(s), want_long, "workers 2: long request")
if 2 in got:
    s = got[2][0]
    u.check("budget of %g s (--max-shot-seconds)" % BUDGET in s.error and s.num_events == 0,
            "workers 2: endless request error %r" % s.error)
    q = queued_seconds(s.error)
    # Taken up at once by the second worker (with one worker it would have waited for the long
    # request, or expired in the queue).
    u.check(q is not None and q < 0.5, "workers 2: endless request queued %r s" % q)
    u.check(BUDGET - 0.2 < took[2] < BUDGET + SLACK,
            "workers 2: endless request answered after %.2f s, budget %g s" % (took[2], BUDGET))
if 1 in took and 2 in took and 3 in took:
    # Not delayed behind both long requests: answered within a second of the first to finish,
    # and at least a second before the endless one.
    u.check(took[3] < took[1] + SLACK, "workers 2: short request answered %.2f s after the long "
            "one" % (took[3] - took[1]))
    u.check(took[3] < took[2] - 1.0, "workers 2: short request answered after %.2f s, the "
            "endless one after %.2f s" % (took[3], took[2]))
    u.check(answer_order == [1, 3, 2], "workers 2: answer order %r" % answer_order)
counts = stop(server, "workers 2")
expect_counts(counts, "workers 2", answered=3, errors=1, over_budget=1, expired=0, abandoned=0,
              abandoned_queued=0, busy=0, publish_failures=0)
took_2 = dict(took)

# The same requests with the default (one worker): the endless request waits for the long one,
# and the short one for both, so it is answered only when the endless one's budget is over.
server, took, answer_order = long_endless_short([])
if 2 in got and 3 in got:
    s = got[2][0]
    u.check("budget of %g s (--max-shot-seconds)" % BUDGET in s.error
            or "expired in the server's queue" in s.error,
            "workers 1: endless request error %r" % s.error)
    u.check(took[3] > BUDGET - 0.5, "workers 1: short request answered after %.2f s, before the "
            "endless one's budget of %g s" % (took[3], BUDGET))
    u.check(answer_order == [1, 2, 3], "workers 1: answer order %r" % answer_order)
counts = stop(server, "workers 1")
expect_counts(counts, "workers 1", answered=3, publish_failures=0)
if 3 in took and 3 in took_2:
    print("short request behind a long and an endless one: answered after %.2f s with 2 workers, "
          "%.2f s with 1" % (took_2[3], took[3]), flush=True)

# 2. The queue bound is the server's, shared by the workers, and counts waiting requests only:
# with --workers 2 --max-queue-requests 2, two endless shots running and five short requests sent
# behind them, two wait and three are answered "server busy" at once. Then SIGTERM: both running
# shots are abandoned and the two queued requests answered with an error, within a fraction of a
# second.
got.clear()
server = start("--workers", "2", "--max-queue-requests", "2")
request(10, endless)
request(11, endless)
time.sleep(0.5)  # both endless shots are under way, one per worker
for rid in (12, 13, 14, 15, 16):
    request(rid, scenarios["short"])
collect([12, 13, 14, 15, 16], 1.0)
busy = sorted(rid for rid in got if got[rid][0].error.startswith("server busy:"))
u.check(busy == [14, 15, 16] and all("2 requests" in got[rid][0].error for rid in busy),
        "shared queue: busy answers %r, answered %r" % (busy, sorted(got)))
u.check(12 not in got and 13 not in got,
        "shared queue: queued requests answered while both workers were busy")
t0 = time.monotonic()
counts = stop(server, "SIGTERM")
stopped_s = time.monotonic() - t0
missing = collect([10, 11, 12, 13], 2)
u.check(not missing, "SIGTERM: %r unanswered" % missing)
for rid in (10, 11):
    if rid in got:
        u.check(got[rid][0].error == "shot abandoned: the server is stopping (SIGINT/SIGTERM)",
                "SIGTERM: running shot %d error %r" % (rid, got[rid][0].error))
for rid in (12, 13):
    if rid in got:
        u.check("abandoned before its turn" in got[rid][0].error,
                "SIGTERM: queued request %d error %r" % (rid, got[rid][0].error))
print("SIGTERM with 2 shots running and 2 queued: exited after %.3f s" % stopped_s, flush=True)
expect_counts(counts, "SIGTERM", answered=7, errors=7, abandoned=2, abandoned_queued=2,
              busy=3, over_budget=0, expired=0, peak_requests=2)

# 3. A burst of 120 requests of four kinds on 3 workers, sent as fast as this client can: every
# answer equal to pool-sim's, shot ids unique; --max-requests 120 stops the server by itself, with
# the report.
got.clear()
del order[:]
server = start("--workers", "3", "--max-requests", "120")
plan = [(5000 + k, names[k % len(names)]) for k in range(120)]
t0 = time.monotonic()
for rid, name in plan:
    request(rid, scenarios[name])
missing = collect([rid for rid, _ in plan], 30)
u.check(not missing, "burst: %d of 120 requests unanswered: %r" % (len(missing), missing[:5]))
for rid, name in plan:
    if rid in got:
        s = got[rid][0]
        if u.check(s.error == "", "burst: request %d (%s) error %r" % (rid, name, s.error)):
            u.compare_result(u.shot_json(s), want[name], "burst: request %d (%s)" % (rid, name))
shot_ids = [got[rid][0].shot_id for rid, _ in plan if rid in got]
u.check(len(set(shot_ids)) == len(shot_ids), "burst: shot ids are not unique")
out_of_order = sum(1 for a, b in zip(order, order[1:]) if b < a)
print("burst: 120 requests on 3 workers answered in %.2f s, equal to pool-sim's; %d answers came "
      "before that of an earlier request" % (time.monotonic() - t0, out_of_order), flush=True)
counts = wait_exit(server, "burst (--max-requests 120)", 10)
expect_counts(counts, "burst", answered=120, errors=0, publish_failures=0, busy=0, expired=0,
              abandoned=0, abandoned_queued=0)

# 4. Bad --workers values exit 2, naming the option; --help shows it.
for value in ("0", "-1", "x", "", "1.5", "257"):
    r = subprocess.run([SERVER, "--workers", value], capture_output=True, text=True, timeout=10)
    u.check(r.returncode == 2 and "--workers" in r.stderr, "--workers %r: exit %r, %r" % (
        value, r.returncode, r.stderr))
r = subprocess.run([SERVER, "--workers"], capture_output=True, text=True, timeout=10)
u.check(r.returncode == 2 and "--workers" in r.stderr, "--workers without a value: exit %r, %r"
        % (r.returncode, r.stderr))
r = subprocess.run([SERVER, "--help"], capture_output=True, text=True, timeout=10)
u.check(r.returncode == 0 and "--workers N" in r.stdout, "--help: %r" % r.stdout[-300:])
answers.close()
u.finish()
