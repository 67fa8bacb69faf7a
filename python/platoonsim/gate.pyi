from typing import Any, Sequence

import numpy as np

from . import BatchSimulation

BASELINES: tuple[str, ...]

class GateTask:
    scenario: str
    decision_s: float
    warmup_s: float
    decisions: int
    discharge_penalty: float
    baseline: str | None
    overrides: dict[str, Any]
    leftmost_lane: int
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
    ) -> None: ...
    def batch(self, seeds: Sequence[int], threads: int | None) -> tuple[BatchSimulation, dict[str, Any]]: ...

def info(d: dict[str, Any], seeds: np.ndarray) -> dict[str, Any]: ...
