"""Organizers written in Python: when they are asked, what their advice does, bad answers."""

from __future__ import annotations

import numpy as np
import pytest

import platoonsim

RUN = {"run.duration_s": 600, "run.warmup_s": 0}


class KeepRight:
    """CAVs in the control section: join the rightmost lane, with desire 0.8."""

    name = "keep-right"
    every_steps = 5

    def __init__(self):
        self.calls = []

    def advise(self, sim, t_s, v):
        self.calls.append((t_s, sim.steps, v["id"].size))
        inside = (v["x_m"] >= 5000) & (v["x_m"] < 6000)
        lanes = np.where(inside, 0, -1)
        return lanes, 0.8


def organizing_changes(sim):
    return [e for e in sim.events() if e["type"] == "lane_change" and e["reason"] == "organizing"]


def test_a_python_organizer_is_asked_every_n_steps_and_moves_cavs():
    org = KeepRight()
    # Under the paper's gap rule (spec 4.3); the safe rule of spec 9.1 refuses some of the gaps.
    run = {**RUN, "lane_change.gap_rule": "published"}
    sim = platoonsim.Simulation("homogeneous", seed=6, overrides=run, organizer=org)
    base = platoonsim.Simulation("homogeneous", seed=6, overrides=run)
    sim.run_until(500.0)
    base.run_until(500.0)
    assert len(org.calls) == 1000  # steps 0, 5, 10, ... 4995
    assert [c[1] for c in org.calls[:3]] == [0, 5, 10]
    assert org.calls[1][0] == 5 * 0.1
    # Advised CAVs move right inside the section (122 changes here); without advice no vehicle
    # organizes.
    moves = organizing_changes(sim)
    assert len(moves) > 100
    assert all(e["kind"] == "cav" and e["side"] == "right" and 5000 <= e["x_m"] < 6050 for e in moves)
    assert organizing_changes(base) == []
    s = sim.finish()
    assert s["strategy"] == "keep-right" and s["collisions"] == 0


def test_builtin_strategies_by_name():
    for name in platoonsim.STRATEGIES:
        if name == "flow-aware":
            continue  # needs the thresholds table's penetration: covered in test_identity
        sim = platoonsim.Simulation("homogeneous", overrides={"run.duration_s": 30, "run.warmup_s": 0}, organizer=name)
        assert sim.run()["strategy"] == name


class Wrong:
    def __init__(self, answer):
        self.answer = answer

    def advise(self, sim, t_s, v):
        return self.answer(v)


@pytest.mark.parametrize(
    "answer, error, message",
    [
        (lambda v: np.zeros(v["id"].size + 1, dtype=int), platoonsim.CommandError, "lanes for"),
        (lambda v: np.zeros(v["id"].size), platoonsim.CommandError, "integer lanes"),
        (lambda v: np.full(v["id"].size, 7), platoonsim.CommandError, "lane 7 does not exist"),
        (lambda v: (np.zeros(v["id"].size, dtype=int), 2.0), platoonsim.CommandError, "strength 2"),
        (lambda v: (1, 2, 3), platoonsim.CommandError, "pair"),
        # Issue 35 item 9: taken as "no advice", and numpy's own ValueError.
        (lambda v: np.full(v["id"].size, -2), platoonsim.CommandError, "lane -2: a lane is an engine index"),
        (
            lambda v: (np.zeros(v["id"].size, dtype=int), np.ones(v["id"].size + 1)),
            platoonsim.CommandError,
            "strengths of shape",
        ),
        (lambda v: 1 / 0, ZeroDivisionError, "division"),
    ],
)
def test_a_bad_advice_raises_from_step(answer, error, message):
    sim = platoonsim.Simulation("homogeneous", overrides=RUN, organizer=Wrong(answer))
    with pytest.raises(error, match=message):
        while sim.vehicles()["id"].size == 0:
            sim.step()
        sim.step()


def test_organizer_settings_are_checked():
    class Every0(KeepRight):
        every_steps = 0

    with pytest.raises(ValueError, match="every_steps = 0"):
        platoonsim.Simulation("homogeneous", overrides=RUN, organizer=Every0())
