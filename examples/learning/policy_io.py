"""A trained policy as a small numpy file, and its forward pass with numpy alone.

stable-baselines3's ``MlpPolicy`` (PPO) is a feed-forward net: hidden layers with tanh, then
the action head. ``export`` writes its policy branch to ``FILE.npz``:

* ``w0, b0, w1, b1, ...``: the hidden layers (weights (out, in), biases (out,));
* ``head_w, head_b``: the action head (the logits of a ``Discrete`` action; the mean of a
  ``Box`` action's Gaussian);
* ``kind``: ``"discrete"`` or ``"box"``; for a box ``low`` and ``high`` (the action bounds).

``NumpyPolicy(FILE)(obs)`` gives the deterministic action (the argmax of the logits, or the
mean clipped to the bounds) for one observation or a batch, without PyTorch.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np


def export(model: Any, path: Path) -> None:
    """Write ``model`` (a stable-baselines3 PPO with an MLP policy) to ``path`` (.npz)."""
    import torch  # noqa: F401  (only to read the weights)

    pol = model.policy
    arrays: dict[str, np.ndarray] = {}
    k = 0
    for layer in pol.mlp_extractor.policy_net:
        if hasattr(layer, "weight"):
            arrays[f"w{k}"] = layer.weight.detach().cpu().numpy().astype(np.float64)
            arrays[f"b{k}"] = layer.bias.detach().cpu().numpy().astype(np.float64)
            k += 1
        elif type(layer).__name__ != "Tanh":
            raise ValueError(f"policy layer {layer} is not supported (Linear and Tanh only)")
    arrays["head_w"] = pol.action_net.weight.detach().cpu().numpy().astype(np.float64)
    arrays["head_b"] = pol.action_net.bias.detach().cpu().numpy().astype(np.float64)
    space = model.action_space
    if hasattr(space, "n"):
        arrays["kind"] = np.array("discrete")
    else:
        arrays["kind"] = np.array("box")
        arrays["low"] = np.asarray(space.low, dtype=np.float64)
        arrays["high"] = np.asarray(space.high, dtype=np.float64)
    np.savez(path, **arrays)


class NumpyPolicy:
    """The deterministic policy of an exported file."""

    def __init__(self, path: Path) -> None:
        with np.load(path) as f:
            self.layers = []
            k = 0
            while f"w{k}" in f:
                self.layers.append((f[f"w{k}"], f[f"b{k}"]))
                k += 1
            self.head = (f["head_w"], f["head_b"])
            self.kind = str(f["kind"])
            self.low = f["low"] if "low" in f else None
            self.high = f["high"] if "high" in f else None
        if self.kind not in ("discrete", "box"):
            raise ValueError(f"{path}: kind = {self.kind!r}: must be 'discrete' or 'box'")

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        h = np.asarray(obs, dtype=np.float64)
        one = h.ndim == 1
        h = np.atleast_2d(h)
        for w, b in self.layers:
            h = np.tanh(h @ w.T + b)
        out = h @ self.head[0].T + self.head[1]
        if self.kind == "discrete":
            a = np.argmax(out, axis=1)
        else:
            a = np.clip(out, self.low, self.high)
        return a[0] if one else a
