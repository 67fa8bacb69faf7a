"""The gate task of ``platoonsim/Platoon-v1`` (docs/learning.md): its parameters, checked, and
the batch that runs it. ``PlatoonEnv`` (gym.py) and ``PlatoonVecEnv`` (vector.py) are views of
one ``GateTask``; the observation and reward are computed in Rust (``crates/py/src/gate.rs``).

Each episode is a pair of runs of the same road with the same seed: the policy's, where the
agent switches the engine's PD organizer on or off in the control section once per decision
interval, and its twin, where the organizer stays off. Both first run ``warmup_s`` with the
organizer off, then ``decisions`` intervals of ``decision_s``. The reward of an interval is
``g + discharge_penalty * c``: ``g`` the change of the paper's L̄ (mean of each CAV's largest
string, over the CAVs that left the road in the interval) and ``c`` the change of the
discharge detector's count, both against the twin. Never organizing earns exactly 0.
"""

from __future__ import annotations

import math
from typing import Any, Sequence

import numpy as np

import platoonsim

# Slowest average speed (m/s) at which the warm-up must bring the first vehicles past the
# discharge detector before the first decision interval starts (72 km/h; the road runs at
# 90-110 km/h below capacity).
_FILL_SPEED_MPS = 20.0
BASELINES = ("flow-aware",)


def _number(name: str, v: Any, low: float, strict: bool) -> float:
    ok = isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool)
    if ok:
        v = float(v)
        ok = math.isfinite(v) and (v > low if strict else v >= low)
    if not ok:
        rel = ">" if strict else ">="
        raise ValueError(f"{name} = {v!r}: must be a finite number {rel} {low:g}")
    return float(v)


class GateTask:
    """The parameters of the gate task, checked at construction.

    ``scenario`` (a plain road with a control section and at least three detectors: upstream,
    control section, discharge; default the homogeneous road), ``penetration``,
    ``demand_vphpl``, ``warmup_s`` (a whole number of decision intervals, long enough that
    vehicles at 72 km/h have passed the discharge detector before the first decision),
    ``decisions`` per episode, ``decision_s`` (also the detectors' aggregation interval),
    ``discharge_penalty`` (λ), ``overrides`` for any other scenario key, and ``baseline``:
    None (the agent's switch decides) or ``"flow-aware"`` (the scenario's Flow-Aware
    strategy organizes from the end of the warm-up and the actions are ignored; to evaluate
    it on the same measures).
    """

    def __init__(
        self,
        scenario: str = "homogeneous",
        penetration: float = 0.5,
        demand_vphpl: float = 2500.0,
        warmup_s: float = 600.0,
        decisions: int = 60,
        decision_s: float = 60.0,
        discharge_penalty: float = 5.0,
        overrides: dict[str, Any] | None = None,
        baseline: str | None = None,
    ) -> None:
        self.decision_s = _number("decision_s", decision_s, 0.0, True)
        self.warmup_s = _number("warmup_s", warmup_s, 0.0, False)
        self.discharge_penalty = _number("discharge_penalty", discharge_penalty, 0.0, False)
        if isinstance(decisions, bool) or not isinstance(decisions, (int, np.integer)) or decisions < 1:
            raise ValueError(f"decisions = {decisions!r}: must be an int >= 1")
        if baseline is not None and baseline not in BASELINES:
            raise ValueError(f"baseline = {baseline!r}: must be None (the agent decides) or one of {BASELINES}")
        self.decisions = int(decisions)
        self.baseline = baseline
        self.scenario = scenario
        self.overrides = {
            "run.penetration": penetration,
            "demand.vph_per_lane": demand_vphpl,
            "run.warmup_s": 0.0,
            "run.duration_s": self.warmup_s + self.decisions * self.decision_s,
            "measurement.aggregation_s": self.decision_s,
            **(overrides or {}),
        }
        # Checked now, so that a bad setting fails here rather than at the first reset.
        plain = platoonsim.BatchSimulation(self.scenario, seeds=[0], threads=1).config(0)
        if plain["road"].get("network") is not None:
            raise ValueError(f"scenario = {scenario!r}: the gate task needs a plain road (a scenario without [network])")
        try:
            probe = platoonsim.BatchSimulation(self.scenario, seeds=[0, 0], overrides=self.overrides, threads=1)
        except platoonsim.ScenarioError as e:
            if "measurement.aggregation_s" in str(e):
                # decision_s is the detectors' interval: say which argument set it.
                raise platoonsim.ScenarioError(f"decision_s = {self.decision_s:g} (sets {e})") from e
            raise
        probe._core.gate_setup(self.decision_s, self.warmup_s, self.decisions, self.discharge_penalty, [True])
        cfg = probe.config(0)
        x_discharge = float(cfg["detectors"][2]["position_m"])
        fill_s = x_discharge / _FILL_SPEED_MPS
        if self.warmup_s < fill_s:
            raise ValueError(
                f"warmup_s = {self.warmup_s:g}: the road is not filled yet; vehicles at 72 km/h "
                f"reach the discharge detector ({x_discharge:g} m) after {fill_s:g} s "
                f"(give at least {math.ceil(fill_s / self.decision_s) * self.decision_s:g})"
            )
        self.leftmost_lane = int(cfg["road"]["lanes"]) - 1

    def batch(self, seeds: Sequence[int], threads: int | None) -> tuple[platoonsim.BatchSimulation, dict[str, Any]]:
        """A batch of the episodes of ``seeds`` (their twins after them), warmed up; the first
        arrays (``BatchCore.gate_reset``)."""
        seeds = [int(s) for s in seeds]
        n = len(seeds)
        ov: dict[str, Any] | list[dict[str, Any]] = self.overrides
        if self.baseline == "flow-aware":
            own = {**self.overrides, "strategy.kind": "flow-aware", "strategy.start_s": self.warmup_s}
            ov = [own] * n + [self.overrides] * n
        b = platoonsim.BatchSimulation(self.scenario, seeds=seeds + seeds, overrides=ov, threads=threads)
        b._core.gate_setup(
            self.decision_s, self.warmup_s, self.decisions, self.discharge_penalty, [self.baseline is None] * n
        )
        return b, b._core.gate_reset()


def info(d: dict[str, Any], seeds: np.ndarray) -> dict[str, Any]:
    """The info arrays of a reset or step, over the worlds (docs/learning.md)."""
    out = {k: v for k, v in d.items() if k not in ("obs", "reward", "done")}
    out["seed"] = seeds.copy()
    return out
