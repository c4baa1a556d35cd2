"""The table and the cushion's parts on LCM (issue 20). pool-sim --lcm-url publishes the shot's
table (table_t) on POOL_TABLE before its first event, every event on POOL_EVENT and right after it
with its part (event2_t, embedding the same event_t byte for byte) on POOL_EVENT2, and the shot2_t
on POOL_SHOT2 with one part per event and the table; pool-shot-server's shot2_t answers carry the
same, and an error answer neither. Everything equals pool-sim's result file for the scenario: a
slow ball rattling in a corner of the WPA table (jaws) and a carom shot (pockets "none")."""
import json
import math
import os
import signal
import subprocess

import lcm_test_util as u

args = u.parse_args()
import lcm  # noqa: E402
from pool_lcm import event2_t, event_t, shot2_t, shot_t, table_t  # noqa: E402

CAROM = {"format": "libpool-scenario/1", "table": "carom",
         "balls": [{"id": 0, "pos": [0.71, 0.528]}, {"id": 1, "pos": [0.71, 0.71]}, {"id": 2, "pos": [2.13, 0.71]}],
         "strike": {"ball": 0, "speed": 3.0, "phi": 20.0}}
carom_path = os.path.join(args.work_dir, "carom.json")
with open(carom_path, "w") as f:
    json.dump(CAROM, f)
scenarios = {"rattle": os.path.join(args.data_dir, "rattle.json"), "carom": carom_path}
want = {name: u.pool_sim_json(args.bin_dir, path, args.work_dir) for name, path in scenarios.items()}
u.check(any(e.get("part") == "jaw" for e in want["rattle"]["events"]), "rattle: no jaw in pool-sim's result")
u.check(any(e.get("part") == "nose" for e in want["carom"]["events"]), "carom: no cushion in pool-sim's result")

FIELDS = ("length", "width", "cushion_height", "corner_mouth", "side_mouth", "corner_cut_angle", "side_cut_angle",
          "corner_jaw_radius", "side_jaw_radius", "corner_shelf", "side_shelf", "corner_hole_radius",
          "side_hole_radius")


def check_table(t, result, label):
    """table_t against the result file's "table" and "ball_radius" (geometry only with jaws)."""
    table = result["table"]
    u.check(t.pockets == table["pockets"], "%s: pockets %r, pool-sim %r" % (label, t.pockets, table["pockets"]))
    for name in FIELDS:
        value = getattr(t, name)
        expected = table.get(name, 0.0)
        u.check(value == expected, "%s: table.%s %r, pool-sim %r" % (label, name, value, expected))
    u.check(t.ball_radius == result["ball_radius"], "%s: ball_radius %r" % (label, t.ball_radius))
    setup = json.loads(t.json)
    u.check({k: setup[k] for k in ("table", "ball_radius", "params", "models")} ==
            {k: result[k] for k in ("table", "ball_radius", "params", "models")},
            "%s: table_t.json %s differs from the result's setup" % (label, t.json))


def parts(result):
    return [e.get("part", "") for e in result["events"]]


# ---- pool-sim --lcm-url: the live stream
for name, path in scenarios.items():
    live = u.Collector(u.URL, ["POOL_TABLE", "POOL_EVENT", "POOL_EVENT2", "POOL_SHOT", "POOL_SHOT2"])
    p = subprocess.run([os.path.join(args.bin_dir, "pool-sim"), path, "--lcm-url", u.URL, "-o", os.devnull],
                       capture_output=True, text=True, timeout=60)
    u.check(p.returncode == 0, "%s: pool-sim --lcm-url: %s" % (name, p.stderr))
    msgs = live.collect_until(lambda m: any(ch == "POOL_SHOT2" for ch, _ in m), 20)
    live.close()
    channels = [ch for ch, _ in msgs]
    n = len(want[name]["events"])
    u.check(channels == ["POOL_TABLE"] + ["POOL_EVENT", "POOL_EVENT2"] * n + ["POOL_SHOT", "POOL_SHOT2"],
            "%s: published %d messages on %s, expected the table, %d event pairs and the shot pair"
            % (name, len(msgs), sorted(set(channels)), n))
    if channels[:1] != ["POOL_TABLE"] or len(msgs) != 2 * n + 3:
        continue
    table = table_t.decode(msgs[0][1])
    events = [event_t.decode(d) for ch, d in msgs if ch == "POOL_EVENT"]
    events2 = [event2_t.decode(d) for ch, d in msgs if ch == "POOL_EVENT2"]
    raw_events = [d for ch, d in msgs if ch == "POOL_EVENT"]
    shot = shot_t.decode(msgs[-2][1])
    two = shot2_t.decode(msgs[-1][1])
    check_table(table, want[name], name + " POOL_TABLE")
    u.check(table.shot_id == shot.shot_id == events[0].shot_id, "%s: the table's shot_id %d, the shot's %d"
            % (name, table.shot_id, shot.shot_id))
    u.check(all(e2.event.encode()[8:] == raw[8:] for e2, raw in zip(events2, raw_events)),
            "%s: event2_t.event differs from the event_t published before it" % name)
    u.check([e2.part for e2 in events2] == parts(want[name]), "%s: POOL_EVENT2 parts %r, pool-sim %r"
            % (name, [e2.part for e2 in events2], parts(want[name])))
    u.check(two.shot.encode() == msgs[-2][1], "%s: shot2_t.shot differs from shot_t" % name)
    u.check(list(two.event_parts) == parts(want[name]), "%s: shot2_t.event_parts %r" % (name, list(two.event_parts)))
    u.check(two.has_table, "%s: shot2_t without its table" % name)
    check_table(two.table, want[name], name + " shot2_t.table")

# ---- pool-shot-server: the answers
server = subprocess.Popen([os.path.join(args.bin_dir, "pool-shot-server"), "--lcm-url", u.URL],
                          stderr=subprocess.PIPE, text=True)
u.wait_for_line(server, "ready")
answers = u.Collector(u.URL, ["POOL_SHOT2"])
client = lcm.LCM(u.URL)
requests = {1: "rattle", 2: "carom"}
for rid, name in requests.items():
    with open(scenarios[name]) as f:
        u.publish_request(client, rid, f.read())
u.publish_request(client, 3, json.dumps(dict(CAROM, table={"preset": "carom", "pockets": "pockets"})))
twos = {}
for _, data in answers.collect_until(lambda m: len(m) >= 3, 30):
    s = shot2_t.decode(data)
    twos[s.shot.request_id] = s
answers.close()
u.check(sorted(twos) == [1, 2, 3], "pool-shot-server answered %r on POOL_SHOT2" % sorted(twos))
for rid, name in requests.items():
    if rid in twos:
        u.check(list(twos[rid].event_parts) == parts(want[name]), "request %d (%s): event_parts" % (rid, name))
        u.check(twos[rid].has_table, "request %d (%s): no table" % (rid, name))
        check_table(twos[rid].table, want[name], "request %d (%s)" % (rid, name))
if 3 in twos:
    u.check(twos[3].shot.error.startswith("table.pockets") and not twos[3].has_table and twos[3].num_event_parts == 0,
            "bad table: error %r, has_table %r" % (twos[3].shot.error, twos[3].has_table))
server.send_signal(signal.SIGTERM)
try:
    server.communicate(timeout=5)
except subprocess.TimeoutExpired:
    server.kill()
    server.communicate()
    u.check(False, "server ignored SIGTERM")
print("table_t on POOL_TABLE before the events, event2_t with the parts on POOL_EVENT2, shot2_t with the parts and "
      "the table from pool-sim --lcm-url and pool-shot-server, equal to pool-sim's result (jaws and carom)", flush=True)
u.finish()
