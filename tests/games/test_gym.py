#!/usr/bin/env python3
"""libpool.gym (docs/python.md "Gymnasium"):

- gymnasium.utils.env_checker.check_env passes for every id and mode, with and without noise;
- the same seed gives the same episode bit for bit (observations, rewards, infos), another seed
  another one; the vectorised environment equals its copies stepped one by one, whatever the
  number of worker threads, autoreset included;
- rewards follow the rules' verdicts (info), the action scaling inverts;
- on PotBall-v0, a random policy and the ghost-ball baseline (libpool.aim), with their success
  rates: the baseline pots most balls, the random policy few.
"""

import sys
import unittest
import warnings

import gymnasium as gym
import numpy as np
from gymnasium.utils.env_checker import check_env

import libpool.gym as lg

IDS = ("libpool/NineBall-v0", "libpool/ThreeCushion-v0", "libpool/PotBall-v0")


def episode(env, seed, steps=30):
    obs, info = env.reset(seed=seed)
    env.action_space.seed(seed)
    trace = [obs.tobytes()]
    for _ in range(steps):
        obs, reward, term, trunc, info = env.step(env.action_space.sample())
        trace.append((obs.tobytes(), reward, term, trunc, sorted(info.items())))
        if term or trunc:
            break
    return trace


class Checker(unittest.TestCase):
    def test_check_env(self):
        for env_id in IDS:
            for kwargs in ({}, {"noise": "fastfiz"}):
                with self.subTest(env=env_id, **kwargs), warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")
                    env = gym.make(env_id, **kwargs).unwrapped
                    check_env(env, skip_render_check=False)
                    env.close()
                    self.assertEqual([str(w.message) for w in caught if "libpool" in str(w.filename)], [])
        for env_id in IDS[:2]:
            env = gym.make(env_id, mode="game").unwrapped
            check_env(env)
            env.close()

    def test_spaces_and_scaling(self):
        for env_id in IDS:
            env = gym.make(env_id)
            obs, _ = env.reset(seed=0)
            self.assertTrue(env.observation_space.contains(obs))
            self.assertEqual(env.action_space.shape, (5,))
            env.close()
        r = 0.028575
        for a in (np.array([-1, -1, -1, -1, -1], np.float32), np.array([1, 0.999, 1, 1, 1], np.float32),
                  np.array([0.3, -0.2, -0.7, 0.1, -0.4], np.float32)):
            s = lg.action_to_strike(a, r)
            self.assertTrue(lg.SPEED_MIN <= s[0] <= lg.SPEED_MAX and 0 <= s[2] <= lg.THETA_MAX)
            self.assertLessEqual(abs(s[3]) + abs(s[4]), 2 * lg.OFFSET_MAX * r + 1e-15)
            np.testing.assert_allclose(lg.strike_to_action(s, r), a, atol=1e-6)


class Determinism(unittest.TestCase):
    def test_same_seed_same_episode(self):
        for env_id in IDS:
            for noise in ("none", "fastfiz"):
                a = gym.make(env_id, noise=noise)
                b = gym.make(env_id, noise=noise)
                self.assertEqual(episode(a, 42), episode(b, 42), (env_id, noise))
                self.assertEqual(episode(a, 42), episode(a, 42), (env_id, noise))
                if env_id != "libpool/NineBall-v0" or noise != "none":  # 9-ball starts from the same rack
                    self.assertNotEqual(episode(a, 42), episode(a, 43), (env_id, noise))

    def test_vector_equals_its_copies(self):
        for env_id in ("libpool/PotBall-v0", "libpool/NineBall-v0"):
            n, steps = 4, 12
            rng = np.random.default_rng(3)
            actions = rng.uniform(-1, 1, (steps, n, 5)).astype(np.float32)
            traces = []
            for workers in (1, 2):
                env = gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point",
                                   workers=workers, noise="fastfiz")
                obs, _ = env.reset(seed=10)
                trace = [obs.tobytes()]
                for t in range(steps):
                    obs, rew, term, trunc, _ = env.step(actions[t])
                    trace.append((obs.tobytes(), rew.tobytes(), term.tobytes(), trunc.tobytes()))
                env.close()
                traces.append(trace)
            self.assertEqual(traces[0], traces[1], env_id)
            # The copies one by one, with Gymnasium's next-step autoreset.
            singles = [gym.make(env_id, noise="fastfiz").unwrapped for _ in range(n)]
            obs = np.stack([e.reset(seed=10 + i)[0] for i, e in enumerate(singles)])
            self.assertEqual(obs.tobytes(), traces[0][0])
            done = [False] * n
            for t in range(steps):
                out = []
                for i, e in enumerate(singles):
                    if done[i]:
                        o, _ = e.reset()
                        out.append((o, 0.0, False, False))
                    else:
                        o, r, te, tr, _ = e.step(actions[t][i])
                        out.append((o, r, te, tr))
                done = [o[2] or o[3] for o in out]
                got = (np.stack([o[0] for o in out]).tobytes(), np.array([o[1] for o in out]).tobytes(),
                       np.array([o[2] for o in out]).tobytes(), np.array([o[3] for o in out]).tobytes())
                self.assertEqual(got, traces[0][t + 1], (env_id, t))


class Rewards(unittest.TestCase):
    def test_rewards_follow_the_rules(self):
        env = gym.make("libpool/NineBall-v0", mode="game", max_shots=60)
        env.reset(seed=1)
        env.action_space.seed(1)
        seen = set()
        for _ in range(60):
            _, reward, term, trunc, info = env.step(env.action_space.sample())
            want = {"win": 10.0, "loss": -10.0}.get(info["outcome"])
            if want is None:
                want = -1.0 if not info["legal"] else float(sum(1 for b in info["pocketed"] if b != 0))
            self.assertEqual(reward, want, info)
            seen.add(info["outcome"])
            if term or trunc:
                break
        self.assertIn("turn_over", seen)
        env = gym.make("libpool/ThreeCushion-v0")
        env.reset(seed=2)
        for _ in range(20):
            _, reward, term, trunc, info = env.step(env.action_space.sample())
            self.assertEqual(reward, float(info["points"]))
            self.assertEqual(term, info["outcome"] != "continue")
            if term:
                break


class Baselines(unittest.TestCase):
    def test_random_policy_and_ghost_ball_on_pot_ball(self):
        episodes = 400
        rates = {}
        for noise in ("none", "fastfiz"):
            env = gym.make("libpool/PotBall-v0", noise=noise)
            env.action_space.seed(0)
            for name, policy in (("random", lambda e: e.action_space.sample()), ("ghost-ball", lg.ghost_ball_action)):
                wins = 0
                for ep in range(episodes):
                    env.reset(seed=ep)
                    wins += env.step(policy(env))[1]
                rates[(name, noise)] = wins / episodes
            env.close()
        print("\nPotBall-v0 success over %d episodes: %s" % (
            episodes, ", ".join(f"{n} (noise {z}) {r:.3f}" for (n, z), r in rates.items())), file=sys.stderr)
        for noise in ("none", "fastfiz"):
            self.assertGreater(rates[("ghost-ball", noise)], 0.45)
            self.assertLess(rates[("random", noise)], 0.08)


if __name__ == "__main__":
    unittest.main(verbosity=2)
