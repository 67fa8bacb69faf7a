"""vehicles(), detectors() and events(): determinism, meaning, agreement with the summary."""

from __future__ import annotations

import sys
import time

import numpy as np

import platoonsim

COLUMNS = ["id", "kind", "lane", "x_m", "v_mps", "a_mps2", "mode", "regime", "platoon_id", "platoon_pos", "leader_id", "length_m"]
RUN = {"run.duration_s": 300, "run.warmup_s": 0}


def test_same_seed_gives_identical_vehicles_at_every_step():
    a = platoonsim.Simulation("homogeneous", seed=9, overrides=RUN)
    b = platoonsim.Simulation("homogeneous", seed=9, overrides=RUN)
    c = platoonsim.Simulation("homogeneous", seed=10, overrides=RUN)
    differs = False
    while not a.done:
        a.step()
        b.step()
        c.step()
        va, vb, vc = a.vehicles(), b.vehicles(), c.vehicles()
        assert list(va) == COLUMNS
        for k in COLUMNS:
            assert va[k].dtype == vb[k].dtype
            assert np.array_equal(va[k], vb[k]), (a.time_s, k)
        differs |= va["id"].shape != vc["id"].shape or not np.array_equal(va["x_m"], vc["x_m"])
    assert a.steps == 3000 and a.time_s == 300.0
    assert differs, "another seed gives other traffic"


def test_vehicle_columns_mean_what_the_docs_say():
    sim = platoonsim.Simulation("homogeneous", seed=3, overrides=RUN)
    sim.run_until(200.0)
    v = sim.vehicles()
    n = v["id"].size
    assert n > 200
    assert set(np.unique(v["kind"])) == {0, 1}
    assert np.all((v["lane"] >= 0) & (v["lane"] < 3))
    assert np.all((v["x_m"] >= 0) & (v["x_m"] <= 6500)) and np.all(v["v_mps"] >= 0)
    # Lane by lane, front first; the leader is the vehicle before in the same lane.
    for i in range(n):
        if v["leader_id"][i] >= 0:
            assert v["id"][i - 1] == v["leader_id"][i] and v["lane"][i - 1] == v["lane"][i]
            assert v["x_m"][i - 1] > v["x_m"][i]
        else:
            assert i == 0 or v["lane"][i - 1] != v["lane"][i]
    members = v["platoon_pos"] > 1
    assert members.sum() > 20 and np.all(v["kind"][members] == 1)
    assert np.all(v["platoon_pos"][1:][members[1:]] == v["platoon_pos"][:-1][members[1:]] + 1)
    # While automated a CAV has a regime; a human driver never.
    assert np.all(v["regime"][v["kind"] == 0] == -1)
    auto = np.array([platoonsim.MODE_LABELS[m].endswith("-auto") for m in v["mode"]])
    assert not np.any(auto & (v["kind"] == 0))


def test_detectors_report_the_latest_closed_interval():
    sim = platoonsim.Simulation("homogeneous", seed=3, overrides={"run.duration_s": 900, "run.warmup_s": 0})
    sim.run_until(299.9)
    assert sim.detectors()["count"].size == 0
    sim.run_until(600.0)
    assert set(sim.detectors()["detector"]) == {"upstream", "control_mid", "discharge"}
    d = sim.detectors()
    assert np.all(d["interval_start_s"] == 300.0) and np.all(d["interval_s"] == 300.0)
    up = (d["detector"] == "upstream") & (d["lane"] == "all")
    # 2500 veh/h/lane offered, free flow upstream: the measured flow is near the demand.
    assert 2000 < d["flow_vph"][up][0] / 3 < 3000
    assert 80 < d["speed_kmh"][up][0] < 130


def test_events_agree_with_the_summary():
    sim = platoonsim.Simulation(
        "homogeneous", seed=5, overrides={"run.duration_s": 900, "run.warmup_s": 0}, organizer="pd"
    )
    events = []
    while not sim.done:
        sim.step(500)
        events += sim.events()
    assert sim.events() == []  # drained
    s = sim.finish()
    by = {}
    for e in events:
        by.setdefault(e["type"], []).append(e)
    assert len(by["entered"]) == s["vehicles_entered"]
    assert len(by["exited"]) == s["vehicles_exited"]
    lane_changes = len(by["lane_change"])
    assert lane_changes > 0
    assert abs(lane_changes / s["vehicles_counted"] - s["lane_changes_per_vehicle"]) < 1e-12
    assert "collision" not in by
    times = [e["t_s"] for e in events]
    assert times == sorted(times)
    lc = by["lane_change"][0]
    assert set(lc) == {
        "t_s", "type", "id", "kind", "from_lane", "to_lane", "side", "x_m", "reason", "cooperative",
    }
    assert abs(lc["from_lane"] - lc["to_lane"]) == 1
    reasons = {e["reason"] for e in by["lane_change"]}
    assert reasons <= {"mandatory", "discretionary", "organizing", "commanded"}
    assert "organizing" in reasons  # PD moves CAVs into the leftmost lane
    organizing = [e for e in by["lane_change"] if e["reason"] == "organizing"]
    assert all(e["kind"] == "cav" and e["side"] == "left" and 5000 <= e["x_m"] <= 6000 + 40 for e in organizing)


def test_events_off_raises_a_clear_error():
    sim = platoonsim.Simulation("homogeneous", overrides=RUN, events=False)
    sim.step(10)
    try:
        sim.events()
    except platoonsim.SimulationError as e:
        assert "events=True" in str(e)
    else:
        raise AssertionError("events() without events=True must raise")


def test_stepping_releases_the_gil():
    import threading

    sim = platoonsim.Simulation("homogeneous", seed=1, overrides={"run.duration_s": 900, "run.warmup_s": 0}, events=False)
    ticks = 0
    done = threading.Event()

    def count():
        nonlocal ticks
        while not done.is_set():
            ticks += 1

    counter = threading.Thread(target=count)
    counter.start()
    try:
        before = ticks
        start = time.perf_counter()
        sim.step(9000)  # the whole run in one call
        during, wall = ticks - before, time.perf_counter() - start
    finally:
        done.set()
        counter.join()
    assert sim.done
    # With the GIL held for the whole call the counter would stand still (a Python thread
    # only runs while the GIL is free: at most one switch interval, 5 ms); it counts on while
    # Rust steps, for most of the call.
    print(f"{during} ticks in {wall:.2f} s of stepping")
    assert during > 0.05 * wall * 1e6 and during > 20 * sys.getswitchinterval() * 1e6, (during, wall)
