"""The AADL text writer: deterministic text, file names, atomic and confined writes."""

from __future__ import annotations

from pathlib import Path

import pytest
from aadl_writer_models import (
    N,
    everything_model,
    i,
    pa,
    package,
    write_unit,
    write_units,
)

from rosaadl import model
from rosaadl.errors import ExportError
from rosaadl.exporters.aadl_text import unit_file_name, write_model
from rosaadl.importers.aadl_syntax import parse

# --------------------------------------------------------------------------- determinism and text hygiene


def test_deterministic_and_clean_text(tmp_path: Path) -> None:
    ws = everything_model()
    first = write_units(ws.units)
    assert write_units(ws.units) == first
    reloaded = model.loads_xmi(model.dumps_xmi(ws))
    assert write_units(reloaded.units) == first
    reloaded_json = model.loads_json(model.dumps_json(ws))
    assert write_units(reloaded_json.units) == first
    for text in first.values():
        assert text.endswith("\n") and not text.endswith("\n\n")
        for line in text.splitlines():
            assert line == line.rstrip(), repr(line)
            assert "\t" not in line
            indent = len(line) - len(line.lstrip(" "))
            assert indent % 2 == 0, repr(line)


def test_same_model_built_in_another_order_gives_the_same_text() -> None:
    a = N("Feature", name="p", category="data port", direction="out", classifier="D")
    b = N("Feature", classifier="D", direction="out", category="data port", name="p")
    ta = write_unit(package("P", N("ComponentType", name="T", category="thread", features=[a])))
    tb = write_unit(package("P", N("ComponentType", category="thread", features=[b], name="T")))
    assert ta == tb


# --------------------------------------------------------------------------- files


def test_unit_file_names() -> None:
    assert unit_file_name(N("AadlPackage", name="ros::nodes::cam")) == "ros-nodes-cam.aadl"
    assert unit_file_name(N("PropertySet", name="SEI")) == "SEI.aadl"
    with pytest.raises(ExportError):
        unit_file_name(N("PropertySet", name="A::B"))


def test_write_model_writes_atomically(tmp_path: Path) -> None:
    ws = everything_model()
    out = tmp_path / "out"
    paths = write_model(ws, out)
    assert [p.name for p in paths] == ["robot-nav.aadl", "Nav_Props.aadl"]
    texts = write_units(ws.units)
    for path in paths:
        assert path.parent == out
        assert path.read_text(encoding="utf-8") == texts[path.name]
    assert sorted(p.name for p in out.iterdir()) == ["Nav_Props.aadl", "robot-nav.aadl"]  # no temporary files
    again = write_model(ws, out)
    assert [p.read_bytes() for p in again] == [p.read_bytes() for p in paths]


@pytest.mark.parametrize(
    "hostile", ["../../etc", "/etc/passwd", "..", "a/../../b", "a::..::b", "C:\\x", "x.aadl"]
)
def test_hostile_unit_names_never_escape(tmp_path: Path, hostile: str) -> None:
    out = tmp_path / "deep" / "out"
    ws = N("AadlModel", name="ws", units=[N("AadlPackage", name="good"), N("AadlPackage", name=hostile)])
    before = sorted(str(p) for p in tmp_path.rglob("*"))
    with pytest.raises(ExportError, match="not an AADL package name"):
        write_model(ws, out)
    assert sorted(str(p) for p in tmp_path.rglob("*")) == before  # nothing written, not even 'good'


def test_error_in_a_later_unit_leaves_no_output(tmp_path: Path) -> None:
    bad = N("ComponentType", name="bad name", category="system")
    ws = N("AadlModel", name="ws", units=[package("first"), package("second", bad)])
    with pytest.raises(ExportError):
        write_model(ws, tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_case_insensitive_duplicates_are_refused(tmp_path: Path) -> None:
    ws = N("AadlModel", name="ws", units=[package("Nodes"), package("nodes")])
    with pytest.raises(ExportError, match="case-insensitive"):
        write_model(ws, tmp_path)
    assert list(tmp_path.iterdir()) == []


def test_write_model_rejects_other_objects(tmp_path: Path) -> None:
    with pytest.raises(ExportError, match="expected an AadlModel"):
        write_model(N("SystemInstance", name="x"), tmp_path)
    with pytest.raises(ExportError, match="expected an AadlPackage or a PropertySet"):
        write_unit(N("ComponentType", name="T", category="system"))


def test_huge_package_is_written_quickly() -> None:
    pkg = package("big")
    for n in range(2000):
        t = N("ComponentType", name=f"t{n}", category="thread")
        t.features.append(N("Feature", name="p", category="data port", direction="out", classifier="D"))
        t.ownedPropertyAssociations.append(pa("Period", i(n + 1, "ms")))
        pkg.classifiers.append(t)
    text = write_unit(pkg)
    assert text.count("  end t") == 2000
    tree = parse(text, "big.aadl")
    assert len(list(tree.find_data("component_type"))) == 2000
