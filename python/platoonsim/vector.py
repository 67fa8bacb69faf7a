"""``PlatoonVecEnv``: N ``PlatoonEnv`` episodes stepped together (docs/python.md).

``gymnasium.make_vec("platoonsim/Platoon-v1", num_envs=N)`` returns it: a native
``gymnasium.vector.VectorEnv`` on ``platoonsim.BatchSimulation`` (2N worlds: the agents' and
their twins), whose worlds step in Rust across a thread pool with the GIL released (not
Gymnasium's Sync/Async wrappers around N single environments). World ``i`` is exactly
``PlatoonEnv`` with the same parameters, seed and actions: the same observations and rewards,
bit for bit.

* Observations: float32 array (N, 8); actions: an int array (N,) of 0 (hold) / 1 (organize);
  rewards (N,); every episode has the same number of decisions, so all worlds end together.
* Autoreset (Gymnasium's ``NEXT_STEP`` mode): the ``step`` after an episode's end starts new
  episodes and returns their first observations, with reward 0 and no end flags.
* Seeding: ``reset(seed=s)`` gives world ``i`` the engine seed ``s + i`` (a list gives one seed
  per world); without a seed, and at every autoreset, the seeds come from the environment's
  generator.
* ``info``: arrays over the worlds, those of ``PlatoonEnv`` (``platoonsim.gym``): per world,
  or (N, 2) for the (agent, twin) totals, or (N, 3) per detector.
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

import gymnasium as gym
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv

import platoonsim
from platoonsim.gate import GateTask, info as gate_info
from platoonsim.gym import ORGANIZE, spaces_of


def check_num_envs(num_envs: Any, worlds_per_env: int = 1) -> None:
    """``num_envs`` of a vector environment whose environments take ``worlds_per_env`` worlds
    each: an int from 1 to ``platoonsim.MAX_WORLDS // worlds_per_env`` (one native batch steps
    at most ``MAX_WORLDS``), refused at construction rather than at the first reset."""
    most = platoonsim.MAX_WORLDS // worlds_per_env
    if isinstance(num_envs, bool) or not isinstance(num_envs, (int, np.integer)) or not 1 <= num_envs <= most:
        raise ValueError(
            f"num_envs = {num_envs!r}: must be an int from 1 to {most} "
            f"(one batch steps at most {platoonsim.MAX_WORLDS} worlds, {worlds_per_env} per environment)"
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
    """``num_envs`` worlds of ``PlatoonEnv`` (each with its twin); the other parameters are
    ``PlatoonEnv``'s, plus ``threads`` (the pool's size, default every core)."""

    metadata = {"render_modes": [], "autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, num_envs: int = 1, threads: int | None = None, **kwargs: Any) -> None:
        check_num_envs(num_envs, worlds_per_env=2)  # each with its twin
        self.task = GateTask(**kwargs)
        self.num_envs = int(num_envs)
        self.threads = threads
        self.single_observation_space, self.single_action_space = spaces_of()
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
        self._seeds = np.asarray(seeds, dtype=np.int64)
        self.batch, d = self.task.batch(self._seeds, self.threads)
        self._ended = False
        return d["obs"], gate_info(d, self._seeds)

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
        d = self.batch._core.gate_step([bool(x) for x in (a.astype(np.int64) == ORGANIZE)])
        truncated = np.asarray(d["done"], dtype=bool)
        self._ended = bool(truncated.all())
        return d["obs"], np.asarray(d["reward"]), false, truncated, gate_info(d, self._seeds)

    def close_extras(self, **kwargs: Any) -> None:
        self.batch = None


class LockstepVecEnv(VectorEnv):
    """A native vector environment of a per-vehicle task (``CavControl-v0``, ``FlowMerge-v0``)
    whose ``num_envs`` worlds run in lockstep: every episode has the same length; autoreset
    ``NEXT_STEP``; ``reset(seed=s)`` seeds world i with s + i; a collision in one world (which
    the tasks' bounded commands should make impossible) ends every world's episode: terminated
    there, truncated elsewhere. A subclass gives ``_task(**kwargs)`` (the task's parameters,
    spaces, ``batch``, ``actions``) and ``_first()`` / ``_advance(a)``, which read the batch's
    reset and step as (obs, info) and (obs, rewards, collisions, done, info)."""

    metadata = {"render_modes": [], "autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, num_envs: int = 1, threads: int | None = None, **kwargs: Any) -> None:
        check_num_envs(num_envs)
        self.task = self._task(**kwargs)
        self.num_envs = int(num_envs)
        self.threads = threads
        self.single_observation_space = self.task.observation_space
        self.single_action_space = self.task.action_space
        tile = lambda b: spaces.Box(  # noqa: E731
            low=np.tile(b.low, (self.num_envs, 1)), high=np.tile(b.high, (self.num_envs, 1)), dtype=np.float32
        )
        self.observation_space = tile(self.task.observation_space)
        self.action_space = tile(self.task.action_space)
        self.batch: platoonsim.BatchSimulation | None = None
        self._rng: np.random.Generator | None = None
        self._ended = np.zeros(self.num_envs, dtype=bool)
        self._seeds = np.zeros(self.num_envs, dtype=np.int64)

    def _task(self, **kwargs: Any) -> Any:
        raise NotImplementedError

    def _first(self) -> tuple[np.ndarray, dict[str, Any]]:
        raise NotImplementedError

    def _advance(self, a: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        raise NotImplementedError

    def _start(self, seeds: Any) -> tuple[np.ndarray, dict[str, Any]]:
        self._seeds = np.asarray(seeds, dtype=np.int64)
        self.batch = self.task.batch(self._seeds, self.threads)
        obs, info = self._first()
        self._ended = np.zeros(self.num_envs, dtype=bool)
        info["seed"] = self._seeds.copy()
        return obs.reshape(self.num_envs, -1), info

    def reset(self, *, seed: int | Sequence[int] | None = None, options: dict[str, Any] | None = None):
        self._rng, seeds = world_seeds(seed, self.num_envs, self._rng)
        return self._start(seeds)

    def step(self, actions: Any):
        if self.batch is None:
            raise RuntimeError("call reset() before step()")
        a = self.task.actions(actions, self.num_envs)
        false = np.zeros(self.num_envs, dtype=bool)
        if self._ended.any():
            # Every world's episode has the same length; NEXT_STEP: new episodes now.
            assert self._rng is not None
            obs, info = self._start(self._rng.integers(0, 2**31 - 1, size=self.num_envs))
            return obs, np.zeros(self.num_envs), false, false.copy(), info
        obs, rew, col, done, info = self._advance(a)
        terminated = col > 0
        # The worlds run in lockstep: a collision in one ends every world's episode, the
        # others' as truncated.
        truncated = (done | terminated.any()) & ~terminated
        self._ended = terminated | truncated
        return obs.reshape(self.num_envs, -1), rew, terminated, truncated, info

    def close_extras(self, **kwargs: Any) -> None:
        self.batch = None
