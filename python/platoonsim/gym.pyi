from typing import Any

import gymnasium as gym
import numpy as np

from . import Simulation

HOLD: int
ORGANIZE: int

def observation(
    v: dict[str, np.ndarray],
    d: dict[str, np.ndarray],
    zone: tuple[float, float],
    leftmost_lane: int,
    space: gym.spaces.Box,
) -> tuple[np.ndarray, dict[str, Any]]: ...
def reward(flow: np.ndarray, size: float, discharge_penalty: float) -> tuple[float, float]: ...

class PlatoonEnv(gym.Env[np.ndarray, int]):
    sim: Simulation | None
    gate: str
    zone: tuple[float, float]
    leftmost_lane: int
    scenario: str
    warmup_s: float
    discharge_penalty: float
    overrides: dict[str, Any]
    decisions: int
    decision_s: float
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
    ) -> None: ...
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]: ...
    def step(self, action: int) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]: ...
