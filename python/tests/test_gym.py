"""PlatoonEnv passes Gymnasium's checker and runs 1,000 random-policy steps."""

from __future__ import annotations

import numpy as np
import pytest

from gymnasium.utils.env_checker import check_env

from platoonsim.gym import PlatoonEnv


def test_check_env_passes():
    check_env(PlatoonEnv(decision_s=10.0, decisions=6), skip_render_check=True)


def test_reset_seed_reproduces_an_episode():
    env = PlatoonEnv(decision_s=10.0, decisions=5)
    runs = []
    for _ in range(2):
        obs, _ = env.reset(seed=11)
        trace = [obs]
        for a in [1, 0, 1, 1, 0]:
            obs, r, term, trunc, _ = env.step(a)
            trace.append(np.append(obs, r))
        assert trunc and not term
        runs.append(np.concatenate(trace))
    assert np.array_equal(runs[0], runs[1])


def test_a_thousand_random_steps():
    env = PlatoonEnv(decision_s=10.0, decisions=60)
    env.action_space.seed(0)
    obs, _ = env.reset(seed=0)
    episodes, rewards, organized = 0, [], []
    for _ in range(1000):
        a = env.action_space.sample()
        obs, r, term, trunc, info = env.step(a)
        assert env.observation_space.contains(obs)
        assert np.isfinite(r)
        rewards.append(r)
        organized.append((a, info["leftmost_share"]))
        if term or trunc:
            assert env.sim.finish()["collisions"] == 0
            episodes += 1
            obs, _ = env.reset()
    assert episodes == 16
    # Strings form: the platoon gain is positive on average at 50 % CAVs.
    assert np.mean(rewards) > 0


@pytest.mark.parametrize(
    "setting, message",
    [
        ({"discharge_penalty": float("nan")}, "discharge_penalty = nan"),
        ({"discharge_penalty": -1.0}, "discharge_penalty = -1.0"),
        ({"advice_every_s": 0.0}, "advice_every_s = 0.0"),
        ({"advice_every_s": float("inf")}, "advice_every_s = inf"),
    ],
)
def test_bad_settings_are_refused(setting, message):
    # Issue 35 item 9: a NaN penalty gave NaN rewards, advice_every_s = 0 was accepted.
    with pytest.raises(ValueError, match=message):
        PlatoonEnv(**setting)
