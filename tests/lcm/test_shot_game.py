"""The rules' verdict on LCM (issue 22): beside every shot_t on POOL_SHOT, pool-shot-server and
pool-sim --lcm-url publish a shot2_t on POOL_SHOT2 carrying the same shot (byte for byte) and, when
the scenario has a "game", the verdict: its fields and game_json equal pool-sim's "game" for the
same scenario. A request without a game gets an empty game; a bad game is answered with the error
naming the field, on both channels. shot_t is unchanged, so old subscribers see what they saw."""
import json
import os
import signal
import subprocess

import lcm_test_util as u

args = u.parse_args()
import lcm  # noqa: E402
from pool_lcm import shot2_t, shot_t  # noqa: E402

R = 0.028575
GAME = {"format": "libpool-scenario/1",
        "balls": [{"id": 0, "pos": [2.1, 0.95]}, {"id": 3, "pos": [2.3, 1.1]}, {"id": 1, "pos": [0.3, 0.3]},
                  {"id": 9, "pos": [1.2, 0.4]}],
        "strike": {"ball": 0, "speed": 1.5, "phi": 36.87, "b": -0.3 * R},
        "game": {"rules": "9ball", "state": {"fouls": 1}}}
PLAIN = dict(GAME)
del PLAIN["game"]
LEGAL = dict(GAME, strike={"ball": 0, "speed": 2.0, "phi": 205.0}, game={"rules": "9ball"})
shots = {1: GAME, 2: PLAIN, 3: LEGAL}
want = {}
for rid, doc in shots.items():
    path = os.path.join(args.work_dir, "shot%d.json" % rid)
    with open(path, "w") as f:
        json.dump(doc, f)
    want[rid] = u.pool_sim_json(args.bin_dir, path, args.work_dir)
BAD = dict(GAME, game={"rules": "9ball", "state": {"fouls": 5}})
BAD_MESSAGE = "game.state.fouls: must be 0, 1 or 2 (a third consecutive foul loses the rack)"


def check_game(msg, result, label):
    g = result.get("game")
    if g is None:
        u.check(msg.game_rules == "" and msg.game_json == "" and msg.game_num_fouls == 0,
                "%s: a game in a shot without one" % label)
        return
    u.check(json.loads(msg.game_json) == g, "%s: game_json %s, pool-sim %s" % (label, msg.game_json, g))
    u.check((msg.game_rules, msg.game_legal, list(msg.game_fouls), msg.game_outcome, msg.game_reason,
             msg.game_ball_in_hand, msg.game_points, msg.game_rails_after_contact, list(msg.game_pocketed))
            == (g["rules"], g["legal"], g["fouls"], g["outcome"], g["reason"], g["ball_in_hand"], g["points"],
                g["rails_after_contact"], g["pocketed"]), "%s: the game fields differ from %s" % (label, g))
    u.check(msg.game_has_first_hit == (g["first_hit"] is not None)
            and (g["first_hit"] is None or msg.game_first_hit == g["first_hit"]), "%s: first_hit" % label)


server = subprocess.Popen([os.path.join(args.bin_dir, "pool-shot-server"), "--lcm-url", u.URL],
                          stderr=subprocess.PIPE, text=True)
u.wait_for_line(server, "ready")
answers = u.Collector(u.URL, ["POOL_SHOT", "POOL_SHOT2"])
client = lcm.LCM(u.URL)
for rid, doc in shots.items():
    u.publish_request(client, rid, json.dumps(doc))
u.publish_request(client, 4, json.dumps(BAD))
ones, twos = {}, {}
for channel, data in answers.collect_until(lambda m: len(m) >= 8, 30):
    if channel == "POOL_SHOT":
        s = shot_t.decode(data)
        ones[s.request_id] = s
    else:
        s = shot2_t.decode(data)
        twos[s.shot.request_id] = s
u.check(sorted(ones) == sorted(twos) == [1, 2, 3, 4], "answered %r on POOL_SHOT, %r on POOL_SHOT2"
        % (sorted(ones), sorted(twos)))
for rid in shots:
    if rid in ones and rid in twos:
        u.check(twos[rid].shot.encode() == ones[rid].encode(), "request %d: shot2_t.shot differs from shot_t" % rid)
        u.compare_result(u.shot_json(ones[rid]), want[rid], "request %d" % rid)
        check_game(twos[rid], want[rid], "request %d" % rid)
if 4 in ones and 4 in twos:
    u.check(ones[4].error == BAD_MESSAGE and twos[4].shot.error == BAD_MESSAGE and twos[4].game_rules == "",
            "bad game: %r / %r" % (ones[4].error, twos[4].shot.error))
answers.close()
server.send_signal(signal.SIGTERM)
try:
    server.communicate(timeout=5)
except subprocess.TimeoutExpired:
    server.kill()
    server.communicate()
    u.check(False, "server ignored SIGTERM")
u.check(server.returncode == 0, "server exit status %r" % server.returncode)

# pool-sim --lcm-url: the same pair for its shot.
listen = u.Collector(u.URL, ["POOL_SHOT", "POOL_SHOT2"])
path = os.path.join(args.work_dir, "shot1.json")
p = subprocess.run([os.path.join(args.bin_dir, "pool-sim"), path, "--lcm-url", u.URL, "-o", os.devnull],
                   capture_output=True, text=True, timeout=60)
u.check(p.returncode == 0, "pool-sim --lcm-url: %s" % p.stderr)
got = dict(listen.collect_until(lambda m: len(m) >= 2, 20))
listen.close()
u.check(set(got) == {"POOL_SHOT", "POOL_SHOT2"}, "pool-sim published on %r" % sorted(got))
if "POOL_SHOT2" in got:
    two = shot2_t.decode(got["POOL_SHOT2"])
    check_game(two, want[1], "pool-sim --lcm-url")
    u.check(two.shot.encode() == got["POOL_SHOT"], "pool-sim: shot2_t.shot differs from shot_t")
print("shot2_t beside shot_t: %d answers with the game equal to pool-sim's, a shot without a game, "
      "a bad game refused naming the field, pool-sim --lcm-url" % len(shots), flush=True)
u.finish()
