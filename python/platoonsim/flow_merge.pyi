from typing import Any

import gymnasium as gym
import numpy as np

from . import BatchSimulation
from .vector import LockstepVecEnv

FEATURES: int
NETWORK_LENGTH_M: float
T_MIN_S: float
ETA1: float
ETA2: float
BASELINES: tuple[str | None, ...]
DEFAULTS: dict[str, Any]

def flow_merge_scenario(
    mainline_vph: float = 2000.0,
    rl_share: float = 0.1,
    merge_vph: float = 100.0,
    speed_limit: float = 30.0,
    duration_s: float = 750.0,
) -> str: ...

class FlowMergeEnv(gym.Env[np.ndarray, np.ndarray]):
    batch: BatchSimulation | None
    def __init__(self, **kwargs: Any) -> None: ...
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]: ...
    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]: ...

class FlowMergeVecEnv(LockstepVecEnv): ...
