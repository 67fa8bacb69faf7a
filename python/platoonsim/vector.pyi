from typing import Any, Sequence

import numpy as np
from gymnasium.vector import VectorEnv

from . import BatchSimulation
from .gate import GateTask

def check_num_envs(num_envs: Any, worlds_per_env: int = 1) -> None: ...

class PlatoonVecEnv(VectorEnv):
    task: GateTask
    batch: BatchSimulation | None
    num_envs: int
    def __init__(self, num_envs: int = 1, threads: int | None = None, **kwargs: Any) -> None: ...
    def reset(
        self, *, seed: int | Sequence[int] | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]: ...
    def step(self, actions: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]: ...

def world_seeds(
    seed: int | Sequence[int] | None, n: int, rng: np.random.Generator | None
) -> tuple[np.random.Generator, np.ndarray]: ...

class LockstepVecEnv(VectorEnv):
    task: Any
    batch: BatchSimulation | None
    num_envs: int
    threads: int | None
    def __init__(self, num_envs: int = 1, threads: int | None = None, **kwargs: Any) -> None: ...
    def reset(
        self, *, seed: int | Sequence[int] | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]: ...
    def step(self, actions: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]: ...
