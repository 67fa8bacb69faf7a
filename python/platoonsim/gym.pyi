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
    # The parameters of platoonsim.gate.GateTask.
    def __init__(self, **kwargs: Any) -> None: ...
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]: ...
    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]: ...
