"""The AADL text writer: names and references checked, reserved words, annex texts, access
connection categories."""

from __future__ import annotations

import logging

import pytest
from aadl_writer_models import (
    N,
    i,
    pa,
    package,
    props_text,
    tokens,
    write_unit,
)

from rosaadl.errors import ExportError
from rosaadl.importers.aadl_syntax import parse

# --------------------------------------------------------------------------- names and references


@pytest.mark.parametrize("bad", ["bad name", "1x", "a__b", "trailing_", "_x", "", "naïve", "x-y", "a::b"])
def test_invalid_feature_names_are_refused_naming_the_element(bad: str) -> None:
    t = N("ComponentType", name="cam", category="device")
    t.features.append(N("Feature", name=bad, category="data port", direction="out"))
    with pytest.raises(ExportError) as info:
        write_unit(package("hw", t))
    message = str(info.value)
    assert "a feature" in message and "hw / cam" in message
    assert info.value.location.path == "hw / cam"


def test_error_carries_the_source_line_when_known() -> None:
    t = N("ComponentType", name="cam", category="device", line=12)
    t.features.append(N("Feature", name="bad name", category="data port", direction="out", line=14, column=7))
    pkg = package("hw", t, sourceFile="hw.aadl")
    with pytest.raises(ExportError) as info:
        write_unit(pkg)
    loc = info.value.location
    assert (loc.file, loc.line, loc.column) == ("hw.aadl", 14, 7)


@pytest.mark.parametrize(
    ("element", "match"),
    [
        (N("Subcomponent", name="s", category="system", classifier="P::T..impl"), "subcomponent classifier"),
        (N("Subcomponent", name="s", category="system", classifier="A; end P;"), "subcomponent classifier"),
        (N("Subcomponent", name="s", category="system", arrayDimensions=["-1"]), "array dimension"),
        (N("Subcomponent", name="s", category="system", inModes=["m1 m2"]), "mode reference"),
        (
            N("Subcomponent", name="s", category="system", classifier="T", prototypeBindings="(x => data A"),
            "prototype",
        ),
        (
            N("Subcomponent", name="s", category="system", classifier="T", prototypeBindings="x); end P; --"),
            "prototype",
        ),
    ],
)
def test_malformed_references_are_refused(element, match: str) -> None:
    impl = N("ComponentImplementation", name="T.i", category="system")
    impl.subcomponents.append(element)
    with pytest.raises(ExportError, match=match):
        write_unit(package("P", impl))


def test_malformed_paths_are_refused() -> None:
    for path in ("a..b", "a.b[x]", "a.b; end", "a b"):
        with pytest.raises(ExportError, match="'applies to' path"):
            props_text(pa("X", i(1), appliesTo=[path]))


def test_reserved_word_names_are_written_with_a_warning(caplog: pytest.LogCaptureFixture) -> None:
    t = N("ComponentType", name="Analyse", category="process")
    t.features.append(
        N("Feature", name="data", category="event data port", direction="out", classifier="m::Scan")
    )
    with caplog.at_level(logging.WARNING, logger="rosaadl.exporters.aadl_text"):
        text = write_unit(package("P", t))
    assert "      data: out event data port m::Scan;" in text
    assert any("reserved word" in rec.getMessage() and "'data'" in rec.getMessage() for rec in caplog.records)
    parse(text, "p.aadl")


def test_annex_text_rules() -> None:
    t = N("ComponentType", name="T", category="system")
    t.annexSubclauses.append(N("AnnexSubclause", name="EMV2", text="{** use types X; **}"))
    t.annexSubclauses.append(N("AnnexSubclause", name="Other", text="\n  multi\n  line\n"))
    text = write_unit(package("P", t))
    assert "    annex EMV2 {** use types X; **};\n" in text
    assert "    annex Other {**\n  multi\n  line\n**};\n" in text
    annexes = tokens(parse(text), "ANNEX_TEXT")
    assert annexes == ["{** use types X; **}", "{**\n  multi\n  line\n**}"]
    t.annexSubclauses.append(N("AnnexSubclause", name="Bad", text="x **} end P;"))
    with pytest.raises(ExportError, match=r"cannot contain '\*\*}'"):
        write_unit(package("P", t))


def test_mode_transition_connections_have_no_text_form() -> None:
    impl = N("ComponentImplementation", name="T.i", category="system")
    impl.connections.append(
        N("Connection", name="c", kind="modeTransitionConnection", source="a", destination="b")
    )
    with pytest.raises(ExportError, match="mode transition connection has no AADL text form"):
        write_unit(package("P", impl))


def test_property_set_needs_applies_to() -> None:
    ps = N("PropertySet", name="PS", ownedProperties=[N("Property", name="X", ownedType=N("AadlBoolean"))])
    with pytest.raises(ExportError, match="applies to"):
        write_unit(ps)


def test_units_type_base_unit_rules() -> None:
    units = N("UnitsType", name="U")
    units.ownedLiterals.extend([N("UnitLiteral", name="a"), N("UnitLiteral", name="b", baseUnit="a")])
    with pytest.raises(ExportError, match="needs a base unit and a factor"):
        write_unit(N("PropertySet", name="PS", ownedPropertyTypes=[units]))


# --------------------------------------------------------------------------- access connection categories


def _access_impl(**conn):
    hw = N("ComponentType", name="board", category="system")
    cpu = N("ComponentType", name="cpu", category="processor")
    cpu.features.append(N("Feature", name="eth", category="bus access", access="requires"))
    cpu_impl = N("ComponentImplementation", name="cpu.impl", category="processor")
    shared = N("ComponentType", name="sw", category="process")
    shared.features.append(N("Feature", name="q", category="data access", access="requires"))
    impl = N("ComponentImplementation", name="board.impl", category="system")
    impl.subcomponents.extend(
        [
            N("Subcomponent", name="net", category="bus"),
            N("Subcomponent", name="c0", category="processor", classifier="cpu.impl"),
            N("Subcomponent", name="app", category="process", classifier="hw::sw"),
            N("Subcomponent", name="unknown", category="system", classifier="other::thing"),
        ]
    )
    impl.connections.append(N("Connection", name="c", kind="access", **conn))
    return package("hw", hw, cpu, cpu_impl, shared, impl)


@pytest.mark.parametrize(
    ("ends", "words"),
    [
        ({"source": "net", "destination": "c0.eth"}, "bus access"),  # a bus subcomponent
        (
            {"source": "c0.eth", "destination": "unknown.x"},
            "bus access",
        ),  # a feature of an implementation's type
        ({"source": "unknown.x", "destination": "app.q"}, "data access"),  # a feature of a qualified type
        (
            {"source": "unknown.x", "destination": "app.q", "accessCategory": "subprogram group"},
            "subprogram group access",
        ),
    ],
)
def test_access_category_is_found(ends: dict, words: str) -> None:
    ws = N("AadlModel", name="ws", units=[_access_impl(**ends)])
    text = write_unit(ws.units[0])
    assert f"      c: {words} " in text
    parse(text, "hw.aadl")


def test_unknown_access_category_is_written_bare_with_a_warning(caplog: pytest.LogCaptureFixture) -> None:
    with caplog.at_level(logging.WARNING, logger="rosaadl.exporters.aadl_text"):
        text = write_unit(_access_impl(source="unknown.x", destination="unknown.y"))
    assert "      c: access unknown.x -> unknown.y;" in text
    assert any("OSATE needs one" in rec.getMessage() for rec in caplog.records)
    parse(text, "hw.aadl")
