"""libpool.aim (ctypes on libpool_planning.so), ctest label "python".

Usage: python test_aim_python.py --pool-aim PATH --struct-sizes PATH --work DIR [unittest arguments]

- the ctypes mirrors match the C structures field by field (aim_struct_sizes.c);
- search() gives what pool-aim prints for the same position and options, number for number;
- a Sim's balls, a game's rules (every shot judged legal by libpool.game on a replay), the ghost
  ball helpers still there (libpool.gym uses them), errors naming the field.
"""
import argparse
import ctypes
import json
import os
import subprocess
import sys
import unittest

ARGS = None

BALLS = {0: (1.0, 0.5), 1: (2.0, 0.3), 2: (0.6, 1.0), 3: (1.5, 0.95)}


def run(cmd, timeout=600):
    return subprocess.run(cmd, capture_output=True, timeout=timeout, text=True)


class Binding(unittest.TestCase):
    def test_struct_layouts(self):
        from libpool import aim
        c = json.loads(run([ARGS.struct_sizes]).stdout)
        mirrors = aim.structs()
        self.assertEqual(set(c), set(mirrors))
        for name, mirror in mirrors.items():
            self.assertEqual(ctypes.sizeof(mirror), c[name]["size"], name)
            for field, offset in c[name]["fields"].items():
                self.assertEqual(getattr(mirror, field).offset, offset, "%s.%s" % (name, field))

    def test_same_as_pool_aim(self):
        from libpool import aim
        path = os.path.join(ARGS.work, "position.json")
        with open(path, "w") as f:
            json.dump({"format": "libpool-scenario/1",
                       "balls": [{"id": i, "pos": list(p)} for i, p in BALLS.items()]}, f)
        r = run([ARGS.pool_aim, path, "-n", "80", "--top", "3", "--seed", "5", "--position"])
        self.assertEqual(r.returncode, 0, r.stderr)
        printed = json.loads(r.stdout)
        shots = aim.search(BALLS, samples=80, top=3, seed=5, position=True)
        self.assertEqual([s.to_dict(rank=k + 1) for k, s in enumerate(shots)], printed)

    def test_sim_balls_and_game(self):
        import libpool
        from libpool import aim, game
        balls = {0: (0.8, 0.6), 1: (1.6, 0.9), 2: (2.3, 0.25), 9: (1.9, 0.5)}
        state = game.State("9ball")
        shots = aim.search(balls, game=state, samples=60, top=3)
        self.assertGreaterEqual(len(shots), 1)
        for s in shots:
            with libpool.Sim() as sim:
                for i, (x, y) in balls.items():
                    sim.add_ball(i, (x, y, 0.028575))
                st = s.strike
                sim.strike(0, st["speed"], st["phi"], st["theta"], st["a"], st["b"])
                sim.run()
                result = game.judge(sim, state)
                self.assertTrue(result.legal)
                self.assertIn(s.ball, result.pocketed)
        with libpool.Sim() as sim:
            for i, (x, y) in balls.items():
                sim.add_ball(i, (x, y, 0.028575))
            from_sim = aim.search(sim, game=state, samples=60, top=3)
        self.assertEqual(from_sim, shots)

    def test_errors_and_helpers(self):
        import libpool
        from libpool import aim
        with self.assertRaises(libpool.PoolError) as e:
            aim.search(BALLS, ball=9)
        self.assertIn("aim.ball: no object ball has id 9", str(e.exception))
        with self.assertRaises(ValueError):
            aim.search(BALLS, pocket="middle")
        with self.assertRaises(ValueError):
            aim.search(BALLS, kinds=["jump"])
        with self.assertRaises(ValueError):
            aim.search(BALLS, noise="loud")
        with self.assertRaises(TypeError):
            aim.search([(0, 1.0)])
        with self.assertRaises(libpool.PoolError):
            aim.search({0: (1.0, 0.5), 1: (1.01, 0.5)})
        pot = aim.best_pot(BALLS[0], {1: BALLS[1]}, [BALLS[2], BALLS[3]], (2.54, 1.27), 0.028575)
        self.assertIsNotNone(pot)
        shots = aim.search(BALLS, ball=1, pocket="se", kinds=["straight"], noise="none", samples=20)
        self.assertEqual(shots[0].p_success, 1.0)
        self.assertEqual((shots[0].ball, shots[0].pocket, shots[0].kind), (1, "se", "straight"))


def main():
    global ARGS
    parser = argparse.ArgumentParser()
    parser.add_argument("--pool-aim", required=True)
    parser.add_argument("--struct-sizes", required=True)
    parser.add_argument("--work", required=True)
    ARGS, rest = parser.parse_known_args()
    os.makedirs(ARGS.work, exist_ok=True)
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
