"""``platoonsim/CavControl-v0``: the CAVs' accelerations set by a policy at an on-ramp merge
(docs/python.md, "CavControl-v0").

The mixed-autonomy merge in the style of Flow's merge benchmark: a one-lane freeway (``lanes``)
with an on-ramp whose traffic merges through a short acceleration lane; a share ``penetration``
of the arrivals are CAVs, whose accelerations the policy sets; every other vehicle, and every
CAV beyond ``max_controlled``, is driven by the models. The task runs in Rust for every world
in parallel (``crates/py/src/control.rs``); this module is its Gymnasium face.

* **Controlled vehicles**: up to ``max_controlled`` CAVs, one per slot; a CAV keeps its slot
  while it is on the road, new CAVs take free slots in order of entry.
* **Observation**: float32 ``(max_controlled * 6,)``, per slot: position / road length; speed /
  ``v_ref``; gap to the leader / ``gap_ref`` and (leader speed - speed) / ``v_ref``; gap of the
  follower / ``gap_ref`` and (speed - follower speed) / ``v_ref`` (no leader or follower: gap
  1, difference 0); gaps bumper to bumper, clipped to [0, 1], speeds to [-2, 2]; 0 for empty
  slots. ``info["mask"]`` says which slots hold a vehicle.
* **Action**: float32 ``(max_controlled,)`` accelerations (m/s²) within the CAVs' limits (the
  widest of their automation's and their drivers', ``cav.max_decel/max_accel`` and
  ``human.max_decel/max_accel``; values outside are clipped; a wrong shape or a non-finite
  value raises ValueError), held for ``action_s``. The engine applies at most the vehicle's own
  ACC/CACC acceleration (``AccelerateCapped``), so its collision avoidance and braking limit
  stay in force: the policy can hold back and brake, not drive into the vehicle ahead.
  Empty slots' actions are ignored.
* **Reward**: mean speed of every vehicle on the road / ``v_ref`` minus ``accel_penalty`` x the
  mean of (a / max_accel)^2 over the controlled vehicles, a the acceleration each applied in
  the step's last engine step (after the cap). ``info["outflow_vph"]``: the vehicles
  that left the road in the step, as a rate.
* **Episode**: ``warmup_s`` of model driving, then ``horizon_s``; truncated at the end,
  terminated if vehicles collided (which the capped action should make impossible).
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np

import gymnasium as gym
from gymnasium import spaces

import platoonsim
from platoonsim.vector import LockstepVecEnv

FEATURES = 6


def merge_scenario(
    lanes: int = 1,
    mainline_vph: float = 2000.0,
    ramp_vph: float = 200.0,
    penetration: float = 0.25,
    duration_s: float = 360.0,
) -> str:
    """The merge as scenario text: 1,200 m of freeway, an on-ramp merging at 700 m through a
    100 m acceleration lane, constant demand."""
    return f"""name = "merge"
[run]
duration_s = {float(duration_s)}
warmup_s = 0.0
penetration = {float(penetration)}

[network]
start_m = 0.0
end_m = 1200.0
interval_s = {float(duration_s)}
mainline_vph = [{float(mainline_vph)}]

[[network.lanes]]
from_m = 0.0
to_m = 1200.0
count = {int(lanes)}

[[network.on_ramps]]
id = "ramp"
x_m = 700.0
accel_lane_m = 100.0
ramp_length_m = 200.0
demand_vph = [{float(ramp_vph)}]
"""


class _Task:
    """The parameters, checked, and the spaces of one world."""

    def __init__(
        self,
        lanes: int = 1,
        mainline_vph: float = 2000.0,
        ramp_vph: float = 200.0,
        penetration: float = 0.25,
        warmup_s: float = 60.0,
        horizon_s: float = 300.0,
        action_s: float = 0.5,
        max_controlled: int = 10,
        v_ref: float = 30.0,
        gap_ref: float = 100.0,
        accel_penalty: float = 0.1,
        overrides: dict[str, Any] | None = None,
    ) -> None:
        for name, v in (("warmup_s", warmup_s), ("accel_penalty", accel_penalty)):
            if not (np.isfinite(v) and v >= 0):
                raise ValueError(f"{name} = {v!r}: must be a finite number >= 0")
        for name, v in (("horizon_s", horizon_s), ("action_s", action_s), ("v_ref", v_ref), ("gap_ref", gap_ref)):
            if not (np.isfinite(v) and v > 0):
                raise ValueError(f"{name} = {v!r}: must be a finite number > 0")
        if isinstance(max_controlled, bool) or not isinstance(max_controlled, (int, np.integer)) or not 1 <= max_controlled <= 1024:
            raise ValueError(f"max_controlled = {max_controlled!r}: must be an int in [1, 1024]")
        self.scenario = merge_scenario(lanes, mainline_vph, ramp_vph, penetration, warmup_s + horizon_s)
        self.overrides = dict(overrides or {})
        self.warmup_s = float(warmup_s)
        self.action_s = float(action_s)
        self.k = int(max_controlled)
        self.v_ref, self.gap_ref, self.accel_penalty = float(v_ref), float(gap_ref), float(accel_penalty)
        # The scenario is checked now (a bad setting fails here, not at the first reset).
        probe = platoonsim.BatchSimulation(self.scenario, seeds=[0], overrides=self.overrides, threads=1)
        cfg = probe.config(0)
        self.steps = max(1, round(self.action_s / probe.dt_s))
        # The CAVs' limits: their automation's, and their drivers' while they drive manually
        # (a lane change): the widest of the two.
        human = cfg["human"]
        self.a_low = min(float(cfg["cav"]["max_decel"]), float(human["max_decel"]["min"]))
        self.a_high = max(float(cfg["cav"]["max_accel"]), float(human["max_accel"]["max"]))
        low = np.tile(np.array([0, -2, 0, -2, 0, -2], dtype=np.float32), self.k)
        high = np.tile(np.array([1, 2, 1, 2, 1, 2], dtype=np.float32), self.k)
        self.observation_space = spaces.Box(low=low, high=high, dtype=np.float32)
        self.action_space = spaces.Box(
            low=np.full(self.k, self.a_low, dtype=np.float32),
            high=np.full(self.k, self.a_high, dtype=np.float32),
            dtype=np.float32,
        )

    def batch(self, seeds: Sequence[int], threads: int | None) -> platoonsim.BatchSimulation:
        b = platoonsim.BatchSimulation(self.scenario, seeds=[int(s) for s in seeds], overrides=self.overrides, threads=threads)
        b._core.control_setup(self.k, self.steps, self.v_ref, self.gap_ref, self.accel_penalty, self.a_low, self.a_high)
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
                f"controlled slot); got {a!r}"
            )
        return np.ascontiguousarray(arr.reshape(-1, self.k))

    def info(self, mask: np.ndarray, outflow: np.ndarray, collisions: np.ndarray) -> dict[str, Any]:
        return {
            "mask": mask,
            "controlled": mask.sum(axis=-1),
            "outflow_vph": outflow * 3600.0 / self.action_s,
            "collisions": collisions,
        }



class CavControlEnv(gym.Env):
    """One merge (module docstring); parameters: ``lanes``, ``mainline_vph``, ``ramp_vph``,
    ``penetration``, ``warmup_s``, ``horizon_s``, ``action_s``, ``max_controlled``, ``v_ref``,
    ``gap_ref``, ``accel_penalty``, ``overrides`` (other scenario keys)."""

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
        obs, mask, _, out, col, _ = self.batch._core.control_reset()
        info = self.task.info(mask[0], out[0], col[0])
        info["seed"] = engine_seed
        return obs[0].reshape(-1), info

    def step(self, action):
        if self.batch is None:
            raise RuntimeError("call reset() before step()")
        a = self.task.actions(action, None)
        obs, mask, rew, out, col, done = self.batch._core.control_step(a)
        info = self.task.info(mask[0], out[0], col[0])
        return obs[0].reshape(-1), float(rew[0]), bool(col[0] > 0), bool(done[0]), info


class CavControlVecEnv(LockstepVecEnv):
    """``num_envs`` merges stepped together; ``threads`` is the pool's size. World ``i`` equals
    a ``CavControlEnv`` with the same parameters, seed and actions. Lockstep episodes,
    autoreset and seeding as ``platoonsim.vector.LockstepVecEnv``."""

    def _task(self, **kwargs: Any) -> _Task:
        return _Task(**kwargs)

    def _first(self):
        obs, mask, _, out, col, _ = self.batch._core.control_reset()
        return obs, self.task.info(mask, out, col)

    def _advance(self, a):
        obs, mask, rew, out, col, done = self.batch._core.control_step(a)
        return obs, rew, col, done, self.task.info(mask, out, col)
