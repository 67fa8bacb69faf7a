"""CavControl-v0: the spaces, the checker, each vector world equal to a single env, the capped
actions that cannot collide, bad actions rejected."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import platoonsim.gym  # noqa: F401  (registers the environments)
from platoonsim.control import CavControlEnv, CavControlVecEnv

KW = {"warmup_s": 30.0, "horizon_s": 40.0, "max_controlled": 6}


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_check_env_passes():
    check_env(CavControlEnv(**KW), skip_render_check=True)


def test_spaces_and_the_slots():
    env = CavControlEnv(**KW)
    assert env.observation_space.shape == (36,)
    assert env.action_space.shape == (6,)
    assert env.action_space.low[0] < 0 < env.action_space.high[0]
    obs, info = env.reset(seed=2)
    mask = info["mask"]
    assert info["controlled"] == mask.sum() > 0
    # Empty slots observe zeros; occupied ones a position in (0, 1].
    rows = obs.reshape(6, 6)
    assert (rows[~mask] == 0).all()
    assert (rows[mask, 0] > 0).all()


def test_vector_worlds_equal_single_envs():
    vec = gym.make_vec("platoonsim/CavControl-v0", num_envs=3, **KW)
    assert isinstance(vec, CavControlVecEnv)
    rng = np.random.default_rng(0)
    acts = [rng.uniform(-2, 1, size=(3, 6)) for _ in range(20)]
    obs, _ = vec.reset(seed=5)
    trace, rewards = [obs], []
    for a in acts:
        obs, r, _, _, _ = vec.step(a)
        trace.append(obs)
        rewards.append(r)
    for i in range(3):
        env = CavControlEnv(**KW)
        o, _ = env.reset(seed=5 + i)
        assert np.array_equal(o, trace[0][i])
        for k, a in enumerate(acts):
            o, r, _, _, _ = env.step(a[i])
            assert np.array_equal(o, trace[k + 1][i]) and r == rewards[k][i]


def test_full_throttle_is_capped_and_never_collides():
    env = CavControlVecEnv(num_envs=2, **KW)
    env.reset(seed=1)
    full = np.full((2, 6), env.single_action_space.high[0])
    for _ in range(80):
        _, _, term, trunc, info = env.step(full)
        assert not term.any()
        assert (info["collisions"] == 0).all()
        if trunc.all():
            break
    assert trunc.all()
    assert all(env.batch.finish(i)["collisions"] == 0 for i in range(2))


def test_bad_actions_are_rejected():
    env = CavControlEnv(**KW)
    env.reset(seed=0)
    for bad in (np.zeros(5), np.full(6, np.nan), "brake", np.zeros((2, 6))):
        with pytest.raises(ValueError, match="finite accelerations of shape \\(6,\\)"):
            env.step(bad)
    vec = CavControlVecEnv(num_envs=2, **KW)
    vec.reset(seed=0)
    with pytest.raises(ValueError, match="shape \\(2, 6\\)"):
        vec.step(np.zeros(6))
    with pytest.raises(ValueError, match="max_controlled"):
        CavControlEnv(max_controlled=0)


def test_full_throttle_leaves_the_models_in_charge():
    # The capped command at the top of the range is the CAV's own acceleration: the run is the
    # uncontrolled run, bit for bit (lane changes and automation untouched).
    import platoonsim
    from platoonsim.control import merge_scenario

    env = CavControlEnv(**KW)
    env.reset(seed=4)
    while True:
        _, _, term, trunc, _ = env.step(env.action_space.high)
        if term or trunc:
            break
    controlled = env.batch.finish(0)
    plain = platoonsim.Simulation(merge_scenario(duration_s=70.0), seed=4, events=False).run()
    skip = {"wall_seconds", "updates_per_second"}
    assert {k: v for k, v in controlled.items() if k not in skip} == {
        k: v for k, v in plain.items() if k not in skip
    }
