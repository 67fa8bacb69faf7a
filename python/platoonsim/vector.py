"""``PlatoonVecEnv``: N ``PlatoonEnv`` episodes stepped together (docs/python.md).

``gymnasium.make_vec("platoonsim/Platoon-v0", num_envs=N)`` returns it: a native
``gymnasium.vector.VectorEnv`` on ``platoonsim.BatchSimulation``, whose worlds step in Rust across
a thread pool with the GIL released (not Gymnasium's Sync/Async wrappers around N single
environments). World ``i`` is exactly ``PlatoonEnv`` with the same parameters, seed and actions:
the same observations and rewards, bit for bit.

* Observations: float32 array (N, 8); actions: an int array (N,) of 0 (hold) / 1 (organize);
  rewards (N,); every episode has the same number of decisions, so all worlds end together.
* Autoreset (Gymnasium's ``NEXT_STEP`` mode): the ``step`` after an episode's end starts new
  episodes and returns their first observations, with reward 0 and no end flags.
* Seeding: ``reset(seed=s)`` gives world ``i`` the engine seed ``s + i`` (a list gives one seed
  per world); without a seed, and at every autoreset, the seeds come from the environment's
  generator.
* ``info``: arrays over the worlds: ``t_s``, ``seed``, ``leftmost_share``,
  ``mean_string_size``, ``discharge_loss`` (after a step), ``flow_vphpl`` and ``speed_kmh`` (N, 3).
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

import gymnasium as gym
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv

import platoonsim
from platoonsim.gym import ORGANIZE, PlatoonEnv, observation, reward


def check_num_envs(num_envs: Any) -> None:
    """``num_envs`` of a vector environment: an int from 1 to ``platoonsim.MAX_WORLDS`` (the
    worlds one native batch steps), refused at construction rather than at the first reset."""
    if (
        isinstance(num_envs, bool)
        or not isinstance(num_envs, (int, np.integer))
        or not 1 <= num_envs <= platoonsim.MAX_WORLDS
    ):
        raise ValueError(
            f"num_envs = {num_envs!r}: must be an int from 1 to {platoonsim.MAX_WORLDS} "
            "(the worlds one batch steps)"
        )


def world_seeds(
    seed: int | Sequence[int] | None, n: int, rng: np.random.Generator | None
) -> tuple[np.random.Generator, np.ndarray]:
    """The engine seeds of a vector reset and the generator of later episodes' seeds: an int s
    gives s + i to world i, a sequence one seed per world, None seeds from the generator."""
    if seed is None:
        if rng is None:
            rng, _ = gym.utils.seeding.np_random(None)
        return rng, rng.integers(0, 2**31 - 1, size=n)
    if isinstance(seed, (int, np.integer)) and not isinstance(seed, bool):
        rng, _ = gym.utils.seeding.np_random(int(seed))
        return rng, int(seed) + np.arange(n)
    seeds = np.asarray(seed)
    if seeds.shape != (n,) or seeds.dtype.kind not in "iu":
        raise ValueError(f"reset: seed must be an int or {n} ints (one per world), got {seed!r}")
    rng, _ = gym.utils.seeding.np_random(int(seeds[0]))
    return rng, seeds


class PlatoonVecEnv(VectorEnv):
    """``num_envs`` worlds of ``PlatoonEnv``; the other parameters are ``PlatoonEnv``'s, plus
    ``threads`` (the pool's size, default every core)."""

    metadata = {"render_modes": [], "autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, num_envs: int = 1, threads: int | None = None, **kwargs: Any) -> None:
        check_num_envs(num_envs)
        # The single environment checks the parameters and holds the episode's settings.
        self.single = PlatoonEnv(**kwargs)
        if self.single.gate != "native":
            raise ValueError("PlatoonVecEnv steps its worlds natively: gate must be \"native\"")
        self.num_envs = int(num_envs)
        self.threads = threads
        self.single_observation_space = self.single.observation_space
        self.single_action_space = self.single.action_space
        self.observation_space = spaces.Box(
            low=np.tile(self.single_observation_space.low, (self.num_envs, 1)),
            high=np.tile(self.single_observation_space.high, (self.num_envs, 1)),
            dtype=np.float32,
        )
        self.action_space = spaces.MultiDiscrete(np.full(self.num_envs, 2))
        self.batch: platoonsim.BatchSimulation | None = None
        self._seeds = np.zeros(self.num_envs, dtype=np.int64)
        self._ended = False
        self._np_random: np.random.Generator | None = None

    def _start(self, seeds: Sequence[int]) -> tuple[np.ndarray, dict[str, Any]]:
        env = self.single
        self._seeds = np.asarray(seeds, dtype=np.int64)
        self.batch = platoonsim.BatchSimulation(
            env.scenario, seeds=[int(s) for s in seeds], overrides=env.overrides, threads=self.threads
        )
        self.batch.use_gate()
        self.batch.run_until(env.warmup_s)
        self._ended = False
        obs, info = self._observe()
        return obs, info

    def _observe(self) -> tuple[np.ndarray, dict[str, Any]]:
        assert self.batch is not None
        env = self.single
        rows, infos = [], []
        for i in range(self.num_envs):
            o, inf = observation(
                self.batch.vehicles(i), self.batch.detectors(i), env.zone, env.leftmost_lane, env.observation_space
            )
            rows.append(o)
            infos.append(inf)
        info = {
            "t_s": self.batch.time_s(),
            "seed": self._seeds.copy(),
            "leftmost_share": np.array([x["leftmost_share"] for x in infos]),
            "mean_string_size": np.array([x["mean_string_size"] for x in infos]),
            "flow_vphpl": np.stack([x["flow_vphpl"] for x in infos]),
            "speed_kmh": np.stack([x["speed_kmh"] for x in infos]),
        }
        return np.stack(rows).astype(np.float32), info

    def reset(
        self, *, seed: int | Sequence[int] | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        self._np_random, seeds = world_seeds(seed, self.num_envs, self._np_random)
        return self._start(seeds)

    def step(self, actions: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        if self.batch is None:
            raise RuntimeError("call reset() before step()")
        a = np.asarray(actions)
        if a.shape != (self.num_envs,) or a.dtype.kind not in "iub" or not np.isin(a, (0, 1)).all():
            raise ValueError(
                f"actions must be {self.num_envs} values of 0 (hold) or 1 (organize), one per world; "
                f"got {actions!r}"
            )
        false = np.zeros(self.num_envs, dtype=bool)
        if self._ended:
            # NEXT_STEP autoreset: new episodes, their first observations, no reward.
            assert self._np_random is not None
            obs, info = self._start(self._np_random.integers(0, 2**31 - 1, size=self.num_envs))
            return obs, np.zeros(self.num_envs), false, false.copy(), info
        self.batch.set_gates(a.astype(np.int64) == ORGANIZE)
        t = float(self.batch.time_s()[0])
        self.batch.run_until(t + self.single.decision_s)
        obs, info = self._observe()
        rewards = np.empty(self.num_envs)
        losses = np.empty(self.num_envs)
        for i in range(self.num_envs):
            rewards[i], losses[i] = reward(
                info["flow_vphpl"][i], info["mean_string_size"][i], self.single.discharge_penalty
            )
        info["discharge_loss"] = losses
        truncated = self.batch.done()
        self._ended = bool(truncated.all())
        return obs, rewards, false, truncated, info

    def close_extras(self, **kwargs: Any) -> None:
        self.batch = None
