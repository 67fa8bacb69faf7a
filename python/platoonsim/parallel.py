"""``FlowMergeParallelEnv``: ``platoonsim/FlowMerge-v0`` in the per-vehicle form, a PettingZoo
``ParallelEnv`` (docs/python.md). Needs ``pettingzoo`` (``pip install "./python[pettingzoo]"``).

* **Agents**: the controlled vehicles (Flow's ``rl_veh``, at most ``num_rl``), named
  ``"cav_<vehicle id>"``. A vehicle becomes an agent when it joins the controlled list and stops
  being one when it leaves the road (``terminated`` for it, a final observation of zeros); an
  agent never comes back. ``possible_agents`` is the agents of the episode so far (an open
  road: which vehicles will come is not known in advance).
* **Spaces**, the same for every agent: observation ``Box(5,)`` float32, the features of one
  slot of ``FlowMergeEnv`` (speed, leader's speed difference and gap, follower's speed
  difference and gap, normalized as there); action ``Box(1,)`` float32, an acceleration in
  [-``max_decel``, ``max_accel``] (clipped), applied as ``AccelerateSafe``.
* **Rewards**: every agent that acted gets the step's reward of ``FlowMergeEnv`` (one reward
  for the system, shared: the task is cooperative); an agent that joined in the step gets 0.
* **No agent, no step**: while no learning vehicle is on the road, nobody can act, so
  ``reset`` and ``step`` advance the world one action at a time (with no commands) until a
  vehicle joins the list or the horizon ends; ``infos[agent]["skipped"]`` counts those actions.
  ``agents`` is therefore empty only at the end of the episode, and ``while env.agents:``
  loops over a whole episode. ``env.t_actions`` is the actions' count including the skipped.
* **Actions**: a dict with one entry per agent: an acceleration (a number or an array of one).
  A missing live agent, an agent that is not live, a non-finite value or another shape raise
  ValueError; values out of bounds are clipped.
* **Ends**: at the horizon every agent is truncated; a collision terminates every agent with
  reward 0 (the safe command should make it impossible).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium import spaces

try:
    from pettingzoo.utils.env import ParallelEnv
except ImportError as e:  # pragma: no cover - exercised only without pettingzoo
    raise ImportError(
        "platoonsim.parallel needs pettingzoo: pip install \"./python[pettingzoo]\""
    ) from e

from platoonsim.flow_merge import FEATURES, _Task


def _name(vehicle_id: int) -> str:
    return f"cav_{int(vehicle_id)}"


class FlowMergeParallelEnv(ParallelEnv):
    """merge0 with one agent per controlled vehicle (module docstring); arguments as
    ``FlowMergeEnv`` (``platoonsim.flow_merge.DEFAULTS``)."""

    metadata = {"name": "platoonsim_flow_merge_v0", "render_modes": [], "is_parallelizable": True}

    def __init__(self, **kwargs: Any) -> None:
        self.task = _Task(**kwargs)
        self._obs_space = spaces.Box(
            low=self.task.observation_space.low[:FEATURES],
            high=self.task.observation_space.high[:FEATURES],
            dtype=np.float32,
        )
        self._act_space = spaces.Box(
            low=np.float32(self.task.a_low), high=np.float32(self.task.a_high), shape=(1,), dtype=np.float32
        )
        self.agents: list[str] = []
        self.possible_agents: list[str] = []
        self.batch = None
        self.t_actions = 0
        self._ids = np.full(self.task.k, -1, dtype=np.int64)
        self._rng = np.random.default_rng()

    # One space object for every agent (PettingZoo asks for the same object on every call; a
    # cache per agent would grow with every vehicle of a long training run).
    def observation_space(self, agent: str) -> spaces.Box:
        return self._obs_space

    def action_space(self, agent: str) -> spaces.Box:
        return self._act_space

    # The world, one action at a time.
    def _advance(self, actions: np.ndarray) -> tuple:
        out = self.batch._core.flow_step(actions.reshape(1, -1))
        self.t_actions += 1
        return out

    def _skip(self, out: tuple) -> tuple[tuple, int]:
        """Advance with no commands while no vehicle is controlled and the episode goes on."""
        skipped = 0
        zeros = np.zeros(self.task.k)
        while not (out[1][0] >= 0).any() and not out[7][0] and not out[6][0] > 0:
            out = self._advance(zeros)
            skipped += 1
        return out, skipped

    def _agent_view(self, out: tuple, skipped: int) -> tuple[dict, dict]:
        obs, ids = out[0][0], out[1][0]
        self._ids = ids.copy()
        observations, infos = {}, {}
        for j, vid in enumerate(ids):
            if vid < 0:
                continue
            a = _name(vid)
            observations[a] = obs[j].copy()
            infos[a] = {"vehicle_id": int(vid), "slot": j, "skipped": skipped, "t_actions": self.t_actions}
        return observations, infos

    def reset(self, seed: int | None = None, options: dict[str, Any] | None = None):
        if seed is not None:
            self._rng = np.random.default_rng(int(seed))
            engine_seed = int(seed)
        else:
            engine_seed = int(self._rng.integers(0, 2**31 - 1))
        self.batch = self.task.batch([engine_seed], threads=1)
        self.t_actions = 0
        out, skipped = self._skip(self.batch._core.flow_reset())
        observations, infos = self._agent_view(out, skipped)
        self.agents = list(observations)
        self.possible_agents = list(self.agents)
        return observations, infos

    def _action_row(self, actions: dict[str, Any]) -> np.ndarray:
        if not isinstance(actions, dict):
            raise ValueError(f"actions must be a dict of agent -> acceleration; got {actions!r}")
        live = set(self.agents)
        extra = sorted(set(actions) - live)
        if extra:
            raise ValueError(f"actions for {extra[0]!r}: not a live agent (live: {sorted(live)})")
        row = np.zeros(self.task.k)
        for j, vid in enumerate(self._ids):
            if vid < 0:
                continue
            a = _name(vid)
            if a not in actions:
                raise ValueError(f"actions: no action for the live agent {a!r}")
            try:
                v = np.asarray(actions[a], dtype=np.float64)
            except (TypeError, ValueError):
                v = np.array([np.nan])
            if v.size != 1 or v.ndim > 1 or not np.isfinite(v).all():
                raise ValueError(
                    f"actions[{a!r}] = {actions[a]!r}: must be one finite acceleration (m/s², "
                    f"clipped to [{self.task.a_low:g}, {self.task.a_high:g}])"
                )
            row[j] = float(v.reshape(-1)[0])
        return row

    def step(self, actions: dict[str, Any]):
        if self.batch is None:
            raise RuntimeError("call reset() before step()")
        if not self.agents:
            raise RuntimeError("the episode is over (no agents): call reset()")
        row = self._action_row(actions)
        acted = list(self.agents)
        out = self._advance(row)
        reward, collided, done = float(out[2][0]), bool(out[6][0] > 0), bool(out[7][0])
        skipped = 0
        if not (collided or done):
            out, skipped = self._skip(out)
            collided, done = bool(out[6][0] > 0), bool(out[7][0])
        observations, infos = self._agent_view(out, skipped)
        now = set(observations)
        rewards, terminated, truncated = {}, {}, {}
        for a in acted:
            rewards[a] = 0.0 if collided else reward
            terminated[a] = collided or a not in now
            truncated[a] = done and not terminated[a]
            if a not in now:
                observations[a] = np.zeros(FEATURES, dtype=np.float32)
                infos[a] = {"left": True, "skipped": skipped, "t_actions": self.t_actions}
        for a in now - set(acted):
            rewards[a] = 0.0
            terminated[a] = collided
            truncated[a] = done and not collided
            self.possible_agents.append(a)
        self.agents = [] if (collided or done) else [a for a in observations if a in now]
        return observations, rewards, terminated, truncated, infos

    def close(self) -> None:
        self.batch = None
