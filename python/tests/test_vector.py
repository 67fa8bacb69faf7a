"""The native vector environment of Platoon-v1: shapes, seeding, autoreset, bad actions,
each world equal to a single PlatoonEnv, and the Flow-Aware baseline."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import platoonsim.gym  # noqa: F401  (registers the environment)
from platoonsim.gym import PlatoonEnv
from platoonsim.vector import PlatoonVecEnv

KW = {"warmup_s": 360.0, "decision_s": 60.0, "decisions": 4}
ACTIONS = [np.array([1, 0, 1]), np.array([0, 0, 1]), np.array([1, 1, 1]), np.array([0, 1, 0])]


def _episode(env, seed):
    obs, info = env.reset(seed=seed)
    trace, rewards = [obs], []
    for a in ACTIONS:
        obs, r, term, trunc, info = env.step(a)
        trace.append(obs)
        rewards.append(r)
    return np.stack(trace), np.stack(rewards), term, trunc, info


def test_make_vec_gives_the_native_vector_env():
    env = gym.make_vec("platoonsim/Platoon-v1", num_envs=3, **KW)
    assert isinstance(env, PlatoonVecEnv)
    assert env.observation_space.shape == (3, 8)
    assert env.single_observation_space.shape == (8,)
    obs, info = env.reset(seed=5)
    assert obs.shape == (3, 8) and obs.dtype == np.float32
    assert list(info["seed"]) == [5, 6, 7]


def test_each_world_equals_a_single_env_and_episodes_repeat():
    env = PlatoonVecEnv(num_envs=3, **KW)
    trace, rewards, term, trunc, _ = _episode(env, 11)
    assert trunc.all() and not term.any()
    again = _episode(env, 11)
    assert np.array_equal(trace, again[0]) and np.array_equal(rewards, again[1])
    for i in range(3):
        single = PlatoonEnv(**KW)
        obs, _ = single.reset(seed=11 + i)
        assert np.array_equal(obs, trace[0, i])
        for k, a in enumerate(ACTIONS):
            obs, r, _, _, _ = single.step(int(a[i]))
            assert np.array_equal(obs, trace[k + 1, i])
            assert r == rewards[k, i]


def test_autoreset_starts_new_episodes_on_the_next_step():
    env = PlatoonVecEnv(num_envs=2, **KW)
    env.reset(seed=1)
    for a in ACTIONS:
        _, _, _, trunc, _ = env.step(a[:2])
    assert trunc.all()
    obs, r, term, trunc, info = env.step(np.zeros(2, dtype=int))
    assert not term.any() and not trunc.any() and (r == 0).all()
    assert np.allclose(info["t_s"], PlatoonEnv(**KW).task.warmup_s)
    assert env.observation_space.contains(obs)


def test_bad_actions_and_seeds_are_rejected():
    env = PlatoonVecEnv(num_envs=2, **KW)
    with pytest.raises(RuntimeError, match="reset"):
        env.step(np.zeros(2, dtype=int))
    env.reset(seed=[4, 9])
    for bad in ([1, 0, 1], [2, 0], [0.5, 1.0], "organize"):
        with pytest.raises(ValueError, match="0 \\(hold\\) or 1 \\(organize\\)"):
            env.step(np.asarray(bad))
    with pytest.raises(ValueError, match="one per world"):
        env.reset(seed=[1, 2, 3])
    with pytest.raises(ValueError, match="num_envs"):
        PlatoonVecEnv(num_envs=0)


def test_too_many_worlds_are_refused_at_construction():
    # One native batch steps at most MAX_WORLDS worlds: more are refused when the vector
    # environment is made, not at its first reset (issue 48, D16).
    from platoonsim.control import CavControlVecEnv

    assert platoonsim.MAX_WORLDS == 4096
    with pytest.raises(ValueError, match="num_envs = 5000: must be an int from 1 to 4096"):
        CavControlVecEnv(num_envs=5000)
    # Each gate environment steps two worlds (its twin).
    with pytest.raises(ValueError, match="num_envs = 3000: must be an int from 1 to 2048"):
        PlatoonVecEnv(num_envs=3000)
    with pytest.raises(ValueError, match="num_envs = 5000"):
        gym.make_vec("platoonsim/Platoon-v1", num_envs=5000, **KW)


def test_the_flow_aware_baseline_ignores_actions_and_organizes():
    # The scenario's Flow-Aware strategy in the agent's worlds, from the end of the warm-up:
    # the same episode whatever the actions, and not the twin's.
    kw = {**KW, "decisions": 3, "demand_vphpl": 2000.0}
    runs = []
    for a in (0, 1):
        env = PlatoonVecEnv(num_envs=2, baseline="flow-aware", **kw)
        env.reset(seed=7)
        for _ in range(3):
            _, r, _, trunc, info = env.step(np.full(2, a))
        runs.append((r, info["platoon_sum"], info["leftmost_share"]))
    assert all(np.array_equal(x, y) for x, y in zip(*runs))
    hold = PlatoonVecEnv(num_envs=2, **kw)
    hold.reset(seed=7)
    for _ in range(3):
        _, _, _, _, held = hold.step(np.zeros(2, dtype=int))
    assert (info["leftmost_share"] > held["leftmost_share"]).all()
    assert (info["platoon_sum"][:, 0] != info["platoon_sum"][:, 1]).any()
