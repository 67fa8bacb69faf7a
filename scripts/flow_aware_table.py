#!/usr/bin/env python3
"""Choose Flow-Aware thresholds per penetration from a sweep of (rho_q, rho_v) on a corridor.

Reads the `runs.csv` of `platoonsim sweep sweeps/flow-aware-sr99.toml` (columns penetration,
strategy.kind, strategy.flow_threshold_vphpl, strategy.speed_threshold_kmh, seed,
network_discharge_vph, avg_platoon_length; the short names also do), pairs every Flow-Aware run with the baseline run of the same penetration
and seed, and per penetration chooses, as `platoonsim experiment calibrate-flow-aware` does on
the homogeneous road (docs/experiments.md), the pair with the largest mean L gain whose mean
discharge change is at least -TOLERANCE %. Writes the thresholds table (the format of
crates/scenario/scenarios/flow_aware_thresholds.toml) to OUT and the whole trade-off to
OUT's directory as tradeoff.csv.

    python3 scripts/flow_aware_table.py out/sweeps/flow-aware-sr99/runs.csv OUT.toml [--tolerance 0.5]
"""
import argparse
import csv
import statistics
import sys
from collections import defaultdict
from pathlib import Path


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", type=Path, help="the sweep's runs.csv")
    ap.add_argument("out", type=Path, help="the thresholds table to write (.toml)")
    ap.add_argument("--tolerance", type=float, default=0.5,
                    help="largest mean discharge loss accepted, percent (default 0.5)")
    a = ap.parse_args()
    if not a.tolerance >= 0:
        sys.exit(f"error: --tolerance {a.tolerance}: must be a number >= 0 (percent)")
    with open(a.runs, newline="") as f:
        rows = list(csv.DictReader(f))
    # A sweep's runs.csv names its axes by their keys (`strategy.kind`, ...).
    for r in rows:
        for k in ("strategy.kind", "strategy.flow_threshold_vphpl", "strategy.speed_threshold_kmh"):
            if k in r:
                r["strategy" if k == "strategy.kind" else k.split(".", 1)[1]] = r[k]
        # A bundle's level is named by its values ("0.2, 1": penetration, demand scale).
        r["penetration"] = r["penetration"].split(",")[0].strip()
    need = {"penetration", "strategy", "flow_threshold_vphpl", "speed_threshold_kmh", "seed",
            "network_discharge_vph", "avg_platoon_length", "collisions"}
    missing = need - set(rows[0] if rows else [])
    if missing:
        sys.exit(f"error: {a.runs}: columns missing: {', '.join(sorted(missing))}")
    base = {}
    for r in rows:
        if r["strategy"] == "none":
            base[(r["penetration"], r["seed"])] = r
    cells = defaultdict(list)
    collided = 0
    for r in rows:
        collided += int(r["collisions"]) > 0
        if r["strategy"] == "none":
            continue
        b = base.get((r["penetration"], r["seed"]))
        if b is None:
            sys.exit(f"error: no baseline run for penetration {r['penetration']} seed {r['seed']}")
        q, q0 = float(r["network_discharge_vph"]), float(b["network_discharge_vph"])
        l, l0 = float(r["avg_platoon_length"]), float(b["avg_platoon_length"])
        key = (float(r["penetration"]), float(r["flow_threshold_vphpl"]),
               float(r["speed_threshold_kmh"]))
        cells[key].append((100.0 * (q - q0) / q0, l / l0 - 1.0))
    if collided:
        sys.exit(f"error: {collided} runs collided: their results are invalid")
    trade = []
    for (p, rq, rv), v in sorted(cells.items()):
        dq = statistics.mean(x for x, _ in v)
        dl = statistics.mean(y for _, y in v)
        trade.append({"penetration": p, "flow_threshold_vphpl": rq, "speed_threshold_kmh": rv,
                      "seeds": len(v), "discharge_change_pct": dq, "platoon_length_gain": dl,
                      "feasible": dq >= -a.tolerance})
    chosen = {}
    for t in trade:
        if t["feasible"]:
            c = chosen.get(t["penetration"])
            if c is None or t["platoon_length_gain"] > c["platoon_length_gain"]:
                chosen[t["penetration"]] = t
    for t in trade:
        t["chosen"] = chosen.get(t["penetration"]) is t
    out_csv = a.out.with_name("tradeoff.csv")
    with open(out_csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(trade[0]))
        w.writeheader()
        w.writerows(trade)
    lines = [f"# Flow-Aware thresholds chosen by scripts/flow_aware_table.py from {a.runs}:",
             f"# per penetration the largest mean L gain whose mean discharge change is at least",
             f"# -{a.tolerance} % ({len(rows)} runs).", ""]
    for p in sorted({t["penetration"] for t in trade}):
        c = chosen.get(p)
        lines.append("[[penetration]]")
        lines.append(f"penetration = {p}")
        if c is None:
            best = max((t for t in trade if t["penetration"] == p),
                       key=lambda t: t["discharge_change_pct"])
            lines += ["feasible = false",
                      f"flow_threshold_vphpl = {best['flow_threshold_vphpl']:g}",
                      f"speed_threshold_kmh = {best['speed_threshold_kmh']:g}",
                      f"mean_platoon_length_gain = {best['platoon_length_gain']:.4f}",
                      f"worst_discharge_change_pct = {best['discharge_change_pct']:.4f}", ""]
        else:
            lines += ["feasible = true",
                      f"flow_threshold_vphpl = {c['flow_threshold_vphpl']:g}",
                      f"speed_threshold_kmh = {c['speed_threshold_kmh']:g}",
                      f"mean_platoon_length_gain = {c['platoon_length_gain']:.4f}",
                      f"worst_discharge_change_pct = {c['discharge_change_pct']:.4f}", ""]
    a.out.write_text("\n".join(lines))
    for t in trade:
        if t["chosen"]:
            print(f"{t['penetration']:.1f}: rho_q {t['flow_threshold_vphpl']:g}, rho_v "
                  f"{t['speed_threshold_kmh']:g}: dQ {t['discharge_change_pct']:+.2f} %, "
                  f"L gain {100 * t['platoon_length_gain']:+.1f} %")
    print(f"wrote {a.out} and {out_csv}")


if __name__ == "__main__":
    main()
