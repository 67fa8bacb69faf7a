"""The homogeneous road in SUMO through libsumo, reading every vehicle every step.

For the speed comparison in docs/performance.md ("From Python"): one straight three-lane edge
of 6 km at 110 km/h, human drivers with Krauss and CAVs with SUMO's CACC model (50 %),
Poisson arrivals per lane at 2,500 veh/h/lane inserted at the lane's average speed, one
simulated hour at 0.1 s. Each step it reads every vehicle's position, speed and lane with
libsumo's per-vehicle calls (`--read`), or only steps (`--no-read`). Prints the vehicle
updates (vehicles on the road summed over the steps) per wall-clock second.

Needs `pip install libsumo` (not a dependency of platoonsim).

    python examples/python/libsumo_loop.py [--no-read] [--duration S]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import libsumo

LENGTH_M = 6000.0
LANES = 3
SPEED_MPS = 110 / 3.6

NET = """<?xml version="1.0" encoding="UTF-8"?>
<net version="1.20" junctionCornerDetail="5" limitTurnSpeed="5.50">
    <location netOffset="0.00,0.00" convBoundary="0.00,0.00,{L:.2f},0.00" origBoundary="0.00,0.00,{L:.2f},0.00" projParameter="!"/>
    <edge id="road" from="A" to="B" priority="-1">
{lanes}
    </edge>
    <junction id="A" type="dead_end" x="0.00" y="0.00" incLanes="" intLanes="" shape="0.00,0.00 0.00,-{w:.2f}"/>
    <junction id="B" type="dead_end" x="{L:.2f}" y="0.00" incLanes="{inc}" intLanes="" shape="{L:.2f},-{w:.2f} {L:.2f},0.00"/>
</net>
"""

ROUTES = """<?xml version="1.0" encoding="UTF-8"?>
<routes>
    <vType id="human" carFollowModel="Krauss" length="4.5" maxSpeed="{v:.3f}" speedDev="0.1"/>
    <vType id="cav" carFollowModel="CACC" length="4.5" maxSpeed="{v:.3f}" speedDev="0.1"/>
    <vTypeDistribution id="mix">
        <vType id="h" carFollowModel="Krauss" length="4.5" maxSpeed="{v:.3f}" speedDev="0.1" probability="{ph}"/>
        <vType id="c" carFollowModel="CACC" length="4.5" maxSpeed="{v:.3f}" speedDev="0.1" probability="{pc}"/>
    </vTypeDistribution>
    <route id="r" edges="road"/>
{flows}
</routes>
"""


def write_scenario(d: Path, penetration: float, demand_vphpl: float, duration_s: float) -> tuple[Path, Path]:
    w = 3.2
    lanes = "\n".join(
        f'        <lane id="road_{i}" index="{i}" speed="{SPEED_MPS:.2f}" length="{LENGTH_M:.2f}" '
        f'shape="0.00,{-(LANES - i - 0.5) * w:.2f} {LENGTH_M:.2f},{-(LANES - i - 0.5) * w:.2f}"/>'
        for i in range(LANES)
    )
    inc = " ".join(f"road_{i}" for i in range(LANES))
    net = d / "road.net.xml"
    net.write_text(NET.format(L=LENGTH_M, lanes=lanes, inc=inc, w=LANES * w))
    # Poisson arrivals: a vehicle each second with this probability, per lane.
    p = demand_vphpl / 3600.0
    flows = "\n".join(
        f'    <flow id="f{i}" type="mix" route="r" begin="0" end="{duration_s:g}" probability="{p:.6f}" '
        f'departLane="{i}" departSpeed="avg" departPos="base"/>'
        for i in range(LANES)
    )
    rou = d / "road.rou.xml"
    rou.write_text(ROUTES.format(v=SPEED_MPS, ph=1 - penetration, pc=penetration, flows=flows))
    return net, rou


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--no-read", action="store_true", help="only step (SUMO's own speed)")
    ap.add_argument("--duration", type=float, default=3600.0)
    ap.add_argument("--pen", type=float, default=0.5)
    ap.add_argument("--demand", type=float, default=2500.0)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        net, rou = write_scenario(Path(tmp), args.pen, args.demand, args.duration)
        libsumo.start(
            ["sumo", "-n", str(net), "-r", str(rou), "--step-length", "0.1", "--begin", "0",
             "--end", f"{args.duration:g}", "--no-step-log", "true", "--no-warnings", "true",
             "--seed", "1"]
        )
        steps = round(args.duration / 0.1)
        updates = 0
        checksum = 0.0
        start = time.perf_counter()
        vehicle = libsumo.vehicle
        for _ in range(steps):
            libsumo.simulationStep()
            ids = vehicle.getIDList()
            updates += len(ids)
            if not args.no_read:
                for vid in ids:
                    x = vehicle.getLanePosition(vid)
                    v = vehicle.getSpeed(vid)
                    lane = vehicle.getLaneIndex(vid)
                    checksum += x + v + lane
        wall = time.perf_counter() - start
        libsumo.close()
    mode = "step only" if args.no_read else "step + read x, v, lane of every vehicle"
    print(
        f"libsumo {libsumo.__version__ if hasattr(libsumo, '__version__') else ''} ({mode}): "
        f"{updates:,} vehicle updates in {wall:.2f} s = {updates / wall / 1e6:.3f} M/s "
        f"(mean {updates / steps:.0f} vehicles on the road; checksum {checksum:.6g})"
    )


if __name__ == "__main__":
    main()
