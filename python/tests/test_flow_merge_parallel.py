"""FlowMerge-v0 as a PettingZoo ParallelEnv: PettingZoo's own API test, agents named after the
controlled vehicles, the shared reward equal to the single env's, agents never revived, bad
actions refused."""

from __future__ import annotations

import os

import numpy as np
import pytest

# scripts/python-tests.sh installs pettingzoo; under CI a missing one fails, elsewhere it skips.
if os.environ.get("CI") != "true":
    pytest.importorskip("pettingzoo")
from pettingzoo.test import parallel_api_test  # noqa: E402

from platoonsim.flow_merge import FlowMergeEnv  # noqa: E402
from platoonsim.parallel import FlowMergeParallelEnv  # noqa: E402

KW = {"warmup_s": 60.0, "horizon": 120, "rl_share": 0.3}


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_pettingzoos_parallel_api_test_passes():
    parallel_api_test(FlowMergeParallelEnv(**KW), num_cycles=120)


def test_agents_are_the_controlled_vehicles_and_share_the_reward():
    pz = FlowMergeParallelEnv(**KW)
    single = FlowMergeEnv(**KW)
    obs, infos = pz.reset(seed=4)
    s_obs, s_info = single.reset(seed=4)
    assert pz.agents == [f"cav_{i}" for i in s_info["ids"][s_info["mask"]]]
    for a in pz.agents:
        assert np.array_equal(obs[a], s_obs.reshape(5, 5)[infos[a]["slot"]])
        assert pz.observation_space(a).shape == (5,) and pz.action_space(a).shape == (1,)
    rng = np.random.default_rng(3)
    gone: set[str] = set()
    for _ in range(60):
        row = rng.uniform(-1.5, 1.5, 5)
        actions = {a: row[infos[a]["slot"]] for a in pz.agents}
        obs, rew, term, trunc, infos = pz.step(actions)
        if any(i.get("skipped", 0) for i in infos.values()):
            break  # the single env has no skipping: compare up to the first skip
        s_obs, s_r, _, _, s_info = single.step(row)
        listed = [f"cav_{i}" for i in s_info["ids"][s_info["mask"]]]
        assert pz.agents == listed
        for a, r in rew.items():
            assert r == (s_r if a in actions else 0.0)
        for a in pz.agents:
            assert np.array_equal(obs[a], s_obs.reshape(5, 5)[infos[a]["slot"]])
        left = {a for a in actions if term[a]}
        assert left.isdisjoint(pz.agents) and not (gone & set(pz.agents))
        gone |= left
        assert set(pz.agents) <= set(pz.possible_agents)
    assert gone, "no vehicle left the road in 60 s"


def test_an_episode_runs_to_its_horizon_with_agents_throughout():
    # With no learning vehicle on the road the env steps on by itself: `agents` is empty only
    # at the end, and the actions (skipped ones included) add up to the horizon.
    pz = FlowMergeParallelEnv(warmup_s=0.0, horizon=200)
    pz.reset(seed=9)
    assert pz.agents and pz.t_actions > 0  # the first learning vehicle entered after some seconds
    while pz.agents:
        _, _, term, trunc, _ = pz.step({a: 0.0 for a in pz.agents})
    assert pz.t_actions == 200
    assert all(trunc[a] or term[a] for a in term)


def test_bad_actions_are_refused():
    pz = FlowMergeParallelEnv(**KW)
    pz.reset(seed=1)
    a0 = pz.agents[0]
    full = {a: 0.0 for a in pz.agents}
    for bad, msg in [
        ({**full, "cav_999999": 0.0}, "not a live agent"),
        ({a: 0.0 for a in pz.agents[1:]}, f"no action for the live agent '{a0}'"),
        ({**full, a0: np.nan}, "must be one finite acceleration"),
        ({**full, a0: [1.0, 2.0]}, "must be one finite acceleration"),
        ({**full, a0: "up"}, "must be one finite acceleration"),
        ([0.0], "must be a dict"),
    ]:
        with pytest.raises(ValueError, match=msg):
            pz.step(bad)
    pz.step({**full, a0: np.array([9.0])})  # out of bounds: clipped
