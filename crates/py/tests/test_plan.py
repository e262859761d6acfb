"""A scene in plan from Python is the command line's: `slipload.simulate(path)` on a scene
in plan gives `slipload simulate PATH --format json`'s numbers bit for bit (every field of
the output contract, `in_plan` included, but the CPU time), with the same overrides."""

import json

import pytest

import slipload

from conftest import ROOT, cli_json, run_cli

SCENE = ROOT / "configs" / "plan-ten-story-pair.json"


def contract(result):
    mine = json.loads(result.to_json())
    mine.pop("cpu_seconds")
    return mine


@pytest.mark.parametrize("method", ["newmark", "exact"])
def test_a_scene_in_plan_runs_as_in_the_cli(method):
    py = slipload.simulate(str(SCENE), method=method, duration=3.0)
    cli = cli_json("simulate", SCENE, "--format", "json", "--method", method, "--duration", "3")
    cli.pop("cpu_seconds")
    assert contract(py) == cli
    assert "D/10" in cli["in_plan"]["drifts"]
    # a path object is a path too
    assert contract(slipload.simulate(SCENE, method=method, duration=3.0)) == cli


def test_a_plan_refusal_is_the_cli_refusal():
    with pytest.raises(slipload.InputError) as e:
        slipload.simulate(str(SCENE), method="delacruz", duration=1.0)
    cli = run_cli("simulate", SCENE, "--method", "delacruz", "--duration", "1", check=False)
    assert cli.returncode != 0
    assert "delacruz steps a chain of floors" in str(e.value)
    assert "delacruz steps a chain of floors" in cli.stderr
