"""Speed of the Python API against the native run (docs/performance.md, "From Python").

One simulated hour of the homogeneous road, 50 % CAV, 2,500 veh/h/lane, seed 1, three ways:
`step()` through the hour in chunks of a simulated minute, `step()` one step at a time, and
one step at a time reading `vehicles()` after every step. Prints vehicle updates per second
for each (the native figure comes from `platoonsim run`'s summary: run it beside this).

    python examples/python/speed.py [mode ...]     # modes: chunks, steps, vehicles
"""

from __future__ import annotations

import sys
import time

import platoonsim

OVERRIDES = {"run.penetration": 0.5, "demand.vph_per_lane": 2500}


def run(mode: str) -> None:
    sim = platoonsim.Simulation("homogeneous", seed=1, overrides=OVERRIDES, events=False)
    start = time.perf_counter()
    read = 0
    if mode == "chunks":
        while not sim.done:
            sim.step(600)
    elif mode == "steps":
        while not sim.done:
            sim.step()
    elif mode == "vehicles":
        while not sim.done:
            sim.step()
            read += sim.vehicles()["id"].size
    else:
        raise SystemExit(f"unknown mode {mode!r}: chunks, steps or vehicles")
    wall = time.perf_counter() - start
    s = sim.finish()
    print(
        f"{mode:8s}: {s['vehicle_updates']:,} vehicle updates in {wall:.2f} s = "
        f"{s['vehicle_updates'] / wall / 1e6:.2f} M/s (engine alone {s['wall_seconds']:.2f} s)"
        + (f"; {read:,} vehicle rows read" if read else "")
    )


if __name__ == "__main__":
    for m in sys.argv[1:] or ["chunks", "steps", "vehicles"]:
        run(m)
