"""Prints every event of the next shot on POOL_EVENT, then the shot from POOL_SHOT, and exits.
usage: python event_subscriber.py [TYPES_DIR]   (default build/release/lcm_types/python)"""
import sys

import lcm

sys.path.insert(0, sys.argv[1] if len(sys.argv) > 1 else "build/release/lcm_types/python")
from pool_lcm import event_t, shot_t  # noqa: E402

lc = lcm.LCM("udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608")
shots = []


def on_event(channel, data):
    e = event_t.decode(data)
    print("event seq=%d t=%.6f %s balls=%s" % (e.seq, e.t, e.type, [b.id for b in e.balls]))


def on_shot(channel, data):
    s = shot_t.decode(data)
    print("shot %d: %d events" % (s.shot_id, s.num_events))
    shots.append(s)


# liblcm keeps at most 30 received messages per subscription until handle() takes them, and
# drops the rest without a word; pool-sim publishes a shot's events in one burst: raise the limit.
lc.subscribe("POOL_EVENT", on_event).set_queue_capacity(10000)
lc.subscribe("POOL_SHOT", on_shot).set_queue_capacity(100)
while not shots:
    lc.handle()
