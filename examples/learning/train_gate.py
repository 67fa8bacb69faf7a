"""PPO (stable-baselines3) on ``platoonsim/Platoon-v1``: when to organize the control section,
rewarded on the L̄ gain and the discharge change against a never-organized twin; trained on
batched worlds, exported to ``policies/gate.npz`` and evaluated on held-out seeds against
always organizing (PD) and the Flow-Aware strategy (docs/learning.md).

    pip install ./python[rl]
    python examples/learning/train_gate.py [--steps N] [--worlds W] [--out DIR]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import torch
from stable_baselines3 import PPO
from stable_baselines3.common.vec_env import VecMonitor

from platoonsim.vector import PlatoonVecEnv
from curve import Curve
from evaluate import main as evaluate_main
from policy_io import export
from sb3_vec import Sb3Vec

HERE = Path(__file__).resolve().parent


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--steps", type=int, default=24_000, help="decisions of training")
    ap.add_argument("--worlds", type=int, default=8, help="episodes stepped together (each with its twin)")
    ap.add_argument("--out", type=Path, default=Path("out/learning"))
    ap.add_argument("--eval-seeds", default="1000-1019", help="held-out seeds of the evaluation")
    ap.add_argument("--policy", type=Path, default=HERE / "policies" / "gate.npz", help="where the policy is exported")
    args = ap.parse_args()
    torch.set_num_threads(1)  # a small MLP: the cores go to the worlds
    args.out.mkdir(parents=True, exist_ok=True)
    args.policy.parent.mkdir(parents=True, exist_ok=True)
    # Training seeds come from the environment's generator (seeded 0): below 2^31, with the
    # evaluation's 1000-1019 among them only by chance (probability about 1e-8 per episode).
    env = PlatoonVecEnv(num_envs=args.worlds)
    decisions = env.task.decisions
    venv = VecMonitor(Sb3Vec(env))
    venv.seed(0)
    # One episode per world per rollout; the discount spans about 50 decisions (50 min).
    model = PPO(
        "MlpPolicy", venv, n_steps=decisions, batch_size=decisions * 2, n_epochs=10,
        gamma=0.98, gae_lambda=0.95, ent_coef=0.01, learning_rate=3e-4, seed=0, verbose=0,
    )
    curve = Curve()
    t0 = time.perf_counter()
    model.learn(total_timesteps=args.steps, callback=curve)
    wall = time.perf_counter() - t0
    curve.write(args.out / "gate_curve", "decisions (environment steps)", "PPO on Platoon-v1")
    print(f"trained {args.steps} decisions on {args.worlds} worlds in {wall:.0f} s")
    export(model, args.policy)
    print(f"policy written to {args.policy}")
    evaluate_main(["gate", "--policy", str(args.policy), "--seeds", args.eval_seeds])


if __name__ == "__main__":
    main()
