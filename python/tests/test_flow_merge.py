"""FlowMerge-v0 (Flow's merge0): the spaces and the controlled list, seeding, each vector world
equal to a single env at any thread count, autoreset, Flow's reward recomputed, the baselines,
bad actions and arguments refused, the extreme policies without a collision, and the PettingZoo
form (its API test and our own checks)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import platoonsim.gym  # noqa: F401  (registers the environments)
from platoonsim.flow_merge import FlowMergeEnv, FlowMergeVecEnv

KW = {"warmup_s": 60.0, "horizon": 40}


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_check_env_passes():
    check_env(FlowMergeEnv(**KW), skip_render_check=True)


def test_spaces_and_the_controlled_list():
    env = FlowMergeEnv(**KW, rl_share=0.3)
    assert env.observation_space.shape == (25,)
    assert env.action_space.shape == (5,)
    assert (env.action_space.low == -1.5).all() and (env.action_space.high == 1.5).all()
    obs, info = env.reset(seed=3)
    ids = info["ids"]
    rows = obs.reshape(5, 5)
    assert (rows[~info["mask"]] == 0).all()
    # Flow's list: occupied slots first, in order of entry.
    listed = ids[ids >= 0]
    assert len(listed) == info["controlled"] > 0
    assert (np.diff(listed) > 0).all() and (ids[len(listed):] == -1).all()
    seen_full = False
    for _ in range(30):
        before = ids[ids >= 0]
        obs, _, _, _, info = env.step(np.zeros(5))
        ids = info["ids"]
        after = ids[ids >= 0]
        seen_full |= len(after) == 5
        # Vehicles that stay keep their order and move up; newcomers join the end.
        stayed = [i for i in before if i in after]
        assert list(after[: len(stayed)]) == stayed
        assert (after[len(stayed):] > (before.max() if len(before) else -1)).all()
        assert (obs.reshape(5, 5)[info["mask"], 0] > 0).any() or not info["mask"].any()
    assert seen_full


def test_seeds_repeat_an_episode_and_differ_between_them():
    def trace(seed):
        env = FlowMergeEnv(**KW)
        obs, _ = env.reset(seed=seed)
        out = [obs]
        rng = np.random.default_rng(0)
        for _ in range(10):
            out.append(env.step(rng.uniform(-1.5, 1.5, 5))[0])
        return np.array(out)

    assert np.array_equal(trace(7), trace(7))
    assert not np.array_equal(trace(7), trace(8))


@pytest.mark.parametrize("threads", [1, 2])
def test_vector_worlds_equal_single_envs(threads):
    vec = gym.make_vec("platoonsim/FlowMerge-v0", num_envs=3, threads=threads, **KW)
    assert isinstance(vec, FlowMergeVecEnv)
    rng = np.random.default_rng(1)
    acts = [rng.uniform(-2, 2, size=(3, 5)) for _ in range(25)]
    obs, _ = vec.reset(seed=11)
    trace, rewards = [obs], []
    for a in acts:
        obs, r, _, _, _ = vec.step(a)
        trace.append(obs)
        rewards.append(r)
    for i in range(3):
        env = FlowMergeEnv(**KW)
        o, _ = env.reset(seed=11 + i)
        assert np.array_equal(o, trace[0][i])
        for k, a in enumerate(acts):
            o, r, _, _, _ = env.step(a[i])
            assert np.array_equal(o, trace[k + 1][i]) and r == rewards[k][i]


def test_autoreset_next_step():
    vec = FlowMergeVecEnv(num_envs=2, warmup_s=10.0, horizon=3)
    vec.reset(seed=0)
    for k in range(3):
        _, _, term, trunc, _ = vec.step(np.zeros((2, 5)))
    assert trunc.all() and not term.any()
    obs, r, term, trunc, info = vec.step(np.zeros((2, 5)))
    assert (r == 0).all() and not term.any() and not trunc.any()
    assert obs.shape == (2, 25) and len(info["seed"]) == 2


def test_the_reward_is_flows():
    # desired_velocity over every vehicle on the road, plus 0.1 x the small-headway penalty of
    # the controlled vehicles, floored at 0; recomputed from the vehicles after the step.
    env = FlowMergeEnv(**KW, rl_share=0.3)
    env.reset(seed=5)
    for _ in range(8):
        _, r, _, _, info = env.step(np.full(5, 1.5))
        v = env.batch.vehicles(0)
        speeds = v["v_mps"]
        target = 20.0 * np.ones(len(speeds))
        r1 = max(np.linalg.norm(target) - np.linalg.norm(speeds - 20.0), 0) / (
            np.linalg.norm(target) + np.finfo(np.float32).eps
        )
        r2 = 0.0
        for vid in info["ids"][info["ids"] >= 0]:
            i = int(np.flatnonzero(v["id"] == vid)[0])
            lead = v["leader_id"][i]
            if lead >= 0 and v["v_mps"][i] > 0:
                li = int(np.flatnonzero(v["id"] == lead)[0])
                gap = v["x_m"][li] - v["length_m"][li] - v["x_m"][i]
                r2 += min(max(gap / v["v_mps"][i], 0) - 1.0, 0.0)
        assert r == pytest.approx(max(r1 + 0.1 * r2, 0.0), rel=1e-12, abs=1e-12)
        assert info["mean_speed_mps"] == pytest.approx(speeds.mean())


def test_the_baselines():
    # acc-only: the actions change nothing; all-human: no learning vehicle at all.
    def run(actions, **kw):
        env = FlowMergeEnv(**KW, **kw)
        env.reset(seed=2)
        return [env.step(a)[0] for a in actions]

    full, brake = [np.full(5, 1.5)] * 15, [np.full(5, -1.5)] * 15
    assert np.array_equal(run(full, baseline="acc-only"), run(brake, baseline="acc-only"))
    assert not np.array_equal(run(full), run(brake))
    env = FlowMergeEnv(**KW, baseline="all-human")
    _, info = env.reset(seed=2)
    for _ in range(10):
        assert info["controlled"] == 0
        _, _, _, _, info = env.step(np.zeros(5))
    assert (env.batch.vehicles(0)["kind"] == 0).all()


def test_bad_actions_and_arguments_are_refused():
    env = FlowMergeEnv(**KW)
    env.reset(seed=0)
    for bad in (np.zeros(4), np.full(5, np.nan), "brake", np.zeros((2, 5)), [0, 0, 0, 0, np.inf]):
        with pytest.raises(ValueError, match=r"finite accelerations of shape \(5,\)"):
            env.step(bad)
    env.step(np.full(5, 99.0))  # out of bounds: clipped, not refused
    vec = FlowMergeVecEnv(num_envs=2, **KW)
    vec.reset(seed=0)
    with pytest.raises(ValueError, match=r"shape \(2, 5\)"):
        vec.step(np.zeros(5))
    for kw, msg in [
        ({"num_rl": 0}, r"num_rl = 0: must be an int in \[1, 1024\]"),
        ({"num_rl": 2.5}, "num_rl = 2.5"),
        ({"horizon": True}, "horizon = True"),
        ({"rl_share": 1.5}, r"rl_share = 1.5: must be a finite number >= 0 and <= 1"),
        ({"max_accel": -1}, "max_accel = -1: must be a finite number > 0"),
        ({"target_velocity": float("nan")}, "target_velocity = nan"),
        ({"baseline": "idm"}, "baseline = 'idm': must be None"),
        ({"overrides": "x"}, "overrides = 'x'"),
    ]:
        with pytest.raises(ValueError, match=msg):
            FlowMergeEnv(**kw)
    with pytest.raises(TypeError, match="unknown argument 'num_cav'; allowed: num_rl"):
        FlowMergeEnv(num_cav=5)
    with pytest.raises(ValueError, match="num_envs = 0"):
        FlowMergeVecEnv(num_envs=0)


@pytest.mark.parametrize("a", [1.5, -1.5])
def test_extreme_policies_never_collide(a):
    # 750 actions of full throttle or full braking, on three seeds, 0 collisions: the safe
    # command's bound, not the policy, keeps the vehicles apart.
    vec = FlowMergeVecEnv(num_envs=3, rl_share=0.3)
    vec.reset(seed=100)
    steps, controlled = 0, 0
    while True:
        _, _, term, trunc, info = vec.step(np.full((3, 5), a))
        steps += 1
        controlled += int(info["controlled"].sum())
        assert not term.any() and (info["collisions"] == 0).all()
        if trunc.all():
            break
    assert steps == 750 and controlled > 1000
    assert all(vec.batch.finish(i)["collisions"] == 0 for i in range(3))
