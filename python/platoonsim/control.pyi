from typing import Any

import gymnasium as gym
import numpy as np

from . import BatchSimulation
from .vector import LockstepVecEnv

FEATURES: int

def merge_scenario(
    lanes: int = 1,
    mainline_vph: float = 2000.0,
    ramp_vph: float = 200.0,
    penetration: float = 0.25,
    duration_s: float = 360.0,
) -> str: ...

class CavControlEnv(gym.Env[np.ndarray, np.ndarray]):
    batch: BatchSimulation | None
    def __init__(self, **kwargs: Any) -> None: ...
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]: ...
    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]: ...

class CavControlVecEnv(LockstepVecEnv): ...
