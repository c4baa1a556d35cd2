"""pool-sim --lcm-url publishes each event on POOL_EVENT and the shot on POOL_SHOT; the Python
example subscriber's --json output equals pool-sim's own result file event for event, to full
double precision. --playback publishes real-time frames on POOL_STATE."""
import json
import os
import subprocess
import sys
import time

import lcm_test_util as u

args = u.parse_args()
from pool_lcm import event_t, shot_t, table_state_t  # noqa: E402

pool_sim = os.path.join(args.bin_dir, "pool-sim")
env = dict(os.environ, LCM_DEFAULT_URL="memq://")  # --lcm-url must win over the environment

for name in ("short", "cut", "bank", "break", "jump"):  # jump: airborne, clears ball 1
    scenario = os.path.join(args.data_dir, name + ".json")
    want = u.pool_sim_json(args.bin_dir, scenario, args.work_dir)
    sub = subprocess.Popen([sys.executable, args.subscriber, "--lcm-url", u.URL, "--types-dir",
                            args.types_dir, "--json", "--count", "1", "--timeout", "20"],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    u.wait_for_line(sub, "subscribed")
    csub = subprocess.Popen([os.path.join(args.bin_dir, "pool-lcm-subscribe"), "--lcm-url", u.URL,
                             "--count", "1", "--timeout", "20"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # Its socket exists before it has joined the group and registered its handlers: wait for the
    # line it prints once subscribed (waiting for the socket lost the first events now and then).
    u.wait_for_line(csub, "subscribed")
    live = u.Collector(u.URL, ["POOL_EVENT", "POOL_SHOT"])
    out = os.path.join(args.work_dir, name + ".lcm-run.json")
    subprocess.run([pool_sim, scenario, "--lcm-url", u.URL, "-o", out], check=True, timeout=60,
                   env=env)
    stdout, stderr = sub.communicate(timeout=30)
    u.check(sub.returncode == 0, "%s: subscriber exit %d: %s" % (name, sub.returncode, stderr))
    got = json.loads(stdout.strip().splitlines()[-1])
    # The C example: one line per event, then one for the shot.
    cout, cerr = csub.communicate(timeout=30)
    lines = cout.strip().splitlines()
    u.check(csub.returncode == 0 and len(lines) == len(want["events"]) + 1 and
            lines[-1].startswith("shot ") and ("events=%d " % len(want["events"])) in lines[-1] and
            all(line.startswith("event ") for line in lines[:-1]),
            "%s: pool-lcm-subscribe printed %r (exit %r, %s)" % (name, lines[-2:], csub.returncode,
                                                                 cerr))
    if len(lines) > 1:
        first = want["events"][1]
        u.check(lines[1].split()[3] == "t=%r" % first["t"] or
                float(lines[1].split()[3][2:]) == first["t"],
                "%s: C subscriber event line %r" % (name, lines[1]))
    u.compare_result(got, want, name + " (POOL_SHOT via pool_lcm_subscribe.py --json)")
    # Publishing changes nothing in the result file.
    with open(out) as f:
        u.check(json.load(f) == want, "%s: pool-sim -o differs when publishing" % name)

    # The live stream: every event once, in order, with the shot's id, before the shot itself.
    msgs = live.collect_until(lambda m: any(ch == "POOL_SHOT" for ch, _ in m), 20)
    live.close()
    events = [event_t.decode(d) for ch, d in msgs if ch == "POOL_EVENT"]
    shots = [shot_t.decode(d) for ch, d in msgs if ch == "POOL_SHOT"]
    if u.check(len(shots) == 1, "%s: %d shots on POOL_SHOT" % (name, len(shots))):
        shot = shots[0]
        u.check([e.seq for e in events] == list(range(len(want["events"]))),
                "%s: POOL_EVENT seq %r" % (name, [e.seq for e in events][:20]))
        u.check(all(e.shot_id == shot.shot_id for e in events),
                "%s: events carry another shot_id" % name)
        u.check([u.event_json(e) for e in events] == u.lcm_events(want["events"]),
                "%s: POOL_EVENT stream differs from pool-sim's events" % name)
        u.check(shot.request_id == 0 and shot.error == "", "%s: request_id/error set" % name)
        u.check(all(events[i].utime <= events[i + 1].utime for i in range(len(events) - 1)),
                "%s: event utimes not increasing" % name)
    print("%s: %d events streamed and matched" % (name, len(want["events"])), flush=True)

# Real-time playback: frames every 1/HZ of simulated time, paced by the wall clock.
hz = 20.0
scenario = os.path.join(args.data_dir, "short.json")
want = u.pool_sim_json(args.bin_dir, scenario, args.work_dir)
end = want["stats"]["sim_time"]
live = u.Collector(u.URL, ["POOL_STATE", "POOL_EVENT", "POOL_SHOT"])
start = time.monotonic()
subprocess.run([pool_sim, scenario, "--lcm-url", u.URL, "--playback", str(hz), "-o",
                os.path.join(args.work_dir, "playback.json")], check=True, timeout=60)
wall = time.monotonic() - start
msgs = live.collect_until(lambda m: any(ch == "POOL_SHOT" for ch, _ in m), 10)
live.close()
frames = [table_state_t.decode(d) for ch, d in msgs if ch == "POOL_STATE"]
expected_frames = int(end * hz + 1e-9) + 1 + (0 if abs(end * hz - round(end * hz)) < 1e-9 else 1)
u.check(len(frames) == expected_frames, "playback: %d frames, expected %d for %.3f s at %g Hz" % (
    len(frames), expected_frames, end, hz))
u.check(wall >= end * 0.95, "playback: took %.3f s of wall time for %.3f s simulated" % (wall, end))
if frames:
    ts = [f.t for f in frames]
    u.check(all(abs(ts[k] - k / hz) < 1e-12 for k in range(len(ts) - 1)) and ts[-1] == end,
            "playback: frame times %r" % ts[:5])
    u.check(all(f.num_balls == len(want["final"]) for f in frames), "playback: ball count")
    u.check([u.ball_json(b) for b in frames[-1].balls] == want["final"],
            "playback: last frame is not the final state")
    u.check(frames[0].balls[0].pos == tuple(want["events"][0]["after"][0]["pos"]) or
            list(frames[0].balls[0].pos) == want["events"][0]["after"][0]["pos"],
            "playback: first frame is not the struck ball at t = 0")
    # Frames arrive at their wall time: the spread of arrival is about the simulated span.
    span = (frames[-1].utime - frames[0].utime) * 1e-6
    u.check(span >= end * 0.95, "playback: frames spread over %.3f s, shot lasts %.3f s" % (
        span, end))
    print("playback: %d frames over %.3f s wall for %.3f s simulated" % (len(frames), span, end))
u.finish()
