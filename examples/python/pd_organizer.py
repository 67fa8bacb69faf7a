"""The pseudo-dedicated lane (PD) strategy written in Python.

The same rule as the built-in `pd` strategy (crates/sim/src/organize/pd.rs, spec 4.7): inside
the zone and the time window, a CAV is advised to join the leftmost through lane at its
position (or stay in a lane further left); elsewhere it gets no advice. Human drivers are not
advised. Run with the same seed, penetration and demand, it gives the summary of
`platoonsim run homogeneous --strategy pd` field for field (python/tests/test_organizer.py).

    python examples/python/pd_organizer.py [duration_s]
"""

from __future__ import annotations

import sys
import time

import numpy as np

import platoonsim


class PdOrganizer:
    """PD: CAVs join the leftmost through lane inside the zone and the time window."""

    name = "pd"  # the summary's `strategy`, as for the built-in one
    every_steps = 1  # the engine asks every step, from the step-start state
    advises_cavs = True
    advises_humans = False

    def __init__(self, zone_start_m: float, zone_end_m: float, start_s: float, end_s: float):
        self.zone = (zone_start_m, zone_end_m)
        self.window = (start_s, end_s)

    @classmethod
    def for_scenario(cls, config: dict) -> "PdOrganizer":
        """The zone and window the built-in strategy would use: `[strategy]`'s if the config
        has them (strategy.kind = "pd"), else the control section and the measurement window,
        which are the defaults of a plain road (docs/organizers.md)."""
        pd = config["strategy"].get("pd")
        if pd is not None:
            return cls(pd["zone_start_m"], pd["zone_end_m"], pd["start_s"], pd["end_s"])
        road = config["road"]
        return cls(road["control_start_m"], road["control_end_m"], config["warmup_s"], config["duration_s"])

    def advise(self, sim: platoonsim.Simulation, t_s: float, v: dict[str, np.ndarray]) -> np.ndarray:
        lanes = np.full(v["id"].shape, -1, dtype=np.int64)
        if not (self.window[0] <= t_s < self.window[1]):
            return lanes
        x = v["x_m"]
        inside = (x >= self.zone[0]) & (x < self.zone[1])
        own = v["lane"][inside].astype(np.int64)
        left = sim.leftmost_through(x[inside])
        # A vehicle left of the leftmost through lane is where it should be; where no lane is
        # open it stays where it is.
        lanes[inside] = np.where(left < 0, own, np.maximum(left, own))
        return lanes


def main() -> None:
    duration = float(sys.argv[1]) if len(sys.argv) > 1 else 3600.0
    overrides = {"run.penetration": 0.5, "demand.vph_per_lane": 2500, "run.duration_s": duration}
    if duration <= 1200:
        overrides["run.warmup_s"] = duration / 3
    config = platoonsim.Simulation("homogeneous", seed=1, overrides=overrides).config
    organizer = PdOrganizer.for_scenario(config)
    sim = platoonsim.Simulation("homogeneous", seed=1, overrides=overrides, organizer=organizer, events=False)
    start = time.perf_counter()
    summary = sim.run()
    wall = time.perf_counter() - start
    print(
        f"strategy {summary['strategy']}: L = {summary['avg_platoon_length']:.3f}, "
        f"P_P = {summary['platooning_probability']:.3f}, discharge "
        f"{summary['discharge_flow_vphpl']:.0f} veh/h/lane, {summary['collisions']} collisions, "
        f"{duration:.0f} s simulated in {wall:.2f} s"
    )


if __name__ == "__main__":
    main()
