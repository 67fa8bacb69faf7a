"""A random policy over PlatoonEnv (Platoon-v1): organize or hold the control section at random,
one decision per detector interval, and report the return of each episode and the paper's
measures against the twin (the same road and seed, never organized).

    python examples/python/random_policy.py [episodes]
"""

from __future__ import annotations

import sys

import numpy as np

from platoonsim.gym import PlatoonEnv


def main() -> None:
    episodes = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    # The homogeneous road, 50 % CAV, 2,500 veh/h/lane; 10 decisions of 60 s here (60 by default).
    env = PlatoonEnv(decisions=10)
    env.action_space.seed(0)
    for ep in range(episodes):
        obs, info = env.reset(seed=ep)
        seed = info["seed"]
        total, organized, done = 0.0, 0, False
        while not done:
            action = env.action_space.sample()
            obs, reward, terminated, truncated, info = env.step(action)
            total += reward
            organized += int(action)
            done = terminated or truncated
        lbar = info["platoon_sum"] / info["cav_exits"]
        q = info["discharge_count"]
        print(
            f"episode {ep} (seed {seed}): return {total:6.2f} over {env.task.decisions} decisions, "
            f"{organized} organized; L̄ gain {100 * (lbar[0] / lbar[1] - 1):+.1f} %, discharge "
            f"change {100 * (q[0] / q[1] - 1):+.1f} % against the twin; collisions {info['collisions'].tolist()}"
        )
        assert info["collisions"].sum() == 0
        assert np.isfinite(total)


if __name__ == "__main__":
    main()
