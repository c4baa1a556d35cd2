"""A shot logged by lcm-logger replays with lcm-logplayer to the same messages, byte for byte,
on the same channels and in the same order; the log file itself holds them too."""
import os
import signal
import subprocess
import time

import lcm_test_util as u

args = u.parse_args()
import lcm  # noqa: E402
from pool_lcm import shot_t  # noqa: E402

log = os.path.join(args.work_dir, "shot.lcmlog")
if os.path.exists(log):
    os.remove(log)
# A bank shot: 8 events, 19 messages with the table, the event pairs and the shot pair. lcm-logger
# 1.3.1 keeps liblcm's default of 30 received messages per subscription until its loop takes them
# and drops the rest: under load it lost part of a 21-event cut's 45 (docs/lcm.md "Logging").
scenario = os.path.join(args.data_dir, "bank.json")
want = u.pool_sim_json(args.bin_dir, scenario, args.work_dir)

# Record: the logger and a live capture both listen while pool-sim publishes.
listeners = len(u.udp_sockets())
logger = subprocess.Popen(["lcm-logger", "-q", "-f", "--lcm-url=" + u.URL, log])
u.wait_for_listeners(listeners + 1)  # lcm-logger prints nothing when it is ready
CHANNELS = ["POOL_TABLE", "POOL_EVENT", "POOL_EVENT2", "POOL_SHOT", "POOL_SHOT2"]
live = u.Collector(u.URL, CHANNELS)
u.wait_for_listeners(listeners + 2)
subprocess.run([os.path.join(args.bin_dir, "pool-sim"), scenario, "--lcm-url", u.URL, "-o",
                os.path.join(args.work_dir, "logged.json")], check=True, timeout=60)
original = live.collect_until(lambda m: any(ch == "POOL_SHOT2" for ch, _ in m), 10)
live.close()
u.wait_until_drained()  # the logger has read every datagram; it writes them out on SIGINT
time.sleep(0.1)
logger.send_signal(signal.SIGINT)
logger.wait(timeout=5)
u.check(len(original) == 2 * len(want["events"]) + 3,
        "live capture: %d messages, expected the table, %d events on POOL_EVENT and POOL_EVENT2, and "
        "the shot on POOL_SHOT and POOL_SHOT2" % (len(original), len(want["events"])))

# The log file holds exactly those messages, besides the LCM_SELF_TEST datagram liblcm sends
# when a udpm:// instance starts (here the live capture's, when the logger is already listening).
logged_all = [(e.channel, e.data) for e in lcm.EventLog(log, "r")]
logged = [m for m in logged_all if m[0] != "LCM_SELF_TEST"]
u.check(logged == original, "log file: %d messages (%s), differ from the live capture" % (
    len(logged), sorted({ch for ch, _ in logged_all})))

# Replay at 10x and capture again.
replayed_capture = u.Collector(u.URL, CHANNELS)
player = subprocess.run(["lcm-logplayer", "-s", "10", "--lcm-url=" + u.URL, log], timeout=60,
                        capture_output=True, text=True)
u.check(player.returncode == 0, "lcm-logplayer exit %d: %s" % (player.returncode, player.stderr))
replayed = replayed_capture.collect_until(lambda m: len(m) >= len(original), 10)
replayed_capture.close()
u.check(replayed == original, "replay: %d messages, differ from the original %d" % (
    len(replayed), len(original)))
shots = [data for ch, data in replayed if ch == "POOL_SHOT"]
if shots:
    shot = shot_t.decode(shots[-1])
    u.check([u.event_json(e) for e in shot.events] == u.lcm_events(want["events"]),
            "replayed shot differs from pool-sim's result")
print("logged and replayed %d messages" % len(replayed))
u.finish()
