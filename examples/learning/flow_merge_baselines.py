"""FlowMerge-v0's baselines (docs/learning.md, "FlowMerge-v0"): mean speed and outflow of full
750-action episodes on seeds 1000-1019 for all-human, acc-only, and two trivial policies of the
learning vehicles (always 0 and always +1.5 m/s²). Every episode must end without a collision
(asserted).

    python examples/learning/flow_merge_baselines.py [--seeds N] [--first S]

Mean speed: the mean over the episode's actions of the mean speed of the vehicles on the road
(Flow's evaluation reward); outflow: vehicles leaving the road per hour, over the whole episode
and over its last 500 s (Flow's ``get_outflow_rate(500)``); return: the sum of the rewards.
Mean ± standard error over the seeds.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from platoonsim.flow_merge import FlowMergeVecEnv

POLICIES = {
    "all-human": ({"baseline": "all-human"}, 0.0),
    "acc-only": ({"baseline": "acc-only"}, 0.0),
    "always 0": ({}, 0.0),
    "always +1.5": ({}, 1.5),
    "always -1.5": ({}, -1.5),
}


def episode(kw: dict, a: float, seeds: list[int]) -> dict[str, np.ndarray]:
    env = FlowMergeVecEnv(num_envs=len(seeds), **kw)
    env.reset(seed=seeds)
    n = len(seeds)
    speeds, outflow, rewards, veh = [], [], [], []
    while True:
        _, r, term, trunc, info = env.step(np.full((n, 5), a))
        assert not term.any() and (info["collisions"] == 0).all()
        speeds.append(info["mean_speed_mps"])
        outflow.append(info["outflow_vph"])
        rewards.append(r)
        veh.append(info["vehicles"])
        if trunc.all():
            break
    speeds, outflow, rewards = np.array(speeds), np.array(outflow), np.array(rewards)
    waiting = np.array([env.batch.finish(i)["vehicles_waiting"] for i in range(n)])
    return {
        "speed": speeds.mean(axis=0),
        "outflow": outflow.mean(axis=0),
        "outflow500": outflow[-500:].mean(axis=0),
        "return": rewards.sum(axis=0),
        "vehicles": np.array(veh).mean(axis=0),
        "waiting": waiting,
    }


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--first", type=int, default=1000)
    ap.add_argument("--policies", nargs="*", default=list(POLICIES))
    args = ap.parse_args()
    seeds = list(range(args.first, args.first + args.seeds))
    print(f"seeds {seeds[0]}-{seeds[-1]}, 750 actions each; mean ± standard error over the seeds")
    print("| policy | mean speed (m/s) | outflow (veh/h) | outflow, last 500 s (veh/h) | return | vehicles on the road | queued at the end |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for name in args.policies:
        kw, a = POLICIES[name]
        t0 = time.perf_counter()
        m = episode(kw, a, seeds)
        se = lambda x: x.std(ddof=1) / np.sqrt(len(x))  # noqa: E731
        print(
            f"| {name} | {m['speed'].mean():.2f} ± {se(m['speed']):.2f} | {m['outflow'].mean():,.0f} ± {se(m['outflow']):,.0f} "
            f"| {m['outflow500'].mean():,.0f} ± {se(m['outflow500']):,.0f} | {m['return'].mean():.1f} ± {se(m['return']):.1f} "
            f"| {m['vehicles'].mean():.1f} | {m['waiting'].mean():.1f} |  ({time.perf_counter() - t0:.0f} s)",
            flush=True,
        )


if __name__ == "__main__":
    main()
