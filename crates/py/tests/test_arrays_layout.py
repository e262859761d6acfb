"""Issue 40 §2: every function that takes an array reads it as numpy shows it, whatever
its memory order. A Fortran-ordered array or a transposed view (both contiguous, but not
row by row) gives the same designs and points as the C-ordered array; a strided view is
refused with an InputError that names the parameter."""

import numpy as np
import pytest

import slipload

from conftest import ROOT

PARETO = ROOT / "configs" / "study-pareto.json"


def layouts(a):
    """The same logical array as C order, Fortran order and a transposed view."""
    a = np.ascontiguousarray(a, dtype=float)
    fortran = np.asfortranarray(a)
    transposed = np.ascontiguousarray(a.T).T
    assert not fortran.flags.c_contiguous and not transposed.flags.c_contiguous
    for x in (fortran, transposed):
        assert np.array_equal(x, a)
    return {"C": a, "Fortran": fortran, "transposed": transposed}


# points whose memory order, read row by row, is another set with other answers
POINTS = np.array([[1.0, 4.0], [2.0, 3.0], [3.0, 1.0], [4.0, 5.0]])
FRONT = np.array([[0.0, 1.0], [0.1, 0.2], [1.0, 0.0]])


@pytest.mark.parametrize("name", ["Fortran", "transposed"])
def test_front_tools_read_rows_as_numpy_shows_them(name):
    reference = np.array([5.0, 6.0])
    want_hv = slipload.hypervolume(POINTS, reference)
    assert slipload.nondominated_ranks(POINTS) == [1, 1, 1, 2]
    assert slipload.knee(FRONT) == 1
    x = layouts(POINTS)[name]
    assert slipload.nondominated_ranks(x) == [1, 1, 1, 2]
    assert slipload.hypervolume(x, reference) == want_hv
    assert slipload.knee(layouts(FRONT)[name]) == 1


@pytest.fixture(scope="module")
def suite():
    return slipload.synthetic_suite(count=2, duration=3.0)


@pytest.mark.parametrize("name", ["Fortran", "transposed"])
def test_batch_designs_runs_the_designs_the_rows_name(suite, name):
    designs = np.array([[0.0, 0.0, 0.0], [5e5, 4e5, 2e5]])
    scene = slipload.load_scene()
    want = slipload.batch_designs(scene, suite, designs, progress=False)
    got = slipload.batch_designs(scene, suite, layouts(designs)[name], progress=False)
    for k in ["peak_drift", "peak_slip", "peak_base_shear"]:
        assert np.array_equal(got[k], want[k]), k
    # design 0 is the bare frame: no slip at all
    assert np.all(got["peak_slip"][0] == 0.0)


def test_evaluate_objectives_scores_the_designs_the_rows_name():
    study = slipload.load_study(str(PARETO))
    designs = np.array([[0.0, 0.0, 0.0], [834095.0, 740831.0, 437510.0]])
    want = slipload.evaluate_objectives(study, designs, progress=False)
    for name in ["Fortran", "transposed"]:
        got = slipload.evaluate_objectives(study, layouts(designs)[name], progress=False)
        assert np.array_equal(got, want), name


def test_a_strided_view_is_refused_naming_the_parameter():
    points = np.vstack([POINTS, POINTS])[::2]
    assert not points.flags.c_contiguous and not points.flags.f_contiguous
    for call in (
        lambda: slipload.nondominated_ranks(points),
        lambda: slipload.knee(points),
        lambda: slipload.hypervolume(points, np.array([5.0, 6.0])),
    ):
        with pytest.raises(slipload.InputError, match=r"^points: the array is not contiguous"):
            call()
    loads = np.full((2, 6), 1e5)[:, ::2]
    assert not loads.flags.c_contiguous and not loads.flags.f_contiguous
    suite = slipload.synthetic_suite(count=1, duration=1.0)
    with pytest.raises(slipload.InputError, match=r"^slip_loads: the array is not contiguous"):
        slipload.batch_designs(slipload.load_scene(), suite, loads, progress=False)
