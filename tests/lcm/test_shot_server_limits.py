"""pool-shot-server's per-request budget: a shot over --max-shot-seconds, --max-events or
--max-balls is answered quickly with an error naming the limit, and the server keeps serving; an
answer over --max-answer-bytes is replaced by the final states (or the error alone) with an error
giving its size; SIGTERM during a long shot stops the server at once, answering the abandoned
request, with exit 0 and the report; bad limit values and pool-sim --playback above 1000 Hz exit
2; the default URL talks to clients on the plain docs/interfaces.md URL. Every part takes a few seconds
at most."""
import json
import os
import signal
import subprocess
import time

import lcm_test_util as u

args = u.parse_args()
import lcm  # noqa: E402
from pool_lcm import shot_t  # noqa: E402

SERVER = os.path.join(args.bin_dir, "pool-shot-server")
data = {n: open(os.path.join(args.data_dir, n + ".json")).read() for n in ("short", "break")}
want = {n: u.pool_sim_json(args.bin_dir, os.path.join(args.data_dir, n + ".json"), args.work_dir)
        for n in ("short", "break")}


grid = u.ball_grid  # n moving balls; frictionless: never ends by itself
endless = grid(1000, True)
answers = u.Collector(u.URL, ["POOL_SHOT"])
client = lcm.LCM(u.URL)


def request(request_id, text):
    u.publish_request(client, request_id, text)


def wait_answer(request_id, timeout):
    """The answer to request_id, or None after timeout seconds."""
    deadline = time.monotonic() + timeout
    while True:
        left = deadline - time.monotonic()
        got = answers.collect_until(lambda m: len(m) >= 1, max(left, 0.0))
        if not got:
            return None
        s = shot_t.decode(got[0][1])
        if s.request_id == request_id:
            return s


def start(*options):
    server = subprocess.Popen([SERVER, "--lcm-url", u.URL, *options], stderr=subprocess.PIPE,
                              text=True)
    u.wait_for_line(server, "ready")
    return server


def stop(server, label, sig=signal.SIGTERM):
    """Sends sig (SIGTERM by default); returns the report line (checks exit 0 within 2 s)."""
    t0 = time.monotonic()
    server.send_signal(sig)
    try:
        _, err = server.communicate(timeout=2)
    except subprocess.TimeoutExpired:
        server.kill()
        _, err = server.communicate()
        u.check(False, "%s: server still running 2 s after SIGTERM" % label)
    u.check(server.returncode == 0, "%s: exit status %r" % (label, server.returncode))
    lines = err.strip().splitlines()
    return (lines[-1] if lines else ""), time.monotonic() - t0


# 1. Time budget: an endless shot is cut at 0.2 s with an error; the next request is answered.
server = start("--max-shot-seconds", "0.2", "--max-balls", "1500")
t0 = time.monotonic()
request(1, endless)
s = wait_answer(1, 5)
took = time.monotonic() - t0
if u.check(s is not None, "over-time request: no answer within 5 s"):
    u.check("budget of 0.2 s (--max-shot-seconds)" in s.error and s.num_events == 0,
            "over-time request: error %r, %d events" % (s.error, s.num_events))
    u.check(took < 3, "over-time request answered after %.2f s (budget 0.2 s)" % took)
    print("endless shot answered after %.2f s: %s" % (took, s.error), flush=True)
request(2, data["short"])
s = wait_answer(2, 5)
if u.check(s is not None, "request after an over-time one: no answer"):
    u.check(s.error == "", "request after an over-time one: error %r" % s.error)
    u.compare_result(u.shot_json(s), want["short"], "request after an over-time one")

# --max-balls: a clear error, nothing simulated.
request(3, grid(1501, False))
s = wait_answer(3, 5)
if u.check(s is not None, "too many balls: no answer"):
    u.check("1501 balls" in s.error and "1500 (--max-balls)" in s.error,
            "too many balls: error %r" % s.error)
report, _ = stop(server, "time budget")
u.check("answered 3 requests (2 with an error)" in report and "2 over budget" in report,
        "time budget: report %r" % report)
print(report, flush=True)

# 2. Event cap and answer size: --max-events 50 is below the break's 96 events; a scenario
# asking for fewer events than the cap gets its shot; answers over --max-answer-bytes carry the
# final states when they fit, the error alone when not.
u.check(len(want["break"]["events"]) > 50, "the break has only %d events: no test of the cap"
        % len(want["break"]["events"]))
server = start("--max-events", "50", "--max-answer-bytes", "4000")
request(10, data["break"])
s = wait_answer(10, 5)
if u.check(s is not None, "over --max-events: no answer"):
    u.check("budget of 50 events (--max-events)" in s.error and s.num_events == 0,
            "over --max-events: error %r" % s.error)
doc = json.loads(data["break"])
doc["options"] = {"max_events": 5}
request(11, json.dumps(doc))
s = wait_answer(11, 5)
if u.check(s is not None, "max_events below the cap: no answer"):
    u.check(s.error == "" and s.num_events == 5 and s.stop_reason == "max_events",
            "max_events 5: error %r, %d events, stop %r" % (s.error, s.num_events, s.stop_reason))
doc["options"] = {"max_events": 40}  # about 7 KB of events: over 4000 bytes
request(12, json.dumps(doc))
s = wait_answer(12, 5)
full = u.pool_sim_json(args.bin_dir, os.path.join(args.data_dir, "break.json"), args.work_dir)
if u.check(s is not None, "oversized answer: no answer"):
    u.check("exceeds the server's limit of 4000 bytes (--max-answer-bytes)" in s.error
            and "40 events" in s.error and s.num_events == 0 and s.num_balls == 16
            and s.stop_reason == "max_events",
            "oversized answer: error %r, %d events, %d balls" % (s.error, s.num_events,
                                                                s.num_balls))
    print("oversized: " + s.error, flush=True)
report, _ = stop(server, "answer size")
u.check("answered 3 requests (2 with an error)" in report and "1 over budget" in report
        and "1 answers over --max-answer-bytes" in report, "answer size: report %r" % report)
print(report, flush=True)

server = start("--max-answer-bytes", "1000")  # not even the 16 final states (1232 bytes) fit
request(13, data["break"])
s = wait_answer(13, 5)
if u.check(s is not None, "oversized, final states too: no answer"):
    u.check("1000 bytes (--max-answer-bytes)" in s.error and "do not fit" in s.error
            and s.num_balls == 0 and s.num_events == 0, "oversized, final states too: %r" % s.error)
request(14, data["short"])  # small enough: answered in full
s = wait_answer(14, 5)
if u.check(s is not None, "small answer under --max-answer-bytes 1000: no answer"):
    u.compare_result(u.shot_json(s), want["short"], "small answer under --max-answer-bytes 1000")
report, _ = stop(server, "answer size 1000")
u.check("1 answers over --max-answer-bytes" in report, "answer size 1000: report %r" % report)

# 3. SIGTERM (then SIGINT) while an endless shot runs (default budget 10 s): exit 0 within 2 s, the abandoned
# request answered with an error, the report printed.
server = start()
request(20, endless)
time.sleep(0.7)  # the shot is under way
report, took = stop(server, "SIGTERM during a shot")
u.check(took < 2, "SIGTERM during a shot: exit after %.2f s" % took)
u.check("answered 1 requests (1 with an error)" in report
        and "1 shots abandoned on stop" in report, "SIGTERM during a shot: report %r" % report)
s = wait_answer(20, 2)
if u.check(s is not None, "abandoned shot: no answer"):
    u.check("abandoned" in s.error, "abandoned shot: error %r" % s.error)
print("SIGTERM during a shot: exit 0 after %.2f s; %s" % (took, report), flush=True)

# The same with SIGINT (Ctrl-C in a terminal).
server = start()
request(21, endless)
time.sleep(0.7)
report, took = stop(server, "SIGINT during a shot", signal.SIGINT)
u.check(took < 2 and "1 shots abandoned on stop" in report,
        "SIGINT during a shot: exit after %.2f s, report %r" % (took, report))
s = wait_answer(21, 2)
u.check(s is not None and "abandoned" in s.error, "SIGINT: abandoned shot not answered with an error")

# 4. Bad option values are refused with exit 2, naming the option.
for opt, value in (("--max-shot-seconds", "0"), ("--max-events", "0"), ("--max-balls", "-1"),
                   ("--max-answer-bytes", "10")):
    r = subprocess.run([SERVER, opt, value], capture_output=True, text=True, timeout=10)
    u.check(r.returncode == 2 and opt in r.stderr, "%s %s: exit %r, %r" % (
        opt, value, r.returncode, r.stderr))

# pool-sim --playback is capped at 1000 Hz (a frame of every ball per period).
for value in ("1001", "1e9"):
    r = subprocess.run([os.path.join(args.bin_dir, "pool-sim"),
                        os.path.join(args.data_dir, "short.json"), "--lcm-url", u.URL,
                        "--playback", value], capture_output=True, text=True, timeout=10)
    u.check(r.returncode == 2 and "--playback" in r.stderr and "1000 Hz" in r.stderr,
            "pool-sim --playback %s: exit %r, %r" % (value, r.returncode, r.stderr))
answers.close()

# 5. Defaults interoperate with the plain docs/interfaces.md URL: a server started with neither
# --lcm-url nor LCM_DEFAULT_URL (its default adds only a receive-buffer size) answers a client and
# a subscriber that use udpm://239.255.76.67:7667?ttl=0 as it stands.
PLAIN = "udpm://239.255.76.67:7667?ttl=0"
env = {k: v for k, v in os.environ.items() if k != "LCM_DEFAULT_URL"}
server = subprocess.Popen([SERVER], stderr=subprocess.PIPE, text=True, env=env)
u.wait_for_line(server, "ready")
answers = u.Collector(PLAIN, ["POOL_SHOT"])
client = lcm.LCM(PLAIN)
request(30, data["short"])
s = wait_answer(30, 5)
if u.check(s is not None, "default URL: no answer on the plain docs/interfaces.md URL"):
    u.check(s.error == "", "default URL: error %r" % s.error)
    u.compare_result(u.shot_json(s), want["short"], "default URL")
report, _ = stop(server, "default URL")
answers.close()
u.finish()
