"""Issue 40 §4, the two fronts accept the same things: a dict given for a file (a scene,
a building, a study, designs) is refused as the command line refuses the same file —
larger than any real one, nested deeper than the JSON reader goes, a NaN or ±inf — with
an InputError naming the field path; numpy numbers and arrays in it are taken as the
numbers they show; integers too large for any argument and wrong argument types raise
InputError naming the parameter; the command line's plausibility warnings reach Python
as UserWarnings, in its words. Also: the design table as a frame of one number per cell
(§5)."""

import json
import warnings

import numpy as np
import pytest

import slipload
from slipload import _slipload

from conftest import ROOT, run_cli

BUILDING = ROOT / "configs" / "benchmark-3story.json"
STUDY = ROOT / "configs" / "study-slurm-check.json"


def building():
    return json.loads(BUILDING.read_text())


def cli_refuses(*args):
    out = run_cli(*args, check=False)
    assert out.returncode != 0, out.stdout
    return out.stderr


def nested(depth):
    deep = [1.0]
    for _ in range(depth):
        deep = [deep]
    return deep


# ------------------------------------------------------------------------- size limits


def test_a_dict_larger_than_any_file_is_refused_naming_it_and_the_limit(tmp_path):
    limit = slipload._slipload.MAX_CONFIG_BYTES
    assert limit == 16 * 1024 * 1024
    big = building()
    big["name"] = "x" * (limit + 1)
    with pytest.raises(slipload.InputError) as e:
        slipload.load_scene(big, duration=1.0)
    message = str(e.value)
    assert message.startswith("scene (a dict): ") and "limit 16.0 MiB" in message, message[:300]
    # the command line refuses the same text as a file, with the same limit
    path = tmp_path / "big.json"
    path.write_text(json.dumps(big))
    assert "limit 16.0 MiB" in cli_refuses("simulate", path, "--duration", 1)
    # many small numbers count as one long text does: refused while the text is written
    many = building()
    many["floor_masses"] = [1e5] * (limit // 4)
    with pytest.raises(slipload.InputError, match=r"scene \(a dict\): .*limit 16\.0 MiB"):
        slipload.load_scene(many, duration=1.0)
    study = json.loads(STUDY.read_text())
    study["description"] = "y" * (limit + 1)
    with pytest.raises(slipload.InputError, match=r"^study \(a dict\): .*limit 16\.0 MiB"):
        slipload.load_study(study)


def test_allow_large_lifts_the_dicts_size_limit():
    text = {"a": "z" * (slipload._slipload.MAX_CONFIG_BYTES + 1)}
    try:
        slipload.allow_large(True)
        assert len(_slipload.dict_json(text, "x (a dict)", "x")) > slipload._slipload.MAX_CONFIG_BYTES
    finally:
        slipload.allow_large(False)
    with pytest.raises(slipload.InputError, match="limit"):
        _slipload.dict_json(text, "x (a dict)", "x")


# ---------------------------------------------------------------- numpy and NaN in dicts


def test_numpy_numbers_and_arrays_in_a_dict_are_the_numbers_they_show():
    plain = building()
    # the file's quantities as bare SI numbers
    plain["floor_masses"] = [4.78e5, 4.78e5, 5.18e5]
    plain["storey_heights"] = [3.96, 3.96, 3.96]
    plain["stiffness_matrix"] = [[float(v.split()[0]) * 1e6 for v in row] for row in plain["stiffness_matrix"]]
    numpy = json.loads(json.dumps(plain))
    numpy["floor_masses"] = np.array(plain["floor_masses"], dtype=np.float64)
    numpy["storey_heights"] = [np.float64(h) for h in plain["storey_heights"]]
    numpy["stiffness_matrix"] = np.asfortranarray(np.array(plain["stiffness_matrix"]))
    numpy["dissipators"][0]["floor"] = np.int64(plain["dissipators"][0]["floor"])
    numpy["dissipators"][0]["slip_load"] = np.float32(2.0e5)
    plain["dissipators"][0]["slip_load"] = float(np.float32(2.0e5))
    a = slipload.simulate(slipload.load_scene(plain, duration=2.0))
    b = slipload.simulate(slipload.load_scene(numpy, duration=2.0))
    np.testing.assert_array_equal(a.peak_drift, b.peak_drift)
    # float32 numbers are the decimals numpy shows, not their bits as a double
    text = _slipload.dict_json(
        {"x": np.float32(0.1), "a": np.array([0.3, 1.0e-7, 2.0e5], dtype=np.float32)}, "x", "x")
    assert json.loads(text) == {"x": 0.1, "a": [0.3, 1.0e-7, 2.0e5]}
    assert float(np.float32(0.1)) != 0.1  # (what tolist() alone would give)
    with pytest.raises(slipload.InputError, match="float16"):
        _slipload.dict_json({"x": np.float16(0.1)}, "x", "x")
    # an array in its logical order, whatever its memory order
    m = np.arange(6.0).reshape(2, 3)
    for view in (m, m.T, np.asfortranarray(m), np.asfortranarray(m).T):
        text = _slipload.dict_json({"m": view, "b": np.bool_(True), "i": np.int64(-3)}, "x", "x")
        assert json.loads(text) == {"m": view.tolist(), "b": True, "i": -3}


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), -float("inf"), np.float64("nan"), np.float32("inf")])
def test_nan_and_inf_in_a_dict_are_refused_naming_the_field(tmp_path, bad):
    b = building()
    b["dissipators"][0]["slip_load"] = bad
    with pytest.raises(slipload.InputError) as e:
        slipload.load_scene(b, duration=1.0)
    message = str(e.value)
    assert message.startswith("scene (a dict): field `dissipators[0].slip_load`: "), message
    assert "finite" in message and "column" not in message
    b = building()
    b["floor_masses"] = np.array([1e5, bad, 1e5])
    with pytest.raises(slipload.InputError, match=r"field `floor_masses\[1\]`"):
        slipload.load_scene(b, duration=1.0)
    # a file cannot hold it either: the command line refuses the same value
    path = tmp_path / "nan.json"
    path.write_text(json.dumps(b, default=list))
    cli_refuses("simulate", path, "--duration", 1)


def test_a_value_no_json_holds_is_refused_naming_the_field():
    b = building()
    b["dissipators"][1]["floor"] = {2}
    with pytest.raises(slipload.InputError, match=r"field `dissipators\[1\]\.floor`: a set"):
        slipload.load_scene(b, duration=1.0)
    with pytest.raises(slipload.InputError, match=r"the key 3 is not a string \(int\)"):
        slipload.load_scene({**building(), 3: "x"}, duration=1.0)


# ------------------------------------------------------------- recursion, integers, types


@pytest.mark.parametrize("depth", [200, 100_000])
def test_a_dict_nested_too_deep_raises_input_error_naming_the_field(tmp_path, depth):
    b = building()
    b["floor_masses"] = nested(depth)
    with pytest.raises(slipload.InputError) as e:
        slipload.load_scene(b, duration=1.0)
    assert str(e.value).startswith("scene (a dict): field `floor_masses[0][0]"), str(e.value)[:200]
    assert "nested more than 128 levels" in str(e.value)
    study = json.loads(STUDY.read_text())
    study["sweep"] = {"points": nested(depth)}
    with pytest.raises(slipload.InputError, match=r"^study \(a dict\): field `sweep\.points\[0\]"):
        slipload.load_study(study)
    with pytest.raises(slipload.InputError, match=r"^designs \(a list\): field `\[0\]"):
        slipload.rank(str(STUDY), [nested(depth)], tmp_path / "r", progress=False)
    if depth == 200:
        path = tmp_path / "deep.json"
        path.write_text(json.dumps(b))
        assert "recursion limit" in cli_refuses("simulate", path, "--duration", 1)


def test_integers_past_any_argument_raise_input_error_naming_it():
    scene = slipload.load_scene(duration=0.2)
    for count in (2**70, 2**64):
        with pytest.raises(slipload.InputError, match=f"count={count}: .*limit") as e:
            slipload.synthetic_suite(count=count)
        assert "more than any real study" in str(e.value)
    with pytest.raises(slipload.InputError, match=f"count={-2**70}: expected a whole number of records"):
        slipload.synthetic_suite(count=-(2**70))
    with pytest.raises(slipload.InputError, match="count='3': expected a whole number of records, 1 or more, got a str"):
        slipload.synthetic_suite(count="3")
    with pytest.raises(slipload.InputError, match="count=2.0: expected"):
        slipload.synthetic_suite(count=2.0)
    for seed in (2**64, -1, 2**70):
        with pytest.raises(slipload.InputError, match=f"seed={seed}: expected a whole number from 0 to 2\\*\\*64 - 1"):
            slipload.synthetic_suite(count=1, seed=seed, duration=2.0)
    assert len(slipload.synthetic_suite(count=np.int64(1), seed=2**64 - 1, duration=2.0)) == 1
    for threads in (2**64, 2**70):
        with pytest.raises(slipload.InputError, match=f"threads={threads}: .*at most"):
            slipload.batch([scene], threads=threads, progress=False)
    with pytest.raises(slipload.InputError, match=f"threads={-2**64}: expected a whole number of worker threads"):
        slipload.batch([scene], threads=-(2**64), progress=False)
    for bad in ("2", 1.5, True):
        with pytest.raises(slipload.InputError, match="threads=.*expected a whole number of worker threads"):
            slipload.batch([scene], threads=bad, progress=False)
    assert len(slipload.batch([scene], threads=np.int32(1), progress=False)) == 1
    with pytest.raises(slipload.InputError, match=f"threads={2**64}"):
        slipload.optimize(str(STUDY), "never-written", threads=2**64, progress=False)
    with pytest.raises(slipload.InputError, match=f"bootstrap: {2**70} is not in"):
        slipload.rank(str(STUDY), "no-such-designs.json", "never-written", bootstrap=2**70, progress=False)
    with pytest.raises(slipload.InputError, match="seed="):
        slipload.rank(str(STUDY), "no-such-designs.json", "never-written", seed=-1, progress=False)


def test_an_integer_past_the_loaders_in_a_dict_names_the_field_as_in_a_file(tmp_path):
    study = json.loads(STUDY.read_text())
    study["suites"][0]["synthetic"]["count"] = 2**70
    with pytest.raises(slipload.InputError, match=r"^study \(a dict\): field `suites\[0\]\.synthetic\.count`") as e:
        slipload.load_study(study)
    assert "column" not in str(e.value)
    study["building"] = str(BUILDING)
    path = tmp_path / "study.json"
    path.write_text(json.dumps(study))
    cli_refuses("sweep", path, "--out", tmp_path / "o")


@pytest.mark.parametrize("progress", ["bar", 0, object(), [print]])
def test_a_wrong_progress_names_it_in_every_long_call(progress):
    with pytest.raises(slipload.InputError, match="^progress: "):
        slipload.batch([slipload.load_scene(duration=0.2)], progress=progress)
    with pytest.raises(slipload.InputError, match="^progress: "):
        slipload.evaluate_objectives(str(STUDY), np.ones((1, 3)), progress=progress)


# ------------------------------------------------------------------ plausibility warnings


def cli_warnings(*args):
    err = run_cli("simulate", *args).stderr
    return [line[len("warning: "):] for line in err.splitlines() if line.startswith("warning: ")]


def python_warnings(call):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = call()
    return [str(w.message) for w in caught if issubclass(w.category, UserWarning)], result


def test_the_plausibility_warnings_are_the_command_lines(tmp_path):
    b = building()
    b["dissipators"][0]["slip_load"] = 50.0  # kN meant, N written
    path = tmp_path / "tiny.json"
    path.write_text(json.dumps(b))
    expected = cli_warnings(path, "--duration", 1)
    assert len(expected) == 1 and "did you mean kN" in expected[0], expected
    scene = slipload.load_scene(str(path), duration=1.0)
    got, result = python_warnings(lambda: slipload.simulate(scene))
    assert got == expected
    assert result.warnings == expected
    got, _ = python_warnings(lambda: slipload.batch([scene], progress=False))
    assert got == expected
    # a step that does not divide the duration
    expected = cli_warnings("--dt", 0.003, "--duration", 1)
    assert len(expected) == 1 and "does not divide" in expected[0], expected
    got, _ = python_warnings(lambda: slipload.simulate(dt=0.003, duration=1.0))
    assert got == expected
    # a plausible run warns nothing, on both fronts
    assert cli_warnings("--duration", 1) == []
    got, result = python_warnings(lambda: slipload.simulate(duration=1.0))
    assert got == [] and result.warnings == []
