"""Throughput of the learning environments (docs/learning.md, "Throughput"): environment steps
and controlled-vehicle steps per second with random actions, for 1, 2, 4 and 8 worlds in one
process (the native vector environments), against a Python loop over 8 single environments,
and, with ``--sumo``, the same merge in SUMO through libsumo (one simulation per process, as
libsumo allows), its CAVs driven by ``vehicle.setAcceleration``.

    python examples/learning/throughput.py [--seconds S] [--sumo] [--only ENV_ID ...]

Needs the package with gymnasium (``pip install ./python[gym]``); ``--sumo`` also needs
``pip install libsumo eclipse-sumo`` (netconvert builds the merge).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

import gymnasium as gym
import platoonsim.gym  # noqa: F401  (registers the environments)
from platoonsim.control import CavControlEnv, merge_scenario
from platoonsim.flow_merge import FlowMergeEnv
from platoonsim.gym import PlatoonEnv

PLATOON = {"warmup_s": 360.0, "decision_s": 60.0, "decisions": 30}
CONTROL = {"warmup_s": 60.0, "horizon_s": 300.0}
# Flow's merge0 as it is: no warm-up, 750 actions of 1 s (the episode's reset is included).
FLOW_MERGE: dict = {}


#: CPU seconds (every thread of this process) of the last ``_rate`` call per wall second: on a
#: shared machine the wall-clock rates fall with the load, the rates per CPU second much less.
CPU_SHARE = [1.0]


def _rate(step, seconds: float) -> tuple[float, float]:
    """Run ``step()`` (returning the controlled vehicles it stepped) for about ``seconds``:
    (calls per second, controlled vehicles per second), wall clock."""
    n, controlled, t0, c0 = 0, 0, time.perf_counter(), time.process_time()
    while time.perf_counter() - t0 < seconds:
        controlled += step()
        n += 1
    dt = time.perf_counter() - t0
    CPU_SHARE[0] = (time.process_time() - c0) / dt
    return n / dt, controlled / dt


def vector(env_id: str, kwargs: dict, worlds: int, seconds: float) -> tuple[float, float]:
    env = gym.make_vec(env_id, num_envs=worlds, **kwargs)
    env.action_space.seed(0)
    env.reset(seed=0)

    def step() -> int:
        _, _, _, _, info = env.step(env.action_space.sample())
        return int(np.sum(info.get("controlled", 0)))

    steps, controlled = _rate(step, seconds)
    return steps * worlds, controlled


def loop(make, worlds: int, seconds: float) -> tuple[float, float]:
    envs = [make() for _ in range(worlds)]
    for i, e in enumerate(envs):
        e.action_space.seed(i)
        e.reset(seed=i)

    def step() -> int:
        c = 0
        for e in envs:
            _, _, term, trunc, info = e.step(e.action_space.sample())
            c += int(info.get("controlled", 0))
            if term or trunc:
                e.reset()
        return c

    steps, controlled = _rate(step, seconds)
    return steps * worlds, controlled


def sumo_merge(seconds: float) -> tuple[float, float]:
    """The merge of ``merge_scenario()`` in SUMO: one lane, the on-ramp at 700 m with a 100 m
    acceleration lane, 2,000 + 200 veh/h, 25 % CAVs (SUMO's CACC model) whose accelerations
    are set at random every 0.5 s (5 steps of 0.1 s), every vehicle read every action."""
    import libsumo

    d = Path(tempfile.mkdtemp())
    (d / "m.nod.xml").write_text(
        '<nodes><node id="A" x="0" y="0"/><node id="B" x="700" y="0"/><node id="C" x="800" y="0"/>'
        '<node id="D" x="1200" y="0"/><node id="R" x="500" y="-100"/></nodes>'
    )
    (d / "m.edg.xml").write_text(
        '<edges><edge id="m1" from="A" to="B" numLanes="1" speed="30.56"/>'
        '<edge id="acc" from="B" to="C" numLanes="2" speed="30.56"/>'
        '<edge id="m2" from="C" to="D" numLanes="1" speed="30.56"/>'
        '<edge id="ramp" from="R" to="B" numLanes="1" speed="25"/></edges>'
    )
    (d / "m.con.xml").write_text(
        '<connections><connection from="m1" to="acc" fromLane="0" toLane="1"/>'
        '<connection from="ramp" to="acc" fromLane="0" toLane="0"/>'
        '<connection from="acc" to="m2" fromLane="1" toLane="0"/></connections>'
    )
    subprocess.run(
        ["netconvert", "-n", "m.nod.xml", "-e", "m.edg.xml", "-x", "m.con.xml", "-o", "m.net.xml"],
        cwd=d, check=True, capture_output=True,
    )
    (d / "m.rou.xml").write_text(
        '<routes><vTypeDistribution id="mix">'
        '<vType id="h" probability="0.75"/><vType id="c" carFollowModel="CACC" probability="0.25"/>'
        '</vTypeDistribution>'
        '<route id="main" edges="m1 acc m2"/><route id="r" edges="ramp acc m2"/>'
        '<flow id="fm" type="mix" route="main" begin="0" end="100000" vehsPerHour="2000"/>'
        '<flow id="fr" type="mix" route="r" begin="0" end="100000" vehsPerHour="200"/></routes>'
    )
    libsumo.start(["sumo", "-n", str(d / "m.net.xml"), "-r", str(d / "m.rou.xml"), "--step-length", "0.1",
                   "--no-step-log", "--no-warnings"])
    for _ in range(600):
        libsumo.simulationStep()
    rng = np.random.default_rng(0)

    def step() -> int:
        ids = libsumo.vehicle.getIDList()
        cavs = [v for v in ids if libsumo.vehicle.getTypeID(v) == "c"][:10]
        for v in ids:
            libsumo.vehicle.getPosition(v), libsumo.vehicle.getSpeed(v)
        for v in cavs:
            libsumo.vehicle.setAcceleration(v, float(rng.uniform(-4.0, 1.5)), 0.5)
        for _ in range(5):
            libsumo.simulationStep()
        return len(cavs)

    try:
        return _rate(step, seconds)
    finally:
        libsumo.close()


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--seconds", type=float, default=10.0, help="seconds per measurement")
    ap.add_argument("--sumo", action="store_true", help="also the merge in SUMO through libsumo")
    ap.add_argument("--only", nargs="*", default=None, help="only these environment ids")
    args = ap.parse_args()
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"cores: {os.cpu_count()}; load average {load:.1f}; {args.seconds:g} s per measurement; random actions")
    print("| environment | set-up | env-steps/s | controlled-vehicle steps/s | env-steps per CPU-second |")
    print("|---|---|---|---|---|")
    for env_id, kwargs, make in (
        ("platoonsim/Platoon-v1", PLATOON, lambda: PlatoonEnv(**PLATOON)),
        ("platoonsim/CavControl-v0", CONTROL, lambda: CavControlEnv(**CONTROL)),
        ("platoonsim/FlowMerge-v0", FLOW_MERGE, lambda: FlowMergeEnv(**FLOW_MERGE)),
    ):
        if args.only is not None and env_id not in args.only:
            continue
        for w in (1, 2, 4, 8):
            s, c = vector(env_id, kwargs, w, args.seconds)
            print(f"| {env_id} | {w} worlds, one batch | {s:,.0f} | {c:,.0f} | {s / CPU_SHARE[0]:,.0f} |", flush=True)
        s, c = loop(make, 8, args.seconds)
        print(f"| {env_id} | Python loop over 8 single envs | {s:,.0f} | {c:,.0f} | {s / CPU_SHARE[0]:,.0f} |", flush=True)
    if args.sumo:
        s, c = sumo_merge(args.seconds)
        print(f"| SUMO merge (libsumo) | 1 simulation | {s:,.0f} | {c:,.0f} | {s / CPU_SHARE[0]:,.0f} |")
    _ = merge_scenario  # the merge both sides run


if __name__ == "__main__":
    main()
