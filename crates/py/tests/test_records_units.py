"""Issue 40 §2, records from Python: a CSV with a byte-order mark keeps its first sample;
a column header that states its unit is read in it, and units that contradict it are
refused naming the file and line; units that override an AT2 title's unit warn (and the
record's notes say so); a record tells by what factor it was scaled."""

import warnings

import numpy as np
import pytest

import slipload

from conftest import ROOT


def test_a_byte_order_mark_keeps_the_first_sample(tmp_path):
    p = tmp_path / "bom.csv"
    p.write_bytes("\ufeff0.1\n0.2\n0.3\n".encode())
    r = slipload.read_record(p, dt=0.01)
    assert np.array_equal(r.accel, [0.1, 0.2, 0.3])


def test_a_header_in_g_is_read_in_g(tmp_path):
    p = tmp_path / "g.csv"
    p.write_text("time_s,accel_g\n0,0.1\n0.01,-0.25\n0.02,0.05\n")
    r = slipload.read_record(p)
    assert r.pga_g == pytest.approx(0.25, rel=1e-15)
    assert slipload.read_record(p, units="g").pga == r.pga
    with pytest.raises(slipload.InputError) as e:
        slipload.read_record(p, units="m/s2")
    assert f"{p}:1: the header `time_s,accel_g` says the values are in g" in str(e.value)


def test_units_that_override_an_at2_title_warn():
    path = ROOT / "records" / "SYL090.AT2"
    with pytest.warns(UserWarning, match="values read in cm/s2 as given, not in g"):
        r = slipload.read_record(path, units="cm/s2")
    assert len(r.notes) == 1 and "UNITS OF G" in r.notes[0]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        plain = slipload.read_record(path)
    assert plain.notes == []
    assert r.pga == pytest.approx(plain.pga * 0.01 / 9.80665, rel=1e-12)


def test_a_record_tells_its_scale_factor():
    r = slipload.read_record(ROOT / "records" / "SYL090.AT2")
    assert r.scale_factor == 1.0
    s = r.scaled_to_pga(0.3)
    assert s.pga_g == pytest.approx(0.3, rel=1e-15)
    assert s.pga / s.scale_factor == pytest.approx(r.pga, rel=1e-12)
    assert s.scaled(2.0).scale_factor == pytest.approx(2.0 * s.scale_factor, rel=1e-15)
