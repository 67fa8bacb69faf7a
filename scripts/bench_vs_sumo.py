#!/usr/bin/env python3
"""platoonsim against Eclipse SUMO on the same road and demand, in one sitting (docs/performance.md).

For each scenario (default: the homogeneous road at 50 % CAV and 2,500 veh/h/lane, and SR-99 at
40 % CAV), the scenario is resolved by `platoonsim show NAME --format json` and built in SUMO:

* a plain road: one edge of the road's length and lanes, a Poisson flow per lane (a vehicle each
  second with probability q/3600), departing at the lane's average speed;
* a corridor (`[network]`): the mainline cut into edges at every lane start and end, merge and
  diverge; an acceleration lane beside the mainline from each merge point over its length; each
  on-ramp an edge of its ramp length into the merge node, each off-ramp an edge out of the
  diverge node; netconvert guesses the lane connections. Demand per interval from the entrance
  and every on-ramp, split by destination with the exit fractions (a vehicle passing a diverge
  leaves there with its fraction), as one flow per origin, destination and interval.

Human drivers drive SUMO's Krauss model and CAVs its CACC model, both with the scenario's speed
limit; both simulators step 0.1 s. platoonsim runs its release binary (`platoonsim run`); SUMO
runs its `sumo` binary with `--duration-log.statistics`. The script prints each simulator's
vehicle updates per wall-clock second (UPS: vehicles on the road summed over the steps, per
second) and the ratio. A benchmark, not a test: run it on a quiet machine.

    scripts/bench_vs_sumo.py [--duration S] [--scenario NAME:PENETRATION ...] [--runs N]

Needs `sumo` and `netconvert` on the PATH (`pip install eclipse-sumo`) and a release build
(`cargo build --release -p platoonsim`).
"""

from __future__ import annotations

import argparse
import json
import re
import statistics
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BIN = ROOT / "target" / "release" / "platoonsim"
LANE_W = 3.2


def resolved(name: str, penetration: float, duration: float) -> dict:
    out = subprocess.run(
        [str(BIN), "show", name, "--penetration", str(penetration), "--duration", str(duration),
         "--warmup", "0", "--format", "json"],
        check=True, capture_output=True, text=True,
    )
    return json.loads(out.stdout)


def vtypes(cfg: dict, vmax: float) -> str:
    p = cfg["penetration"]
    length = cfg["human"]["length_m"]["mean"]
    return (
        f'<vTypeDistribution id="mix">'
        f'<vType id="h" carFollowModel="Krauss" length="{length}" maxSpeed="{vmax:.3f}" probability="{1 - p}"/>'
        f'<vType id="c" carFollowModel="CACC" length="{length}" maxSpeed="{vmax:.3f}" probability="{p}"/>'
        f"</vTypeDistribution>"
    )


def plain(cfg: dict, d: Path) -> tuple[Path, Path]:
    road = cfg["road"]
    L, n = road["length_m"], road["lanes"]
    vmax = cfg["human"]["desired_speed_kmh"]["mean"] / 3.6
    (d / "r.nod.xml").write_text(f'<nodes><node id="A" x="0" y="0"/><node id="B" x="{L}" y="0"/></nodes>')
    (d / "r.edg.xml").write_text(f'<edges><edge id="road" from="A" to="B" numLanes="{n}" speed="{vmax:.3f}"/></edges>')
    p = cfg["demand"]["vph_per_lane"] / 3600.0
    flows = "".join(
        f'<flow id="f{i}" type="mix" route="r" begin="0" end="{cfg["duration_s"]}" probability="{p:.6f}" '
        f'departLane="{i}" departSpeed="avg" departPos="base"/>'
        for i in range(n)
    )
    (d / "r.rou.xml").write_text(f'<routes>{vtypes(cfg, vmax)}<route id="r" edges="road"/>{flows}</routes>')
    return build(d)


def corridor(cfg: dict, d: Path) -> tuple[Path, Path]:
    net = cfg["road"]["network"]
    L = cfg["road"]["length_m"]
    vmax = cfg["human"]["desired_speed_kmh"]["mean"] / 3.6
    ramp_v = net["ramp_speed_kmh"] / 3.6
    on, off = net["on_ramps"], net["off_ramps"]
    # Break points of the mainline: lane extents, merges, acceleration-lane ends, diverges.
    cuts = {0.0, L}
    for e in net["through_lanes"]:
        cuts |= {e["from_m"], e["to_m"]}
    for r in on:
        cuts |= {r["x_m"], min(L, r["x_m"] + r["accel_lane_m"])}
    for r in off:
        cuts.add(r["x_m"])
    xs = sorted(c for c in cuts if 0.0 <= c <= L)

    def lanes_at(x: float) -> int:
        through = sum(1 for e in net["through_lanes"] if e["from_m"] <= x < e["to_m"])
        accel = sum(1 for r in on if r["x_m"] <= x < r["x_m"] + r["accel_lane_m"])
        return max(1, through + accel)

    nodes = [f'<node id="n{i}" x="{x:.2f}" y="0"/>' for i, x in enumerate(xs)]
    edges, main = [], []
    for i in range(len(xs) - 1):
        eid = f"m{i}"
        main.append((xs[i], xs[i + 1], eid))
        edges.append(f'<edge id="{eid}" from="n{i}" to="n{i + 1}" numLanes="{lanes_at(xs[i])}" speed="{vmax:.3f}"/>')
    node_at = {x: f"n{i}" for i, x in enumerate(xs)}
    for k, r in enumerate(on):
        nodes.append(f'<node id="on{k}" x="{r["x_m"] - r["ramp_length_m"]:.2f}" y="-60"/>')
        edges.append(f'<edge id="on{k}" from="on{k}" to="{node_at[r["x_m"]]}" numLanes="1" speed="{ramp_v:.3f}"/>')
    for k, r in enumerate(off):
        nodes.append(f'<node id="off{k}" x="{r["x_m"] + 150:.2f}" y="-60"/>')
        edges.append(f'<edge id="off{k}" from="{node_at[r["x_m"]]}" to="off{k}" numLanes="1" speed="{ramp_v:.3f}"/>')
    (d / "r.nod.xml").write_text("<nodes>" + "".join(nodes) + "</nodes>")
    (d / "r.edg.xml").write_text("<edges>" + "".join(edges) + "</edges>")

    def path(x_from: float, x_to: float) -> list[str]:
        return [e for a, b, e in main if a >= x_from and b <= x_to]

    scale = net.get("demand_scale", 1.0)
    interval = net["interval_s"]
    dur = cfg["duration_s"]
    flows, routes = [], []
    origins = [("main", 0.0, net["mainline_vph"], [])] + [
        (f"on{k}", r["x_m"], r["demand_vph"], [f"on{k}"]) for k, r in enumerate(on)
    ]
    for oid, x0, series, head in origins:
        downstream = [(k, r) for k, r in enumerate(off) if r["x_m"] > x0]
        for t, q in enumerate(series):
            begin = t * interval
            if begin >= dur or q <= 0:
                continue
            end = min(dur, (t + 1) * interval)
            stay = 1.0
            shares = []
            for k, r in downstream:
                f = r["exit_fraction"][min(t, len(r["exit_fraction"]) - 1)]
                shares.append((f"off{k}", r["x_m"], stay * f))
                stay *= 1 - f
            shares.append(("end", L, stay))
            for dest, x1, share in shares:
                vph = q * scale * share
                if vph <= 0:
                    continue
                rid = f"{oid}_{dest}"
                if rid not in {r[0] for r in routes}:
                    tail = [] if dest == "end" else [dest]
                    routes.append((rid, " ".join(head + path(x0, x1) + tail)))
                flows.append(
                    f'<flow id="{rid}_{t}" type="mix" route="{rid}" begin="{begin}" end="{end}" '
                    f'vehsPerHour="{vph:.3f}" departLane="best" departSpeed="avg"/>'
                )
    route_xml = "".join(f'<route id="{r}" edges="{e}"/>' for r, e in routes)
    (d / "r.rou.xml").write_text(f"<routes>{vtypes(cfg, vmax)}{route_xml}{''.join(flows)}</routes>")
    return build(d)


def build(d: Path) -> tuple[Path, Path]:
    subprocess.run(
        ["netconvert", "-n", "r.nod.xml", "-e", "r.edg.xml", "-o", "r.net.xml", "--no-turnarounds"],
        cwd=d, check=True, capture_output=True,
    )
    return d / "r.net.xml", d / "r.rou.xml"


def sumo_ups(net: Path, rou: Path, duration: float) -> tuple[float, str]:
    """SUMO's UPS and its vehicle statistics line (inserted, running, teleports)."""
    out = subprocess.run(
        ["sumo", "-n", str(net), "-r", str(rou), "--step-length", "0.1", "--end", str(duration),
         "--no-step-log", "--no-warnings", "--duration-log.statistics"],
        check=True, capture_output=True, text=True,
    ).stdout
    m = re.search(r"UPS: ([0-9.]+)", out)
    if not m:
        raise SystemExit(f"sumo printed no UPS:\n{out}")
    ins = re.search(r"Inserted: (\d+)", out)
    tel = re.search(r"Teleports: (\d+)", out)
    stats = f"SUMO inserted {ins.group(1) if ins else '?'}, teleports {tel.group(1) if tel else 0}"
    return float(m.group(1)), stats


def platoonsim_ups(name: str, penetration: float, duration: float, d: Path) -> tuple[float, str]:
    subprocess.run(
        [str(BIN), "run", name, "--penetration", str(penetration), "--duration", str(duration),
         "--warmup", "0", "--out", str(d / "run"), "-q"],
        check=True, capture_output=True,
    )
    s = json.loads((d / "run" / "summary.json").read_text())
    return s["vehicle_updates"] / s["wall_seconds"], f"platoonsim entered {s['vehicles_entered']}"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--duration", type=float, default=3600.0)
    ap.add_argument("--scenario", action="append", help="NAME:PENETRATION (repeatable)")
    ap.add_argument("--runs", type=int, default=3, help="runs of each simulator (median)")
    args = ap.parse_args()
    if not BIN.exists():
        raise SystemExit(f"{BIN} is missing: cargo build --release -p platoonsim")
    for spec in args.scenario or ["homogeneous:0.5", "sr99:0.4"]:
        name, pen = spec.split(":")
        cfg = resolved(name, float(pen), args.duration)
        with tempfile.TemporaryDirectory() as tmp:
            d = Path(tmp)
            net, rou = corridor(cfg, d) if cfg["road"].get("network") else plain(cfg, d)
            ours, theirs = [], []
            for _ in range(args.runs):
                ups, ours_stats = platoonsim_ups(name, float(pen), args.duration, d)
                ours.append(ups)
                ups, their_stats = sumo_ups(net, rou, args.duration)
                theirs.append(ups)
            o, s = statistics.median(ours), statistics.median(theirs)
            print(
                f"{name} at {100 * float(pen):.0f} % CAV, {args.duration:g} s: platoonsim {o / 1e6:.2f} M "
                f"updates/s, SUMO {s / 1e6:.3f} M updates/s, ratio {o / s:.0f}x (medians of {args.runs}; "
                f"{ours_stats}, {their_stats})",
                flush=True,
            )


if __name__ == "__main__":
    main()
