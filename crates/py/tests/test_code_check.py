"""A study with property bounds and limits from Python: the same keys as a study file,
the code check as a dict and a DataFrame, the verdict, and the same files as the command
line (which exits with code 3 when no design meets the limits)."""

import json

import pytest

import slipload

from conftest import ROOT, run_cli


def study(drift_limit):
    """The benchmark building on 2 short synthetic records, a short sweep and refinement,
    slip loads x 0.8 and x 1.25, a mean drift limit and no unacceptable response."""
    return {
        "name": "check-from-python",
        "building": str(ROOT / "configs" / "benchmark-3story.json"),
        "suites": [
            {
                "name": "syn",
                "synthetic": {"count": 2, "seed": 2007, "pga_g": 0.4, "duration_s": 4.0},
                "limits": {
                    "criteria": [{"metric": "peak_drift_ratio", "statistic": "mean", "max": drift_limit}],
                    "unacceptable": {"max_count": 0},
                },
            }
        ],
        "property_bounds": {"slip_load": {"lower": 0.8, "upper": 1.25}, "objective_reads": "worst"},
        "space": {"free": {"lower_kn": [0, 0, 0], "upper_kn": [2000, 2000, 2000]}},
        "objective": {"terms": [{"metric": "peak_drift_ratio", "statistic": "mean"}]},
        "fidelity": {"method": "newmark", "check_method": "newmark", "check_dt_factor": 0.5},
        "sweep": {"sampler": "halton", "points": 6, "seed": 2007},
        "refine": {"method": "trust-region", "starts": 1, "max_evaluations": 4, "finalists": 2},
    }


def test_the_check_of_a_passing_design_as_a_dataframe(tmp_path):
    report = slipload.optimize(study(0.012), tmp_path / "py")
    assert report.passes is True
    check = report.code_check
    assert check["verdict"].startswith("PASS")
    lines = check["check"]["lines"]
    # one criterion and the count, at each of the three property cases
    assert [(l["case"], l["criterion"]) for l in lines] == [
        (case, crit)
        for case in ("nominal", "lower", "upper")
        for crit in ("mean peak_drift_ratio", "unacceptable responses")
    ]
    assert all(l["demand"] <= l["limit"] for l in lines)
    pd = pytest.importorskip("pandas")
    frame = report.check_frame()
    assert isinstance(frame, pd.DataFrame)
    assert list(frame["source"].unique()) == ["suites[0].limits.criteria[0]", "suites[0].limits.unacceptable"]
    assert bool(frame["pass"].all())


def test_no_passing_design_is_a_verdict_not_an_error(tmp_path):
    spec = study(0.001)
    report = slipload.optimize(spec, tmp_path / "py")
    assert report.passes is False
    assert report.code_check["verdict"].startswith("FAIL")
    # the command line writes the same check and exits with 3
    path = tmp_path / "study.json"
    path.write_text(json.dumps(spec))
    out = run_cli("--quiet", "optimize", path, "--out", tmp_path / "cli", check=False)
    assert out.returncode == 3, out.stderr
    assert "no evaluated design meets the study's limits" in out.stderr
    assert (tmp_path / "cli" / "code-check.json").read_text() == (tmp_path / "py" / "code-check.json").read_text()


def test_the_submittal_keys_from_python_give_the_command_lines_files(tmp_path):
    """A risk category, a rest after the records and a test protocol: Python takes the
    study file's keys and writes the command line's bytes; the compliance matrix and the
    test protocol come back as DataFrames."""
    spec = study(0.012)
    spec["risk_category"] = "III"
    del spec["suites"][0]["limits"]["unacceptable"]
    spec["suites"][0]["free_vibration_s"] = 5
    spec["devices"] = {"brace_angle_deg": 40, "test_protocol": {"cycles": 5, "band_percent": 15}}
    report = slipload.optimize(spec, tmp_path / "py")
    path = tmp_path / "study.json"
    path.write_text(json.dumps(spec))
    out = run_cli("--quiet", "optimize", path, "--out", tmp_path / "cli", check=False)
    assert out.returncode == report_code(report), out.stderr
    for name in ("code-check.json", "device-table.json"):
        assert (tmp_path / "cli" / name).read_text() == (tmp_path / "py" / name).read_text()
    # risk category III with two records: no unacceptable response allowed
    counts = [l for l in report.code_check["check"]["lines"] if l["criterion"] == "unacceptable responses"]
    assert counts and all(l["limit"] == 0 for l in counts)
    pd = pytest.importorskip("pandas")
    matrix = report.compliance_frame()
    assert "§16.4.1.1" in set(matrix["clause"])
    assert set(matrix["status"]) <= {"pass", "fail", "stated", "not_checked", "not_covered"}
    tests = report.protocol_frame()
    assert list(tests.index) == [1, 2, 3]
    assert bool((tests["force_kn_lower"] < tests["force_kn_nominal"]).all())


def report_code(report):
    """The command line's exit code for a report: 0 when the design passes, 3 when none does."""
    return 0 if report.passes else 3
