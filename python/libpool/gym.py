"""Gymnasium environments on libpool and its rules (docs/python.md "Gymnasium"). Needs gymnasium
(pip install ./python[gym]).

    import gymnasium as gym
    import libpool.gym  # registers the ids
    env = gym.make("libpool/NineBall-v0", noise="fastfiz")
    obs, info = env.reset(seed=1)
    obs, reward, terminated, truncated, info = env.step(env.action_space.sample())

Ids:
  libpool/NineBall-v0       9-ball from the break under the WPA rules
  libpool/ThreeCushion-v0   three cushion from UMB's opening position on a carom table
  libpool/PotBall-v0        one shot: pot the target ball (cue ball, target and `obstacles`
                            other balls placed at random), judged by the 9-ball rules

The action is the five cue parameters, each scaled to [-1, 1] (Box(-1, 1, (5,), float32)):
  speed = SPEED_MIN + (x0 + 1) / 2 (SPEED_MAX - SPEED_MIN)   m/s (0.5 to 8)
  phi   = 180 x1                                           degrees, the aim from +x
  theta = (x2 + 1) / 2 THETA_MAX                           degrees, cue elevation (0 to 30)
  a     = OFFSET_MAX R x3, b = OFFSET_MAX R x4             m, tip offsets (within R/2)
Observations are float32 in [0, 1]: every ball slot's x / L, y / W and whether it is on the table,
then what the rules' state needs (see each class). Rewards come from the rules (libpool.game).

`mode="inning"` (default): the episode is one player's inning, it ends (terminated) when the turn
would pass or the game ends; `mode="game"`: the agent plays both players until the game ends,
each step's reward being the shooter's (info["player"] says who shot). A cue ball in hand is
placed by the environment: where it lies when it is still on the table, else on the head spot or
the nearest free point of the long string. Noise (`noise=` "none", "fastfiz" or a spec) perturbs
each strike with libpool.game's noise, its sample drawn from the episode's seed: the same seed
gives the same episode bit for bit.

PoolVectorEnv (and gym.make_vec(id, num_envs, vectorization_mode="vector_entry_point")) steps N
tables at once on `workers` threads: the simulation runs in C without the GIL, so the tables use
every core.
"""

import math
import os
from concurrent.futures import ThreadPoolExecutor
from ctypes import byref

import gymnasium
import numpy as np
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv

from . import Sim, aim, game, make_strike
from ._ffi import BallState as CBallState, Error as CError, Vec3

_MOTION_POCKETED, _MOTION_OFF_TABLE = 6, 7

__all__ = ["NineBallEnv", "ThreeCushionEnv", "PotBallEnv", "PoolVectorEnv", "make_vector",
           "SPEED_MIN", "SPEED_MAX", "THETA_MAX", "OFFSET_MAX", "action_to_strike", "strike_to_action",
           "ghost_ball_action"]

SPEED_MIN, SPEED_MAX = 0.5, 8.0  # m/s: a touch to a hard break
THETA_MAX = 30.0                 # degrees: massé curves on the cloth, no jumps (planar mode)
OFFSET_MAX = 0.5                 # of R: tip offsets a miscue-free cue reaches


def action_to_strike(action, radius):
    """The strike (speed m/s, phi deg, theta deg, a m, b m) of a scaled action in [-1, 1]^5
    (values outside are clipped)."""
    x = [min(1.0, max(-1.0, float(v))) for v in action]
    if len(x) != 5:
        raise ValueError(f"action: 5 values (speed, phi, theta, a, b), not {len(x)}")
    return (SPEED_MIN + 0.5 * (x[0] + 1.0) * (SPEED_MAX - SPEED_MIN), 180.0 * x[1],
            0.5 * (x[2] + 1.0) * THETA_MAX, OFFSET_MAX * radius * x[3], OFFSET_MAX * radius * x[4])


def strike_to_action(strike, radius):
    """The scaled action of a strike (inverse of action_to_strike; phi wrapped to [-180, 180))."""
    speed, phi, theta, a, b = strike
    phi = (phi + 180.0) % 360.0 - 180.0
    x = [2.0 * (speed - SPEED_MIN) / (SPEED_MAX - SPEED_MIN) - 1.0, phi / 180.0, 2.0 * theta / THETA_MAX - 1.0,
         a / (OFFSET_MAX * radius), b / (OFFSET_MAX * radius)]
    return np.clip(np.array(x, dtype=np.float32), -1.0, 1.0)


class _PoolEnv(gymnasium.Env):
    """What the three environments share: a table of balls at rest, the rules' state, a shot per
    step, judged by libpool.game."""

    metadata = {"render_modes": ["ansi"], "render_fps": 1}
    rules = None
    slots = ()   # ball ids of the observation's slots, in order

    def __init__(self, noise="none", mode="inning", max_shots=100, render_mode=None):
        if mode not in ("inning", "game"):
            raise ValueError(f"mode: 'inning' or 'game', not {mode!r}")
        if render_mode not in (None, "ansi"):
            raise ValueError(f"render_mode: None or 'ansi', not {render_mode!r}")
        self.render_mode = render_mode
        self.mode = mode
        self.max_shots = int(max_shots)
        self.noise = game.noise(noise)
        self._def = self._sim_def()
        self.radius = self._def.params.ball_radius
        self.length, self.width = self._def.table.length, self._def.table.width
        self._sim = Sim(table=self._def.table, params=self._def.params, max_time=self._def.max_time,
                        max_events=self._def.max_events)
        # The shot's buffers, reused: every step is one pool_game_shoot call (set up, strike, run,
        # judge, final states), which runs without the GIL.
        self._c_balls = (CBallState * game.MAX_BALLS)()
        self._c_final = (CBallState * game.MAX_BALLS)()
        self._c_result = game.CResult()
        self._c_error = CError()
        self._glib = game._load()
        self.action_space = spaces.Box(-1.0, 1.0, (5,), np.float32)
        n = len(self.slots) * 3 + self._state_size()
        self.observation_space = spaces.Box(0.0, 1.0, (n,), np.float32)
        self.balls = {}
        self.state = None
        self.shots = 0
        self._episode_seed = 0

    # -- what subclasses define --
    def _sim_def(self):
        return Sim().definition

    def _start(self):
        """The balls and state of a new episode (self.np_random is seeded)."""
        raise NotImplementedError

    def _state_size(self):
        return 0

    def _state_features(self):
        return []

    def _reward(self, result, before):
        raise NotImplementedError

    def _episode_over(self, result):
        if result.outcome in ("win", "loss"):
            return True
        return self.mode == "inning" and result.outcome == "turn_over"

    # -- gymnasium --
    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        # The noise of the whole episode follows from the seeded generator.
        self._episode_seed = int(self.np_random.integers(0, 2 ** 63))
        self.shots = 0
        self.balls, self.state = self._start()
        return self._observation(), {"player": self.state.player}

    def step(self, action):
        self._prepare(action)
        self._shoot()
        return self._finish()

    # A step in three phases, so that PoolVectorEnv runs the middle one (the C shot, without the
    # GIL) of every table at once on its threads, and the Python phases one table after another.
    def _prepare(self, action):
        if self.state is None:
            raise RuntimeError("step() before reset()")
        strike = action_to_strike(action, self.radius)
        if not self.noise.is_zero():
            strike = game.noisy_strike(strike, self.noise, self._episode_seed, self.shots)
        before = self.state
        cue = before.cue_ball
        if cue not in self.balls:
            self.balls[cue] = self._free_spot()
        self._ids = sorted(self.balls)
        balls = self._c_balls
        for k, bid in enumerate(self._ids):
            x, y = self.balls[bid]
            balls[k] = CBallState(bid, 0, Vec3(x, y, self.radius), Vec3(), Vec3())
        self._c_strike = make_strike(*strike)
        self._c_state = before._to_c()
        self._before = before

    def _shoot(self):
        with self._sim.lock:
            self._code = self._glib.pool_game_shoot(self._sim._p(), byref(self._def), self._c_balls,
                                                    len(self._ids), byref(self._c_strike), byref(self._c_state),
                                                    byref(self._c_result), self._c_final, byref(self._c_error))

    def _finish(self):
        before = self._before
        if self._code != 0:  # a strike the library refuses (noise can push a^2 + b^2 past R^2)
            return self._refused(self._c_error.message.decode("utf-8", "replace"), before)
        result = game.Result._from_c(before.rules, self._c_result)
        final = self._c_final
        self.shots += 1
        self.balls = {final[k].id: (final[k].pos.x, final[k].pos.y) for k in range(len(self._ids))
                      if final[k].motion not in (_MOTION_POCKETED, _MOTION_OFF_TABLE)}
        for bid in result.spot:
            spot = game.spot_position(result.state, bid, list(self.balls.items()), self._def.table, self.radius)
            if spot is not None:
                self.balls[bid] = spot
        self.state = result.state
        reward = float(self._reward(result, before))
        terminated = self._episode_over(result)
        truncated = not terminated and self.shots >= self.max_shots
        info = {"player": before.player, "legal": result.legal, "outcome": result.outcome,
                "fouls": tuple(result.fouls), "pocketed": tuple(result.pocketed), "points": result.points}
        return self._observation(), reward, terminated, truncated, info

    def _refused(self, message, before):
        # The library refused the strike: a foul that wastes the shot (the turn passes).
        self.shots += 1
        info = {"player": before.player, "legal": False, "outcome": "turn_over", "fouls": ("refused",),
                "pocketed": (), "points": 0, "error": message}
        return self._observation(), -1.0, self.mode == "inning", self.shots >= self.max_shots, info

    def _free_spot(self):
        """Head spot, else the nearest free point of the long string."""
        y = 0.5 * self.width
        for k in range(200):
            for sign in (1, -1):
                x = 0.25 * self.length + sign * k * 0.25 * self.radius
                if 2 * self.radius < x < self.length - 2 * self.radius and all(
                        math.hypot(x - bx, y - by) > 2 * self.radius + 1e-6 for bx, by in self.balls.values()):
                    return (x, y)
        return (0.25 * self.length, y)

    def _observation(self):
        values = []
        for bid in self._slot_ids():
            if bid in self.balls:
                x, y = self.balls[bid]
                values += (min(1.0, max(0.0, x / self.length)), min(1.0, max(0.0, y / self.width)), 1.0)
            else:
                values += (0.0, 0.0, 0.0)
        values += self._state_features()
        return np.array(values, dtype=np.float32)

    def _slot_ids(self):
        return self.slots

    def render(self):
        if self.render_mode != "ansi":
            return None
        balls = ", ".join(f"{b}: ({x:.3f}, {y:.3f})" for b, (x, y) in sorted(self.balls.items()))
        return f"{self.rules} shot {self.shots}, player {self.state.player}: {balls}"

    def close(self):
        self._sim.close()

    def _placed_break(self, rules):
        return {bid: pos for bid, pos in game.rack(rules, table=self._def.table, params=self._def.params)}


class NineBallEnv(_PoolEnv):
    """9-ball from the break (WPA rules). Observation: the cue ball and balls 1..9 (x/L, y/W,
    on the table), then break, ball in hand, fouls / 2, opponent's fouls / 2, player. Reward per
    shot: +1 per object ball legally pocketed, +10 for the rack won, -1 for a foul, -10 for the
    rack lost."""

    rules = "9ball"
    slots = tuple(range(10))

    def _start(self):
        return self._placed_break("9ball"), game.State.default("9ball")

    def _state_size(self):
        return 5

    def _state_features(self):
        s = self.state
        return [float(s.break_shot), float(s.ball_in_hand), s.fouls / 2.0, s.opponent_fouls / 2.0, float(s.player)]

    def _reward(self, result, before):
        if result.outcome == "win":
            return 10.0
        if result.outcome == "loss":
            return -10.0
        if not result.legal:
            return -1.0
        return float(sum(1 for b in result.pocketed if b != before.cue_ball))


class ThreeCushionEnv(_PoolEnv):
    """Three cushion from UMB's opening position on a carom table (game.carom_sim_def). The
    observation's slots are the shooter's ball, the opponent's, the red; then break, the
    shooter's and the opponent's score / target. Reward: +1 per point. `target` (default 10) ends
    the game in mode "game"."""

    rules = "three_cushion"
    slots = (0, 1, 2)

    def __init__(self, noise="none", mode="inning", max_shots=100, target=10, render_mode=None):
        self.target = int(target)
        super().__init__(noise=noise, mode=mode, max_shots=max_shots, render_mode=render_mode)

    def _sim_def(self):
        return game.carom_sim_def()

    def _start(self):
        s = game.State.default("three_cushion")
        s.target = self.target
        return self._placed_break("three_cushion"), s

    def _slot_ids(self):
        s = self.state
        red = next(b for b in (0, 1, 2) if b not in (s.cue_ball, s.opponent_cue_ball))
        return (s.cue_ball, s.opponent_cue_ball, red)

    def _state_size(self):
        return 3

    def _state_features(self):
        s = self.state
        scale = max(self.target, 1)
        return [float(s.break_shot), s.points / scale, s.opponent_points / scale]

    def _reward(self, result, before):
        return float(result.points)


class PotBallEnv(_PoolEnv):
    """One shot: pot the target ball. The cue ball (0), the target (1) and `obstacles` other balls
    (2, 3, ...) are placed uniformly at random on a 9 ft table, apart from each other and the
    cushions. Judged by the 9-ball rules (the target is the lowest ball): reward 1 when the shot
    is legal and pockets the target, else 0. Observation: the slots of the cue ball, the target
    and the obstacles."""

    rules = "9ball"

    def __init__(self, obstacles=0, noise="none", render_mode=None):
        self.obstacles = int(obstacles)
        if not 0 <= self.obstacles <= 7:
            raise ValueError("obstacles: 0 to 7")
        self.slots = tuple(range(2 + self.obstacles))
        super().__init__(noise=noise, mode="inning", max_shots=1, render_mode=render_mode)

    def _start(self):
        margin = 2.0 * self.radius + 0.01
        balls = {}
        for bid in self.slots:
            while True:
                x = float(self.np_random.uniform(margin, self.length - margin))
                y = float(self.np_random.uniform(margin, self.width - margin))
                if all(math.hypot(x - bx, y - by) > 2.0 * self.radius + 0.005 for bx, by in balls.values()):
                    balls[bid] = (x, y)
                    break
        return balls, game.State("9ball")

    def _reward(self, result, before):
        return 1.0 if result.legal and 1 in result.pocketed else 0.0

    def _episode_over(self, result):
        return True


def ghost_ball_action(env):
    """The ghost-ball baseline's action for PotBallEnv (or any env whose target is ball 1): the
    easiest straight pot of ball 1 (libpool.aim), or a full hit on it when none is clear."""
    env = env.unwrapped
    cue, target = env.balls[0], env.balls[1]
    others = [p for b, p in env.balls.items() if b not in (0, 1)]
    shot = aim.best_pot(cue, {1: target}, others, (env.length, env.width), env.radius)
    if shot is None:
        return strike_to_action((2.0, math.degrees(math.atan2(target[1] - cue[1], target[0] - cue[0])), 0, 0, 0),
                                env.radius)
    return strike_to_action((shot.speed, shot.phi, 0.0, 0.0, -0.2 * env.radius), env.radius)


class PoolVectorEnv(VectorEnv):
    """N copies of an environment stepped together on `workers` threads (default: every core),
    with Gymnasium's next-step autoreset: after an episode ends, the next step() resets that copy
    (its reward 0, not terminated). Copy i is seeded with seed + i."""

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, env_fns, workers=None):
        self.envs = [fn() for fn in env_fns]
        self.num_envs = len(self.envs)
        first = self.envs[0]
        self.single_observation_space = first.observation_space
        self.single_action_space = first.action_space
        self.observation_space = gymnasium.vector.utils.batch_space(first.observation_space, self.num_envs)
        self.action_space = gymnasium.vector.utils.batch_space(first.action_space, self.num_envs)
        self.metadata = dict(first.metadata, autoreset_mode=AutoresetMode.NEXT_STEP)
        self.render_mode = None
        self._workers = max(1, min(int(workers or os.cpu_count() or 1), self.num_envs))
        self._pool = ThreadPoolExecutor(self._workers) if self._workers > 1 else None
        self._autoreset = np.zeros(self.num_envs, dtype=bool)

    def _map(self, fn, items):
        if self._pool is None:
            return [fn(*it) for it in items]
        return list(self._pool.map(lambda it: fn(*it), items))

    def reset(self, *, seed=None, options=None):
        seeds = [None] * self.num_envs if seed is None else [seed + i for i in range(self.num_envs)]
        out = self._map(lambda env, s: env.reset(seed=s, options=options), list(zip(self.envs, seeds)))
        self._autoreset[:] = False
        infos = {}
        for i, (_, info) in enumerate(out):
            infos = self._add_info(infos, info, i)
        return np.stack([o for o, _ in out]), infos

    def step(self, actions):
        actions = np.asarray(actions)

        # Python work one table after another; the shots (C, without the GIL) on the threads.
        stepping = [i for i in range(self.num_envs) if not self._autoreset[i]]
        for i in stepping:
            self.envs[i]._prepare(actions[i])
        self._map(lambda env: env._shoot(), [(self.envs[i],) for i in stepping])
        out = []
        for i, env in enumerate(self.envs):
            if self._autoreset[i]:
                obs, info = env.reset()
                out.append((obs, 0.0, False, False, info))
            else:
                out.append(env._finish())
        obs = np.stack([o[0] for o in out])
        rewards = np.array([o[1] for o in out], dtype=np.float64)
        terminations = np.array([o[2] for o in out], dtype=bool)
        truncations = np.array([o[3] for o in out], dtype=bool)
        infos = {}
        for i, o in enumerate(out):
            infos = self._add_info(infos, o[4], i)
        self._autoreset = terminations | truncations
        return obs, rewards, terminations, truncations, infos

    def close_extras(self, **kwargs):
        if self._pool is not None:
            self._pool.shutdown()
        for env in self.envs:
            env.close()


def make_vector(env_id=None, num_envs=1, workers=None, **kwargs):
    """A PoolVectorEnv of num_envs copies of a registered id (or of NineBall-v0)."""
    env_id = env_id or "libpool/NineBall-v0"
    entry = gymnasium.spec(env_id).entry_point
    cls = entry if isinstance(entry, type) else globals()[entry.split(":")[1]]
    return PoolVectorEnv([lambda: cls(**kwargs) for _ in range(num_envs)], workers=workers)


def _vector_entry(cls):
    def make(num_envs=1, workers=None, **kwargs):
        return PoolVectorEnv([lambda: cls(**kwargs) for _ in range(num_envs)], workers=workers)
    return make


for _id, _cls in (("libpool/NineBall-v0", NineBallEnv), ("libpool/ThreeCushion-v0", ThreeCushionEnv),
                  ("libpool/PotBall-v0", PotBallEnv)):
    if _id not in gymnasium.registry:
        gymnasium.register(id=_id, entry_point=_cls, vector_entry_point=_vector_entry(_cls))
