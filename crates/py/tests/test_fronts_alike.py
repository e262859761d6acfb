"""Issue 40 §4, the two fronts accept the same things: thread counts, record steps
(1 µs … 1 s, for arrays and synthetic records as for files), counts, windows and scale
lists are refused or accepted by Python as by the command line (from the same library
checks); a wrong ``progress`` raises InputError naming it; ``knee`` of nothing is None;
``nondominated_ranks`` takes collapsed designs (+inf)."""

import numpy as np
import pytest

import slipload

from conftest import ROOT, run_cli


def cli_refuses(*args):
    out = run_cli(*args, check=False)
    assert out.returncode != 0, out.stdout
    return out.stderr


@pytest.mark.parametrize("dt", [5.0, 1.5, 5e-7])
def test_a_record_step_outside_the_readers_band_is_refused_by_both_fronts(tmp_path, dt):
    with pytest.raises(slipload.InputError, match="accelerograph") as e:
        slipload.record_from_array(np.zeros(40), dt)
    assert str(e.value).startswith("dt:")
    with pytest.raises(slipload.InputError, match="accelerograph"):
        slipload.synthetic_suite(count=1, duration=20.0, dt=dt)
    err = cli_refuses("record", "synth", "--dt", dt, "--duration", 20, "--out", tmp_path / "r.csv")
    assert "accelerograph" in err and "--dt" in err
    assert not (tmp_path / "r.csv").exists()


def test_a_record_step_at_the_bands_ends_is_taken_by_both_fronts(tmp_path):
    for dt in (1.0, 1e-6):
        assert slipload.record_from_array(np.zeros(3), dt).dt == dt
    assert len(slipload.synthetic_suite(count=1, duration=30.0, dt=1.0)[0]) == 31
    out = tmp_path / "slow.csv"
    run_cli("record", "synth", "--dt", 1, "--duration", 30, "--out", out)
    # what the command line wrote, Python reads
    assert slipload.read_record(out).dt == 1.0


def test_thread_counts_are_refused_and_taken_as_the_command_line_does():
    scene = slipload.load_scene(duration=0.2)
    for bad in (0, -1):
        with pytest.raises(slipload.InputError, match=f"threads={bad}"):
            slipload.batch([scene], threads=bad, progress=False)
        assert "--threads" in cli_refuses("--threads", bad, "simulate", "--duration", 0.2)
    with pytest.raises(slipload.InputError, match="at most"):
        slipload.batch([scene], threads=10**6, progress=False)
    assert "at most" in cli_refuses("--threads", 10**6, "simulate", "--duration", 0.2)
    assert len(slipload.batch([scene], threads=1, progress=False)) == 1


def test_a_suite_of_no_record_is_refused_by_both_fronts(tmp_path):
    with pytest.raises(slipload.InputError, match="count=0"):
        slipload.synthetic_suite(count=0)
    with pytest.raises(slipload.InputError, match="count=-1"):
        slipload.synthetic_suite(count=-1)
    assert "--count 0" in cli_refuses("record", "synth", "--count", 0, "--out", tmp_path / "d")
    assert len(slipload.synthetic_suite(count=1, duration=2.0)) == 1


def test_a_window_of_no_length_is_refused_by_both_fronts():
    with pytest.raises(slipload.InputError, match="window"):
        slipload.load_scene(window=(1.0, 0.0))
    assert "window" in cli_refuses("simulate", "--window", "1,0")
    record = slipload.synthetic_suite(count=1, duration=4.0)[0]
    with pytest.raises(slipload.InputError, match="duration > 0"):
        record.window(1.0, 0.0)
    assert record.window(1.0, 1.0).duration == pytest.approx(1.0)
    assert slipload.load_scene(window=(1.0, 2.0)).duration == pytest.approx(2.0)


def test_an_empty_scale_list_is_refused_as_the_command_line_refuses_it(tmp_path):
    # the library's check (check_scales) refuses it: both fronts say the same words
    for kw, flag in (("period_scales", "--period-scales"), ("intensity_scales", "--intensity-scales")):
        with pytest.raises(slipload.InputError, match=f"^{flag}: an empty list") as e:
            slipload.table(out=tmp_path / kw, progress=False, **{kw: []})
        assert not (tmp_path / kw).exists()
        for given in (f"{flag}=", f"{flag}= "):
            assert str(e.value) in cli_refuses("table", given, "--out", tmp_path / "cli")
        assert not (tmp_path / "cli").exists()


@pytest.mark.parametrize("progress", ["yes", 3, [1]])
def test_a_wrong_progress_raises_input_error_naming_it(progress):
    with pytest.raises(slipload.InputError, match="progress"):
        slipload.batch([slipload.load_scene(duration=0.2)], progress=progress)


def test_the_knee_of_nothing_is_none():
    assert slipload.knee(np.empty((0, 2))) is None
    assert slipload.knee([]) is None
    assert slipload.knee(np.array([])) is None
    assert slipload.nondominated_ranks(np.empty((0, 3))) == []
    assert slipload.knee(np.array([[1.0, 2.0], [2.0, 1.0], [1.2, 1.2]])) == 2


def test_collapsed_designs_rank_last():
    inf = np.inf
    points = np.array([[1.0, 3.0], [inf, inf], [2.0, 1.0], [3.0, 3.5], [inf, inf]])
    assert slipload.nondominated_ranks(points) == [1, 3, 1, 2, 3]
    for bad in (np.nan, -inf):
        with pytest.raises(slipload.InputError, match=r"points\[1, 0\]"):
            slipload.nondominated_ranks(np.array([[1.0, 2.0], [bad, 1.0]]))
    # the knee stays a front's, where a collapsed design is no member
    with pytest.raises(slipload.InputError, match="finite"):
        slipload.knee(points)


def test_an_error_in_a_dict_names_the_field_path_not_a_position_in_internal_json():
    import json

    building = json.loads((ROOT / "configs" / "benchmark-3story.json").read_text())
    building["dissipators"][1]["floor"] = "second"
    with pytest.raises(slipload.InputError) as e:
        slipload.load_scene(building, duration=1.0)
    message = str(e.value)
    assert "field `dissipators[1].floor`" in message, message
    assert "line 1 column" not in message, message
    scene = {"building": building, "excitation": {"record": {"file": 3}}}
    building["dissipators"][1]["floor"] = 2
    with pytest.raises(slipload.InputError, match=r"field `excitation\.record\.file`") as e:
        slipload.load_scene(scene, duration=1.0)
    assert "column" not in str(e.value)
    study = json.loads((ROOT / "configs" / "study-slurm-check.json").read_text())
    study["sweep"]["points"] = "many"
    with pytest.raises(slipload.InputError, match=r"study \(a dict\): field `sweep\.points`") as e:
        slipload.load_study(study)
    assert "column" not in str(e.value)
    # a JSON text of the caller's keeps its position, with the field beside it
    with pytest.raises(slipload.InputError) as e:
        slipload.Scene.from_json('{\n "floor_masses": [1e5],\n "storey_stiffness": ["x"]}')
    assert "line 3 column" in str(e.value) and "field `storey_stiffness[0]`" in str(e.value)
