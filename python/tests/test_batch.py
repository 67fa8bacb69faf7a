"""BatchSimulation: N worlds stepped together equal N single runs, at any thread count."""

from __future__ import annotations

import numpy as np
import pytest

import platoonsim

OV = {"run.duration_s": 300, "run.warmup_s": 0, "demand.vph_per_lane": 2000}


def _same(a: dict, b: dict) -> bool:
    skip = {"wall_seconds", "updates_per_second"}
    return {k: v for k, v in a.items() if k not in skip} == {k: v for k, v in b.items() if k not in skip}


@pytest.mark.parametrize("threads", [1, 2])
def test_each_world_is_the_single_run_of_its_seed(threads):
    b = platoonsim.BatchSimulation("homogeneous", seeds=[3, 4, 5], overrides=OV, organizer="pd", threads=threads)
    assert b.num_worlds == 3 and b.threads == threads
    b.step(1500)
    mid = [b.vehicles(i) for i in range(3)]
    b.step(10_000)  # past the end: each world stops at its duration
    assert b.done().all()
    for i, seed in enumerate([3, 4, 5]):
        single = platoonsim.Simulation("homogeneous", seed=seed, overrides=OV, organizer="pd", events=False)
        single.step(1500)
        v = single.vehicles()
        assert all(np.array_equal(v[k], mid[i][k]) for k in v)
        assert _same(b.finish(i), single.run())


def test_concatenated_vehicles_carry_their_world():
    b = platoonsim.BatchSimulation("homogeneous", seeds=[1, 2], overrides=OV)
    b.run_until(120.0)
    v = b.vehicles()
    for i in range(2):
        w = b.vehicles(i)
        assert np.array_equal(v["id"][v["world"] == i], w["id"])
        assert np.array_equal(v["x_m"][v["world"] == i], w["x_m"])
    assert np.allclose(b.time_s(), 120.0)


def test_per_world_overrides_and_commands():
    b = platoonsim.BatchSimulation(
        "homogeneous", seeds=[1, 1], overrides=[OV, {**OV, "demand.vph_per_lane": 1000}]
    )
    b.run_until(60.0)
    assert len(b.vehicles(1)["id"]) < len(b.vehicles(0)["id"])
    ids = b.vehicles(0)["id"][:2]
    b.command(0, ids, "desired_speed", 20.0)
    b.run_until(90.0)
    v = b.vehicles(0)
    assert (v["v_mps"][np.isin(v["id"], ids)] < 20.1).all()


def test_the_gate_switches_pd_per_world():
    b = platoonsim.BatchSimulation("homogeneous", seeds=[2, 2], overrides={**OV, "run.penetration": 0.5})
    b.use_gate()
    b.set_gates([True, False])
    b.run_until(300.0)
    on, off = b.finish(0), b.finish(1)
    assert on["avg_platoon_length"] > off["avg_platoon_length"]
    assert on["lane_changes_per_cav"] > off["lane_changes_per_cav"]


def test_bad_arguments_are_named():
    with pytest.raises(platoonsim.ScenarioError, match=r"seeds\[1\] = -1"):
        platoonsim.BatchSimulation("homogeneous", seeds=[1, -1])
    with pytest.raises(ValueError, match="a batch has 1 to"):
        platoonsim.BatchSimulation("homogeneous", seeds=[])
    with pytest.raises(ValueError, match="2 dicts for 3 worlds"):
        platoonsim.BatchSimulation("homogeneous", seeds=[1, 2, 3], overrides=[OV, OV])
    with pytest.raises(platoonsim.ScenarioError, match="(?s)world 1: .*run.penetration"):
        platoonsim.BatchSimulation("homogeneous", seeds=[1, 2], overrides=[OV, {"run.penetration": 2}])
    with pytest.raises(TypeError, match="Python organizers"):
        platoonsim.BatchSimulation("homogeneous", seeds=[1], organizer=object())  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="threads = 0"):
        platoonsim.BatchSimulation("homogeneous", seeds=[1], threads=0)
    b = platoonsim.BatchSimulation("homogeneous", seeds=[1, 2], overrides=OV)
    with pytest.raises(IndexError, match="worlds 0 to 1"):
        b.vehicles(2)
    with pytest.raises(ValueError, match="one boolean per world"):
        b.set_gates([True])
    with pytest.raises(platoonsim.SimulationError, match="use_gate"):
        b.set_gates([True, False])
    with pytest.raises(platoonsim.CommandError, match="world 0: .*not on the road"):
        b.command(0, [10**9], "release")
