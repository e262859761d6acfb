"""The script `slipload opensees` writes never runs what a user wrote.

User text reaches the script through four carriers: the scene's name, the building's name,
the record's path and the title lines of an AT2 record. Each carrier is given hostile text
(PEP 263 encoding declarations, among them `unicode_escape`, which would turn an escaped
newline into a real one; quotes, triple quotes, backslashes, newlines, NUL, non-ASCII
letters, a Unicode line separator, and a line of Python that writes a marker file), the
script is run with openseespy, and the test checks that no marker file appeared, that the
script ran to its JSON and that every name comes back exactly as written.
"""

import importlib.util
import json
import pathlib
import subprocess
import sys

import pytest

from conftest import ROOT, run_cli

pytestmark = pytest.mark.skipif(
    importlib.util.find_spec("openseespy") is None,
    reason="openseespy is not installed (scripts/test.sh installs it)",
)

MARKER = "PWNED"
# a line of code that, if it ever ran, would leave the marker file in the working folder
PAYLOAD = f"__import__('pathlib').Path('{MARKER}').write_text('ran')"

HOSTILE = {
    "unicode_escape cookie": f"# -*- coding: unicode_escape -*-\\n{PAYLOAD}\\n#",
    "latin-1 cookie": "# vim: set fileencoding=latin-1 : \u00e9\u00e8",
    "utf-16 cookie": "coding=utf-16 \u5730\u9707",
    "newline then code": f"x\n{PAYLOAD}\n",
    "carriage return then code": f"x\r{PAYLOAD}\r",
    "quotes": f"\"); {PAYLOAD}; (\"",
    "triple quotes": f"\"\"\"\n{PAYLOAD}\n'''",
    "backslashes": f"a\\\\\" + {PAYLOAD} + \"\\",
    "NUL and controls": f"a\x00b\x07\x1b[31m\x7f {PAYLOAD}",
    "non-ASCII": "Ko\u00e7aeli \u00e9 \u5730\u9707 \U0001f600 \u2028 \u0085 end",
}
# A path cannot hold NUL or '/' and an AT2 line ends at a newline: the carriers that cannot
# take a character say so, and take the rest of the text.
NO_NUL = {"record path", "AT2 title"}


def carried(carrier: str, text: str) -> str:
    if carrier in NO_NUL:
        text = text.replace("\x00", "")
    if carrier == "record path":
        text = text.replace("/", "|")
    if carrier == "AT2 title":
        text = text.replace("\r", " ").replace("\n", " ").replace("\x85", " ").replace("\u2028", " ")
    return text


def building_json(name: str) -> dict:
    building = json.loads((ROOT / "configs" / "benchmark-3story-massless.json").read_text())
    building["name"] = name
    return building


def at2_with_title(source: pathlib.Path, title: str) -> str:
    lines = source.read_text().splitlines()
    # the PEER header: three title lines, then NPTS/DT
    return "\n".join([lines[0], title, lines[2], *lines[3:]]) + "\n"


@pytest.mark.parametrize("case", list(HOSTILE))
@pytest.mark.parametrize("carrier", ["scene name", "building name", "record path", "AT2 title"])
def test_hostile_text_on_every_carrier_is_data(carrier, case, tmp_path):
    text = carried(carrier, HOSTILE[case])
    source = ROOT / "records" / "I-ELC180.AT2"
    record = tmp_path / "record.AT2"
    if carrier == "record path":
        record = tmp_path / f"rec {text}.AT2"
    record.write_bytes(
        (at2_with_title(source, text) if carrier == "AT2 title" else source.read_text()).encode("utf-8")
    )
    (tmp_path / "building.json").write_text(
        json.dumps(building_json(text if carrier == "building name" else "plain building")),
        encoding="utf-8",
    )
    scene = {
        "name": text if carrier == "scene name" else "plain scene",
        "building": "building.json",
        "excitation": {"record": {"file": record.name, "window": [0, 1]}},
        "method": {"name": "newmark", "dt": 0.005},
    }
    (tmp_path / "scene.json").write_text(json.dumps(scene), encoding="utf-8")
    script = tmp_path / "design.py"
    run_cli("opensees", tmp_path / "scene.json", "--out", script)
    assert script.read_bytes().isascii()
    work = tmp_path / "run"
    work.mkdir()
    ran = subprocess.run([sys.executable, str(script)], cwd=work, capture_output=True, text=True)
    assert not (work / MARKER).exists(), "the script ran text from a name"
    assert ran.returncode == 0, ran.stderr
    out = json.loads(ran.stdout)
    assert out["steps"] == 200
    if carrier == "scene name":
        assert out["scene"] == text
    if carrier == "building name":
        assert out["building"] == text
    if carrier == "record path":
        assert out["record"] == str(record)
    if carrier == "AT2 title":
        assert text.strip() in out["record_provenance"]
