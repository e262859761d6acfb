"""A scene in plan from Python is the command line's: `slipload.simulate(path)` on a scene
in plan gives `slipload simulate PATH --format json`'s numbers bit for bit (every field of
the output contract, `in_plan` included, but the CPU time), with the same overrides."""

import importlib.util
import json
import subprocess
import sys

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


@pytest.mark.skipif(
    importlib.util.find_spec("openseespy") is None,
    reason="openseespy is not installed (scripts/test.sh installs it)",
)
@pytest.mark.parametrize(
    "angles, extras",
    [((0.0, 90.0), False), ((30.0, 120.0), False), ((30.0, 120.0), True)],
)
def test_opensees_runs_the_plan_to_newmarks_peaks(angles, extras, tmp_path):
    """The plan in OpenSees (masters at the centres of mass, rigid links to the lines,
    zeroLength lines and dampers) solves newmark's discrete equations in other
    coordinates: every line's peak drift agrees to the Newton tolerance (1e-6 relative,
    the chain's bound), under both components at once, yielding and slipping; with
    `extras`, also with P-Delta (leaning zeroLength springs at each storey's load
    centroid) and storey dashpots on two lines (Viscous zeroLength elements)."""
    building = json.loads((ROOT / "configs" / "plan-ten-story.json").read_text())
    building["damping"] = {"rayleigh": {"ratio": 0.02, "modes": [1, 4]}}
    if extras:
        # the centres of mass off the plan's middle, so the load's centroid moves too
        for k, floor in enumerate(building["floors"]):
            floor["centre_of_mass"] = [15.0 + 0.2 * k, 10.0]
        building["p_delta"] = {}
        n = len(building["lines"][0]["storey_stiffness"])
        building["lines"][0]["storey_damping"] = ["2 MN*s/m"] * n
        building["lines"][2]["storey_damping"] = [3.0e6] * n
    # the flexible line's first storeys yield
    building["lines"][1]["storey_yield"] = [
        {"storey": s, "yield_drift": "12 mm", "post_yield_ratio": 0.05} for s in (1, 2, 3)
    ]
    (tmp_path / "plan.json").write_text(json.dumps(building))
    records = ROOT / "records" / "pairs"
    scene = {
        "building": "plan.json",
        "ground": [
            {"record": {"file": str(records / "RSN1044_NORTHR_NWH090.AT2")}, "angle_deg": angles[0]},
            {"record": {"file": str(records / "RSN1044_NORTHR_NWH360.AT2")}, "angle_deg": angles[1]},
        ],
        "duration": 6,
    }
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    script = tmp_path / "plan.py"
    run_cli("opensees", path, "--out", script)
    ran = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True)
    assert ran.returncode == 0, ran.stderr
    opensees = json.loads(ran.stdout)
    mine = cli_json("simulate", path, "--format", "json")
    assert opensees["dt"] == mine["dt"]
    names = mine["in_plan"]["drifts"]
    assert mine["peak_plastic_drift"] and max(mine["peak_plastic_drift"]) > 0, "a line yields"
    assert max(mine["peak_slip"]) > 0, "the dampers slip"
    scale = max(mine["peak_drift"])
    if extras:
        # P-Delta and the dashpots change the answer both tools agree on
        for key in ("p_delta",):
            building.pop(key)
        for line in building["lines"]:
            line.pop("storey_damping", None)
        (tmp_path / "plan.json").write_text(json.dumps(building))
        plain = cli_json("simulate", path, "--format", "json")
        assert max(abs(a - b) for a, b in zip(plain["peak_drift"], mine["peak_drift"])) > 1e-3 * scale
    worst = 0.0
    for name, peak in zip(opensees["drifts"], opensees["peak_drift"]):
        k = names.index(name)
        assert abs(peak - mine["peak_drift"][k]) <= 1e-6 * scale, (name, peak, mine["peak_drift"][k])
        worst = max(worst, abs(peak - mine["peak_drift"][k]) / scale)
    print(f"{angles} extras={extras}: largest difference {worst:.1e} of the largest drift")


HOSTILE = [
    "# -*- coding: unicode_escape -*-\\nimport os; os.system('touch PWNED')",
    '"""; import os; os.system("touch PWNED"); """',
    "'\\'; __import__('os').system('touch PWNED') #",
    "line\nimport os\nos.system('touch PWNED')",
    "nul\x00byte and caf\u00e9 \u5730\u9707",
]


@pytest.mark.parametrize("text", HOSTILE)
def test_the_plans_script_reads_every_name_as_data(text, tmp_path):
    """Scene, building and line names reach the script as ASCII literals: loading it runs
    nothing of them, and each name comes back unchanged."""
    building = json.loads((ROOT / "configs" / "plan-ten-story.json").read_text())
    building["name"] = text
    building["damping"] = "none"
    building["lines"][0]["name"] = text
    scene = {"name": text, "building": building, "duration": 0.05}
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    script = tmp_path / "plan.py"
    run_cli("opensees", path, "--out", script)
    body = script.read_bytes()
    assert body.isascii()
    assert body.splitlines()[1] == b"# -*- coding: utf-8 -*-"
    # load it without running the analysis (its main guard), in a fresh interpreter
    probe = (
        "import json, runpy, sys; ns = runpy.run_path(sys.argv[1], run_name='probe'); "
        "print(json.dumps([ns['SCENE'], ns['BUILDING'], ns['LINES'][0][0]]))"
    )
    ran = subprocess.run([sys.executable, "-c", probe, str(script)], cwd=tmp_path, capture_output=True, text=True)
    assert ran.returncode == 0, ran.stderr
    assert json.loads(ran.stdout) == [text, text, text]
    assert not (tmp_path / "PWNED").exists()


def short_plan_study(tmp_path):
    pairs = ROOT / "records" / "pairs"
    study = {
        "name": "short plan study",
        "building": str(ROOT / "configs" / "plan-ten-story.json"),
        "suites": [
            {
                "name": "newhall",
                "pairs": [[str(pairs / "RSN1044_NORTHR_NWH090.AT2"), str(pairs / "RSN1044_NORTHR_NWH360.AT2")]],
                "angles_deg": [0, 90],
                "duration_s": 3,
            }
        ],
        "space": {"placement": "lines", "slip_load_kn": [0, 4000]},
        "sweep": {"points": 3},
        "refine": {"max_evaluations": 4},
    }
    path = tmp_path / "study.json"
    path.write_text(json.dumps(study))
    return path


def test_a_study_in_plan_optimises_as_in_the_cli(tmp_path):
    study = short_plan_study(tmp_path)
    py_out, cli_out = tmp_path / "py", tmp_path / "cli"
    got = slipload.optimize(study, py_out)
    run_cli("optimize", study, "--out", cli_out)
    assert got["summary"] == (cli_out / "plan-summary.txt").read_text()
    assert "plan-optimum.json" in got["files"] and "plan-view" in got["figures"]
    for name in got["files"] + [f"{s}.csv" for s in got["figures"]]:
        assert (py_out / name).read_bytes() == (cli_out / name).read_bytes(), name
    # a rerun takes every design from the journal
    again = slipload.optimize(study, py_out)
    assert again["replayed"] == got["sweep_designs"] + got["refine_designs"]
    with pytest.raises(ValueError, match="refines with 'model'"):
        slipload.optimize(study, tmp_path / "x", refine="sqp")
