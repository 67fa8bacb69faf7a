from typing import Any

import gymnasium as gym
import numpy as np

from . import BatchSimulation
from .gate import GateTask

HOLD: int
ORGANIZE: int
FEATURES: int

def spaces_of() -> tuple[gym.spaces.Box, gym.spaces.Discrete]: ...

class PlatoonEnv(gym.Env[np.ndarray, int]):
    task: GateTask
    batch: BatchSimulation | None
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
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]: ...
    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]: ...
