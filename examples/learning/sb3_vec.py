"""A Gymnasium vector environment as a stable-baselines3 ``VecEnv``.

SB3 has its own vector interface: ``step`` returns ``dones`` (terminated or truncated), the
next episode's first observation in place of the last one, and the last one in
``infos[i]["terminal_observation"]`` (with ``"TimeLimit.truncated"`` for a truncation). The
platoonsim vector environments reset in Gymnasium's ``NEXT_STEP`` mode; this adapter makes the
reset step at once when episodes end (all worlds end together in both environments).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from stable_baselines3.common.vec_env import VecEnv


class Sb3Vec(VecEnv):
    def __init__(self, env: Any) -> None:
        self.env = env
        super().__init__(env.num_envs, env.single_observation_space, env.single_action_space)
        self._actions: np.ndarray | None = None
        self._seed: int | None = None

    def reset(self) -> np.ndarray:
        obs, _ = self.env.reset(seed=self._seed)
        self._seed = None
        return obs

    def step_async(self, actions: np.ndarray) -> None:
        self._actions = actions

    def step_wait(self):
        assert self._actions is not None
        obs, rew, term, trunc, info = self.env.step(self._actions)
        dones = term | trunc
        infos: list[dict[str, Any]] = [{} for _ in range(self.num_envs)]
        for k, v in info.items():
            if isinstance(v, np.ndarray) and v.shape[:1] == (self.num_envs,):
                for i in range(self.num_envs):
                    infos[i][k] = v[i]
        if dones.any():
            # NEXT_STEP autoreset: the step after the end starts new episodes.
            first, _, _, _, _ = self.env.step(np.asarray(self._actions))
            for i in np.flatnonzero(dones):
                infos[i]["terminal_observation"] = obs[i]
                infos[i]["TimeLimit.truncated"] = bool(trunc[i] and not term[i])
            obs = np.where(dones[:, None], first, obs)
        return obs, rew.astype(np.float32), dones, infos

    def close(self) -> None:
        self.env.close()

    def seed(self, seed: int | None = None):
        self._seed = seed
        return [None if seed is None else seed + i for i in range(self.num_envs)]

    def get_attr(self, attr_name: str, indices=None):
        return [getattr(self.env, attr_name, None)] * self.num_envs

    def set_attr(self, attr_name: str, value: Any, indices=None) -> None:
        setattr(self.env, attr_name, value)

    def env_method(self, method_name: str, *args, indices=None, **kwargs):
        return [getattr(self.env, method_name)(*args, **kwargs)] * self.num_envs

    def env_is_wrapped(self, wrapper_class, indices=None):
        return [False] * self.num_envs
