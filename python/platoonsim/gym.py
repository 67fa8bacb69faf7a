"""``PlatoonEnv``: platoon organization as a Gymnasium environment, ``platoonsim/Platoon-v1``
(docs/learning.md, docs/python.md).

The agent decides once per decision interval whether the control section is organized (the
engine's PD rule: CAVs join the leftmost lane inside the section) or held (no advice). An
episode is a pair of runs of the same road and seed (``platoonsim.gate``): the agent's, and a
twin where the organizer stays off; both warm up with the organizer off until the road is
filled, then run ``decisions`` intervals (an hour by default).

* **Action**: ``Discrete(2)``: 0 hold, 1 organize, for the next ``decision_s`` seconds.
* **Observation** (float32, 8 values, of the agent's run only): for each of the first three
  detectors (upstream, control section, discharge on the homogeneous road) the flow of the
  last interval in 1000 veh/h/lane and its mean speed in 100 km/h (0 when no vehicle crossed);
  then, inside the control section now, the share of the CAVs in the leftmost lane and the
  mean size of the CACC strings the CAVs are in, divided by 10.
* **Reward** of an interval: ``l_gain + discharge_penalty * discharge_change``, both against
  the twin over the interval: the change of the paper's L̄ (each CAV's largest string, over
  the CAVs that left the road) and of the discharge detector's count. Holding throughout
  earns exactly 0.
* **Episode end**: truncated after ``decisions`` decisions; never terminated.
* **info**: ``l_gain``, ``discharge_change`` (the interval's), ``cav_exits``,
  ``platoon_sum``, ``discharge_count`` and ``collisions`` as (agent, twin) running totals (the
  episode's L̄ gain is ``(platoon_sum/cav_exits)[0] / (platoon_sum/cav_exits)[1] − 1``),
  ``flow_vphpl``, ``speed_kmh``, ``leftmost_share``, ``mean_string_size``, ``t_s``, ``seed``.

Seeding: ``reset(seed=s)`` runs the engine with seed ``s``; without one, the seed comes from
the environment's generator (itself seeded by the first ``reset(seed=...)``).
``gymnasium.make_vec("platoonsim/Platoon-v1", num_envs=N)`` gives N of these environments
stepped together (``platoonsim.vector``). ``Platoon-v0`` (short episodes rewarded against
the upstream flow while the road was still filling) is gone; Gymnasium's registry names v1.
"""

from __future__ import annotations

from typing import Any

import numpy as np

try:
    import gymnasium as gym
    from gymnasium import spaces
except ImportError as e:  # pragma: no cover - the message is the point
    raise ImportError(
        "platoonsim.gym needs gymnasium: pip install gymnasium (or ./python[gym])"
    ) from e

from platoonsim.gate import GateTask, info as gate_info

HOLD, ORGANIZE = 0, 1
FEATURES = 8


def spaces_of() -> tuple[spaces.Box, spaces.Discrete]:
    """The observation and action spaces of one world."""
    high = np.array([10.0] * 3 + [3.0] * 3 + [1.0, 1.0], dtype=np.float32)
    return spaces.Box(low=np.zeros(FEATURES, dtype=np.float32), high=high, dtype=np.float32), spaces.Discrete(2)


def _single(d: dict[str, Any]) -> dict[str, Any]:
    """World 0's entries of a batch's arrays."""
    return {k: (v[0] if isinstance(v, np.ndarray) else v) for k, v in d.items()}


class PlatoonEnv(gym.Env):
    """Organize or hold the control section, one decision per interval, against a twin.

    Parameters: those of ``platoonsim.gate.GateTask`` (``scenario``, ``penetration``,
    ``demand_vphpl``, ``warmup_s``, ``decisions``, ``decision_s``, ``discharge_penalty``,
    ``overrides``, ``baseline``).
    """

    metadata = {"render_modes": []}

    def __init__(self, **kwargs: Any) -> None:
        super().__init__()
        self.task = GateTask(**kwargs)
        self.observation_space, self.action_space = spaces_of()
        self.batch = None

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        engine_seed = int(seed) if seed is not None else int(self.np_random.integers(0, 2**31 - 1))
        self.batch, d = self.task.batch([engine_seed], threads=1)
        self._seed = np.array([engine_seed])
        self._ended = False
        return d["obs"][0], _single(gate_info(d, self._seed))

    def step(self, action):
        if self.batch is None:
            raise RuntimeError("call reset() before step()")
        if not self.action_space.contains(action):
            raise ValueError(f"action {action!r} is not in {self.action_space} (0 hold, 1 organize)")
        if self._ended:
            raise RuntimeError("the episode has ended: call reset()")
        d = self.batch._core.gate_step([int(action) == ORGANIZE])
        self._ended = bool(d["done"][0])
        return d["obs"][0], float(d["reward"][0]), False, self._ended, _single(gate_info(d, self._seed))


# `gymnasium.make("platoonsim/Platoon-v1")`.
if "platoonsim/Platoon-v1" not in gym.registry:
    gym.register(
        id="platoonsim/Platoon-v1",
        entry_point="platoonsim.gym:PlatoonEnv",
        vector_entry_point="platoonsim.vector:PlatoonVecEnv",
    )
if "platoonsim/CavControl-v0" not in gym.registry:
    gym.register(
        id="platoonsim/CavControl-v0",
        entry_point="platoonsim.control:CavControlEnv",
        vector_entry_point="platoonsim.control:CavControlVecEnv",
    )
if "platoonsim/FlowMerge-v0" not in gym.registry:
    gym.register(
        id="platoonsim/FlowMerge-v0",
        entry_point="platoonsim.flow_merge:FlowMergeEnv",
        vector_entry_point="platoonsim.flow_merge:FlowMergeVecEnv",
    )
