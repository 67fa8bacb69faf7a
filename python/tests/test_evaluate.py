"""examples/learning/evaluate.py runs with numpy alone: the exported policy's forward pass, the
seed ranges, and one JSON object per policy and baseline."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from conftest import REPO

LEARNING = REPO / "examples" / "learning"
sys.path.insert(0, str(LEARNING))

from evaluate import parse_seeds  # noqa: E402
from policy_io import NumpyPolicy  # noqa: E402


def _write(path, kind="discrete"):
    # Two hidden units: h = tanh(W0 x), logits = Wh h + bh.
    w0 = np.array([[1.0, 0.0], [0.0, -1.0]])
    arrays = {"w0": w0, "b0": np.zeros(2), "head_w": np.array([[1.0, 0.0], [0.0, 1.0]]), "head_b": np.zeros(2)}
    if kind == "box":
        arrays.update(low=np.full(2, -0.5), high=np.full(2, 0.5))
    np.savez(path, kind=np.array(kind), **arrays)


def test_the_numpy_policy_is_the_mlp_forward_pass(tmp_path):
    _write(tmp_path / "d.npz")
    pol = NumpyPolicy(tmp_path / "d.npz")
    # logits = (tanh(x0), tanh(-x1)): argmax 0 when x0 > -x1.
    assert pol(np.array([1.0, 0.0])) == 0
    assert pol(np.array([0.0, -1.0])) == 1
    assert pol(np.array([[2.0, 0.0], [0.0, -3.0]])).tolist() == [0, 1]
    _write(tmp_path / "b.npz", "box")
    box = NumpyPolicy(tmp_path / "b.npz")
    assert np.allclose(box(np.array([0.1, 5.0])), [np.tanh(0.1), -0.5])


def test_seed_ranges():
    assert parse_seeds("1000-1003") == [1000, 1001, 1002, 1003]
    assert parse_seeds("4,9") == [4, 9]
    for bad in ("5-2", "a-b", "", "-3"):
        with pytest.raises(Exception, match="--seeds"):
            parse_seeds(bad)


def test_json_has_one_object_per_policy_and_baseline(tmp_path):
    # A policy that always holds (its logits favour action 0 whatever it observes).
    np.savez(
        tmp_path / "gate.npz", kind=np.array("discrete"), w0=np.zeros((4, 8)), b0=np.zeros(4),
        head_w=np.zeros((2, 4)), head_b=np.array([1.0, 0.0]),
    )
    out = subprocess.run(
        [sys.executable, str(LEARNING / "evaluate.py"), "gate", "--seeds", "1000", "--json", "--policy", str(tmp_path / "gate.npz")],
        check=True, capture_output=True, text=True,
    ).stdout
    rows = [json.loads(line) for line in out.splitlines()]
    assert [r["policy"] for r in rows] == ["gate", "pd", "flow-aware"]
    for r in rows:
        assert set(r) == {"task", "policy", "seeds", "mean_speed_mps", "outflow_vph", "l_gain", "discharge_change"}
        assert r["task"] == "gate" and r["seeds"] == [1000]
    hold, pd, fa = rows
    assert hold["l_gain"] == 0.0 and hold["discharge_change"] == 0.0
    # Always organizing grows the strings most and costs discharge; Flow-Aware keeps it.
    assert pd["l_gain"] > fa["l_gain"] > 0
    assert pd["discharge_change"] < fa["discharge_change"]
