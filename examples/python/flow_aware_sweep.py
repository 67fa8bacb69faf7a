"""Flow-Aware threshold sweep: discharge flow and platoon length against the flow threshold.

Runs the homogeneous road at 50 % CAV and 2,500 veh/h/lane with the Flow-Aware strategy for a
range of flow thresholds (rho_q, `strategy.flow_threshold_vphpl`) at one speed threshold, plus
the baseline (`none`) and PD, for a few seeds, and draws the mean of each against rho_q
(`flow_aware_sweep.png` and `.svg` in the output directory, default the current one).

    python examples/python/flow_aware_sweep.py [out_dir] [--quick]

--quick runs 20 minutes (10 of warm-up) instead of the scenario's hour, with two seeds.
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import platoonsim  # noqa: E402

THRESHOLDS_VPHPL = [2000, 2200, 2300, 2400, 2500, 2600, 2800]
SPEED_THRESHOLD_KMH = 80.0


def run(strategy: str, seed: int, base: dict, flow: float | None = None) -> dict:
    overrides = dict(base)
    if flow is not None:
        overrides["strategy.flow_threshold_vphpl"] = flow
        overrides["strategy.speed_threshold_kmh"] = SPEED_THRESHOLD_KMH
    sim = platoonsim.Simulation("homogeneous", seed=seed, overrides=overrides, organizer=strategy, events=False)
    s = sim.run()
    if s["collisions"]:
        raise RuntimeError(f"{strategy} seed {seed}: {s['collisions']} collisions (a failed run)")
    return s


def main() -> None:
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    quick = "--quick" in sys.argv
    out = Path(args[0]) if args else Path(".")
    out.mkdir(parents=True, exist_ok=True)
    base = {"run.penetration": 0.5, "demand.vph_per_lane": 2500}
    if quick:
        base |= {"run.duration_s": 1200, "run.warmup_s": 600}
    seeds = [1, 2] if quick else [1, 2, 3]

    def mean(strategy, flow=None):
        runs = [run(strategy, s, base, flow) for s in seeds]
        return (
            np.mean([r["discharge_flow_vphpl"] for r in runs]),
            np.mean([r["avg_platoon_length"] for r in runs]),
        )

    none_q, none_l = mean("none")
    pd_q, pd_l = mean("pd")
    fa = [mean("flow-aware", f) for f in THRESHOLDS_VPHPL]
    for f, (q, l) in zip(THRESHOLDS_VPHPL, fa):
        print(f"rho_q = {f:5d} veh/h/lane: discharge {q:7.1f} veh/h/lane, L = {l:.3f}")
    print(f"none: discharge {none_q:7.1f}, L = {none_l:.3f}; pd: discharge {pd_q:7.1f}, L = {pd_l:.3f}")

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    x = np.array(THRESHOLDS_VPHPL)
    for ax, k, ylabel, ref_none, ref_pd in [
        (ax1, 0, "discharge flow (veh/h/lane)", none_q, pd_q),
        (ax2, 1, "mean platoon length L̄ (vehicles)", none_l, pd_l),
    ]:
        ax.plot(x, [m[k] for m in fa], "o-", color="tab:blue", label=f"flow-aware (ρ_v = {SPEED_THRESHOLD_KMH:g} km/h)")
        ax.axhline(ref_none, color="gray", ls="--", label="none")
        ax.axhline(ref_pd, color="tab:red", ls=":", label="pd")
        ax.set_xlabel("flow threshold ρ_q (veh/h/lane)")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
    ax1.legend(loc="best", fontsize=8)
    minutes = base.get("run.duration_s", 3600) / 60
    fig.suptitle(
        f"homogeneous road, 50 % CAV, 2,500 veh/h/lane, {minutes:.0f} min, mean of {len(seeds)} seeds"
    )
    for ext in ("png", "svg"):
        fig.savefig(out / f"flow_aware_sweep.{ext}", dpi=120)
    print(f"figure: {out / 'flow_aware_sweep.png'} and .svg")


if __name__ == "__main__":
    main()
