"""Platoon-v1 (the gate task against a twin): Gymnasium's checker, seeding, the reward's
zero, the filled road at the first decision, the paper's measures over an hour, bad settings."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

from gymnasium.utils.env_checker import check_env

from platoonsim.gym import PlatoonEnv

# Short episodes for the tests: the warm-up that fills the 6.5 km road, 60-s decisions.
KW = {"warmup_s": 360.0, "decision_s": 60.0, "decisions": 4}


def test_check_env_passes():
    check_env(PlatoonEnv(**KW), skip_render_check=True)


def test_reset_seed_reproduces_an_episode():
    env = PlatoonEnv(**KW)
    runs = []
    for _ in range(2):
        obs, _ = env.reset(seed=11)
        trace = [obs]
        for a in [1, 0, 1, 1]:
            obs, r, term, trunc, _ = env.step(a)
            trace.append(np.append(obs, r))
        assert trunc and not term
        runs.append(np.concatenate(trace))
    assert np.array_equal(runs[0], runs[1])
    with pytest.raises(RuntimeError, match="reset"):
        env.step(0)


def test_holding_throughout_earns_exactly_zero():
    # The twin is the same road and seed with the organizer off: an agent that never
    # organizes drives exactly its traffic.
    env = PlatoonEnv(**KW)
    env.reset(seed=3)
    for _ in range(4):
        _, r, _, _, info = env.step(0)
        assert r == 0.0 and info["l_gain"] == 0.0 and info["discharge_change"] == 0.0
    for key in ("cav_exits", "platoon_sum", "discharge_count"):
        assert info[key][0] == info[key][1] > 0
    assert info["collisions"].tolist() == [0, 0]


def test_the_road_is_filled_at_the_first_decision():
    # Platoon-v0 started deciding while the discharge detector had only just started
    # counting (a 6.1 % "discharge loss" for never organizing in free flow). At the default
    # warm-up the discharge detector passes what the upstream one does.
    env = PlatoonEnv(demand_vphpl=2000.0, decisions=1)
    ratios = []
    for seed in range(4):
        _, info = env.reset(seed=seed)
        ratios.append(info["flow_vphpl"][2] / info["flow_vphpl"][0])
    assert 0.9 < np.mean(ratios) < 1.1, ratios


def test_organizing_for_an_hour_gives_the_paper_measures():
    # Always organizing is PD: over an hour the strings grow (L̄ gain > 0) at 50 % CAVs.
    env = PlatoonEnv(decisions=60)
    env.reset(seed=1)
    rewards = []
    for _ in range(60):
        _, r, _, trunc, info = env.step(1)
        rewards.append(r)
    assert trunc
    lbar = info["platoon_sum"] / info["cav_exits"]
    assert lbar[0] / lbar[1] - 1 > 0.05
    assert info["collisions"].tolist() == [0, 0]
    assert np.isfinite(rewards).all() and len(set(rewards)) > 10


@pytest.mark.parametrize(
    "setting, message",
    [
        ({"discharge_penalty": float("nan")}, "discharge_penalty = nan"),
        ({"discharge_penalty": -1.0}, "discharge_penalty = -1.0"),
        ({"decision_s": 0.0}, "decision_s = 0.0"),
        ({"decision_s": 0.05}, "(?s)decision_s = 0.05 .*aggregation_s = 0.05: must be a whole number of steps"),
        ({"warmup_s": 630.0}, "warmup_s = 630: must be a whole number of decision intervals"),
        ({"warmup_s": 240.0}, "warmup_s = 240: the road is not filled yet"),
        ({"decisions": 0}, "decisions = 0"),
        ({"baseline": "pd"}, "baseline = 'pd'"),
        ({"scenario": "sr99"}, "plain road"),
    ],
)
def test_bad_settings_are_refused(setting, message):
    with pytest.raises(ValueError, match=message):
        PlatoonEnv(**setting)


def test_v0_is_gone_and_names_v1():
    with pytest.raises(gym.error.DeprecatedEnv, match="Platoon-v1"):
        gym.make("platoonsim/Platoon-v0")
