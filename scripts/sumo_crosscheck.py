#!/usr/bin/env python3
"""Cross-check an imported corridor against SUMO (docs/import.md, "Cross-check with SUMO").

The same SUMO network and routes run in SUMO (the `sumo` binary of the `eclipse-sumo` Python
package, or $SUMO_HOME/bin, or the PATH) and, imported with `platoonsim import sumo
--edge-detectors`, in platoonsim at 0 % CAV, each over several seeds. Prints a Markdown report:

* hourly flow and time-mean speed at the downstream end of every mainline edge, in both, with
  the GEH of the two flows (SUMO: E1 loops on every lane 1 m before the edge's end, written as
  an additional file, 40 m before it on the last edge, where SUMO removes arriving vehicles;
  platoonsim: the edge detectors, 1 m before the end);
* mean travel time per origin-destination pair, over the corridor in both (from the mainline
  entrance or the on-ramp's merge to the off-ramp's diverge or the mainline end: SUMO's route
  exit times, platoonsim's trips.csv);
* where speeds drop: the mainline edges whose mean speed is below 80 % of the corridor's
  highest, and the bottleneck, the downstream end of the most downstream such stretch.

Means are over the seeds and over the window [--warmup-s, duration). A benchmark-style script,
not a CI test; it needs SUMO (python3 -m pip install eclipse-sumo) and a built platoonsim.

    scripts/sumo_crosscheck.py NET.net.xml ROUTES.rou.xml [--mainline E1,E2,...]
        [--seeds 1,2,3] [--duration-s S] [--warmup-s S] [--work DIR]
"""

import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from collections import defaultdict
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def fail(msg):
    print(f"error: {msg}", file=sys.stderr)
    sys.exit(1)


def sanitize(edge_id):
    """The importer's name of an edge: characters outside [A-Za-z0-9_.-] become `_`."""
    return "".join(c if c.isascii() and (c.isalnum() or c in "_.-") else "_" for c in edge_id)


def sumo_binary(name):
    """A SUMO binary: $SUMO_HOME/bin, the `sumo` Python package's, or the PATH."""
    homes = []
    if os.environ.get("SUMO_HOME"):
        homes.append(Path(os.environ["SUMO_HOME"]))
    try:
        import sumo  # the eclipse-sumo package

        homes.append(Path(sumo.SUMO_HOME))
    except ImportError:
        pass
    for home in homes:
        if (home / "bin" / name).exists():
            return str(home / "bin" / name)
    found = shutil.which(name)
    if found:
        return found
    fail(f"SUMO's {name} not found: python3 -m pip install eclipse-sumo, or set SUMO_HOME")


def platoonsim_binary(given):
    if given:
        return given
    if os.environ.get("PLATOONSIM"):
        return os.environ["PLATOONSIM"]
    if shutil.which("platoonsim"):
        return "platoonsim"
    built = REPO / "target" / "release" / "platoonsim"
    if built.exists():
        return str(built)
    fail("platoonsim not found: set PLATOONSIM, put it on the PATH, or cargo build --release")


def run(cmd, what):
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        fail(f"{what} failed ({' '.join(map(str, cmd))}):\n{proc.stdout}{proc.stderr}")
    return proc


def read_net(path):
    """Edge id -> list of (lane id, length) of the network's normal (not internal) edges, and
    (from edge, to edge) -> length of the internal lane of a connection between them."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as e:
        fail(f"{path}: {e}")
    edges, internal = {}, {}
    for edge in root.iter("edge"):
        lanes = [(lane.get("id"), float(lane.get("length"))) for lane in edge.iter("lane")]
        if edge.get("function") == "internal":
            internal.update(lanes)
        else:
            edges[edge.get("id")] = lanes
    via = {}
    for c in root.iter("connection"):
        if c.get("via") in internal:
            via.setdefault((c.get("from"), c.get("to")), internal[c.get("via")])
    return edges, via


def origin_destination(edges, mainline):
    """The corridor's names of a route's entrance and exit, as in platoonsim's trips.csv:
    `mainline` or the on-ramp edge that joins it; the off-ramp edge that leaves it or `end`.
    None for a route that does not use the mainline."""
    on = [i for i, e in enumerate(edges) if e in mainline]
    if not on:
        return None
    first, last = on[0], on[-1]
    origin = "mainline" if first == 0 else sanitize(edges[first - 1])
    if last == len(edges) - 1:
        dest = "end" if edges[last] == mainline[-1] else sanitize(edges[last])
    else:
        dest = sanitize(edges[last + 1])
    return origin, dest, first, last


# SUMO removes a vehicle in the step it reaches the end of its route, before a loop 1 m from
# the end counts it; on the last mainline edge, where most routes end, the loops sit this far
# upstream instead (more than a 1-s step at 120 km/h; the edge has no exit in between).
LAST_EDGE_LOOP_BEFORE_END_M = 40.0


def loop_offset(e, mainline):
    """How far before the edge's end SUMO's loops sit (m)."""
    return LAST_EDGE_LOOP_BEFORE_END_M if e == mainline[-1] else 1.0


def write_loops(path, edges, mainline, period, output):
    """E1 loops on every lane of every mainline edge, 1 m before its downstream end (the
    place of platoonsim's edge detectors), on the last edge see LAST_EDGE_LOOP_BEFORE_END_M."""
    lines = ["<additional>"]
    for e in mainline:
        for lane, length in edges[e]:
            pos = max(length - loop_offset(e, mainline), 0.0)
            lines.append(
                f'  <inductionLoop id="{lane}" lane="{lane}" pos="{pos:.2f}" '
                f'period="{period}" file="{output}" friendlyPos="true"/>'
            )
    lines.append("</additional>")
    Path(path).write_text("\n".join(lines) + "\n")


class Tally:
    """Counts and speed sums per mainline edge, travel times per O-D, over seeds."""

    def __init__(self):
        self.count = defaultdict(float)
        self.speed_sum = defaultdict(float)
        self.tt = defaultdict(list)
        self.notes = []


def sumo_seed(args, edges, mainline, work, seed, tally):
    out = work / f"sumo-{seed}"
    out.mkdir(parents=True, exist_ok=True)
    add = out / "loops.add.xml"
    e1 = out / "e1.xml"
    write_loops(add, edges, mainline, args.aggregation_s, e1.name)
    vehroutes = out / "vehroutes.xml"
    proc = run(
        [
            sumo_binary("sumo"),
            "-n", args.net, "-r", args.routes, "-a", str(add),
            "--begin", "0", "--end", str(args.duration_s), "--seed", str(seed),
            "--vehroute-output", str(vehroutes), "--vehroute-output.exit-times",
            "--tripinfo-output", str(out / "tripinfo.xml"),
            "--no-step-log", "--duration-log.statistics",
        ],
        "sumo",
    )
    # SUMO's end-of-run statistics: vehicles still waiting to be inserted, teleports (a
    # vehicle stuck for 300 s is moved on), collisions; the last two only when there are any.
    stats = {}
    for line in proc.stdout.splitlines():
        key, _, value = line.strip().partition(":")
        if key in ("Waiting", "Teleports", "Collisions") and value.strip():
            stats[key] = value.strip().split()[0]
    tally.notes.append(
        f"SUMO seed {seed}: teleports {stats.get('Teleports', '0')}, collisions "
        f"{stats.get('Collisions', '0')}, still waiting to be inserted {stats.get('Waiting', '?')}"
    )
    lane_edge = {lane: e for e in mainline for lane, _ in edges[e]}
    for iv in ET.parse(e1).getroot().iter("interval"):
        if float(iv.get("begin")) < args.warmup_s:
            continue
        n = float(iv.get("nVehContrib"))
        e = lane_edge[iv.get("id")]
        tally.count[e] += n
        if n > 0:
            tally.speed_sum[e] += n * float(iv.get("speed")) * 3.6
    for veh in ET.parse(vehroutes).getroot().iter("vehicle"):
        if veh.get("arrival") is None:
            continue
        route = veh.find("route")
        if route is None or route.get("exitTimes") is None:
            continue
        edges_of = route.get("edges").split()
        exits = [float(t) for t in route.get("exitTimes").split()]
        od = origin_destination(edges_of, mainline)
        if od is None:
            continue
        origin, dest, first, last = od
        t_in = float(veh.get("depart")) if first == 0 else exits[first - 1]
        t_out = exits[last]
        if args.warmup_s <= t_in < args.duration_s:
            tally.tt[(origin, dest)].append(t_out - t_in)


def platoonsim_seed(args, scenario, mainline, work, seed, tally, binary):
    out = work / f"platoonsim-{seed}"
    run(
        [binary, "-q", "run", str(scenario), "--penetration", "0", "--seed", str(seed),
         "--trips", "--out", str(out)],
        "platoonsim run",
    )
    by_name = {sanitize(e): e for e in mainline}
    with open(out / "detectors.csv", newline="") as f:
        for row in csv.DictReader(f):
            if row["lane"] != "all" or row["detector"] not in by_name:
                continue
            if float(row["interval_start_s"]) < args.warmup_s:
                continue
            e = by_name[row["detector"]]
            n = float(row["count"])
            tally.count[e] += n
            if n > 0 and row["speed_kmh"]:
                tally.speed_sum[e] += n * float(row["speed_kmh"])
    with open(out / "trips.csv", newline="") as f:
        for row in csv.DictReader(f):
            if row["status"] != "exited" or not row["travel_time_s"]:
                continue
            if args.warmup_s <= float(row["entered_s"]) < args.duration_s:
                tally.tt[(row["origin"], row["destination"])].append(float(row["travel_time_s"]))
    with open(out / "summary.json") as f:
        s = json.load(f)
    tally.notes.append(
        f"platoonsim seed {seed}: collisions {s['collisions']}, missed exits "
        f"{s.get('missed_exits', 0)}, still queued {s['vehicles_waiting']}"
    )


def bottleneck(speeds, mainline):
    """The congested edges (mean speed below 80 % of the highest) and the bottleneck: the
    downstream end of the most downstream congested stretch."""
    top = max(speeds.values()) if speeds else 0
    slow = [e for e in mainline if speeds.get(e, top) < 0.8 * top]
    if not slow:
        return "none (every edge within 80 % of the highest mean speed)"
    last = slow[-1]
    i = mainline.index(last)
    after = mainline[i + 1] if i + 1 < len(mainline) else None
    lowest = min(slow, key=lambda e: speeds[e])
    where = f"at the end of `{last}`" + (f" (speeds recover on `{after}`)" if after else "")
    return f"congested: {', '.join(f'`{e}`' for e in slow)}; lowest mean speed on `{lowest}` ({speeds[lowest]:.0f} km/h); bottleneck {where}"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("net", help="SUMO network (.net.xml)")
    p.add_argument("routes", help="SUMO routes (.rou.xml) of flows, vehicles, trips with routes")
    p.add_argument("--mainline", help="mainline edges, upstream first (as for import sumo)")
    p.add_argument("--seeds", default="1,2,3", help="seeds, comma-separated (default 1,2,3)")
    p.add_argument("--duration-s", type=int, default=3600, help="simulated time (s, default 3600)")
    p.add_argument("--warmup-s", type=int, default=600, help="start of the window (s, default 600)")
    p.add_argument("--interval-s", type=int, default=900, help="import's demand interval (s)")
    p.add_argument("--aggregation-s", type=int, default=300, help="SUMO loop period (s, default 300)")
    p.add_argument("--work", help="directory for the runs (default: a temporary one, removed)")
    p.add_argument("--platoonsim", help="platoonsim binary")
    args = p.parse_args()
    for f in (args.net, args.routes):
        if not Path(f).is_file():
            fail(f"{f}: no such file")
    try:
        seeds = [int(s) for s in args.seeds.split(",")]
    except ValueError:
        fail(f"--seeds {args.seeds!r}: must be whole numbers separated by commas")
    if not 0 <= args.warmup_s < args.duration_s or args.warmup_s % args.aggregation_s:
        fail(f"--warmup-s {args.warmup_s}: must be in [0, duration) and a multiple of {args.aggregation_s}")
    binary = platoonsim_binary(args.platoonsim)
    work = Path(args.work) if args.work else Path(tempfile.mkdtemp(prefix="crosscheck-"))
    work.mkdir(parents=True, exist_ok=True)

    scenario = work / "scenario.toml"
    cmd = [binary, "import", "sumo", args.net, "--routes", args.routes, "--edge-detectors",
           "--interval-s", str(args.interval_s), "--duration-s", str(args.duration_s),
           "--out", str(scenario)]
    if args.mainline:
        cmd[4:4] = ["--mainline", args.mainline]
    imported = run(cmd, "platoonsim import sumo")
    edges, via = read_net(args.net)
    # The mainline: as given, else the edges whose detectors the import made, in corridor order.
    if args.mainline:
        mainline = args.mainline.split(",")
    else:
        shown = run([binary, "show", str(scenario), "--format", "json"], "platoonsim show")
        dets = json.loads(shown.stdout)["detectors"]
        by_name = {sanitize(e): e for e in edges}
        mainline = [by_name[d["name"]] for d in sorted(dets, key=lambda d: d["position_m"])
                    if d["name"] in by_name]
    missing = [e for e in mainline if e not in edges]
    if missing:
        fail(f"--mainline: {', '.join(missing)} not in {args.net}")

    sumo_t, sim_t = Tally(), Tally()
    for seed in seeds:
        sumo_seed(args, edges, mainline, work, seed, sumo_t)
        platoonsim_seed(args, scenario, mainline, work, seed, sim_t, binary)

    hours = (args.duration_s - args.warmup_s) / 3600 * len(seeds)
    # Corridor coordinate of each edge's end, as the import counts it (internal lanes included).
    pos, x = {}, 0.0
    for i, e in enumerate(mainline):
        x += edges[e][0][1]
        pos[e] = x
        if i + 1 < len(mainline):
            x += via.get((e, mainline[i + 1]), 0.0)

    def speeds(t):
        return {e: t.speed_sum[e] / t.count[e] for e in mainline if t.count[e] > 0}

    su_v, pl_v = speeds(sumo_t), speeds(sim_t)
    print(f"Window {args.warmup_s}-{args.duration_s} s, seeds {args.seeds}, 0 % CAV.\n")
    print("| mainline edge | end (m) | SUMO veh/h | platoonsim veh/h | GEH | SUMO km/h | platoonsim km/h |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for e in mainline:
        a, b = sumo_t.count[e] / hours, sim_t.count[e] / hours
        geh = ((a - b) ** 2 / ((a + b) / 2)) ** 0.5 if a + b > 0 else 0.0
        print(f"| `{e}` | {pos[e]:.0f} | {a:.0f} | {b:.0f} | {geh:.2f} | "
              f"{su_v.get(e, float('nan')):.1f} | {pl_v.get(e, float('nan')):.1f} |")
    print()
    print("| origin → destination | SUMO trips | SUMO mean travel time (s) | platoonsim trips | platoonsim mean travel time (s) |")
    print("|---|---:|---:|---:|---:|")
    for od in sorted(set(sumo_t.tt) | set(sim_t.tt)):
        a, b = sumo_t.tt.get(od, []), sim_t.tt.get(od, [])
        ma = f"{sum(a) / len(a):.1f}" if a else "–"
        mb = f"{sum(b) / len(b):.1f}" if b else "–"
        print(f"| {od[0]} → {od[1]} | {len(a)} | {ma} | {len(b)} | {mb} |")
    print()
    print(f"* SUMO: {bottleneck(su_v, mainline)}")
    print(f"* platoonsim: {bottleneck(pl_v, mainline)}")
    print()
    for note in sumo_t.notes + sim_t.notes:
        print(f"* {note}")
    summary = [l for l in (imported.stdout + imported.stderr).splitlines() if l.strip()]
    print("\nImport summary:\n")
    for line in summary:
        print(f"    {line}")
    if not args.work:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
