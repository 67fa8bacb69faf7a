"""Evaluate a shipped policy and the baselines of a task on given seeds, with numpy alone
(docs/learning.md).

    python examples/learning/evaluate.py gate --seeds 1000-1019 [--json] [--policy FILE]

Tasks and what is compared:

* ``gate`` (``platoonsim/Platoon-v1`` at its defaults): the policy (``policies/gate.npz``)
  against ``pd`` (always organize) and ``flow-aware`` (the scenario's Flow-Aware strategy
  with its built-in thresholds). Each episode runs against its never-organized twin;
  ``l_gain`` and ``discharge_change`` are the episode's L̄ gain and discharge-count change
  against the twin, averaged over the seeds.

Printed: a Markdown table (mean ± standard error over the seeds). With ``--json``: one JSON
object per policy and baseline on stdout, ``{"task", "policy", "seeds", "mean_speed_mps",
"outflow_vph", "l_gain", "discharge_change"}``. Every episode must end without a collision.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any, Callable

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from policy_io import NumpyPolicy  # noqa: E402

POLICIES = {"gate": HERE / "policies" / "gate.npz"}


def parse_seeds(text: str) -> list[int]:
    """``A-B`` (inclusive) or ``A,B,C``."""
    try:
        if "-" in text:
            a, b = (int(x) for x in text.split("-", 1))
            seeds = list(range(a, b + 1))
        else:
            seeds = [int(x) for x in text.split(",")]
    except ValueError:
        seeds = []
    if not seeds or any(s < 0 for s in seeds):
        raise argparse.ArgumentTypeError(f"--seeds {text!r}: give A-B (A <= B) or A,B,C of ints >= 0")
    return seeds


def _mean_se(x: list[float]) -> tuple[float, float]:
    a = np.asarray(x, dtype=float)
    se = float(a.std(ddof=1) / np.sqrt(len(a))) if len(a) > 1 else 0.0
    return float(a.mean()), se


def gate_episode(seeds: list[int], act: Callable[[np.ndarray], np.ndarray] | None, baseline: str | None) -> dict[str, Any]:
    """One episode per seed of Platoon-v1, all in one batch; ``act`` maps (N, 8) observations
    to (N,) actions (ignored for a baseline strategy)."""
    from platoonsim.vector import PlatoonVecEnv

    env = PlatoonVecEnv(num_envs=len(seeds), baseline=baseline)
    obs, _ = env.reset(seed=seeds)
    speeds = []
    while True:
        a = np.zeros(len(seeds), dtype=np.int64) if act is None else np.asarray(act(obs), dtype=np.int64)
        obs, _, _, trunc, info = env.step(a)
        speeds.append(info["mean_speed_mps"][:, 0])
        if trunc.all():
            break
    if info["collisions"].sum() != 0:
        raise SystemExit(f"collisions in the gate episodes: {info['collisions'].tolist()}")
    lbar = info["platoon_sum"] / info["cav_exits"]
    q = info["discharge_count"].astype(float)
    hours = env.task.decisions * env.task.decision_s / 3600.0
    return {
        "mean_speed_mps": np.mean(speeds, axis=0).tolist(),
        "outflow_vph": (q[:, 0] / hours).tolist(),
        "l_gain": (lbar[:, 0] / lbar[:, 1] - 1).tolist(),
        "discharge_change": (q[:, 0] / q[:, 1] - 1).tolist(),
    }


def evaluate_gate(seeds: list[int], policy: Path | None) -> list[dict[str, Any]]:
    runs: list[tuple[str, Callable[[np.ndarray], np.ndarray] | None, str | None]] = []
    if policy is not None:
        pol = NumpyPolicy(policy)
        runs.append((policy.stem, pol, None))
    runs += [("pd", lambda o: np.ones(len(o), dtype=np.int64), None), ("flow-aware", None, "flow-aware")]
    rows = []
    for name, act, baseline in runs:
        per_seed = gate_episode(seeds, act, baseline)
        rows.append({"task": "gate", "policy": name, "seeds": seeds, **per_seed})
    return rows


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("task", choices=sorted(POLICIES))
    ap.add_argument("--seeds", type=parse_seeds, default=parse_seeds("1000-1019"))
    ap.add_argument("--policy", type=Path, default=None, help="an exported policy (.npz); default the shipped one")
    ap.add_argument("--json", action="store_true", help="one JSON object per policy on stdout")
    args = ap.parse_args(argv)
    policy = args.policy or POLICIES[args.task]
    if not policy.exists():
        if args.policy is not None:
            ap.error(f"--policy {policy}: no such file")
        print(f"note: no shipped policy at {policy}; evaluating the baselines only", file=sys.stderr)
        policy = None
    rows = evaluate_gate(args.seeds, policy)
    fields = ("mean_speed_mps", "outflow_vph", "l_gain", "discharge_change")
    if args.json:
        for r in rows:
            print(json.dumps({**{k: r[k] for k in ("task", "policy", "seeds")}, **{f: _mean_se(r[f])[0] for f in fields}}))
        return 0
    print(f"{args.task}, seeds {args.seeds[0]}-{args.seeds[-1]} ({len(args.seeds)}), mean ± standard error:\n")
    print("| policy | mean speed (m/s) | outflow (veh/h) | L̄ gain | discharge change |")
    print("|---|---:|---:|---:|---:|")
    for r in rows:
        m = {f: _mean_se(r[f]) for f in fields}
        print(
            f"| {r['policy']} | {m['mean_speed_mps'][0]:.2f} ± {m['mean_speed_mps'][1]:.2f} | "
            f"{m['outflow_vph'][0]:,.0f} ± {m['outflow_vph'][1]:,.0f} | "
            f"{100 * m['l_gain'][0]:+.1f} ± {100 * m['l_gain'][1]:.1f} % | "
            f"{100 * m['discharge_change'][0]:+.2f} ± {100 * m['discharge_change'][1]:.2f} % |"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
