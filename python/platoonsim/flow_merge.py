"""``platoonsim/FlowMerge-v0``: Flow's merge benchmark ``merge0`` (Vinitsky et al. 2018) on
platoonsim's engine (docs/learning.md, "FlowMerge-v0"; docs/python.md).

One highway lane, 100 m of inflow and 500 m before the merge, 100 m after it; one merge lane of
200 m joining at the merge (here: its last 100 m are an acceleration lane beside the 100 m after
the merge). 2,000 veh/h on the highway, of which ``rl_share`` = 10 % learning vehicles (CAVs),
100 veh/h of human drivers on the merge. Every ``action_s`` = 1 s the policy sets the
accelerations of up to ``num_rl`` = 5 learning vehicles; 750 actions per episode.

* **Controlled list** (Flow's ``rl_veh``): learning vehicles in order of entry; one that leaves
  the road leaves the list and the later ones move up; new ones join its end. Slot ``j`` of the
  observation and of the action is the list's ``j``-th vehicle; ``info["ids"]`` gives the
  vehicle ids (-1: empty slot), ``info["mask"]`` the occupied slots. Learning vehicles beyond
  the list drive by their own ACC/CACC law.
* **Observation**: float32 ``(5 * num_rl,)``, per slot: speed / v_max; (leader speed - speed) /
  v_max; gap to the leader / L_net; (speed - follower speed) / v_max; gap of the follower /
  L_net, with v_max = ``speed_limit`` (30 m/s) and L_net = 900 m (the sum of Flow's edges); no
  leader: leader speed v_max and gap L_net; no follower: speed 0 and gap L_net; gaps bumper to
  bumper; speeds clipped to [0, 2], differences to [-2, 2], gaps to [0, 1]; 0 for empty slots.
* **Action**: float32 ``(num_rl,)`` accelerations in [-``max_decel``, ``max_accel``] (1.5 m/s²
  each); values outside are clipped; a wrong shape or a non-finite value raises ValueError.
  Applied as the engine's ``AccelerateSafe`` command: within the vehicle's limits and never
  above its collision-free speed behind the vehicle ahead (SUMO's speed mode that regards the
  safe speed, as in Flow). Empty slots' actions are ignored.
* **Reward**: Flow's: max(r1 + 0.1 r2, 0) with r1 = max(|v* 1| - |v - v*|, 0) / |v* 1| over the
  speeds v of every vehicle on the road (v* = ``target_velocity`` = 20 m/s) and r2 the sum over
  the controlled vehicles with a leader of min(time headway / 1 s - 1, 0); 0 in a step with a
  collision.
* **Episode**: ``warmup_s`` (0: the road starts empty, as Flow's episodes start nearly empty)
  then ``horizon`` actions; truncated at the end, terminated by a collision.
* ``baseline``: ``None`` (the policy drives), ``"acc-only"`` (the actions are ignored: every
  learning vehicle drives by its ACC/CACC law) or ``"all-human"`` (no learning vehicles).

The task runs in Rust for every world in parallel (``crates/py/src/flow_merge.rs``).
``FlowMergeVecEnv`` is the native vector environment, ``platoonsim.parallel.FlowMergeParallelEnv``
the PettingZoo form (one agent per controlled vehicle).
"""

from __future__ import annotations

import math
from typing import Any, Sequence

import numpy as np

import gymnasium as gym
from gymnasium import spaces

import platoonsim
from platoonsim.vector import LockstepVecEnv

FEATURES = 5
#: Flow's network length: the sum of merge0's edges (m).
NETWORK_LENGTH_M = 900.0
#: Flow's reward: smallest acceptable time headway (s) and the weights of its two terms.
T_MIN_S, ETA1, ETA2 = 1.0, 1.0, 0.1
BASELINES = (None, "acc-only", "all-human")

#: The arguments of the environments and their defaults (merge0's values).
DEFAULTS: dict[str, Any] = {
    "num_rl": 5,
    "horizon": 750,
    "action_s": 1.0,
    "warmup_s": 0.0,
    "mainline_vph": 2000.0,
    "rl_share": 0.1,
    "merge_vph": 100.0,
    "max_accel": 1.5,
    "max_decel": 1.5,
    "target_velocity": 20.0,
    "speed_limit": 30.0,
    "baseline": None,
    "overrides": None,
}


def flow_merge_scenario(
    mainline_vph: float = 2000.0,
    rl_share: float = 0.1,
    merge_vph: float = 100.0,
    speed_limit: float = 30.0,
    duration_s: float = 750.0,
) -> str:
    """merge0's network and demand as scenario text: 700 m of one-lane highway (100 m inflow,
    500 m before the merge, 100 m after), the merge lane joining at 600 m through a 100 m
    acceleration lane (200 m of ramp roadway), human drivers only on the merge (its
    ``penetration`` 0), constant demand; desired speeds N(1, 0.1) x the speed limit (SUMO's
    default speed factor) within +-2 standard deviations; merge vehicles enter at 7.5 m/s at
    most (merge0's depart speed there)."""
    v = float(speed_limit) * 3.6
    return f"""name = "flow-merge"
[run]
duration_s = {float(duration_s)}
warmup_s = 0.0
penetration = {float(rl_share)}

[human]
desired_speed_kmh = {{ mean = {v}, sd = {0.1 * v}, min = {0.8 * v}, max = {1.2 * v} }}

[network]
start_m = 0.0
end_m = 700.0
interval_s = {float(duration_s)}
mainline_vph = [{float(mainline_vph)}]
ramp_speed_kmh = 27.0

[[network.lanes]]
from_m = 0.0
to_m = 700.0
count = 1

[[network.on_ramps]]
id = "merge"
x_m = 600.0
accel_lane_m = 100.0
ramp_length_m = 200.0
demand_vph = [{float(merge_vph)}]
penetration = 0.0
"""


def _number(name: str, v: Any, low: float, *, strict: bool = False, high: float = math.inf) -> float:
    ok = isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool)
    if ok:
        f = float(v)
        ok = math.isfinite(f) and (f > low if strict else f >= low) and f <= high
    if not ok:
        lo = f"> {low:g}" if strict else f">= {low:g}"
        hi = f" and <= {high:g}" if math.isfinite(high) else ""
        raise ValueError(f"{name} = {v!r}: must be a finite number {lo}{hi}")
    return float(v)


def _int(name: str, v: Any, low: int, high: int) -> int:
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or not low <= v <= high:
        raise ValueError(f"{name} = {v!r}: must be an int in [{low}, {high}]")
    return int(v)


class _Task:
    """The arguments, checked, and the spaces of one world."""

    def __init__(self, **kwargs: Any) -> None:
        unknown = sorted(set(kwargs) - set(DEFAULTS))
        if unknown:
            raise TypeError(
                f"FlowMerge-v0: unknown argument {unknown[0]!r}; allowed: {', '.join(DEFAULTS)}"
            )
        a = {**DEFAULTS, **kwargs}
        self.k = _int("num_rl", a["num_rl"], 1, 1024)
        self.horizon = _int("horizon", a["horizon"], 1, 10_000_000)
        self.action_s = _number("action_s", a["action_s"], 0.0, strict=True)
        self.warmup_s = _number("warmup_s", a["warmup_s"], 0.0)
        mainline = _number("mainline_vph", a["mainline_vph"], 0.0)
        rl_share = _number("rl_share", a["rl_share"], 0.0, high=1.0)
        merge = _number("merge_vph", a["merge_vph"], 0.0)
        self.a_high = _number("max_accel", a["max_accel"], 0.0, strict=True)
        self.a_low = -_number("max_decel", a["max_decel"], 0.0, strict=True)
        self.target_v = _number("target_velocity", a["target_velocity"], 0.0, strict=True)
        self.v_max = _number("speed_limit", a["speed_limit"], 0.0, strict=True, high=100.0)
        self.baseline = a["baseline"]
        if self.baseline not in BASELINES:
            raise ValueError(
                f"baseline = {self.baseline!r}: must be None (the policy drives), "
                "'acc-only' or 'all-human'"
            )
        overrides = a["overrides"]
        if overrides is not None and not isinstance(overrides, dict):
            raise ValueError(f"overrides = {overrides!r}: must be a dict of scenario keys or None")
        if self.baseline == "all-human":
            rl_share = 0.0
        self.overrides = dict(overrides or {})
        duration = self.warmup_s + self.horizon * self.action_s
        self.scenario = flow_merge_scenario(mainline, rl_share, merge, self.v_max, duration)
        # The scenario is checked now (a bad setting fails here, not at the first reset).
        probe = platoonsim.BatchSimulation(self.scenario, seeds=[0], overrides=self.overrides, threads=1)
        self.dt = float(probe.dt_s)
        self.steps = max(1, round(self.action_s / self.dt))
        low = np.tile(np.array([0, -2, 0, -2, 0], dtype=np.float32), self.k)
        high = np.tile(np.array([2, 2, 1, 2, 1], dtype=np.float32), self.k)
        self.observation_space = spaces.Box(low=low, high=high, dtype=np.float32)
        self.action_space = spaces.Box(
            low=np.full(self.k, self.a_low, dtype=np.float32),
            high=np.full(self.k, self.a_high, dtype=np.float32),
            dtype=np.float32,
        )

    def batch(self, seeds: Sequence[int], threads: int | None) -> platoonsim.BatchSimulation:
        b = platoonsim.BatchSimulation(
            self.scenario, seeds=[int(s) for s in seeds], overrides=self.overrides, threads=threads
        )
        b._core.flow_setup(
            self.k, self.steps, self.v_max, NETWORK_LENGTH_M, self.target_v, T_MIN_S, ETA1, ETA2,
            self.a_low, self.a_high, self.baseline is None,
        )
        b.run_until(self.warmup_s)
        return b

    def actions(self, a: Any, n: int | None) -> np.ndarray:
        """The actions as (worlds, slots) float64; ``n`` None: one world's ``(k,)``."""
        shape = (self.k,) if n is None else (n, self.k)
        try:
            arr = np.asarray(a, dtype=np.float64)
        except (TypeError, ValueError):
            arr = np.array([np.nan])
        if arr.shape != shape or not np.isfinite(arr).all():
            raise ValueError(
                f"actions must be finite accelerations of shape {shape} (m/s², one per "
                f"controlled slot; clipped to [{self.a_low:g}, {self.a_high:g}]); got {a!r}"
            )
        return np.ascontiguousarray(arr.reshape(-1, self.k))

    def info(self, out: tuple) -> dict[str, Any]:
        _, ids, _, mean_v, vehicles, outflow, collisions, _ = out
        mask = ids >= 0
        return {
            "ids": ids,
            "mask": mask,
            "controlled": mask.sum(axis=-1),
            "mean_speed_mps": mean_v,
            "vehicles": vehicles,
            "outflow_vph": outflow * 3600.0 / (self.steps * self.dt),
            "collisions": collisions,
        }



class FlowMergeEnv(gym.Env):
    """One merge0 world (module docstring); arguments: ``DEFAULTS``."""

    metadata = {"render_modes": []}

    def __init__(self, **kwargs: Any) -> None:
        super().__init__()
        self.task = _Task(**kwargs)
        self.observation_space = self.task.observation_space
        self.action_space = self.task.action_space
        self.batch: platoonsim.BatchSimulation | None = None

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        engine_seed = int(seed) if seed is not None else int(self.np_random.integers(0, 2**31 - 1))
        self.batch = self.task.batch([engine_seed], threads=1)
        out = self.batch._core.flow_reset()
        info = {k: v[0] for k, v in self.task.info(out).items()}
        info["seed"] = engine_seed
        return out[0][0].reshape(-1), info

    def step(self, action):
        if self.batch is None:
            raise RuntimeError("call reset() before step()")
        out = self.batch._core.flow_step(self.task.actions(action, None))
        obs, _, rew, _, _, _, col, done = out
        info = {k: v[0] for k, v in self.task.info(out).items()}
        return obs[0].reshape(-1), float(rew[0]), bool(col[0] > 0), bool(done[0]), info


class FlowMergeVecEnv(LockstepVecEnv):
    """``num_envs`` merge0 worlds stepped together; ``threads`` is the pool's size. World ``i``
    equals a ``FlowMergeEnv`` with the same arguments, seed and actions, bit for bit. Lockstep
    episodes, autoreset and seeding as ``platoonsim.vector.LockstepVecEnv``."""

    def _task(self, **kwargs: Any) -> _Task:
        return _Task(**kwargs)

    def _first(self):
        out = self.batch._core.flow_reset()
        return out[0], self.task.info(out)

    def _advance(self, a):
        out = self.batch._core.flow_step(a)
        obs, _, rew, _, _, _, col, done = out
        return obs, rew, col, done, self.task.info(out)
