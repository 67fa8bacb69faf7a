"""platoonsim: a microscopic freeway simulator for CACC platoons in mixed traffic.

``Simulation`` runs one scenario (a built-in name, a file path or TOML text) step by step.
Stepping happens in Rust with the GIL released; the state comes back as whole numpy arrays
(``vehicles()``), so a step read from Python costs a few array copies, not a call per vehicle.
The reference is docs/python.md in the repository.

    >>> import platoonsim
    >>> sim = platoonsim.Simulation("homogeneous", seed=1, overrides={"run.duration_s": 600})
    >>> _ = sim.run_until(300.0)
    >>> v = sim.vehicles()
    >>> float(v["v_mps"].mean()) > 0
    True
"""

from __future__ import annotations

import json
import os
from typing import Any, Mapping, Protocol, Sequence, runtime_checkable

import numpy as np

from ._platoonsim import (
    BUILTIN_SCENARIOS,
    MAX_WORLDS,
    MODE_LABELS,
    REGIME_LABELS,
    STRATEGIES,
    BatchCore as _BatchCore,
    CommandError,
    Core as _Core,
    ScenarioError,
    SimulationError,
    __version__,
)

__all__ = [
    "Simulation",
    "BatchSimulation",
    "Organizer",
    "ScenarioError",
    "CommandError",
    "SimulationError",
    "MODE_LABELS",
    "REGIME_LABELS",
    "KINDS",
    "STRATEGIES",
    "BUILTIN_SCENARIOS",
    "MAX_WORLDS",
    "__version__",
]

#: Vehicle kinds by the codes of ``vehicles()["kind"]``.
KINDS = ("human", "cav")


@runtime_checkable
class Organizer(Protocol):
    """A platoon-organization strategy written in Python.

    The engine asks it every ``every_steps`` steps (before the step, from the state at the
    step start) for lane advice per vehicle; the advice holds until the next call. Attributes
    read once, when the organizer is installed:

    * ``name``: the summary's ``strategy`` (default ``"python"``),
    * ``every_steps``: steps between two calls (default 1),
    * ``advises_cavs`` (default True) and ``advises_humans`` (default False): which vehicles
      the engine consults the advice for.
    """

    def advise(
        self, sim: "Simulation", t_s: float, vehicles: dict[str, np.ndarray]
    ) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
        """Lane advice for every vehicle of ``vehicles`` (the columns of ``sim.vehicles()``
        at time ``t_s``, the step start): an integer array of lanes to join (engine index,
        0 = rightmost), -1 for no advice; or a pair (lanes, strengths) with the desire in
        [0, 1] to use instead of 1."""
        ...


def _int_ids(ids: Any, what: str) -> np.ndarray:
    """Vehicle ids as a contiguous int64 array, or a CommandError naming what was wrong."""
    arr = np.atleast_1d(np.asarray(ids))
    if arr.ndim != 1:
        raise CommandError(f"{what}: ids must be one-dimensional, got shape {arr.shape}")
    if arr.size == 0:
        return np.zeros(0, dtype=np.int64)
    if arr.dtype.kind not in "iu":
        if arr.dtype.kind == "f" and np.all(np.isfinite(arr)) and np.all(arr == np.round(arr)):
            arr = arr.astype(np.int64)
        else:
            raise CommandError(
                f"{what}: ids must be integer vehicle ids, got {arr.dtype} values {arr[:5].tolist()!r}"
            )
    return np.ascontiguousarray(arr, dtype=np.int64)


def _command_args(ids: Any, kind: Any, value: Any, steps: Any) -> tuple[np.ndarray, np.ndarray | None, int]:
    """A command's ids, values (one per id) and steps, checked, or a CommandError."""
    arr = _int_ids(ids, kind if isinstance(kind, str) else "command")
    if not isinstance(kind, str):
        raise CommandError(f"command: kind must be a string, got {type(kind).__name__}")
    values = None
    if value is not None:
        try:
            v = np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise CommandError(f"{kind}: value {value!r} is not a number") from e
        try:
            values = np.ascontiguousarray(np.broadcast_to(v, arr.shape))
        except ValueError as e:
            raise CommandError(
                f"{kind}: {v.size} values for {arr.size} vehicle ids (one per id, or one for all)"
            ) from e
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 1:
        raise CommandError(f"{kind}: steps = {steps!r} must be an int of at least 1")
    return arr, values, int(steps)


class Simulation:
    """One run of a scenario, stepped from Python.

    Parameters
    ----------
    scenario:
        A built-in scenario name (``BUILTIN_SCENARIOS``), the path of a scenario file, or the
        text of one (TOML).
    seed:
        The run's seed (``run.seed``); the scenario's when None.
    overrides:
        Scenario keys to change, as ``platoonsim run --set KEY=VALUE`` does:
        ``{"run.penetration": 0.5, "demand.vph_per_lane": 2500}``. Checked exactly like the
        same value written in the file; a bad one raises ``ScenarioError`` (a ValueError) with
        the command line's message, naming the key.
    organizer:
        A built-in strategy name (``STRATEGIES``: sets ``strategy.kind``), or a Python
        organizer (see ``Organizer``), or None for the scenario's strategy.
    events:
        Buffer the engine's events for ``events()`` (an observer in Rust). False saves the
        per-step cost of looking for mode changes when no one reads them.
    """

    def __init__(
        self,
        scenario: str | os.PathLike[str],
        seed: int | None = None,
        overrides: Mapping[str, Any] | None = None,
        organizer: str | Organizer | None = None,
        events: bool = True,
    ) -> None:
        if not isinstance(scenario, (str, os.PathLike)):
            raise TypeError(
                f"scenario must be a built-in name, a path or TOML text, got {type(scenario).__name__}"
            )
        if seed is not None and (isinstance(seed, bool) or not isinstance(seed, (int, np.integer))):
            raise TypeError(f"seed must be an int, got {type(seed).__name__}")
        if seed is not None and not 0 <= int(seed) < 2**63:
            raise ScenarioError(f"seed = {seed}: must be in [0, 2^63)")
        if overrides is not None and not isinstance(overrides, Mapping):
            raise TypeError(f"overrides must be a dict of scenario keys, got {type(overrides).__name__}")
        strategy = organizer if isinstance(organizer, str) else None
        self._core = _Core(
            os.fspath(scenario),
            None if seed is None else int(seed),
            None if overrides is None else dict(overrides),
            strategy,
            bool(events),
        )
        self._organizer: Organizer | None = None
        self._every = 1
        self._summary: dict[str, Any] | None = None
        self._config: dict[str, Any] | None = None
        if organizer is not None and not isinstance(organizer, str):
            self._install(organizer)

    def _install(self, organizer: Any) -> None:
        if not callable(getattr(organizer, "advise", None)):
            raise TypeError(
                f"organizer must be a strategy name or an object with an advise(sim, t_s, vehicles) "
                f"method, got {type(organizer).__name__}"
            )
        every = getattr(organizer, "every_steps", 1)
        if isinstance(every, bool) or not isinstance(every, (int, np.integer)) or every < 1:
            raise ValueError(f"organizer.every_steps = {every!r}: must be an int of at least 1")
        name = str(getattr(organizer, "name", "python"))
        self._core.use_organizer(
            name,
            bool(getattr(organizer, "advises_humans", False)),
            bool(getattr(organizer, "advises_cavs", True)),
        )
        self._organizer = organizer
        self._every = int(every)

    # -- time ---------------------------------------------------------------------------

    @property
    def time_s(self) -> float:
        """Simulated time after the steps done (s)."""
        return self._core.time_s

    @property
    def steps(self) -> int:
        """Steps done."""
        return self._core.steps

    @property
    def dt_s(self) -> float:
        """Step length (s)."""
        return self._core.dt_s

    @property
    def done(self) -> bool:
        """True once the scenario's duration has been simulated (or after ``finish()``)."""
        return self._core.done

    def _advise(self) -> None:
        org = self._organizer
        assert org is not None
        vehicles = self._core.vehicles()
        # The time the engine passes to its own strategies: steps × dt at the step start.
        t_s = self._core.steps * self._core.dt_s
        result = org.advise(self, t_s, vehicles)
        ids = vehicles["id"]
        if isinstance(result, tuple):
            if len(result) != 2:
                raise CommandError("advise() must return lanes or a pair (lanes, strengths)")
            lanes, strengths = result
        else:
            lanes, strengths = result, None
        lanes = np.asarray(lanes)
        if lanes.shape != ids.shape:
            raise CommandError(
                f"advise() returned {lanes.shape} lanes for {ids.shape[0]} vehicles (one each, -1 for none)"
            )
        if lanes.dtype.kind not in "iu":
            raise CommandError(f"advise() must return integer lanes, got {lanes.dtype}")
        if lanes.size and lanes.min() < -1:
            raise CommandError(
                f"advise() returned lane {lanes.min()}: a lane is an engine index >= 0, or -1 for no advice"
            )
        if strengths is None:
            strengths = np.ones(ids.shape, dtype=np.float64)
        else:
            given = np.asarray(strengths, dtype=np.float64)
            try:
                strengths = np.ascontiguousarray(np.broadcast_to(given, ids.shape))
            except ValueError:
                raise CommandError(
                    f"advise() returned strengths of shape {given.shape} for {ids.shape[0]} vehicles "
                    "(one each, or one for all)"
                ) from None
        self._core.set_advice(ids, np.ascontiguousarray(lanes, dtype=np.int64), strengths)

    def step(self, n: int = 1) -> int:
        """Advance ``n`` steps (fewer if the run ends first); returns the steps done. With a
        Python organizer, it is called before every ``every_steps``-th step."""
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
            raise ValueError(f"step: n = {n!r} must be a non-negative int")
        n = int(n)
        if self._organizer is None:
            return self._core.step(n)
        done = 0
        while done < n and not self._core.done:
            steps = self._core.steps
            if steps % self._every == 0:
                self._advise()
            chunk = min(n - done, self._every - steps % self._every)
            k = self._core.step(chunk)
            if k == 0:
                break
            done += k
        return done

    def run_until(self, t_s: float) -> int:
        """Step until the simulated time is ``t_s`` (or the run ends); returns the steps done."""
        t_s = float(t_s)
        if self._organizer is None:
            return self._core.run_until(t_s)
        target = round(t_s / self.dt_s)
        return self.step(max(0, target - self.steps))

    def run(self) -> dict[str, Any]:
        """Step to the end of the run and return ``finish()``'s summary."""
        self.step(self._core.total_steps)
        return self.finish()

    # -- state --------------------------------------------------------------------------

    def vehicles(self) -> dict[str, np.ndarray]:
        """Every vehicle on the road now, as numpy columns (docs/python.md), lane by lane
        (0 = rightmost) and front first: ``id``, ``kind`` (0 human, 1 CAV), ``lane``,
        ``x_m``, ``v_mps``, ``a_mps2``, ``mode`` (index into MODE_LABELS), ``regime`` (index
        into REGIME_LABELS, -1 while not automated), ``platoon_id``, ``platoon_pos`` (1 =
        leads its string), ``leader_id`` (-1: first in its lane), ``length_m``."""
        return self._core.vehicles()

    def detectors(self) -> dict[str, np.ndarray]:
        """The latest closed aggregation interval of every detector, as the rows it has in
        detectors.csv (per lane, then ``"all"``); ``speed_kmh`` is NaN when no vehicle
        crossed. Empty before the first interval closes."""
        d = self._core.detectors()
        for k in ("detector", "kind", "lane"):
            d[k] = np.asarray(d[k], dtype=str)
        return d

    def events(self) -> list[dict[str, Any]]:
        """The events since the last call, oldest first (docs/python.md lists their fields)."""
        return self._core.events()

    @property
    def config(self) -> dict[str, Any]:
        """The validated scenario, as in scenario.json."""
        if self._config is None:
            self._config = json.loads(self._core.config_json())
        return self._config

    def leftmost_through(self, x_m: Any) -> np.ndarray:
        """The leftmost through lane (the PD lane) at each position ``x_m``; -1 where none."""
        x = np.ascontiguousarray(np.atleast_1d(np.asarray(x_m, dtype=np.float64)))
        return self._core.leftmost_through(x)

    # -- commands -----------------------------------------------------------------------

    def command(
        self,
        ids: Any,
        kind: str,
        value: Any = None,
        steps: int = 1,
        side: str | None = None,
    ) -> None:
        """Command the vehicles ``ids`` (one id or an array) from the next step on.

        ``kind``: ``"accelerate"`` (``value`` m/s² for ``steps`` steps, no lane change;
        ``"accelerate_capped"``: at most the model's own acceleration;
        ``"accelerate_safe"``: within the vehicle's limits and below its collision-free speed),
        ``"desired_speed"`` (``value`` m/s until released), ``"change_lane"`` (``side``
        ``"left"`` or ``"right"``, as soon as the gaps allow) or ``"release"``. ``value`` is
        one number or one per id. An unknown id or a value out of range raises CommandError
        and applies none of the batch."""
        arr, values, n = _command_args(ids, kind, value, steps)
        self._core.command(kind, arr, values, n, side)

    def accelerate(self, ids: Any, accel_mps2: Any, steps: int = 1) -> None:
        """``command(ids, "accelerate", accel_mps2, steps)``."""
        self.command(ids, "accelerate", accel_mps2, steps)

    def set_desired_speed(self, ids: Any, speed_mps: Any) -> None:
        """``command(ids, "desired_speed", speed_mps)``."""
        self.command(ids, "desired_speed", speed_mps)

    def change_lane(self, ids: Any, side: str) -> None:
        """``command(ids, "change_lane", side=side)``."""
        self.command(ids, "change_lane", side=side)

    def release(self, ids: Any) -> None:
        """``command(ids, "release")``."""
        self.command(ids, "release")

    def commanded(self) -> list[int]:
        """Ids of the vehicles under command, in the order the commands were given."""
        return self._core.commanded()

    def use_gate(self) -> None:
        """Organize with the scenario's PD rule (its zone and window) behind a switch that
        ``set_gate`` turns on and off, off at first: the engine's own organizer, so stepping
        stays in Rust. Before the first step; not with a Python organizer."""
        if self._organizer is not None:
            raise SimulationError("use_gate: this Simulation has a Python organizer")
        self._core.use_gate()

    def set_gate(self, on: bool) -> None:
        """Turn the gated PD organizer (``use_gate``) on or off for the next steps."""
        self._core.set_gate(bool(on))

    # -- results ------------------------------------------------------------------------

    def finish(self, out_dir: str | os.PathLike[str] | None = None) -> dict[str, Any]:
        """End the run now and return the summary (the fields of summary.json). Vehicles still
        on the road count with what they did so far, as at the end of a CLI run. With
        ``out_dir``, also write summary.json, detectors.csv, scenario.json, scenario.toml,
        road.json and (if vehicles collided) collisions.csv there, removing an earlier run's
        files, as ``platoonsim run --out`` does (the same writer). Later calls return the same
        summary (and may write it elsewhere)."""
        text = self._core.finish(None if out_dir is None else os.fspath(out_dir))
        self._summary = json.loads(text)
        return dict(self._summary)

    def summary(self) -> dict[str, Any]:
        """The summary of the run (``finish()`` first if it is still open)."""
        if self._summary is None:
            return self.finish()
        return dict(self._summary)

    def __repr__(self) -> str:
        return (
            f"<platoonsim.Simulation {self.config.get('name')!r} t={self.time_s:g} s"
            f"{' done' if self.done else ''}>"
        )


def _seed_list(seeds: Any) -> list[int]:
    if isinstance(seeds, (str, bytes)) or not isinstance(seeds, (Sequence, np.ndarray)):
        raise TypeError(f"seeds must be a sequence of ints (one per world), got {type(seeds).__name__}")
    out = []
    for i, s in enumerate(seeds):
        if isinstance(s, bool) or not isinstance(s, (int, np.integer)) or not 0 <= int(s) < 2**63:
            raise ScenarioError(f"seeds[{i}] = {s!r}: must be an int in [0, 2^63)")
        out.append(int(s))
    return out


class BatchSimulation:
    """N independent runs of one scenario stepped together in Rust across a thread pool, the
    GIL released (docs/python.md, "Batched worlds").

    World ``i`` is exactly ``Simulation(scenario, seed=seeds[i], overrides=...)``: same
    vehicles, same summary, bit for bit, whatever ``threads`` is. ``overrides`` is one dict
    for every world or a sequence of one dict per world; ``organizer`` a built-in strategy
    name. Python organizers are not offered (they would run under the GIL inside the parallel
    step): use the scenario's strategy, or ``use_gate`` for a PD rule switched per world.
    ``threads``: the pool's size (default: every core).
    """

    def __init__(
        self,
        scenario: str | os.PathLike[str],
        seeds: Sequence[int],
        overrides: Mapping[str, Any] | Sequence[Mapping[str, Any]] | None = None,
        organizer: str | None = None,
        threads: int | None = None,
    ) -> None:
        if not isinstance(scenario, (str, os.PathLike)):
            raise TypeError(
                f"scenario must be a built-in name, a path or TOML text, got {type(scenario).__name__}"
            )
        seed_list = _seed_list(seeds)
        if overrides is None:
            ov = None
        elif isinstance(overrides, Mapping):
            ov = [dict(overrides)]
        elif isinstance(overrides, Sequence) and all(isinstance(o, Mapping) for o in overrides):
            ov = [dict(o) for o in overrides]
        else:
            raise TypeError("overrides must be a dict of scenario keys, or a sequence of one dict per world")
        if organizer is not None and not isinstance(organizer, str):
            raise TypeError(
                "organizer must be a built-in strategy name (STRATEGIES); Python organizers "
                "need a Simulation each"
            )
        if threads is not None and (isinstance(threads, bool) or not isinstance(threads, (int, np.integer))):
            raise TypeError(f"threads must be an int, got {type(threads).__name__}")
        self._core = _BatchCore(os.fspath(scenario), seed_list, ov, organizer, None if threads is None else int(threads))
        self.seeds = seed_list
        self._summaries: dict[int, dict[str, Any]] = {}

    @property
    def num_worlds(self) -> int:
        return self._core.num_worlds

    @property
    def threads(self) -> int:
        return self._core.threads

    @property
    def dt_s(self) -> float:
        return self._core.dt_s

    def time_s(self) -> np.ndarray:
        """Simulated time of each world (s)."""
        return np.asarray(self._core.time_s())

    def done(self) -> np.ndarray:
        """Whether each world has simulated its whole duration."""
        return np.asarray(self._core.done(), dtype=bool)

    def step(self, n: int = 1) -> np.ndarray:
        """Advance every world ``n`` steps (fewer where a run ends); the steps each did."""
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
            raise ValueError(f"step: n = {n!r} must be a non-negative int")
        return np.asarray(self._core.step(int(n)), dtype=np.int64)

    def run_until(self, t_s: float) -> np.ndarray:
        """Step every world to simulated time ``t_s``; the steps each did."""
        return np.asarray(self._core.run_until(float(t_s)), dtype=np.int64)

    def _check(self, i: Any) -> int:
        if isinstance(i, bool) or not isinstance(i, (int, np.integer)) or not 0 <= int(i) < self.num_worlds:
            raise IndexError(f"world {i!r}: the batch has worlds 0 to {self.num_worlds - 1}")
        return int(i)

    def vehicles(self, world: int | None = None) -> dict[str, np.ndarray]:
        """The vehicles of one world (as ``Simulation.vehicles()``), or of every world
        concatenated in world order with a ``world`` column."""
        if world is not None:
            return self._core.vehicles(self._check(world))
        parts = [self._core.vehicles(i) for i in range(self.num_worlds)]
        out = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
        out["world"] = np.concatenate(
            [np.full(len(p["id"]), i, dtype=np.int64) for i, p in enumerate(parts)]
        )
        return out

    def detectors(self, world: int) -> dict[str, np.ndarray]:
        """World ``world``'s latest closed detector interval (as ``Simulation.detectors()``)."""
        d = self._core.detectors(self._check(world))
        for k in ("detector", "kind", "lane"):
            d[k] = np.asarray(d[k], dtype=str)
        return d

    def config(self, world: int = 0) -> dict[str, Any]:
        """World ``world``'s validated scenario, as in scenario.json."""
        return json.loads(self._core.config_json(self._check(world)))

    def command(
        self, world: int, ids: Any, kind: str, value: Any = None, steps: int = 1, side: str | None = None
    ) -> None:
        """``Simulation.command`` for the vehicles ``ids`` of world ``world``."""
        w = self._check(world)
        arr, values, n = _command_args(ids, kind, value, steps)
        self._core.command(w, kind, arr, values, n, side)

    def use_gate(self) -> None:
        """Every world organizes with the scenario's PD rule behind its own switch, off at
        first (``Simulation.use_gate``). Before the first step."""
        self._core.use_gate()

    def set_gates(self, on: Any) -> None:
        """Switch each world's gate: ``on[i]`` for world i (booleans, one per world)."""
        arr = np.asarray(on)
        if arr.shape != (self.num_worlds,) or arr.dtype.kind not in "biu":
            raise ValueError(
                f"set_gates: one boolean per world ({self.num_worlds}), got shape {arr.shape} of {arr.dtype}"
            )
        self._core.set_gates([bool(x) for x in arr])

    def finish(self, world: int, out_dir: str | os.PathLike[str] | None = None) -> dict[str, Any]:
        """End world ``world``'s run and return its summary (as ``Simulation.finish``)."""
        w = self._check(world)
        text = self._core.finish(w, None if out_dir is None else os.fspath(out_dir))
        self._summaries[w] = json.loads(text)
        return dict(self._summaries[w])

    def summaries(self) -> list[dict[str, Any]]:
        """Every world's summary (finishing the worlds still open)."""
        return [self.finish(i) for i in range(self.num_worlds)]

    def __repr__(self) -> str:
        return f"<platoonsim.BatchSimulation {self.num_worlds} worlds on {self.threads} threads>"
