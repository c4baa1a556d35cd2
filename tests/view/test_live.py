"""pool-view --live: the bridge from LCM to the page. Run inside a private network namespace
(tests/lcm/netns_run.sh): the LCM multicast and every connection stay on its loopback.

It serves the page at / and the stream at /stream and nothing else; keeps serving while clients
disconnect, reset, stall or send garbage; forwards a shot published by pool-sim --lcm-url exactly
(every event's after-states equal the result file's); a late client gets the current shot; and
the page in headless Chromium follows the stream to the shot's final positions.

    test_live.py --bin-dir BUILD/tools --source-dir REPO --types-dir BUILD/lcm_types/python
                 --work-dir DIR
"""
import argparse
import json
import os
import re
import shutil
import socket
import struct
import subprocess
import sys
import time
import unittest
import urllib.error
import urllib.request

ARGS = None
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608"

from websockets.sync.client import connect  # noqa: E402


def work(name):
    return os.path.join(ARGS.work_dir, name)




class LiveTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(ARGS.work_dir, exist_ok=True)
        cls.server = subprocess.Popen(
            [sys.executable, os.path.join(ARGS.source_dir, "tools", "pool-view"), "--live",
             "--port", "0", "--lcm-url", URL, "--types-dir", ARGS.types_dir],
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        line = cls.server.stderr.readline().decode()
        m = re.search(r"serving http://127\.0\.0\.1:(\d+)/", line)
        if not m:
            cls.server.kill()
            raise AssertionError("pool-view --live did not start: " + line)
        cls.port = int(m.group(1))
        cls.base = f"http://127.0.0.1:{cls.port}"
        rack = work("rack.json")
        r = subprocess.run([os.path.join(ARGS.bin_dir, "pool-rack"), "8ball", "--gap", "0",
                            "--speed", "8", "-o", rack], capture_output=True, timeout=60)
        assert r.returncode == 0, r.stderr
        cls.rack = rack

    @classmethod
    def tearDownClass(cls):
        cls.server.terminate()
        try:
            cls.server.wait(10)
        except subprocess.TimeoutExpired:
            cls.server.kill()
            cls.server.wait()
        cls.server.stderr.close()

    def alive(self):
        self.assertIsNone(self.server.poll(), "pool-view --live exited")
        with urllib.request.urlopen(self.base + "/", timeout=10) as r:
            self.assertEqual(r.status, 200)

    def publish_shot(self, name):
        """pool-sim --lcm-url on the rack; returns its result document."""
        out = work(name + ".json")
        r = subprocess.run([os.path.join(ARGS.bin_dir, "pool-sim"), self.rack, "--lcm-url", URL,
                            "-o", out], capture_output=True, timeout=60)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out, encoding="utf-8") as f:
            return json.load(f)

    @staticmethod
    def receive_shot(ws, timeout=30):
        """Messages until a "shot" one: (hello seen, table message, events, shot message)."""
        deadline = time.monotonic() + timeout
        hello, table, events = None, None, []
        while True:
            msg = json.loads(ws.recv(timeout=max(0.1, deadline - time.monotonic())))
            if msg["type"] == "hello":
                hello = msg
            elif msg["type"] == "table":
                table = msg
            elif msg["type"] == "event":
                events.append(msg)
            elif msg["type"] == "shot":
                return hello, table, events, msg

    def test_serves_only_the_page_and_the_stream(self):
        with urllib.request.urlopen(self.base + "/", timeout=10) as r:
            self.assertEqual(r.status, 200)
            self.assertIn("text/html", r.headers["Content-Type"])
            page = r.read().decode()
        self.assertIn('<script id="pool-data" type="application/json">null</script>', page)
        for path in ("/etc/passwd", "/../../etc/passwd", "/stream/../x", "/favicon.ico", "/index"):
            with self.subTest(path=path):
                with self.assertRaises(urllib.error.HTTPError) as cm:
                    urllib.request.urlopen(self.base + path, timeout=10)
                self.assertEqual(cm.exception.code, 404)
        # /stream without a websocket handshake is refused, not served.
        with self.assertRaises(urllib.error.HTTPError) as cm:
            urllib.request.urlopen(self.base + "/stream", timeout=10)
        self.assertGreaterEqual(cm.exception.code, 400)
        # The default address is this machine's loopback only.
        self.assertIn("--host", subprocess.run(
            [sys.executable, os.path.join(ARGS.source_dir, "tools", "pool-view"), "--help"],
            capture_output=True, text=True, timeout=30).stdout)

    def test_hostile_clients_and_a_shot_forwarded_exactly(self):
        hostile = []
        # Raw garbage on the TCP port, a half-sent request, a connection reset at once.
        for data in (b"\x00\xff" * 500 + b"\r\n\r\n", b"GET / HTTP/1.1\r\nHost: x", b"NOT HTTP\r\n\r\n"):
            s = socket.create_connection(("127.0.0.1", self.port), timeout=5)
            s.sendall(data)
            hostile.append(s)
        s = socket.create_connection(("127.0.0.1", self.port), timeout=5)
        s.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
        s.close()  # RST
        # A websocket client sending garbage (text, binary, too large): it is dropped or ignored.
        noisy = connect(f"ws://127.0.0.1:{self.port}/stream", open_timeout=10)
        noisy.send("garbage {not json")
        noisy.send(os.urandom(3000))
        try:
            noisy.send(b"x" * 100000)  # above the 4 KiB a client may send: the server closes it
        except Exception:
            pass
        # A client that never reads (its socket buffers fill), and one that leaves mid-stream.
        stalled = connect(f"ws://127.0.0.1:{self.port}/stream", open_timeout=10)
        stalled.socket.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
        leaving = connect(f"ws://127.0.0.1:{self.port}/stream", open_timeout=10)
        good = connect(f"ws://127.0.0.1:{self.port}/stream", open_timeout=10, max_size=None)
        leaving.socket.close()
        # Several shots through all of them: the good client gets each one whole.
        for k in range(6):
            result = self.publish_shot(f"shot{k}")
            hello, table, events, shot = self.receive_shot(good)
            if k == 0:
                self.assertEqual(hello["table"]["length"], 2.54)
                self.assertEqual(hello["params"]["mu_slide"], 0.2)
            # The shot's own table (POOL_TABLE) before its events, as pool-sim's result has it.
            self.assertIsNotNone(table)
            for key in ("table", "ball_radius", "params", "models"):
                self.assertEqual(table[key], result[key], key)
                self.assertEqual(shot["result"][key], result[key], key)
            self.assertEqual(table["table"]["pockets"], "jaws")
            # The events with their cushion parts (POOL_EVENT2), exactly the result's.
            self.assertTrue(any("part" in e for e in result["events"]))
            self.assertEqual([e["event"] for e in events], result["events"])
            self.assertEqual([e["seq"] for e in events], list(range(len(result["events"]))))
            self.assertEqual(shot["result"]["events"], result["events"])
            self.assertEqual(shot["result"]["final"], result["final"])
            self.assertEqual(shot["result"]["stats"]["stop_reason"], result["stats"]["stop_reason"])
            self.assertEqual(len({e["shot_id"] for e in events} | {shot["shot_id"], table["shot_id"]}), 1)
        self.alive()
        # A late client gets the last shot first.
        late = connect(f"ws://127.0.0.1:{self.port}/stream", open_timeout=10, max_size=None)
        hello, table, events, shot = self.receive_shot(late)
        self.assertIsNotNone(hello)
        self.assertIsNotNone(table)
        self.assertEqual(shot["result"]["events"], result["events"])
        for c in (late, good, noisy, stalled):
            try:
                c.close()
            except Exception:
                pass
        for s in hostile:
            s.close()
        self.alive()

    def test_first_shot_whole_when_lcm_is_slow_to_start(self):
        # The LCM thread imports lcm and the types before it subscribes; on a loaded machine that
        # took long enough for a client connected at "serving" to miss the first shot's table and
        # first events (3 failures in about 115 runs). Types that take a second to import make it
        # certain: the server announces itself only once it listens.
        slow = work("slow_types")
        shutil.rmtree(slow, ignore_errors=True)
        shutil.copytree(os.path.join(ARGS.types_dir, "pool_lcm"), os.path.join(slow, "pool_lcm"))
        init = os.path.join(slow, "pool_lcm", "__init__.py")
        with open(init, encoding="utf-8") as f:
            code = f.read()
        with open(init, "w", encoding="utf-8") as f:
            f.write("import time\ntime.sleep(1.0)\n" + code)
        server = subprocess.Popen(
            [sys.executable, os.path.join(ARGS.source_dir, "tools", "pool-view"), "--live",
             "--port", "0", "--lcm-url", URL, "--types-dir", slow],
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        try:
            line = server.stderr.readline().decode()
            m = re.search(r"serving http://127\.0\.0\.1:(\d+)/", line)
            self.assertIsNotNone(m, line)
            client = connect(f"ws://127.0.0.1:{m.group(1)}/stream", open_timeout=10, max_size=None)
            result = self.publish_shot("slow_start")
            hello, table, events, shot = self.receive_shot(client)
            self.assertIsNotNone(table)
            self.assertEqual([e["seq"] for e in events], list(range(len(result["events"]))))
            self.assertEqual(shot["result"]["events"], result["events"])
            client.close()
        finally:
            server.terminate()
            server.wait(10)
            server.stderr.close()

    def test_bad_lcm_url_is_refused(self):
        r = subprocess.run(
            [sys.executable, os.path.join(ARGS.source_dir, "tools", "pool-view"), "--live",
             "--port", "0", "--lcm-url", "nosuchprovider://x", "--types-dir", ARGS.types_dir],
            capture_output=True, text=True, timeout=60)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("pool-view: --lcm-url: nosuchprovider://x", r.stderr)

    def test_page_follows_the_stream(self):
        from browser import Browser
        with Browser() as b:
            b.open(self.base + "/")
            deadline = time.monotonic() + 20
            while not b.evaluate("document.getElementById('title').textContent.includes('live')"):
                self.assertLess(time.monotonic(), deadline, "the page did not connect")
                time.sleep(0.1)
            result = self.publish_shot("followed")
            expected = len(result["events"])
            deadline = time.monotonic() + 30
            while b.evaluate("poolView.view ? poolView.view.shot.events.length : 0") != expected \
                    or b.evaluate("poolView.view.shot.final.length") == 0:
                self.assertLess(time.monotonic(), deadline, "the page did not get the shot")
                time.sleep(0.1)
            end = result["stats"]["end_time"]
            drawn = b.evaluate("poolView.seek(%r); [...document.querySelectorAll('circle.ball')]"
                               ".map(c => [+c.dataset.id, +c.getAttribute('cx'), "
                               "+c.getAttribute('cy')])" % end)
            final = {f["id"]: f["pos"] for f in result["final"]}
            self.assertEqual(len(drawn), len(final))
            for bid, x, y in drawn:
                self.assertEqual([x, y], final[bid][:2], f"ball {bid}")
            # Drawn on the shot's own table: its pockets' jaws and facings (pockets "jaws").
            self.assertEqual(b.evaluate("document.querySelectorAll('.jaw').length"), 12)
            self.assertEqual(b.evaluate("document.querySelectorAll('.facing').length"), 12)
            self.assertEqual(b.errors, [])


def main():
    global ARGS
    p = argparse.ArgumentParser()
    p.add_argument("--bin-dir", required=True)
    p.add_argument("--source-dir", required=True)
    p.add_argument("--types-dir", required=True)
    p.add_argument("--work-dir", required=True)
    ARGS, rest = p.parse_known_args()
    from browser import chromium_path
    if chromium_path() is None:
        print("SKIP: chromium is not installed (tools/setup.sh installs it)", file=sys.stderr)
        return 77
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False, verbosity=2)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
