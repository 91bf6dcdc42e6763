"""Atomic writes, contained paths and the hardened XML parser."""

from __future__ import annotations

import pytest

from rosaadl import model
from rosaadl.errors import ExportError, ImportFormatError, ValidationError
from rosaadl.fileio import atomic_write, atomic_write_text, parse_xml_bytes, safe_join


def test_atomic_write_leaves_old_file_on_failure(tmp_path) -> None:
    target = tmp_path / "out.txt"
    atomic_write_text(target, "old")
    with pytest.raises(RuntimeError), atomic_write(target, "w") as handle:
        handle.write("partial")
        raise RuntimeError("boom")
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["out.txt"]


def test_safe_join_refuses_escapes(tmp_path) -> None:
    assert safe_join(tmp_path, "a", "b.py") == tmp_path / "a" / "b.py"
    for bad in (("..", "x"), ("/etc/passwd",), ("a", "../../x")):
        with pytest.raises(ExportError, match="outside"):
            safe_join(tmp_path, *bad)


BOMB = b"""<?xml version="1.0"?>
<!DOCTYPE lolz [<!ENTITY lol "lol"><!ENTITY lol1 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
<!ENTITY lol2 "&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;">]>
<aadl:AadlModel xmlns:aadl="urn:rosaadl:aadl:1.0" name="&lol2;"/>"""
EXTERNAL = b"""<?xml version="1.0"?>
<!DOCTYPE r [<!ENTITY x SYSTEM "file:///etc/passwd">]>
<aadl:AadlModel xmlns:aadl="urn:rosaadl:aadl:1.0" name="&x;"/>"""
EXTERNAL_DTD = b"""<?xml version="1.0"?>
<!DOCTYPE r SYSTEM "http://example.invalid/r.dtd">
<aadl:AadlModel xmlns:aadl="urn:rosaadl:aadl:1.0" name="x"/>"""


@pytest.mark.parametrize(
    "data", [BOMB, EXTERNAL, EXTERNAL_DTD], ids=["entity-bomb", "external-entity", "external-dtd"]
)
def test_hostile_xml_is_refused(data: bytes) -> None:
    with pytest.raises(ImportFormatError, match="DOCTYPE|entity"):
        parse_xml_bytes(data, "evil.xmi")
    with pytest.raises(ValidationError, match="DOCTYPE|entity") as info:
        model.loads_xmi(data, "evil.xmi")
    assert info.value.location.file == "evil.xmi"


@pytest.mark.parametrize(
    ("data", "line"),
    [(b"", 1), (b"<a>\n<b>\n", 3), (b"\xff\xfe<garbage", 1), (b"<a/>trailing", 1)],
    ids=["empty", "truncated", "binary", "trailing"],
)
def test_malformed_xml_is_located(data: bytes, line: int) -> None:
    with pytest.raises(ImportFormatError) as info:
        parse_xml_bytes(data, "bad.xml")
    assert info.value.location.file == "bad.xml" and info.value.location.line == line


def test_unknown_class_and_feature_are_located() -> None:
    good = model.dumps_xmi(model.new("AadlModel", name="w", units=[model.new("AadlPackage", name="p")]))
    bad_class = good.replace(b"aadl:AadlPackage", b"aadl:AadlPakage")
    with pytest.raises(ValidationError) as info:
        model.loads_xmi(bad_class, "m.xmi")
    assert info.value.location.line == 3 and "units" in (info.value.location.path or "")
    bad_feature = good.replace(b'name="p"', b'nmae="p"')
    with pytest.raises(ValidationError, match="nmae") as info:
        model.loads_xmi(bad_feature, "m.xmi")
    assert info.value.location.line == 3
