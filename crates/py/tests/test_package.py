"""The package as installed: its version is the workspace's, every public name is
documented and has a stub, `help` states units and defaults."""

import inspect
import pathlib
import re

import slipload

from conftest import ROOT


def test_version_is_the_workspace_version():
    text = (ROOT / "Cargo.toml").read_text()
    m = re.search(r'\[workspace\.package\][^\[]*?version\s*=\s*"([^"]+)"', text, re.S)
    assert m, "no workspace version in Cargo.toml"
    assert slipload.__version__ == m.group(1)


def test_every_public_name_is_documented():
    missing = []
    for name in slipload.__all__:
        obj = getattr(slipload, name)
        if name.isupper() or name.startswith("__"):
            continue
        if not (inspect.getdoc(obj) or "").strip():
            missing.append(name)
        if inspect.isclass(obj):
            for attr, member in vars(obj).items():
                if attr.startswith("_"):
                    continue
                if not (getattr(member, "__doc__", None) or "").strip():
                    missing.append(f"{name}.{attr}")
    assert not missing, f"undocumented: {missing}"


def test_every_public_name_has_a_stub():
    here = pathlib.Path(slipload.__file__).parent
    stubs = (here / "_slipload.pyi").read_text()
    # the pure-Python modules are typed in place
    init = (here / "__init__.py").read_text() + (here / "_errors.py").read_text()
    for name in slipload.__all__:
        if name.startswith("__"):
            continue
        declared = re.search(rf"^(class|def) {name}\b", stubs, re.M) or re.search(
            rf"^(class|def) {name}\b|^{name}\s*[:=]", init, re.M
        )
        assert declared, f"{name}: neither typed in __init__.py nor stubbed in _slipload.pyi"
    assert (pathlib.Path(slipload.__file__).parent / "py.typed").exists()


def test_help_says_units_and_defaults():
    doc = inspect.getdoc(slipload.simulate)
    for words in ["m/s²", "N", "default", "histories", "energies", "newmark"]:
        assert words in doc, words
    doc = inspect.getdoc(slipload.batch_designs)
    assert "(designs, records, storeys)" in doc
