#!/usr/bin/env python3
"""Example LCM subscriber for libpool: prints events (POOL_EVENT) and shots (POOL_SHOT, or
POOL_SHOT2 with --json).

Uses the PyPI `lcm` package and the Python types lcm-gen writes at build time into
BUILD/lcm_types/python (package pool_lcm). Run it with the project's venv:

    .venv/bin/python tools/pool_lcm_subscribe.py --lcm-url 'udpm://239.255.76.67:7667?ttl=0'
    .venv/bin/python tools/pool_lcm_subscribe.py --json --count 1 > shot.json

Text mode prints one line per event and per shot. --json prints each shot (from POOL_SHOT2: the
shot with its cushion parts and table), one per line, as a libpool-result/1 document (the shape
`pool-sim -o` writes: table, ball_radius, params, models, events with their parts, final, stats)
plus an "lcm" object with shot_id, request_id and utime, and "error" when the shot carries one.
"""
import argparse
import glob
import json
import os
import sys
import time

STATE_NAMES = ["stationary", "spinning", "sliding", "rolling", "airborne", "linked",
               "pocketed", "off_table"]
EVENT_TYPES = ["strike", "slide_roll", "roll_stop", "spin_stop", "ball_ball", "ball_cushion",
               "ball_table", "pocket", "off_table", "link_begin", "link_step", "link_end"]
DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608"


def find_types_dir(explicit):
    """The directory holding the generated pool_lcm package."""
    if explicit:
        candidates = [explicit]
    else:
        root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
        candidates = [os.environ.get("POOL_LCM_TYPES_DIR", "")]
        candidates += [os.path.join(root, "build", "release", "lcm_types", "python")]
        candidates += sorted(glob.glob(os.path.join(root, "build", "*", "lcm_types", "python")))
        candidates += sorted(glob.glob(os.path.join(root, "build*", "lcm_types", "python")))
    for c in candidates:
        if c and os.path.isfile(os.path.join(c, "pool_lcm", "shot_t.py")):
            return c
    sys.exit("pool_lcm_subscribe: generated Python types not found (build the project, or pass "
             "--types-dir BUILD/lcm_types/python); looked in: " + ", ".join(c for c in candidates if c))


def ball_json(b):
    """A ball_state_t as a result-file ball object."""
    state = STATE_NAMES[b.state] if 0 <= b.state < len(STATE_NAMES) else str(b.state)
    return {"id": b.id, "pos": list(b.pos), "vel": list(b.vel), "omega": list(b.omega),
            "state": state}


def event_json(e, part=""):
    """An event_t as a result-file event object (part: the cushion's, from event2_t or shot2_t)."""
    out = {"t": e.t, "type": e.type, "balls": [b.id for b in e.balls]}
    if e.rail:
        out["rail"] = e.rail
    if part:
        out["part"] = part
    if e.pocket:
        out["pocket"] = e.pocket
    out["after"] = [ball_json(b) for b in e.balls]
    return out


def shot2_json(s2):
    """A shot2_t as a libpool-result/1 document: shot_json's, with the table's setup first and
    each event's cushion part."""
    doc = shot_json(s2.shot, list(s2.event_parts) if s2.num_event_parts == s2.shot.num_events else None)
    if s2.has_table:
        try:
            setup = json.loads(s2.table.json)
        except ValueError:
            setup = {}
        doc = dict({k: setup[k] for k in ("table", "ball_radius", "params", "models") if k in setup}, **doc)
    return doc


def shot_json(s, parts=None):
    """A shot_t as a libpool-result/1 document (parts: one per event, as shot2_t carries them)."""
    counts = {}
    for e in s.events:
        counts[e.type] = counts.get(e.type, 0) + 1
    ordered = {t: counts[t] for t in EVENT_TYPES if t in counts}
    ordered.update({t: n for t, n in counts.items() if t not in ordered})
    doc = {
        "format": "libpool-result/1",
        "events": [event_json(e, parts[i] if parts else "") for i, e in enumerate(s.events)],
        "final": [ball_json(b) for b in s.final_states],
        "stats": {
            "events": s.num_events,
            "sim_time": s.sim_time,
            "stop_reason": s.stop_reason,
            "balls": s.num_balls,
            "event_counts": ordered,
            "pocketed": [b.id for b in s.final_states if b.state == 6],
            "off_table": [b.id for b in s.final_states if b.state == 7],
        },
        "lcm": {"shot_id": s.shot_id, "request_id": s.request_id, "utime": s.utime},
    }
    if s.error:
        doc["error"] = s.error
    return doc


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--lcm-url", default=None,
                        help="LCM provider (default $LCM_DEFAULT_URL, else " + DEFAULT_URL + ")")
    parser.add_argument("--types-dir", default=None,
                        help="directory holding the generated pool_lcm package "
                             "(default: $POOL_LCM_TYPES_DIR, else build/*/lcm_types/python)")
    parser.add_argument("--count", type=int, default=0,
                        help="exit after N shots (0: run until interrupted)")
    parser.add_argument("--json", action="store_true",
                        help="print each shot as libpool-result/1 JSON, one per line (no events)")
    parser.add_argument("--timeout", type=float, default=0.0,
                        help="exit with status 1 when nothing arrived for S seconds")
    args = parser.parse_args()

    sys.path.insert(0, find_types_dir(args.types_dir))
    import lcm
    from pool_lcm import event_t, shot2_t, shot_t

    url = args.lcm_url or os.environ.get("LCM_DEFAULT_URL") or DEFAULT_URL
    lc = lcm.LCM(url)
    shots = []

    def on_event(channel, data):
        e = event_t.decode(data)
        extra = (" rail=" + e.rail if e.rail else "") + (" pocket=" + e.pocket if e.pocket else "")
        print("event shot=%d seq=%d t=%r %s balls=%s%s" % (
            e.shot_id, e.seq, e.t, e.type, ",".join(str(b.id) for b in e.balls), extra),
            flush=True)

    def on_shot(channel, data):
        if args.json:
            s2 = shot2_t.decode(data)
            shots.append(s2.shot.shot_id)
            print(json.dumps(shot2_json(s2)), flush=True)
            return
        s = shot_t.decode(data)
        shots.append(s.shot_id)
        err = ' error="%s"' % s.error if s.error else ""
        print("shot shot=%d request=%d events=%d balls=%d sim_time=%r stop=%s%s" % (
            s.shot_id, s.request_id, s.num_events, s.num_balls, s.sim_time,
            s.stop_reason or "-", err), flush=True)

    subs = [lc.subscribe("POOL_SHOT2" if args.json else "POOL_SHOT", on_shot)]
    if not args.json:
        subs.append(lc.subscribe("POOL_EVENT", on_event))
    # liblcm keeps at most 30 received messages per subscription until handle() takes them and
    # drops the rest silently; pool-sim publishes a shot's events in one burst.
    for sub in subs:
        sub.set_queue_capacity(10000)
    # Tests wait for this line before publishing.
    print("pool_lcm_subscribe: subscribed on " + url, file=sys.stderr, flush=True)

    last = time.monotonic()
    try:
        while args.count == 0 or len(shots) < args.count:
            if lc.handle_timeout(100) > 0:
                last = time.monotonic()
            elif args.timeout > 0 and time.monotonic() - last > args.timeout:
                print("pool_lcm_subscribe: nothing received for %g s" % args.timeout,
                      file=sys.stderr)
                return 1
    except KeyboardInterrupt:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
