"""The shot planner on LCM: pool-aim-server answers every aim_request_t on POOL_AIM_REQUEST with an
aim_reply_t on POOL_AIM carrying the same request_id. A request with room enough in its budget is
answered with exactly what pool-aim prints for the same position and options (number for number),
and its shots, replayed by pool-sim, drop their ball in their pocket; a 9-ball position's shots are
legal under the rules; a tiny budget is answered in time with what was found; bad scenarios and
options are answered with an error naming the field, and the server keeps serving."""
import json
import os
import subprocess
import time

import lcm_test_util as u

args = u.parse_args()
import lcm  # noqa: E402
from pool_lcm import aim_reply_t, aim_request_t  # noqa: E402

POSITION = {"format": "libpool-scenario/1",
            "balls": [{"id": 0, "pos": [1.0, 0.5]}, {"id": 1, "pos": [2.0, 0.3]}, {"id": 2, "pos": [0.6, 1.0]},
                      {"id": 3, "pos": [1.5, 0.95]}]}
NINE = {"format": "libpool-scenario/1",
        "balls": [{"id": 0, "pos": [0.8, 0.6]}, {"id": 1, "pos": [1.6, 0.9]}, {"id": 2, "pos": [2.3, 0.25]},
                  {"id": 9, "pos": [1.9, 0.5]}],
        "game": {"rules": "9ball"}}
BUSY = {"format": "libpool-scenario/1",
        "balls": [{"id": i, "pos": [0.3 + 0.55 * (i % 4) + 0.05 * (i // 4), 0.2 + 0.27 * (i // 4) + 0.03 * (i % 4)]}
                  for i in range(16)]}


def request(rid, doc, **kw):
    msg = aim_request_t()
    msg.utime = int(time.time() * 1e6)
    msg.request_id = rid
    msg.scenario_json = doc if isinstance(doc, str) else json.dumps(doc)
    msg.pocket, msg.noise, msg.kinds = kw.get("pocket", ""), kw.get("noise", ""), kw.get("kinds", "")
    msg.has_ball, msg.ball = "ball" in kw, kw.get("ball", 0)
    msg.top, msg.samples, msg.seed = kw.get("top", 0), kw.get("samples", 0), kw.get("seed", 0)
    msg.time_budget, msg.position = kw.get("time_budget", 0.0), kw.get("position", False)
    msg.distinct = kw.get("distinct", False)
    return msg.encode()


def write(name, doc):
    path = os.path.join(args.work_dir, name)
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


def replay(doc, shot):
    d = dict(doc)
    d["strike"] = {"ball": 0, "speed": shot.speed, "phi": shot.phi, "theta": shot.theta, "a": shot.a, "b": shot.b}
    return u.pool_sim_json(args.bin_dir, write("replay.json", d), args.work_dir)


requests = {
    3: request(3, BUSY, top=1, samples=50, time_budget=0.05),
    1: request(1, POSITION, top=3, samples=80, seed=5, time_budget=60.0),
    8: request(8, POSITION, time_budget=0.001),
    2: request(2, NINE, top=2, samples=60, time_budget=60.0),
    4: request(4, "{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}, "
                  "{\"id\": 1, \"pos\": [0.51, 0.5]}]}"),
    5: request(5, POSITION, pocket="middle"),
    6: request(6, POSITION, ball=9),
    7: request(7, POSITION, samples=1000000),
}
server = subprocess.Popen([os.path.join(args.bin_dir, "pool-aim-server"), "--lcm-url", u.URL, "--max-time-budget",
                           "60", "--max-requests", str(len(requests))], stderr=subprocess.PIPE, text=True)
u.wait_for_line(server, "ready")
answers = u.Collector(u.URL, ["POOL_AIM"])
client = lcm.LCM(u.URL)
client.publish("POOL_AIM_REQUEST", b"not an aim_request_t")
replies = {}
# Request 3 alone (its budget starts when it arrives), then the others at once: request 8, right
# behind request 1, finds its millisecond gone.
for batch in ([3], [rid for rid in requests if rid != 3]):
    for rid in batch:
        client.publish("POOL_AIM_REQUEST", requests[rid])
    for _, data in answers.collect_until(lambda m: len(m) >= len(batch), 120):
        r = aim_reply_t.decode(data)
        replies[r.request_id] = r
answers.close()
u.check(sorted(replies) == sorted(requests), "answered %r" % sorted(replies))

# 1: pool-aim's list for the same position and options, and shots that pot.
if 1 in replies:
    r = replies[1]
    p = subprocess.run([os.path.join(args.bin_dir, "pool-aim"), write("position.json", POSITION), "--top", "3",
                        "-n", "80", "--seed", "5"], capture_output=True, text=True, timeout=300)
    printed = json.loads(p.stdout)
    u.check(r.error == "" and r.num_shots == len(printed) >= 1, "request 1: %r, %d shots" % (r.error, r.num_shots))
    for s, want in zip(r.shots, printed):
        got = {"speed": s.speed, "phi": s.phi, "theta": s.theta, "a": s.a, "b": s.b}
        u.check({k: want["strike"][k] for k in got} == got and s.ball == want["ball"] and s.pocket == want["pocket"]
                and s.kind == want["kind"] and [s.ci_low, s.ci_high] == want["ci95"]
                and s.p_success == want["p_success"] and s.samples == want["samples"]
                and list(s.cue_final) == want["cue_ball_final"], "request 1: %r differs from pool-aim's %r" % (got, want))
        result = replay(POSITION, s)
        u.check(any(e["type"] == "pocket" and e["balls"] == [s.ball] and e["pocket"] == s.pocket
                    for e in result["events"]), "request 1: the shot does not pot ball %d" % s.ball)
# 2: 9-ball, legal.
if 2 in replies:
    r = replies[2]
    u.check(r.error == "" and r.num_shots >= 1, "request 2: %r" % r.error)
    for s in r.shots:
        result = replay(NINE, s)
        u.check(result["game"]["legal"] and result["game"]["first_hit"] == 1, "request 2: %r" % result["game"])
# 3: a tiny budget: answered soon, saying the budget cut the search short.
if 3 in replies:
    r = replies[3]
    u.check(r.error == "" and r.budget_reached and r.seconds < 2.0,
            "request 3: error %r, budget_reached %r, %.3f s" % (r.error, r.budget_reached, r.seconds))
for rid, needle in ((8, "time_budget: 0.001 s ran out while the request waited"), (4, "balls[1].pos: overlaps ball 0"), (5, "pocket: 'middle' is not a pocket"),
                    (6, "aim.ball: no object ball has id 9"), (7, "samples: 1000000")):
    if rid in replies:
        u.check(needle in replies[rid].error and replies[rid].num_shots == 0,
                "request %d: error %r lacks %r" % (rid, replies[rid].error, needle))
try:
    out, err = server.communicate(timeout=30)
except subprocess.TimeoutExpired:
    server.kill()
    out, err = server.communicate()
    u.check(False, "the server did not stop after its requests")
u.check(server.returncode == 0, "server exit %r: %s" % (server.returncode, err))
u.check("aim_request_t" in err, "the bad datagram was not reported: %r" % err)
print("pool-aim-server: %d requests answered (pool-aim's list, 9-ball legal, a tiny budget, 5 errors)"
      % len(replies), flush=True)
u.finish()
