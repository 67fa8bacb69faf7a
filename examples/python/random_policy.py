"""A random policy over PlatoonEnv: organize or hold the control section at random, one
decision per detector interval, and report the return of each episode.

    python examples/python/random_policy.py [episodes]
"""

from __future__ import annotations

import sys

import numpy as np

from platoonsim.gym import PlatoonEnv


def main() -> None:
    episodes = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    env = PlatoonEnv()  # the homogeneous road, 50 % CAV, 2,500 veh/h/lane, 20 decisions of 30 s
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
        summary = env.sim.finish()
        print(
            f"episode {ep} (seed {seed}): return {total:7.2f} over {env.decisions} decisions, "
            f"{organized} organized; leftmost share of CAVs in the section at the end "
            f"{info['leftmost_share']:.2f}, collisions {summary['collisions']}"
        )
        assert np.isfinite(total)


if __name__ == "__main__":
    main()
