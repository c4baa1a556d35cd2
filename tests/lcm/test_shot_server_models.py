"""The models (issues 12 and 25) travel in a shot request's scenario_json and reach the
simulation in pool-shot-server: a request with "models" (and the model parameters) is answered
with exactly pool-sim's result for the same scenario, whose result says which models made it, and
which differs from the default models' answer; bad models are answered with error set, naming the
field."""
import copy
import json
import os
import signal
import subprocess

import lcm_test_util as u

args = u.parse_args()
import lcm  # noqa: E402
from pool_lcm import shot_t  # noqa: E402

MODELS = {"cushion": "mathavan2010", "ball_ball_friction": "alciatore", "squirt": "endmass"}
# A cut with side whose balls go on into cushions: each of the three models changes it (squirt the
# cue ball's launch, the friction law the throw, the cushion law every rebound).
BASE = {"format": "libpool-scenario/1",
        "params": {"throw_a": 0.012, "cue_end_mass": 0.1},
        "balls": [{"id": 0, "pos": [1.0, 0.5]}, {"id": 1, "pos": [1.5, 0.62]}],
        "strike": {"ball": 0, "speed": 2.2, "phi": 12.0, "theta": 0.0, "a": 0.011, "b": -0.004}}


def with_models(models):
    doc = copy.deepcopy(BASE)
    if models is not None:
        doc["models"] = models
    return doc


shots = {"models": with_models(MODELS), "default": with_models(None),
         "cushion_only": with_models({"cushion": "petit"}), "thesis": with_models("thesis")}
want = {}
for name, doc in shots.items():
    path = os.path.join(args.work_dir, name + ".json")
    with open(path, "w") as f:
        json.dump(doc, f)
    want[name] = u.pool_sim_json(args.bin_dir, path, args.work_dir)
u.check(want["models"].get("models") == MODELS,
        "pool-sim's result does not carry the models: %r" % want["models"].get("models"))

server = subprocess.Popen([os.path.join(args.bin_dir, "pool-shot-server"), "--lcm-url", u.URL],
                          stderr=subprocess.PIPE, text=True)
u.wait_for_line(server, "ready")
answers = u.Collector(u.URL, ["POOL_SHOT"])
client = lcm.LCM(u.URL)

u.check(want["thesis"].get("models") == {"cushion": "petit", "ball_ball_friction": "constant",
                                         "squirt": "none"},
        "pool-sim's thesis result: models %r" % want["thesis"].get("models"))

ids = {"models": 1, "default": 2, "cushion_only": 3, "thesis": 4}
bad = {11: ({"cushion": "rubber"}, 'models.cushion: unknown model "rubber" (petit, mathavan2010)'),
       12: ({"spin": "none"}, "models.spin: unknown field"),
       13: ("mathavan2010", 'models: unknown model set "mathavan2010" (default, thesis)'),
       14: (["thesis"], "models: must be a model set name or an object")}
for name, rid in ids.items():
    u.publish_request(client, rid, json.dumps(shots[name]))
for rid, (models, _) in bad.items():
    u.publish_request(client, rid, json.dumps(with_models(models)))

expected = len(ids) + len(bad)
got = {}
for _, data in answers.collect_until(lambda m: len(m) >= expected, 30):
    s = shot_t.decode(data)
    got[s.request_id] = s
u.check(sorted(got) == sorted(list(ids.values()) + list(bad)),
        "answered %r" % sorted(got))

for name, rid in ids.items():
    if rid in got:
        u.check(got[rid].error == "", "%s: error %r" % (name, got[rid].error))
        u.compare_result(u.shot_json(got[rid]), want[name], "request %d (%s)" % (rid, name))
# The models changed the shot: the answers are not the default one's (so they were not dropped on
# the way, which the equality with pool-sim alone would not show if pool-sim dropped them too).
if all(rid in got for rid in ids.values()):
    default_final = u.shot_json(got[ids["default"]])["final"]
    for name in ("models", "cushion_only", "thesis"):
        u.check(u.shot_json(got[ids[name]])["final"] != default_final,
                "%s: the same final states as the default models" % name)
for rid, (_, message) in bad.items():
    if rid in got:
        s = got[rid]
        u.check(s.error == message and s.num_events == 0 and s.num_balls == 0,
                "bad request %d: error %r (want %r), %d events" % (rid, s.error, message,
                                                                  s.num_events))
print("models reached the simulation through %d requests; %d bad ones refused naming the field"
      % (len(ids), len(bad)), flush=True)

answers.close()
server.send_signal(signal.SIGTERM)
try:
    server.communicate(timeout=5)
except subprocess.TimeoutExpired:
    server.kill()
    server.communicate()
    u.check(False, "server ignored SIGTERM")
u.check(server.returncode == 0, "server exit status %r" % server.returncode)
u.finish()
