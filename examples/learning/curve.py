"""The learning curve of a stable-baselines3 run: the mean episode return of the last 100
episodes after each rollout, written as CSV and drawn as PNG and SVG."""

from __future__ import annotations

import csv
import time
from pathlib import Path

import numpy as np
from stable_baselines3.common.callbacks import BaseCallback


class Curve(BaseCallback):
    def __init__(self) -> None:
        super().__init__()
        self.points: list[tuple[int, float, float]] = []
        self.t0 = time.perf_counter()

    def _on_rollout_end(self) -> None:
        eps = [e["r"] for e in self.model.ep_info_buffer]
        if eps:
            self.points.append((self.num_timesteps, float(np.mean(eps)), time.perf_counter() - self.t0))

    def _on_step(self) -> bool:
        return True

    def write(self, stem: Path, x_label: str, title: str) -> None:
        with open(stem.with_suffix(".csv"), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["env_steps", "mean_return", "wall_s"])
            w.writerows(self.points)
        try:
            import matplotlib

            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            return
        fig, ax = plt.subplots(figsize=(6, 3.5))
        ax.plot([c[0] for c in self.points], [c[1] for c in self.points])
        ax.set_xlabel(x_label)
        ax.set_ylabel("mean episode return (last 100)")
        ax.set_title(title)
        fig.tight_layout()
        for ext in ("png", "svg"):
            fig.savefig(stem.with_suffix(f".{ext}"))
