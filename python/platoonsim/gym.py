"""``PlatoonEnv``: platoon organization as a Gymnasium environment (docs/python.md).

One episode is one run of the homogeneous road (or any plain-road scenario with a control
section): a warm-up with no organization, then one decision every ``decision_s`` seconds,
which is also the detectors' aggregation interval. The agent decides per decision interval
whether the control section is organized (PD: CAVs join the leftmost lane inside the section)
or held (no advice).

* **Action**: ``Discrete(2)``: 0 hold, 1 organize, for the next ``decision_s`` seconds.
* **Observation** (float32, 8 values): for each of the first three detectors (upstream,
  control section, discharge on the homogeneous road) the flow of the last interval in
  1000 veh/h/lane and its mean speed in 100 km/h (0 when no vehicle crossed); then, inside
  the control section now, the share of the CAVs that are in the leftmost lane and the mean
  size of the CACC strings the CAVs are in, divided by 10 (the maximum platoon size).
* **Reward**: the platoon gain minus the discharge loss of the interval:
  ``(Lbar - 1) - discharge_penalty * max(0, 1 - q_discharge / q_upstream)``, with ``Lbar``
  the mean string size of the CAVs in the control section at the end of the interval and the
  flows those of the upstream and discharge detectors over the interval (0 loss when no
  vehicle passed upstream).
* **Episode end**: truncated when the run's duration is reached; never terminated.

Seeding: ``reset(seed=s)`` runs the engine with seed ``s``; without one, the seed comes from
the environment's generator (itself seeded by the first ``reset(seed=...)``).

The gate is the engine's own PD organizer behind a switch (``Simulation.use_gate``; advice at
every step, stepping stays in Rust). ``gate="python"`` keeps the earlier Python organizer that
refreshes its advice every ``advice_every_s``. ``gymnasium.make_vec("platoonsim/Platoon-v0",
num_envs=N)`` gives N of these environments stepped together (``platoonsim.vector``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

try:
    import gymnasium as gym
    from gymnasium import spaces
except ImportError as e:  # pragma: no cover - the message is the point
    raise ImportError(
        "platoonsim.gym needs gymnasium: pip install gymnasium (or ./python[gym])"
    ) from e

import platoonsim

HOLD, ORGANIZE = 0, 1
_N_DETECTORS = 3


class _Gate:
    """The PD rule, switched on and off by the agent; asked every ``every_steps`` steps."""

    name = "gym-pd-gate"
    advises_cavs = True
    advises_humans = False

    def __init__(self, zone: tuple[float, float], every_steps: int):
        self.zone = zone
        self.every_steps = every_steps
        self.on = False

    def advise(self, sim: platoonsim.Simulation, t_s: float, v: dict[str, np.ndarray]) -> np.ndarray:
        lanes = np.full(v["id"].shape, -1, dtype=np.int64)
        if not self.on:
            return lanes
        x = v["x_m"]
        inside = (x >= self.zone[0]) & (x < self.zone[1])
        own = v["lane"][inside].astype(np.int64)
        left = sim.leftmost_through(x[inside])
        lanes[inside] = np.where(left < 0, own, np.maximum(left, own))
        return lanes


def zone_platoons(
    v: dict[str, np.ndarray], zone: tuple[float, float], leftmost_lane: int
) -> tuple[float, float]:
    """(share of the section's CAVs in the leftmost lane, mean string size of its CAVs)."""
    inside = (v["x_m"] >= zone[0]) & (v["x_m"] < zone[1]) & (v["kind"] == 1)
    if not inside.any():
        return 0.0, 1.0
    share = float(np.mean(v["lane"][inside] == leftmost_lane))
    # A CAV's string size: the number of vehicles on the road that share its platoon_id.
    ids, counts = np.unique(v["platoon_id"], return_counts=True)
    sizes = counts[np.searchsorted(ids, v["platoon_id"][inside])]
    return share, float(np.mean(sizes))


def flows(d: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Flow (veh/h/lane) and speed (km/h, 0 if none) of the first detectors' last interval."""
    flow = np.zeros(_N_DETECTORS)
    speed = np.zeros(_N_DETECTORS)
    rows = np.flatnonzero(d["lane"] == "all")[:_N_DETECTORS]
    lanes_per: dict[str, int] = {}
    for name, lane in zip(d["detector"], d["lane"]):
        if lane != "all":
            lanes_per[name] = lanes_per.get(name, 0) + 1
    for k, r in enumerate(rows):
        flow[k] = d["flow_vph"][r] / max(1, lanes_per.get(d["detector"][r], 1))
        s = d["speed_kmh"][r]
        speed[k] = 0.0 if np.isnan(s) else s
    return flow, speed


def observation(
    v: dict[str, np.ndarray],
    d: dict[str, np.ndarray],
    zone: tuple[float, float],
    leftmost_lane: int,
    space: spaces.Box,
) -> tuple[np.ndarray, dict[str, Any]]:
    """The observation and the info of one world from its vehicles and detectors."""
    flow, speed = flows(d)
    share, size = zone_platoons(v, zone, leftmost_lane)
    obs = np.concatenate([flow / 1000.0, speed / 100.0, [share, size / 10.0]]).astype(np.float32)
    obs = np.clip(obs, space.low, space.high)
    info = {"flow_vphpl": flow, "speed_kmh": speed, "leftmost_share": share, "mean_string_size": size}
    return obs, info


def reward(flow: np.ndarray, size: float, discharge_penalty: float) -> tuple[float, float]:
    """(reward, discharge loss) of an interval."""
    loss = max(0.0, 1.0 - flow[2] / flow[0]) if flow[0] > 0 else 0.0
    return float((size - 1.0) - discharge_penalty * loss), loss


class PlatoonEnv(gym.Env):
    """Organize or hold the control section, one decision per detector interval.

    Parameters: ``scenario`` (a plain road with a control section and at least three
    detectors, default the homogeneous road), ``penetration``, ``demand_vphpl``,
    ``warmup_s`` (no decisions; long enough for traffic to reach the control section),
    ``decisions`` per episode, ``decision_s`` (the detector interval), ``discharge_penalty``,
    ``overrides`` for any other scenario key, and ``gate``: ``"native"`` (the engine's PD
    organizer switched on and off) or ``"python"`` (a Python organizer refreshing its advice
    every ``advice_every_s``).
    """

    metadata = {"render_modes": []}

    def __init__(
        self,
        scenario: str = "homogeneous",
        penetration: float = 0.5,
        demand_vphpl: float = 2500.0,
        warmup_s: float = 240.0,
        decisions: int = 20,
        decision_s: float = 30.0,
        advice_every_s: float = 1.0,
        discharge_penalty: float = 5.0,
        overrides: dict[str, Any] | None = None,
        gate: str = "native",
    ) -> None:
        super().__init__()
        if gate not in ("native", "python"):
            raise ValueError(f"gate = {gate!r}: must be \"native\" or \"python\"")
        self.gate = gate
        # NaN compares false with every bound: each check says what is allowed.
        if not (math.isfinite(discharge_penalty) and discharge_penalty >= 0):
            raise ValueError(f"discharge_penalty = {discharge_penalty}: must be a finite number >= 0")
        if not (math.isfinite(advice_every_s) and advice_every_s > 0):
            raise ValueError(f"advice_every_s = {advice_every_s}: must be a finite number of seconds > 0")
        if decisions < 1 or decision_s <= 0 or warmup_s < 0:
            raise ValueError(
                f"decisions = {decisions} (>= 1), decision_s = {decision_s} (> 0) and "
                f"warmup_s = {warmup_s} (>= 0) are out of range"
            )
        self.scenario = scenario
        self.decision_s = float(decision_s)
        self.warmup_s = float(warmup_s)
        self.decisions = int(decisions)
        self.discharge_penalty = float(discharge_penalty)
        self.overrides = {
            "run.penetration": penetration,
            "demand.vph_per_lane": demand_vphpl,
            "run.warmup_s": 0.0,
            "run.duration_s": self.warmup_s + self.decisions * self.decision_s,
            "measurement.aggregation_s": self.decision_s,
            **(overrides or {}),
        }
        self.advice_every_s = float(advice_every_s)
        self.action_space = spaces.Discrete(2)
        high = np.array([10.0] * _N_DETECTORS + [3.0] * _N_DETECTORS + [1.0, 1.0], dtype=np.float32)
        self.observation_space = spaces.Box(low=np.zeros(8, dtype=np.float32), high=high, dtype=np.float32)
        # Checked now, so that a bad setting fails here rather than at the first reset.
        probe = platoonsim.Simulation(self.scenario, overrides=self.overrides, events=False)
        road = probe.config["road"]
        if road.get("network") is not None:
            raise ValueError("PlatoonEnv needs a plain road (a scenario without [network])")
        if len(probe.config["detectors"]) < _N_DETECTORS:
            raise ValueError(f"PlatoonEnv needs at least {_N_DETECTORS} detectors")
        self.zone = (float(road["control_start_m"]), float(road["control_end_m"]))
        # On a plain road the leftmost through lane is the last one everywhere.
        self.leftmost_lane = int(road["lanes"]) - 1
        self._every = max(1, round(self.advice_every_s / probe.dt_s))
        self.sim: platoonsim.Simulation | None = None
        self._gate: _Gate | None = None

    # -- observation and reward ----------------------------------------------------------

    def _observe(self) -> tuple[np.ndarray, dict[str, Any]]:
        assert self.sim is not None
        obs, info = observation(
            self.sim.vehicles(), self.sim.detectors(), self.zone, self.leftmost_lane, self.observation_space
        )
        info["t_s"] = self.sim.time_s
        return obs, info

    # -- the Gymnasium API ---------------------------------------------------------------

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        engine_seed = int(seed) if seed is not None else int(self.np_random.integers(0, 2**31 - 1))
        if self.gate == "native":
            self._gate = None
            self.sim = platoonsim.Simulation(self.scenario, seed=engine_seed, overrides=self.overrides, events=False)
            self.sim.use_gate()
        else:
            self._gate = _Gate(self.zone, self._every)
            self.sim = platoonsim.Simulation(
                self.scenario, seed=engine_seed, overrides=self.overrides, organizer=self._gate, events=False
            )
        self.sim.run_until(self.warmup_s)
        obs, info = self._observe()
        info["seed"] = engine_seed
        return obs, info

    def step(self, action):
        if self.sim is None:
            raise RuntimeError("call reset() before step()")
        if not self.action_space.contains(action):
            raise ValueError(f"action {action!r} is not in {self.action_space} (0 hold, 1 organize)")
        on = int(action) == ORGANIZE
        if self._gate is not None:
            self._gate.on = on
        else:
            self.sim.set_gate(on)
        self.sim.run_until(self.sim.time_s + self.decision_s)
        obs, info = self._observe()
        r, loss = reward(info["flow_vphpl"], info["mean_string_size"], self.discharge_penalty)
        info["discharge_loss"] = loss
        truncated = self.sim.done
        return obs, r, False, truncated, info


# `gymnasium.make("platoonsim/Platoon-v0")`.
if "platoonsim/Platoon-v0" not in gym.registry:
    gym.register(
        id="platoonsim/Platoon-v0",
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
