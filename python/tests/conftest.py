"""Shared helpers: the repository, the command-line binary, the Python PD organizer."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples" / "python"
sys.path.insert(0, str(EXAMPLES))

# A short homogeneous run: 50 % CAV, 2500 veh/h/lane, 15 min with a 5 min warm-up.
SHORT = {"run.penetration": 0.5, "demand.vph_per_lane": 2500, "run.duration_s": 900, "run.warmup_s": 300}


def cli_binary() -> Path:
    path = Path(os.environ.get("PLATOONSIM_CLI", REPO / "target" / "release" / "platoonsim"))
    if not path.exists():
        pytest.fail(f"{path} is missing: build it with cargo build --release -p platoonsim")
    return path


def cli_run(tmp: Path, *args: str) -> dict:
    """`platoonsim run ARGS --out tmp -q`, and its summary.json."""
    subprocess.run([str(cli_binary()), "run", *args, "--out", str(tmp), "-q"], check=True, capture_output=True)
    return json.loads((tmp / "summary.json").read_text())


def without_wall(summary: dict) -> dict:
    return {k: v for k, v in summary.items() if k != "wall_seconds"}
