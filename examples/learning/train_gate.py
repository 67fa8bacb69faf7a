"""PPO (stable-baselines3) on ``platoonsim/Platoon-v0``: when to organize the control section,
trained on batched worlds, evaluated on held-out seeds and demands against the Flow-Aware rule
with its hand-tuned thresholds, always-organize (PD) and never (docs/learning.md).

The Flow-Aware rule as a gate reads the same observation as the agent: organize for the next
interval while the upstream and control-section detectors report a flow below rho_q and a
speed above rho_v (the thresholds of ``flow_aware_thresholds`` at 50 % CAV: 2,750 veh/h/lane,
97 km/h; docs/model-choices.md 6.17).

    pip install ./python[rl]
    python examples/learning/train_gate.py [--steps N] [--worlds W] [--out DIR]
"""

from __future__ import annotations

import argparse
import csv
import time
from pathlib import Path

import numpy as np

from stable_baselines3 import PPO
from stable_baselines3.common.vec_env import VecMonitor

from platoonsim.gym import PlatoonEnv
from platoonsim.vector import PlatoonVecEnv
from curve import Curve
from sb3_vec import Sb3Vec

TRAIN = {"decision_s": 30.0, "decisions": 10, "warmup_s": 240.0}
EVAL_SEEDS = range(1000, 1010)
EVAL_DEMANDS = (2000.0, 2500.0, 2800.0)
RHO_Q, RHO_V = 2750.0, 97.0


def flow_aware(obs: np.ndarray) -> int:
    flow, speed = obs[0:3] * 1000.0, obs[3:6] * 100.0
    return int(flow[0] < RHO_Q and flow[1] < RHO_Q and speed[0] > RHO_V and speed[1] > RHO_V)


def evaluate(model: PPO, out: Path) -> list[dict]:
    policies = {
        "never (hold)": lambda o: 0,
        "always (PD)": lambda o: 1,
        "Flow-Aware thresholds": flow_aware,
        "PPO": lambda o: int(model.predict(o, deterministic=True)[0]),
    }
    rows = []
    for demand in EVAL_DEMANDS:
        env = PlatoonEnv(**TRAIN, demand_vphpl=demand)
        for label, pol in policies.items():
            for seed in EVAL_SEEDS:
                obs, _ = env.reset(seed=seed)
                ret, sizes, losses, organized = 0.0, [], [], 0
                while True:
                    a = pol(obs)
                    organized += a
                    obs, r, term, trunc, info = env.step(a)
                    ret += r
                    sizes.append(info["mean_string_size"])
                    losses.append(info["discharge_loss"])
                    if term or trunc:
                        break
                s = env.sim.finish()
                assert s["collisions"] == 0
                rows.append({
                    "policy": label, "demand_vphpl": demand, "seed": seed, "return": ret,
                    "mean_string_size": float(np.mean(sizes)), "discharge_loss": float(np.mean(losses)),
                    "organized_share": organized / TRAIN["decisions"],
                    "discharge_vphpl": s["discharge_flow_vphpl"],
                })
    with open(out / "gate_eval.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    return rows


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--steps", type=int, default=20_000, help="decisions of training")
    ap.add_argument("--worlds", type=int, default=8)
    ap.add_argument("--out", type=Path, default=Path("out/learning"))
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    # Training at the default demand (2,500 veh/h/lane) and seeds below 1000; the evaluation
    # also at held-out demands, on held-out seeds.
    venv = VecMonitor(Sb3Vec(PlatoonVecEnv(num_envs=args.worlds, **TRAIN)))
    venv.seed(0)
    model = PPO("MlpPolicy", venv, n_steps=64, batch_size=128, learning_rate=3e-4, gamma=0.9, seed=0, verbose=0)
    curve = Curve()
    t0 = time.perf_counter()
    model.learn(total_timesteps=args.steps, callback=curve)
    wall = time.perf_counter() - t0
    curve.write(args.out / "gate_curve", "decisions (environment steps)", "PPO on Platoon-v0")
    print(f"trained {args.steps} decisions on {args.worlds} worlds in {wall:.0f} s")
    rows = evaluate(model, args.out)
    print("| policy | demand veh/h/lane | return | mean string size | discharge loss | organized | discharge veh/h/lane |")
    print("|---|---|---|---|---|---|---|")
    for demand in EVAL_DEMANDS:
        for label in ("never (hold)", "always (PD)", "Flow-Aware thresholds", "PPO"):
            sel = [r for r in rows if r["policy"] == label and r["demand_vphpl"] == demand]
            m = {k: np.mean([r[k] for r in sel]) for k in ("return", "mean_string_size", "discharge_loss", "organized_share", "discharge_vphpl")}
            print(
                f"| {label} | {demand:.0f} | {m['return']:.2f} | {m['mean_string_size']:.2f} | "
                f"{100 * m['discharge_loss']:.2f} % | {100 * m['organized_share']:.0f} % | {m['discharge_vphpl']:.0f} |"
            )


if __name__ == "__main__":
    main()
