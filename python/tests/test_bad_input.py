"""Bad input from Python raises a clear exception (a ValueError or TypeError naming the
field), never a crash; the messages are the command line's."""

from __future__ import annotations

import pytest

import platoonsim


@pytest.mark.parametrize(
    "overrides, message",
    [
        ({"run.nope": 1}, "run.nope: unknown field 'nope' in [run]; allowed keys: seed, dt_s"),
        ({"run.penetration": 1.5}, "run.penetration = 1.5: must be in [0, 1]"),
        ({"run.penetration": "half"}, "run.penetration: invalid type: string \"half\", expected f64"),
        ({"demand.vph_per_lane": -10}, "demand.vph_per_lane"),
        ({"road..lanes": 3}, "is not a key"),
        ({"strategy.kind": "platoon"}, "\"platoon\""),
    ],
)
def test_bad_overrides_raise_scenario_errors_naming_the_key(overrides, message):
    with pytest.raises(platoonsim.ScenarioError) as e:
        platoonsim.Simulation("homogeneous", overrides=overrides)
    assert message in str(e.value)
    assert isinstance(e.value, ValueError)


def test_messages_are_those_of_the_command_line(tmp_path):
    import subprocess

    from conftest import cli_binary

    p = subprocess.run(
        [str(cli_binary()), "run", "homogeneous", "--set", "run.penetration=1.5", "--out", str(tmp_path), "-q"],
        capture_output=True,
        text=True,
    )
    assert p.returncode != 0
    with pytest.raises(platoonsim.ScenarioError) as e:
        platoonsim.Simulation("homogeneous", overrides={"run.penetration": 1.5})
    assert p.stderr.strip() == f"error: {e.value}"


def test_wrong_types_raise_type_errors():
    with pytest.raises(TypeError, match=r'overrides\["run.penetration"\]: a value of type NoneType'):
        platoonsim.Simulation("homogeneous", overrides={"run.penetration": None})
    with pytest.raises(TypeError, match="overrides must be a dict"):
        platoonsim.Simulation("homogeneous", overrides=["run.seed=1"])
    with pytest.raises(TypeError, match="seed must be an int"):
        platoonsim.Simulation("homogeneous", seed="1")
    with pytest.raises(TypeError, match="scenario must be"):
        platoonsim.Simulation(42)
    with pytest.raises(TypeError, match="advise"):
        platoonsim.Simulation("homogeneous", organizer=object())


def test_unknown_scenarios_strategies_and_bad_text():
    with pytest.raises(platoonsim.ScenarioError, match="homogeneous, sr99"):
        platoonsim.Simulation("nowhere")
    with pytest.raises(platoonsim.ScenarioError, match=r'strategy: must be one of "none", "pd"'):
        platoonsim.Simulation("homogeneous", organizer="platoon")
    with pytest.raises(platoonsim.ScenarioError, match="scenario text"):
        platoonsim.Simulation("name = 'x'\n[road]\nlanes = 'three'\n")
    with pytest.raises(platoonsim.ScenarioError, match="seed = -1"):
        platoonsim.Simulation("homogeneous", seed=-1)


def test_a_scenario_as_toml_text_runs():
    import pathlib

    text = (pathlib.Path(__file__).parents[2] / "crates/scenario/scenarios/homogeneous.toml").read_text()
    text = text.replace("duration_s = 3600", "duration_s = 60").replace("warmup_s = 1200", "warmup_s = 0")
    sim = platoonsim.Simulation(text, seed=1)
    assert sim.config["duration_s"] == 60.0
    assert sim.run()["steps"] == 600


def test_misuse_of_the_run_raises():
    sim = platoonsim.Simulation("homogeneous", overrides={"run.duration_s": 10, "run.warmup_s": 0})
    with pytest.raises(ValueError, match="non-negative int"):
        sim.step(-1)
    with pytest.raises(ValueError, match="non-negative int"):
        sim.step(1.5)
    with pytest.raises(ValueError, match="finite"):
        sim.run_until(float("nan"))
    assert sim.step(1000) == 100 and sim.done
    assert sim.step(5) == 0  # nothing left to do
    sim.finish()
    with pytest.raises(platoonsim.SimulationError, match="finished"):
        sim.step()
    with pytest.raises(platoonsim.SimulationError, match="finished"):
        sim.vehicles()
    assert sim.summary()["steps"] == 100
