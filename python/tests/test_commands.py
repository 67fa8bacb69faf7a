"""Commands vectorized over vehicle ids: they act from the next step, as in the library."""

from __future__ import annotations

import numpy as np
import pytest

import platoonsim

RUN = {"run.duration_s": 600, "run.warmup_s": 0}


def started(t_s: float = 200.0, **kw) -> platoonsim.Simulation:
    sim = platoonsim.Simulation("homogeneous", seed=2, overrides=RUN, **kw)
    sim.run_until(t_s)
    return sim


def row(sim, vid):
    v = sim.vehicles()
    i = np.flatnonzero(v["id"] == vid)
    return {k: a[i[0]] for k, a in v.items()} if i.size else None


def test_accelerate_applies_the_commanded_acceleration_to_every_id():
    sim = started()
    v = sim.vehicles()
    ids = v["id"][(v["x_m"] > 1000) & (v["x_m"] < 1500)][:4]
    assert ids.size == 4
    sim.accelerate(ids, -2.0, steps=20)
    assert sim.commanded() == ids.tolist()
    sim.step()
    after = sim.vehicles()
    for vid in ids:
        i = np.flatnonzero(after["id"] == vid)[0]
        assert after["a_mps2"][i] == -2.0
    sim.step(19)
    assert sim.commanded() == []  # ended by itself after 20 steps
    assert sim.finish()["collisions"] == 0


def test_desired_speed_slows_a_vehicle_and_release_gives_it_back():
    sim = started(events=False)
    v = sim.vehicles()
    vid = int(v["id"][(v["x_m"] > 500) & (v["x_m"] < 800) & (v["kind"] == 0)][0])
    sim.set_desired_speed(vid, 15.0)
    sim.run_until(sim.time_s + 60.0)
    slowed = row(sim, vid)
    assert abs(slowed["v_mps"] - 15.0) < 1.0
    sim.release(vid)
    assert sim.commanded() == []
    sim.run_until(sim.time_s + 60.0)
    assert row(sim, vid)["v_mps"] > 20.0


def test_change_lane_is_a_commanded_lane_change_event():
    sim = started()
    sim.events()
    v = sim.vehicles()
    pick = (v["lane"] == 0) & (v["x_m"] > 2000) & (v["kind"] == 0)
    vid = int(v["id"][pick][0])
    sim.change_lane(vid, "left")
    changes = []
    for _ in range(200):
        sim.step()
        changes += [e for e in sim.events() if e["type"] == "lane_change" and e["id"] == vid]
        if changes:
            break
    assert changes, "the driver changes lanes once a gap allows"
    assert changes[0]["reason"] == "commanded" and changes[0]["to_lane"] == 1
    assert row(sim, vid)["lane"] == 1


def test_a_bad_command_raises_and_changes_nothing():
    sim = started()
    v = sim.vehicles()
    good = v["id"][:3]
    with pytest.raises(platoonsim.CommandError, match=r"vehicle 999999 is not on the road"):
        sim.accelerate(np.append(good, 999999), -1.0)
    assert sim.commanded() == []  # the whole batch was refused
    with pytest.raises(platoonsim.CommandError, match=r"accel_mps2 = 50: must be finite, within ±20"):
        sim.accelerate(good, 50.0)
    with pytest.raises(platoonsim.CommandError, match=r"must be finite"):
        sim.accelerate(good, float("nan"))
    with pytest.raises(platoonsim.CommandError, match=r"speed_mps = -1"):
        sim.set_desired_speed(good, -1.0)
    with pytest.raises(platoonsim.CommandError, match=r'side = "up": must be "left" or "right"'):
        sim.change_lane(good, "up")
    with pytest.raises(platoonsim.CommandError, match=r"2 values for 3 vehicle ids"):
        sim.accelerate(good, [1.0, 2.0])
    with pytest.raises(platoonsim.CommandError, match=r"must be one of"):
        sim.command(good, "teleport")
    with pytest.raises(platoonsim.CommandError, match=r"integer vehicle ids"):
        sim.accelerate(["a", "b"], 1.0)
    with pytest.raises(platoonsim.CommandError, match=r"not on the road"):
        sim.release(-5)
    rightmost = v["id"][v["lane"] == 0][:1]
    with pytest.raises(platoonsim.CommandError, match=r"cannot change Right"):
        sim.change_lane(rightmost, "right")
    assert sim.commanded() == []
    sim.step(10)
    assert sim.finish()["collisions"] == 0


@pytest.mark.parametrize("speed", [10.0, 20.0])
def test_set_desired_speed_then_change_lane_completes_without_braking(speed):
    # An open road (600 veh/h/lane): a CAV set to a low speed and then commanded left changes
    # within a few seconds and never brakes for it (before issue 29 it dropped back to
    # 2.2 m/s behind the faster traffic of the target lane and waited 10 s). The engine side
    # is pinned by crates/sim/tests/commanded_change.rs.
    overrides = {**RUN, "demand.vph_per_lane": 600, "run.penetration": 0.5}
    sim = platoonsim.Simulation("homogeneous", seed=2, overrides=overrides)
    sim.run_until(200.0)
    v = sim.vehicles()
    pick = (v["lane"] == 0) & (v["kind"] == 1) & (v["mode"] == 1) & (v["x_m"] > 1000) & (v["x_m"] < 3000)
    vid = int(v["id"][pick][0])
    sim.set_desired_speed(vid, speed)
    sim.step(300)
    assert abs(row(sim, vid)["v_mps"] - speed) < 0.5
    sim.change_lane(vid, "left")
    accels = []
    for _ in range(60):
        sim.step()
        r = row(sim, vid)
        accels.append(r["a_mps2"])
        if r["lane"] == 1:
            break
    assert row(sim, vid)["lane"] == 1, "changed within 6 s"
    assert min(accels) > -0.1, f"no braking for the change: {min(accels)}"
    assert sim.finish()["collisions"] == 0
