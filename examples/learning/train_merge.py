"""PPO (stable-baselines3) on ``platoonsim/CavControl-v0``: CAV accelerations at a merge,
trained on batched worlds, evaluated on held-out seeds and demands against all-human traffic
and ACC-only CAVs (docs/learning.md).

    pip install ./python[rl]
    python examples/learning/train_merge.py [--steps N] [--worlds W] [--out DIR]

Writes DIR/merge_curve.csv and .png (mean episode return against environment steps),
DIR/merge_eval.csv (one row per policy, demand and seed) and prints the evaluation table.
"""

from __future__ import annotations

import argparse
import csv
import time
from pathlib import Path

import numpy as np

from stable_baselines3 import PPO
from stable_baselines3.common.vec_env import VecMonitor

from platoonsim.control import CavControlEnv, CavControlVecEnv
from curve import Curve
from sb3_vec import Sb3Vec

TRAIN = {"warmup_s": 60.0, "horizon_s": 180.0, "mainline_vph": 2000.0, "ramp_vph": 200.0}
EVAL_SEEDS = range(1000, 1010)
EVAL_DEMANDS = (1800.0, 2000.0, 2200.0)


def episode(env: CavControlEnv, seed: int, policy) -> dict[str, float]:
    obs, info = env.reset(seed=seed)
    ret, speeds, outflow, n = 0.0, [], 0.0, 0
    while True:
        obs, r, term, trunc, info = env.step(policy(obs))
        ret += r
        outflow += float(info["outflow_vph"])
        v = env.batch.vehicles(0)["v_mps"]
        speeds.append(float(v.mean()) if len(v) else 0.0)
        n += 1
        if term or trunc:
            break
    s = env.batch.finish(0)
    assert s["collisions"] == 0, "a collision"
    return {"return": ret, "outflow_vph": outflow / n, "mean_speed_kmh": 3.6 * float(np.mean(speeds))}


def evaluate(model: PPO, out: Path) -> list[dict]:
    rows = []
    for demand in EVAL_DEMANDS:
        for label, pen, policy in (
            ("all-human", 0.0, None),
            ("ACC-only", 0.25, None),
            ("PPO", 0.25, model),
        ):
            env = CavControlEnv(**{**TRAIN, "mainline_vph": demand, "penetration": pen})
            high = env.action_space.high
            # No policy: every action is the CAV's own acceleration (the capped command at
            # the top of the range leaves the ACC/CACC law in charge).
            act = (lambda o: high) if policy is None else (lambda o, m=policy: m.predict(o, deterministic=True)[0])
            for seed in EVAL_SEEDS:
                r = episode(env, seed, act)
                rows.append({"policy": label, "mainline_vph": demand, "seed": seed, **r})
    with open(out / "merge_eval.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    return rows


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--steps", type=int, default=200_000, help="environment steps of training")
    ap.add_argument("--worlds", type=int, default=8)
    ap.add_argument("--out", type=Path, default=Path("out/learning"))
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    venv = VecMonitor(Sb3Vec(CavControlVecEnv(num_envs=args.worlds, **TRAIN)))
    venv.seed(0)
    model = PPO("MlpPolicy", venv, n_steps=256, batch_size=512, learning_rate=3e-4, gamma=0.99, seed=0, verbose=0)
    curve = Curve()
    t0 = time.perf_counter()
    model.learn(total_timesteps=args.steps, callback=curve)
    wall = time.perf_counter() - t0
    curve.write(args.out / "merge_curve", "environment steps", "PPO on CavControl-v0")
    print(f"trained {args.steps} environment steps on {args.worlds} worlds in {wall:.0f} s")
    rows = evaluate(model, args.out)
    print("| policy | mainline veh/h | return | outflow veh/h | mean speed km/h |")
    print("|---|---|---|---|---|")
    for demand in EVAL_DEMANDS:
        for label in ("all-human", "ACC-only", "PPO"):
            sel = [r for r in rows if r["policy"] == label and r["mainline_vph"] == demand]
            m = {k: np.mean([r[k] for r in sel]) for k in ("return", "outflow_vph", "mean_speed_kmh")}
            print(f"| {label} | {demand:.0f} | {m['return']:.2f} | {m['outflow_vph']:.0f} | {m['mean_speed_kmh']:.1f} |")


if __name__ == "__main__":
    main()
