#!/usr/bin/env python3
"""Write the example's field data: the S1-S5 cross-section rows of a run's detectors.csv as
tidy CSV (docs/field-data.md). The example's `field.csv` is a twin experiment: the corridor
run with known values (buffer factor 3.0 on the stretch, mean desired speed 105 km/h) and a
seed the calibration does not use, so the fit can be checked against the truth:

    platoonsim run examples/calibrate/corridor.toml --seed 101 \\
        --set network.behaviour[0].buffer_factor=3.0 --set human.desired_speed_kmh.mean=105 \\
        --out out/truth
    python3 examples/calibrate/make_field.py out/truth/detectors.csv examples/calibrate/field.csv
"""
import csv
import sys

src, dst = sys.argv[1], sys.argv[2]
with open(src, newline="") as f, open(dst, "w", newline="") as g:
    w = csv.writer(g)
    w.writerow(["station", "time", "flow_vph", "speed_kmh", "occupancy", "interval_s"])
    for r in csv.DictReader(f):
        if r["lane"] == "all" and r["kind"] == "mainline" and r["detector"].startswith("S"):
            speed = f"{float(r['speed_kmh']):.1f}" if r["speed_kmh"] else ""
            w.writerow([r["detector"], r["clock"], f"{float(r['flow_vph']):.0f}", speed,
                        f"{float(r['occupancy']):.4f}", r["interval_s"]])
