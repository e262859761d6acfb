"""`slipload opensees` writes a design as a self-contained OpenSeesPy script; run with
openseespy, the script gives the peak drifts of slipload's `newmark` at the same time step.

Both programs solve the same discrete equations (Newmark average acceleration; each
massless damper and each yielding storey's plastic part an elastic-perfectly plastic
element, whose return mapping OpenSees's ElasticPP computes by Newton and `newmark`
solves exactly), so the peaks agree to OpenSees's Newton tolerance (1e-12 m on the
displacement correction): the issue asks for 1e-6 relative or better, and that is the
bound held here, on the benchmark building with massless dampers (full condensed frame
matrix, Rayleigh damping) and on the ten-storey yielding frame with P-Delta (modal
damping), yielding and past its collapse limit. A few seconds of each record keep it fast.
"""

import importlib.util
import json
import subprocess
import sys

import pytest

from conftest import ROOT, cli_json, run_cli

pytestmark = pytest.mark.skipif(
    importlib.util.find_spec("openseespy") is None,
    reason="openseespy is not installed (scripts/test.sh installs it)",
)

# Same scheme, same dt: the tolerance on the peak drifts (measured: about 1e-13).
TOLERANCE = 1e-6

CASES = {
    # the benchmark's condensed frame with massless dampers, 5 s of El Centro
    "benchmark": ["configs/benchmark-3story-massless.json", "--record", "records/I-ELC180.AT2", "--duration", "5", "--dt", "0.0025"],
    # the ten-storey frame at MCE (0.6 g): storeys 3 to 8 yield
    "ten-story yielding": [
        "configs/ten-story-yielding.json", "--record", "records/RSN1158_KOCAELI_DZC180.AT2",
        "--scale-pga-g", "0.6", "--window", "5s,8s", "--dt", "0.0025",
    ],
    # the same frame at 2 g: storey 1 ratchets past its collapse limit and the run stops
    "ten-story collapse": [
        "configs/ten-story-yielding.json", "--record", "records/RSN1158_KOCAELI_DZC180.AT2",
        "--scale-pga-g", "2.0", "--window", "5s,8s", "--dt", "0.0025",
    ],
}


def rel(a, b):
    return abs(a - b) / abs(b)


@pytest.mark.parametrize("case", list(CASES))
def test_opensees_runs_the_design_to_newmarks_peaks(case, tmp_path):
    scene = CASES[case]
    script = tmp_path / "design.py"
    run_cli("opensees", *scene, "--out", script)
    ran = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True)
    assert ran.returncode == 0, ran.stderr
    opensees = json.loads(ran.stdout)
    slipload = cli_json("simulate", *scene, "--method", "newmark", "--format", "json")
    assert opensees["dt"] == slipload["dt"]
    assert opensees["steps"] == slipload["steps"]
    assert opensees["retried_steps"] == []
    drift = [rel(o, s) for o, s in zip(opensees["peak_drift"], slipload["peak_drift"], strict=True)]
    shear = rel(opensees["peak_base_shear"], slipload["peak_base_shear"])
    print(f"{case}: max rel. diff. of the peak drifts {max(drift):.1e}, of the peak base shear {shear:.1e}")
    assert max(drift) <= TOLERANCE, drift
    assert shear <= TOLERANCE, shear
    if case == "ten-story yielding":
        assert max(slipload["peak_ductility"]) > 1.5, "the frame must yield for the check to cover yielding"
        assert slipload.get("collapse") is None and opensees["collapse"] is None
    if case == "ten-story collapse":
        c, o = slipload["collapse"], opensees["collapse"]
        assert (o["storey"], o["time"]) == (c["storey"], c["time"])
        assert rel(o["drift"], c["drift"]) <= TOLERANCE


def test_a_scene_it_cannot_write_is_refused_with_the_alternative(tmp_path):
    # the benchmark's dampers have mass: newmark's contact between two masses has no
    # OpenSees element; method bilinear (mass ignored) is what the script can write
    out = run_cli("opensees", "--duration", "1", "--out", tmp_path / "b.py", check=False)
    assert out.returncode != 0
    assert "mass m' = 350.11 kg" in out.stderr and "method bilinear" in out.stderr
    assert not (tmp_path / "b.py").exists()
    run_cli("opensees", "--duration", "1", "--method", "bilinear", "--out", tmp_path / "b.py")
    assert (tmp_path / "b.py").read_text().startswith("#!/usr/bin/env python3\n")
