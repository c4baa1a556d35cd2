"""pool-view in a real browser: headless Chromium loads pages written by pool-view and by
pool-sim --view, steps to given times and reads the drawn balls back from the SVG; every
position must be pool_sim_state_at's (through the Python binding) at that time, bit for bit: the
page evaluates libpool's closed forms with the same arithmetic (tools/view/pool_view.html).

    test_view.py --bin-dir BUILD/tools --source-dir REPO --work-dir DIR
"""
import argparse
import json
import os
import subprocess
import sys
import unittest

ARGS = None
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from browser import Browser, chromium_path  # noqa: E402

# The drawn state of every ball: id, cx, cy, data-z, data-state, visible, side-view cy.
READ_BALLS = """[...document.querySelectorAll("circle.ball")].map(c => {
  const side = document.querySelector('circle.side-ball[data-id="' + c.dataset.id + '"]');
  return [+c.dataset.id, +c.getAttribute("cx"), +c.getAttribute("cy"), +c.dataset.z,
          c.dataset.state, c.parentNode.getAttribute("visibility") !== "hidden",
          side ? +side.getAttribute("cy") : null];
})"""


def run(*args, **kw):
    return subprocess.run(args, capture_output=True, timeout=120, **kw)


def work(name):
    return os.path.join(ARGS.work_dir, name)


def tool(name):
    return os.path.join(ARGS.bin_dir, name)


def pool_view(*args):
    return run(sys.executable, os.path.join(ARGS.source_dir, "tools", "pool-view"), *args)


def reference_sim(scenario):
    """The shot of a scenario file simulated through the Python binding: the oracle."""
    import libpool
    import libpool.batch
    lay = libpool.batch.load_layout(scenario)
    d = lay.sim_def
    sim = libpool.Sim(table=d.table, params=d.params, max_time=d.max_time,
                      max_events=d.max_events, airborne=d.airborne, models=d.models)
    for b in lay.balls:
        sim.add_ball(b.id, tuple(b.pos), tuple(b.vel), tuple(b.omega))
    if lay.strike is not None:
        sim.strike(lay.strike_ball, *lay.strike)
    sim.run()
    return sim


def page_of(scenario, name):
    """(pool-sim --view page, pool-view page of the same result): both paths."""
    result, page = work(name + ".json"), work(name + ".html")
    r = run(tool("pool-sim"), scenario, "-o", result, "--view", page)
    assert r.returncode == 0, r.stderr
    second = work(name + ".pool-view.html")
    r = pool_view(result, "-o", second)
    assert r.returncode == 0, r.stderr
    return result, page, second


class ViewTest(unittest.TestCase):
    browser = None

    @classmethod
    def setUpClass(cls):
        os.makedirs(ARGS.work_dir, exist_ok=True)
        rack = work("break_scenario.json")
        r = run(tool("pool-rack"), "8ball", "--gap", "0", "--speed", "8", "-o", rack)
        assert r.returncode == 0, r.stderr
        cls.scenes = {
            "break": rack,  # 184 events, balls pocketed
            "jump": os.path.join(ARGS.source_dir, "compare/scenarios/airborne/jump.json"),
            # LINK steps, a ball resting on two others, no strike: the initial states matter.
            "rest_on_two": os.path.join(ARGS.source_dir, "compare/scenarios/link/rest_on_two.json"),
            # Cut at max_time while balls fly and roll.
            "airborne_break": os.path.join(ARGS.source_dir,
                                           "compare/scenarios/link/airborne_break.json"),
        }
        cls.browser = Browser()

    @classmethod
    def tearDownClass(cls):
        if cls.browser:
            cls.browser.close()

    def load(self, page):
        self.browser.errors = []
        self.browser.open("file://" + os.path.abspath(page))
        self.assertTrue(self.browser.evaluate("poolView.ready"))

    def drawn_at(self, times):
        expr = "(%s).map(t => { poolView.seek(t); return %s; })" % (json.dumps(times), READ_BALLS)
        return self.browser.evaluate(expr)

    def test_drawn_positions_are_state_at(self):
        for name, scenario in self.scenes.items():
            with self.subTest(scene=name):
                result, page, second = page_of(scenario, name)
                with open(page, "rb") as a, open(second, "rb") as b:
                    self.assertEqual(a.read(), b.read(), "pool-view and pool-sim --view differ")
                sim = reference_sim(scenario)
                end = sim.end_time
                events = sim.events
                # Every event time, halfway between events, a regular grid, and the end.
                times = sorted({e.time for e in events}
                               | {(a.time + b.time) / 2 for a, b in zip(events, events[1:])}
                               | {end * k / 61 for k in range(62)})
                self.load(page)
                self.assertEqual(self.browser.evaluate("poolView.endTime()"), end)
                drawn = self.drawn_at(times)
                airborne = False
                for t, balls in zip(times, drawn):
                    ref = sim.state_at(t)
                    self.assertEqual([b[0] for b in balls], [r.id for r in ref])
                    for (bid, x, y, z, state, visible, side_z), r in zip(balls, ref):
                        where = f"{name}: ball {bid} at t = {t!r}"
                        self.assertEqual((x, y, z), r.pos, where)
                        self.assertEqual(state, r.motion, where)
                        self.assertEqual(visible, r.motion not in ("pocketed", "off_table"), where)
                        if side_z is not None:
                            self.assertEqual(side_z, r.pos[2], where)
                        airborne |= r.motion == "airborne"
                # The side view exists exactly for shots that leave the cloth.
                has_side = self.browser.evaluate("!document.getElementById('side-panel').hidden")
                self.assertEqual(has_side, airborne, name)
                # One marker per event on the timeline, one line per event in the list.
                self.assertEqual(self.browser.evaluate(
                    "document.querySelectorAll('#timeline .event-mark').length"), len(events))
                self.assertEqual(self.browser.evaluate(
                    "document.querySelectorAll('#event-list li').length"), len(events))
                self.assertEqual(self.browser.errors, [])

    def test_controls(self):
        _, page, _ = page_of(self.scenes["break"], "controls")
        self.load(page)
        b = self.browser
        end = b.evaluate("poolView.endTime()")
        # Play at 1x for about 0.4 s of wall time: the clock moves, then stops on pause.
        b.evaluate("document.getElementById('play').click()")
        b.evaluate("new Promise(r => setTimeout(r, 400))")
        b.evaluate("document.getElementById('play').click()")
        t1 = b.evaluate("poolView.time()")
        self.assertGreater(t1, 0.1)
        self.assertLess(t1, 3.0)
        b.evaluate("new Promise(r => setTimeout(r, 200))")
        self.assertEqual(b.evaluate("poolView.time()"), t1)
        # Speed 4x plays faster.
        b.evaluate("poolView.seek(0); const s = document.getElementById('speed'); s.value = '4';"
                   "s.dispatchEvent(new Event('change')); document.getElementById('play').click()")
        b.evaluate("new Promise(r => setTimeout(r, 400))")
        b.evaluate("document.getElementById('play').click()")
        self.assertGreater(b.evaluate("poolView.time()"), 2 * t1)
        # The slider seeks.
        b.evaluate("const r = document.getElementById('time-slider'); r.value = '2.5';"
                   "r.dispatchEvent(new Event('input'))")
        self.assertEqual(b.evaluate("poolView.time()"), 2.5)
        # Next / previous event land on event times.
        times = b.evaluate("poolView.view.shot.events.map(e => e.t)")
        b.evaluate("poolView.seek(1.0); document.getElementById('next-event').click()")
        self.assertEqual(b.evaluate("poolView.time()"), min(t for t in times if t > 1.0))
        b.evaluate("document.dispatchEvent(new KeyboardEvent('keydown', {key: 'ArrowLeft'}))")
        self.assertEqual(b.evaluate("poolView.time()"), max(t for t in times if t < 1.0 + 1e-9
                                                             and t < min(x for x in times if x > 1.0)))
        # Trails: drawn up to the current time; off, none.
        b.evaluate(f"poolView.seek({end})")
        points = b.evaluate("[...document.querySelectorAll('polyline.trail')].map(p => "
                            "p.getAttribute('points').split(' ').filter(Boolean).length)")
        self.assertGreater(min(points), 0)
        self.assertGreater(max(points), 100)
        b.evaluate("const c = document.getElementById('trails'); c.checked = false;"
                   "c.dispatchEvent(new Event('change'))")
        self.assertEqual(b.evaluate("[...document.querySelectorAll('polyline.trail')].map(p => "
                                    "p.getAttribute('points')).join('')"), "")
        # Marks of the collisions so far; the table to scale with its six pockets and diamonds.
        self.assertGreater(b.evaluate("document.querySelectorAll('#mark-layer > *').length"), 20)
        self.assertEqual(b.evaluate("document.querySelectorAll('.hole').length"), 6)
        self.assertEqual(b.evaluate("document.querySelectorAll('.diamond').length"), 18)
        self.assertEqual(b.evaluate("[+document.getElementById('cloth').getAttribute('width'), "
                                    "+document.getElementById('cloth').getAttribute('height')]"),
                         [2.54, 1.27])
        self.assertEqual(b.errors, [])

    def test_pockets_to_scale(self):
        """Pockets "jaws" drawn from the result's table fields, checked against the geometry
        itself, not the page's arithmetic: each facing ends on its hole's edge, leaves its
        pocket's axis at the cut angle less the rail's angle to the axis (a corner's facings 7 deg
        off the diagonal for 142 deg, a side's 14 deg off the perpendicular for 104 deg), and each
        jaw starts on its rail's nose line; "mouth_lines" keeps the thesis openings, "none" has no
        pocket. A table with other cut angles and holes moves them."""
        import math
        b = self.browser
        read = """[...document.querySelectorAll('.facing')].map(f => [f.dataset.pocket, +f.getAttribute('x1'),
            +f.getAttribute('y1'), +f.getAttribute('x2'), +f.getAttribute('y2')])"""
        holes = """Object.fromEntries([...document.querySelectorAll('.hole')].map(h => [h.dataset.pocket,
            [+h.getAttribute('cx'), +h.getAttribute('cy'), +h.getAttribute('r')]]))"""
        jaw_starts = """[...document.querySelectorAll('.jaw')].map(j => [j.dataset.pocket,
            ...j.getAttribute('d').split(' ').slice(1, 3).map(Number)])"""
        for corner_cut, side_cut, corner_hole in ((142.0, 104.0, 0.06985), (135.0, 100.0, 0.075)):
            scenario = work("pockets_%g.json" % corner_cut)
            with open(scenario, "w") as f:
                json.dump({"format": "libpool-scenario/1",
                           "table": {"preset": "wpa-9ft", "corner_cut_angle": corner_cut, "side_cut_angle": side_cut,
                                     "corner_hole_radius": corner_hole},
                           "balls": [{"id": 0, "pos": [1.0, 0.6]}], "strike": {"ball": 0, "speed": 1.0}}, f)
            result, page, second = page_of(scenario, "pockets_%g" % corner_cut)
            with open(result, encoding="utf-8") as f:
                table = json.load(f)["table"]
            L, W = table["length"], table["width"]
            axis = {"sw": (-1, -1), "se": (1, -1), "nw": (-1, 1), "ne": (1, 1), "s": (0, -1), "n": (0, 1)}
            for p in (page, second):
                self.load(p)
                facings, hole, jaws = b.evaluate(read), b.evaluate(holes), b.evaluate(jaw_starts)
                self.assertEqual(len(facings), 12)
                self.assertEqual(len(jaws), 12)
                self.assertEqual(sorted(hole), sorted(axis))
                for name, x1, y1, x2, y2 in facings:
                    cx, cy, r = hole[name]
                    self.assertAlmostEqual(math.hypot(x2 - cx, y2 - cy), r, delta=1e-9, msg=name)
                    self.assertAlmostEqual(r, corner_hole if len(name) == 2 else table["side_hole_radius"],
                                           delta=1e-12)
                    ax, ay = axis[name]
                    cos = abs((x2 - x1) * ax + (y2 - y1) * ay) / math.hypot(x2 - x1, y2 - y1) / math.hypot(ax, ay)
                    off_axis = math.degrees(math.acos(min(cos, 1.0)))
                    want = corner_cut - 135.0 if len(name) == 2 else side_cut - 90.0
                    self.assertAlmostEqual(off_axis, want, delta=1e-6, msg=name)
                for name, x, y in jaws:  # on a nose line: x = 0 or L, y = 0 or W
                    self.assertAlmostEqual(min(abs(x), abs(x - L), abs(y), abs(y - W)), 0.0, delta=1e-12, msg=name)
                self.assertEqual(b.errors, [])
        for pockets, mouths, holes_drawn in (("mouth_lines", 6, 6), ("none", 0, 0)):
            scenario = work("pockets_%s.json" % pockets)
            with open(scenario, "w") as f:
                json.dump({"format": "libpool-scenario/1", "table": {"preset": "wpa-9ft", "pockets": pockets},
                           "balls": [{"id": 0, "pos": [1.0, 0.6]}], "strike": {"ball": 0, "speed": 1.0}}, f)
            _, page, _ = page_of(scenario, "pockets_" + pockets)
            self.load(page)
            self.assertEqual(b.evaluate("document.querySelectorAll('.mouth').length"), mouths, pockets)
            self.assertEqual(b.evaluate("document.querySelectorAll('.hole').length"), holes_drawn, pockets)
            self.assertEqual(b.evaluate("document.querySelectorAll('.jaw, .facing').length"), 0, pockets)

    def test_degrades_gracefully(self):
        # An older result (no initial, params or table), with fields this page does not know
        # (a cushion part, a game, an unknown event type): it loads, draws every ball, says what
        # it assumed, and throws nothing.
        result, _, _ = page_of(self.scenes["break"], "old")
        with open(result, encoding="utf-8") as f:
            doc = json.load(f)
        for key in ("initial", "params", "table"):
            del doc[key]
        doc["game"] = {"rules": "8ball", "outcome": "continue", "fouls": []}
        doc["events"][5]["part"] = "jaw"
        doc["events"].insert(7, {"t": doc["events"][6]["t"], "type": "future_event", "balls": [],
                                 "after": [], "extra": {"a": [1, 2]}})
        doc["name"] = "a </script><script>window.injected = 1</script> name"
        path = work("old_edited.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(doc, f)
        page = work("old_edited.html")
        r = pool_view(path, "-o", page)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.load(page)
        b = self.browser
        self.assertIsNone(b.evaluate("window.injected === undefined ? null : 1"))
        self.assertIn("no initial states", b.evaluate("document.getElementById('warnings').textContent"))
        self.assertIn("8ball", b.evaluate("document.getElementById('summary').textContent"))
        self.assertEqual(b.evaluate("document.querySelectorAll('circle.ball').length"), 16)
        # Before its first event a ball rests where that event finds it: exact for a struck shot.
        sim = reference_sim(self.scenes["break"])
        for t in (0.0, 0.1, 1.0, 3.0):
            drawn = self.drawn_at([t])[0]
            ref = sim.state_at(t)
            for (bid, x, y, z, *_), rb in zip(drawn, ref):
                self.assertEqual((x, y, z), rb.pos, f"ball {bid} at {t}")
        self.assertEqual(b.errors, [])

    def test_bad_input_exits_2_naming_the_field(self):
        cases = [
            ("not json", "(document): malformed JSON"),
            ('{"format": "libpool-scenario/1", "events": [], "final": []}', "format:"),
            ('{"format": "libpool-result/1", "final": []}', "events: must be an array"),
            ('{"format": "libpool-result/1", "events": [{"t": "x"}], "final": []}', "events[0].t"),
            ('{"format": "libpool-result/1", "events": [{"t": NaN}], "final": []}', "NaN"),
            ("[1]", "(document): must be a JSON object"),
        ]
        for i, (text, expected) in enumerate(cases):
            with self.subTest(text=text):
                src, out = work(f"bad{i}.json"), work(f"bad{i}.html")
                with open(src, "w", encoding="utf-8") as f:
                    f.write(text)
                r = pool_view(src, "-o", out)
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertIn(expected, r.stderr.decode())
                self.assertFalse(os.path.exists(out))
        r = pool_view(work("missing.json"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("missing.json: No such file or directory", r.stderr.decode())
        r = pool_view("--bogus")
        self.assertEqual(r.returncode, 2)
        r = pool_view("--help")
        self.assertEqual(r.returncode, 0)
        self.assertIn(b"--live", r.stdout)
        r = pool_view(work("break_scenario.json"), "--max-input", "10")
        self.assertEqual(r.returncode, 2)
        self.assertIn("larger than the limit of 10 bytes", r.stderr.decode())


def main():
    global ARGS
    p = argparse.ArgumentParser()
    p.add_argument("--bin-dir", required=True)
    p.add_argument("--source-dir", required=True)
    p.add_argument("--work-dir", required=True)
    ARGS, rest = p.parse_known_args()
    if chromium_path() is None:
        print("SKIP: chromium is not installed (tools/setup.sh installs it)", file=sys.stderr)
        return 77
    prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False, verbosity=2)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
