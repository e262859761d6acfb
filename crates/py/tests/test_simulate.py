"""One simulation from Python is the command line's simulation: the same scene through
`slipload.simulate` and through `slipload simulate --format json` gives the same numbers,
bit for bit (every field of the output contract but the CPU time)."""

import json

import numpy as np
import pytest

import slipload

from conftest import ROOT, cli_json


def same_contract(py_result, cli):
    """Every field of the output contract equal, bit for bit, but cpu_seconds."""
    mine = json.loads(py_result.to_json())
    mine.pop("cpu_seconds")
    cli = dict(cli)
    cli.pop("cpu_seconds")
    assert mine == cli
    # the attributes are the contract's numbers, not a re-derivation
    assert np.array_equal(py_result.peak_drift, np.array(cli["peak_drift"]))
    assert np.array_equal(py_result.peak_abs_acceleration, np.array(cli["peak_abs_acceleration"]))
    assert np.array_equal(py_result.residual_drift, np.array(cli["residual_drift"]))
    assert np.array_equal(py_result.peak_slip, np.array(cli["peak_slip"]))
    assert np.array_equal(py_result.transitions, np.array(cli["transitions"]))
    assert py_result.peak_base_shear == cli["peak_base_shear"]
    if cli.get("peak_drift_ratio") is not None:
        assert np.array_equal(py_result.peak_drift_ratio, np.array(cli["peak_drift_ratio"]))
    if cli.get("energy") is not None:
        for k, v in cli["energy"].items():
            assert py_result.energy[k] == v, k


def test_default_scene_is_the_cli_default():
    same_contract(slipload.simulate(), cli_json("simulate", "--format", "json"))


@pytest.mark.parametrize("method", ["newmark", "hht", "bilinear", "delacruz", "exact"])
def test_every_method_matches_the_cli(method):
    # delacruz is conditionally stable: at its default step T1/200 it fails on this record
    # (see the next test), at 1 ms it runs
    dt = ["--dt", "0.001"] if method == "delacruz" else []
    py = slipload.simulate(slipload.load_scene(duration=4.0), method=method, dt=0.001 if dt else None)
    cli = cli_json("simulate", "--format", "json", "--method", method, "--duration", "4", *dt)
    same_contract(py, cli)


def test_a_failed_run_fails_as_in_the_cli():
    from conftest import run_cli

    with pytest.raises(slipload.SimulationError) as e:
        slipload.simulate(slipload.load_scene(duration=4.0), method="delacruz")
    cli = run_cli("simulate", "--method", "delacruz", "--duration", "4", check=False)
    assert cli.returncode != 0
    assert str(e.value) in cli.stderr
    assert isinstance(e.value, RuntimeError)


def test_scene_file_with_record_and_window():
    scene = ROOT / "configs" / "paper-benchmark-sylmar.json"
    same_contract(slipload.simulate(str(scene)), cli_json("simulate", scene, "--format", "json"))


def test_a_scale_factor_is_the_cli_scale():
    """``scale=`` is ``--scale``: the record times the factor, the same bits; a scene
    re-resolved with ``scale_pga_g`` takes that in place of the factor."""
    rec = ROOT / "records" / "elCentro.AT2"
    scaled = slipload.load_scene(record=rec, scale=1.7)
    same_contract(slipload.simulate(scaled), cli_json("simulate", "--record", rec, "--scale", "1.7", "--format", "json"))
    again = slipload.load_scene(scaled, scale_pga_g=0.3)
    same_contract(slipload.simulate(again),
                  cli_json("simulate", "--record", rec, "--scale-pga-g", "0.3", "--format", "json"))
    with pytest.raises(slipload.InputError, match="not both"):
        slipload.load_scene(record=rec, scale=2.0, scale_pga_g=0.3)


def test_yielding_frame_reports_ductility_as_the_cli():
    scene = ROOT / "configs" / "ten-story-yielding.json"
    rec = ROOT / "records" / "I-ELC180.AT2"
    py = slipload.simulate(slipload.load_scene(str(scene), record=str(rec), scale_pga_g=0.5, duration=6.0))
    cli = cli_json("simulate", scene, "--record", rec, "--scale-pga-g", "0.5", "--duration", "6", "--format", "json")
    same_contract(py, cli)
    assert py.peak_ductility is not None and py.peak_plastic_drift is not None


def test_numpy_record_runs_as_the_file_it_came_from():
    rec_path = ROOT / "records" / "RIO270.AT2"
    from_file = slipload.read_record(str(rec_path))
    arr = slipload.record_from_array(from_file.accel, from_file.dt, name="rio")
    assert np.array_equal(arr.accel, from_file.accel)
    py = slipload.simulate(slipload.load_scene(record=arr, duration=5.0))
    cli = cli_json("simulate", "--record", rec_path, "--duration", "5", "--format", "json")
    same_contract(py, cli)


def test_a_record_in_g_is_scaled_to_si():
    a = np.array([0.0, 0.1, -0.2, 0.05])
    r = slipload.record_from_array(a, 0.01, units="g")
    assert np.array_equal(r.accel, a * 9.80665)
    assert r.pga_g == pytest.approx(0.2, rel=1e-15)


def test_only_what_is_asked_is_computed():
    bare = slipload.simulate(outputs=[])
    assert bare.energy is None and bare.history is None
    full = slipload.simulate(outputs=["histories", "energies"])
    assert full.energy is not None
    h = full.history
    assert h.array.shape == (len(h), len(h.columns))
    assert h.columns[0] == "t_s"
    assert np.array_equal(h.time, h.array[:, 0])
    assert np.array_equal(h["x1_m"], h.array[:, h.columns.index("x1_m")])
    # the peaks do not depend on what else was computed: energies on or off, the same bits;
    # histories on, the integrator's step loop that stores every step (a separate path)
    # agrees to round-off (measured 4e-17 m on 2e-2 m)
    assert np.array_equal(bare.peak_drift, slipload.simulate(outputs=["energies"]).peak_drift)
    assert np.allclose(bare.peak_drift, full.peak_drift, rtol=1e-9, atol=0)
    assert bare.peak_base_shear == pytest.approx(full.peak_base_shear, rel=1e-9)


def test_history_csv_is_the_cli_history(tmp_path):
    out = tmp_path / "h.csv"
    from conftest import run_cli

    run_cli("simulate", "--duration", "2", "--history", out)
    py = slipload.simulate(slipload.load_scene(duration=2.0), outputs=["histories", "energies"])
    assert py.history.to_csv() == out.read_text()


def test_energy_balance_closes():
    e = slipload.simulate(outputs=["energies"]).energy
    # input = kinetic + strain + viscous + friction at the end; the balance error is that
    # residual relative to the input, round-off of the step's exact energy accounting
    assert abs(e["balance_error"]) < 1e-8
    assert e["input"] == pytest.approx(e["kinetic"] + e["strain"] + e["viscous"] + e["friction"], rel=1e-8)


def test_with_slip_loads_changes_only_the_dampers():
    base = slipload.load_scene(duration=4.0)
    stiffer = base.with_slip_loads(np.array([2e6, 2e6, 2e6]))
    assert np.array_equal(stiffer.slip_loads, [2e6, 2e6, 2e6])
    assert stiffer.dt == base.dt and stiffer.duration == base.duration
    assert not np.array_equal(slipload.simulate(stiffer).peak_drift, slipload.simulate(base).peak_drift)


def test_to_pandas():
    pd = pytest.importorskip("pandas")
    h = slipload.simulate(slipload.load_scene(duration=1.0), outputs=["histories"]).history
    df = h.to_pandas()
    assert isinstance(df, pd.DataFrame)
    assert list(df.columns) == h.columns and len(df) == len(h)


def test_spectrum_and_intensity_are_the_cli_figures():
    from conftest import run_cli

    rec = ROOT / "records" / "RIO270.AT2"
    r = slipload.read_record(str(rec))
    i = r.intensity()
    assert i["pga"] == r.pga
    s = r.spectrum(periods=np.array([0.0, 0.5, 1.0]))
    assert s["psa"][0] == r.pga
    assert s["sd"].shape == (3,)
    # the CLI's `record info` reports the same PGA (to its printed digits)
    text = run_cli("record", "info", rec).stdout
    assert f"{r.pga_g:.4f}" in text or f"{r.pga_g:.3f}" in text
