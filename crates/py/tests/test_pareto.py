"""Fronts from Python: the study's objective vectors are the batch's responses reduced as
the study says; the front's tools answer hand-made sets; a study with objectives writes
the command line's files, pareto files included."""

import json

import numpy as np
import pytest

import slipload

from conftest import ROOT, run_cli

PARETO = ROOT / "configs" / "study-pareto.json"


def test_hypervolume_ranks_and_knee_of_hand_made_sets():
    pts = np.array([[1.0, 2.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]])
    # the union of [1,3]x[2,3] and [2,3]x[1,3]: 2 + 2 - 1
    assert slipload.hypervolume(pts, np.array([3.0, 3.0])) == 3.0
    assert slipload.nondominated_ranks(pts) == [1, 1, 2, 1]
    front = np.array([[0.0, 1.0], [0.1, 0.2], [1.0, 0.0]])
    assert slipload.knee(front) == 1
    with pytest.raises(slipload.InputError, match="objectives"):
        slipload.hypervolume(pts, np.array([3.0, 3.0, 3.0]))


def test_objective_vectors_are_the_batch_responses_reduced():
    study = slipload.load_study(str(PARETO))
    designs = np.array([[0.0, 0.0, 0.0], [834095.0, 740831.0, 437510.0], [2e6, 2e6, 2e6]])
    f = slipload.evaluate_objectives(study, designs, progress=False)
    assert f.shape == (3, 2)
    scene = str(ROOT / "configs" / "benchmark-3story.json")
    b = slipload.batch_designs(scene, study.records, designs, method="newmark", outputs=[], progress=False)
    drift = b["peak_drift_ratio"].max(axis=2).mean(axis=1)
    accel = b["peak_abs_acceleration"].max(axis=2).mean(axis=1)
    # the study sums the records in order, numpy pairwise: the same to round-off of a
    # ten-term mean
    assert np.allclose(f[:, 0], drift, rtol=1e-13, atol=0)
    assert np.allclose(f[:, 1], accel, rtol=1e-13, atol=0)
    # stiffer braces: less drift, more floor acceleration than the bare frame
    assert f[2, 0] < f[0, 0]


def test_a_study_without_objectives_is_refused():
    with pytest.raises(slipload.InputError, match="objectives"):
        slipload.evaluate_objectives(slipload.load_study(), np.ones((1, 3)), progress=False)


def test_optimize_with_objectives_writes_the_cli_bytes(tmp_path):
    from test_study import same_folders

    report = slipload.optimize(str(PARETO), tmp_path / "py", progress=False)
    run_cli("optimize", PARETO, "--out", tmp_path / "cli", "--quiet")
    files = same_folders(tmp_path / "py", tmp_path / "cli")
    assert "pareto.json" in files and "pareto-front.svg" in files
    assert report.pareto == json.loads((tmp_path / "py" / "pareto.json").read_text())
    assert report.pareto_table and report.pareto_table[0]["design"]
