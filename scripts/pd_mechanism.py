#!/usr/bin/env python3
"""Where PD's discharge change comes from on the homogeneous road (issue 43, item 4).

Usage: scripts/pd_mechanism.py BASELINE_RUN PD_RUN [BASELINE_RUN PD_RUN ...]

Each run directory is a `platoonsim run homogeneous` output written with `--trajectories P`
(P = 1 s is enough) covering the control section (`--trajectory-x 4900,6100`, say) over
(part of) the measurement window. Pairs are (baseline, PD) of the same seed. Prints, per
pair and as the mean over the pairs:

- the discharge change by lane at the measurement detector (`detectors.csv`, the intervals
  after the warm-up): the lane contributions add up to the cross-section's change, so the PD
  lane's own share is read off directly;
- CAVs waiting for a gap toward the PD lane in the control section (samples in `blc` modes of
  CAVs under PD, converted to vehicle-seconds per hour of the sampled window), by lane, and
  as a share of the vehicle-seconds spent in that lane of the control section;
- lane-change disturbances: for every lane change in the control section, the new
  follower's hardest braking in the next 5 s; the count of followers braking harder than
  2 m/s² (b_c of spec 4.3) per hour;
- lane changes per CAV in the control section beside the geometric need (the lanes between a
  CAV's lane where it enters the control section and the PD lane, the leftmost).

Plain Python (csv module): no third-party package needed.
"""

import csv
import json
import sys
from collections import defaultdict

FOLLOWER_WINDOW_S = 5.0
FOLLOWER_BRAKE_MPS2 = -2.0


def scenario(run):
    with open(f"{run}/scenario.json") as f:
        return json.load(f)


def lane_discharge(run, detector, warmup):
    """Mean flow (veh/h) per lane ('1', '2', ... and 'all') after the warm-up."""
    sums, counts = defaultdict(float), defaultdict(int)
    with open(f"{run}/detectors.csv") as f:
        for r in csv.DictReader(f):
            if r["detector"] == detector and float(r["interval_start_s"]) >= warmup:
                sums[r["lane"]] += float(r["flow_vph"])
                counts[r["lane"]] += 1
    return {lane: sums[lane] / counts[lane] for lane in sums}


def trajectories(run):
    """Samples by vehicle: id -> [(t, kind, lane, x, v, a, mode)] in time order (lane 0 =
    the rightmost)."""
    by_id = defaultdict(list)
    with open(f"{run}/trajectories.csv") as f:
        for r in csv.DictReader(f):
            by_id[r["id"]].append(
                (
                    float(r["t_s"]),
                    r["kind"],
                    int(r["lane"]) - 1,  # 1 = the rightmost lane in the file
                    float(r["x_m"]),
                    float(r["v_mps"]),
                    float(r["a_mps2"]),
                    r["mode"],
                )
            )
    return by_id


def mechanism(run, cfg):
    road = cfg["road"]
    x0, x1 = road["control_start_m"], road["control_end_m"]
    lanes = road["lanes"]
    pd_lane = lanes - 1
    warmup = cfg["warmup_s"]
    by_id = trajectories(run)
    times = sorted({s[0] for samples in by_id.values() for s in samples if s[0] >= warmup})
    if len(times) < 2:
        raise SystemExit(f"{run}: no trajectory samples after the warm-up")
    period = times[1] - times[0]
    hours = (times[-1] - times[0] + period) / 3600.0
    wait = defaultdict(float)  # lane -> veh-s of CAVs in blc
    occupied = defaultdict(float)  # lane -> veh-s of all vehicles
    changes = []  # (t, new lane, x) of each lane change in the control section
    cav_changes, cav_need, cavs = 0, 0, 0
    # Position samples per (t, lane) for finding new followers.
    at = defaultdict(list)
    for vid, samples in by_id.items():
        for t, kind, lane, x, v, a, mode in samples:
            at[(t, lane)].append((x, vid))
    for vid, samples in by_id.items():
        entered = None
        for i, (t, kind, lane, x, v, a, mode) in enumerate(samples):
            inside = x0 <= x <= x1 and t >= warmup
            if inside:
                occupied[lane] += period
                if kind == "cav" and mode.startswith("blc"):
                    wait[lane] += period
                if entered is None:
                    entered = lane
            if i > 0 and inside and lane != samples[i - 1][2]:
                changes.append((t, lane, x))
                if kind == "cav":
                    cav_changes += 1
        if entered is not None and samples[0][1] == "cav":
            cavs += 1
            cav_need += pd_lane - entered
    accel = {}  # (id, t) -> a
    for vid, samples in by_id.items():
        for t, kind, lane, x, v, a, mode in samples:
            accel[(vid, t)] = a
    braked = 0
    for t, lane, x in changes:
        behind = [p for p in at[(t, lane)] if p[0] < x - 0.1]
        if not behind:
            continue
        follower = max(behind)[1]
        hardest = min(
            (accel.get((follower, t + k * period), 0.0) for k in range(int(FOLLOWER_WINDOW_S / period) + 1)),
            default=0.0,
        )
        if hardest < FOLLOWER_BRAKE_MPS2:
            braked += 1
    return {
        "wait_veh_s_per_h": {l: wait[l] / hours for l in range(lanes)},
        "wait_share": {l: wait[l] / occupied[l] if occupied[l] else 0.0 for l in range(lanes)},
        "changes_per_h": len(changes) / hours,
        "followers_braking_per_h": braked / hours,
        "lc_per_cav": cav_changes / cavs if cavs else float("nan"),
        "need_per_cav": cav_need / cavs if cavs else float("nan"),
    }


def main(args):
    if len(args) < 2 or len(args) % 2:
        raise SystemExit(__doc__)
    rows = []
    for base, pd in zip(args[::2], args[1::2]):
        cfg = scenario(pd)
        det = cfg["detectors"][cfg["measurement_detector"]]["name"]
        qb = lane_discharge(base, det, cfg["warmup_s"])
        qp = lane_discharge(pd, det, cfg["warmup_s"])
        lanes = cfg["road"]["lanes"]
        total = qb["all"]
        dq = {l: (qp[str(l + 1)] - qb[str(l + 1)]) / total * 100.0 for l in range(lanes)}
        m = mechanism(pd, cfg)
        rows.append((dq, (qp["all"] - total) / total * 100.0, m))
        print(f"{pd}: dQ {rows[-1][1]:+.2f} % =", " + ".join(f"lane {l + 1} {dq[l]:+.2f}" for l in range(lanes)))
        print(
            "  CAVs waiting (veh-s per h, share of the lane's veh-s):",
            ", ".join(
                f"lane {l + 1} {m['wait_veh_s_per_h'][l]:.0f} ({100 * m['wait_share'][l]:.0f} %)"
                for l in range(lanes)
            ),
        )
        print(
            f"  lane changes in the control section {m['changes_per_h']:.0f}/h, new followers "
            f"braking beyond {-FOLLOWER_BRAKE_MPS2:g} m/s² within {FOLLOWER_WINDOW_S:g} s "
            f"{m['followers_braking_per_h']:.0f}/h; LC per CAV {m['lc_per_cav']:.2f} "
            f"beside a need of {m['need_per_cav']:.2f}"
        )
    n = len(rows)
    lanes = len(rows[0][0])
    mean = lambda f: sum(f(r) for r in rows) / n
    print(f"mean of {n} pair(s): dQ {mean(lambda r: r[1]):+.2f} % =", " + ".join(
        f"lane {l + 1} {mean(lambda r: r[0][l]):+.2f}" for l in range(lanes)))
    print("  CAVs waiting (veh-s per h):", ", ".join(
        f"lane {l + 1} {mean(lambda r: r[2]['wait_veh_s_per_h'][l]):.0f} "
        f"({100 * mean(lambda r: r[2]['wait_share'][l]):.0f} %)" for l in range(lanes)))
    print(
        f"  lane changes {mean(lambda r: r[2]['changes_per_h']):.0f}/h, followers braking "
        f"{mean(lambda r: r[2]['followers_braking_per_h']):.0f}/h, LC per CAV "
        f"{mean(lambda r: r[2]['lc_per_cav']):.2f} beside a need of "
        f"{mean(lambda r: r[2]['need_per_cav']):.2f}"
    )


if __name__ == "__main__":
    main(sys.argv[1:])
