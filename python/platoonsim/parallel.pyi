from typing import Any

import numpy as np
from gymnasium import spaces
from pettingzoo.utils.env import ParallelEnv

from . import BatchSimulation

class FlowMergeParallelEnv(ParallelEnv[str, np.ndarray, np.ndarray]):
    agents: list[str]
    possible_agents: list[str]
    batch: BatchSimulation | None
    t_actions: int
    def __init__(self, **kwargs: Any) -> None: ...
    def observation_space(self, agent: str) -> spaces.Box: ...
    def action_space(self, agent: str) -> spaces.Box: ...
    def reset(
        self, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, np.ndarray], dict[str, dict[str, Any]]]: ...
    def step(
        self, actions: dict[str, Any]
    ) -> tuple[
        dict[str, np.ndarray],
        dict[str, float],
        dict[str, bool],
        dict[str, bool],
        dict[str, dict[str, Any]],
    ]: ...
    def close(self) -> None: ...
