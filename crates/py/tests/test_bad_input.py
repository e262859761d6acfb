"""Bad input from Python: each a clear exception (InputError, a ValueError, with the
message the command line prints for the same input), the interpreter alive."""

import json

import numpy as np
import pytest

import slipload

from conftest import ROOT, run_cli


def cli_error(*args):
    out = run_cli(*args, check=False)
    assert out.returncode != 0, out.stdout
    return out.stderr


def bad_scene_file(tmp_path, text):
    p = tmp_path / "scene.json"
    p.write_text(text)
    return p


@pytest.mark.parametrize(
    "text, says",
    [
        ('{"building": "%s", "duration": -1}' % (ROOT / "configs" / "benchmark-3story.json"), "duration"),
        ('{"floor_masses": [1e5], "storey_stiffness": [1e8], "storey_heights": [3], "dissipators": [{"floor": 2, "brace_stiffness": 1e8, "slip_load": 1e5}]}', "floor"),
        ('{"floor_masses": [1e5], "storey_stiffnes": [1e8]}', "storey_stiffnes"),
        ('{"floor_masses": "heavy", "storey_stiffness": [1e8]}', "line 1 column 24"),
        ('{"floor_masses": [1e5], "storey_stiffness": [1e8]', "EOF"),
    ],
)
def test_a_bad_scene_file_raises_the_cli_message(tmp_path, text, says):
    path = bad_scene_file(tmp_path, text)
    with pytest.raises(slipload.InputError) as e:
        slipload.simulate(str(path))
    assert isinstance(e.value, ValueError)
    message = str(e.value)
    assert says in message
    assert str(path) in message, "the message names the file"
    assert message in cli_error("simulate", path)


def test_a_dict_goes_through_the_same_validation():
    building = json.loads((ROOT / "configs" / "benchmark-3story.json").read_text())
    building["floor_masses"] = [1e5, -1.0, 1e5]
    with pytest.raises(slipload.InputError, match="floor_masses"):
        slipload.load_scene(building, duration=1.0)
    with pytest.raises(slipload.InputError, match="missing field|storey_stiffness|stiffness"):
        slipload.load_scene({"floor_masses": [1e5]}, duration=1.0)
    building["floor_masses"] = [1e5, float("nan"), 1e5]
    with pytest.raises(slipload.InputError, match="finite"):
        slipload.load_scene(building, duration=1.0)


def test_a_missing_file_is_a_file_error():
    with pytest.raises(slipload.FileError) as e:
        slipload.load_scene("no/such/scene.json")
    assert isinstance(e.value, OSError)
    assert "no/such/scene.json" in str(e.value)
    with pytest.raises(slipload.FileError):
        slipload.read_record("no/such/record.AT2")


@pytest.mark.parametrize(
    "accel, dt, says",
    [
        (np.array([], dtype=float), 0.01, "empty"),
        (np.array([0.0, np.nan, 0.1]), 0.01, "accel[1] is NaN"),
        (np.array([0.0, np.inf]), 0.01, "accel[1] is inf"),
        (np.array([0, 1, 2]), 0.01, "int64"),
        (np.arange(10.0)[::2], 0.01, "not contiguous"),
        (np.zeros((3, 2)), 0.01, "2-D"),
        ([0.0, 0.1], 0.01, "list"),
        (np.array([0.0, 0.1]), -0.01, "dt"),
        (np.array([0.0, 0.1]), 0.0, "dt"),
        (np.array([0.0, 0.1]), float("nan"), "dt"),
        (np.array([0.0, 1e9]), 0.01, "beyond any physical record"),
    ],
)
def test_bad_arrays_are_refused(accel, dt, says):
    with pytest.raises(slipload.InputError) as e:
        slipload.record_from_array(accel, dt)
    assert says in str(e.value)


def test_wrong_types_and_values_are_refused():
    with pytest.raises(slipload.InputError, match="method"):
        slipload.simulate(method="verlet")
    with pytest.raises(slipload.InputError, match="outputs"):
        slipload.simulate(outputs=["movies"])
    with pytest.raises(slipload.InputError, match="scene"):
        slipload.simulate(42)
    with pytest.raises(slipload.InputError, match="dt"):
        slipload.simulate(dt=-0.001)
    with pytest.raises(slipload.InputError, match="unknown acceleration unit `furlongs`"):
        slipload.record_from_array(np.zeros(4), 0.01, units="furlongs")
    with pytest.raises(slipload.InputError, match="window"):
        slipload.load_scene(window=(-1.0, 2.0))
    with pytest.raises(TypeError):
        slipload.simulate(duration="long")
    scene = slipload.load_scene(duration=1.0)
    with pytest.raises(slipload.InputError, match="3 dissipator"):
        scene.with_slip_loads(np.array([1e5, 1e5]))
    with pytest.raises(slipload.InputError, match="slip_loads\\[1\\]"):
        scene.with_slip_loads(np.array([1e5, -1.0, 1e5]))
    with pytest.raises(slipload.InputError, match="weight"):
        scene.with_slip_loads(np.array([1e5, 1e22, 1e5]))


def test_bad_batch_inputs_are_refused():
    scene = slipload.load_scene(duration=1.0)
    suite = slipload.synthetic_suite(count=2, duration=2.0)
    with pytest.raises(slipload.InputError, match="empty"):
        slipload.batch([])
    with pytest.raises(slipload.InputError, match="records"):
        slipload.batch_designs(scene, [], np.ones((1, 3)))
    with pytest.raises(slipload.InputError, match="2-D"):
        slipload.batch_designs(scene, suite, np.ones(3))
    with pytest.raises(slipload.InputError, match=r"slip_loads\[0, 1\] is NaN"):
        slipload.batch_designs(scene, suite, np.array([[1.0, np.nan, 1.0]]))
    with pytest.raises(slipload.InputError, match="float64"):
        slipload.batch_designs(scene, suite, np.array([[1.0, 1.0, 1.0], [1.0, 1.0]], dtype=object))
    with pytest.raises(slipload.InputError, match=r"slip_loads\[0\]: 2 value"):
        slipload.batch_designs(scene, suite, np.ones((2, 2)))
    with pytest.raises(slipload.InputError, match="threads"):
        slipload.batch([scene], threads=0)


def test_bad_study_inputs_raise_the_cli_message(tmp_path):
    study = json.loads((ROOT / "configs" / "study-slurm-check.json").read_text())
    study["sweep"]["points"] = 0
    path = tmp_path / "study.json"
    path.write_text(json.dumps(study))
    with pytest.raises(slipload.InputError) as e:
        slipload.load_study(str(path))
    assert "points" in str(e.value)
    assert str(e.value) in cli_error("sweep", path, "--out", tmp_path / "o")
    assert not (tmp_path / "o").exists()
    f = tmp_path / "a-file"
    f.write_text("")
    with pytest.raises(slipload.InputError, match="not a folder"):
        slipload.sweep(str(ROOT / "configs" / "study-slurm-check.json"), f)


def test_the_interpreter_survives_a_panic_as_an_exception():
    # an InternalError is a RuntimeError: a bug caught before it reaches the interpreter
    assert issubclass(slipload.InternalError, RuntimeError)
    assert issubclass(slipload.InputError, slipload.SlipLoadError)
    # the interpreter is alive after every refusal above
    assert slipload.simulate(slipload.load_scene(duration=0.5)).steps > 0
