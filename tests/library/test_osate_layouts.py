"""The library's copies of OSATE's property sets keep OSATE's layout ("order is data").

OSATE's ``.aaxl2`` files name units, enumeration literals and record fields by their position
in the property set that declares them (``ARINC653.aadl#/0/@ownedPropertyType.8/@ownedField.1``
= ``Schedule_Window.Duration``). For every property set of the library that OSATE ships (the
predeclared sets and the SEI-contributed ones), every container the current era table of
:mod:`rosaadl.importers.osate_eras` knows must sit at the same position in the library's
declaration, of the same kind, and the library's properties, and each container's literals or
fields, must start with OSATE's, in OSATE's order (the library may append declarations and
literals, never insert them).
"""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path

import pytest
from pyecore.ecore import EObject

from rosaadl.exporters.aaxl2.osate_sets import era_catalogue
from rosaadl.importers import osate_eras
from rosaadl.importers.aadl_text import library_files, read_files
from rosaadl.model import is_a

ERA = osate_eras.CURRENT_ERA
SHIPPED = [path.stem for path in library_files() if osate_eras.table(ERA).has_set(path.stem)]

#: era-table step → the list (or single reference) of aadl.ecore holding it
_LISTS = {
    "ownedPropertyType": "ownedPropertyTypes",
    "ownedProperty": "ownedProperties",
    "ownedPropertyConstant": "ownedPropertyConstants",
    "ownedField": "ownedFields",
}
_STEP = re.compile(r"@(\w+?)(?:\.(\d+))?\Z")


@cache
def _library_sets() -> dict[str, EObject]:
    model = read_files([], warnings=[])
    return {unit.name.lower(): unit for unit in model.units if is_a(unit, "PropertySet")}


def _at(unit: EObject, fragment: str) -> EObject | None:
    """The element of a property set at an era-neutral path (``@ownedProperty.3/@ownedPropertyType``)."""
    current: EObject | None = unit
    for step in fragment.split("/"):
        match = _STEP.match(step)
        assert match is not None, step
        name, number = match.group(1), match.group(2)
        if number is not None:
            items = getattr(current, _LISTS[name], None)
            current = items[int(number)] if items is not None and int(number) < len(items) else None
        else:
            current = getattr(current, "ownedType" if name == "ownedPropertyType" else name, None)
        if current is None:
            return None
    return current


def _layout(element: EObject | None) -> tuple[str, tuple[str, ...]] | None:
    """(kind, literal or field names) of an enumeration, units or record type; ("other", ())
    for another type; None for nothing."""
    if element is None:
        return None
    for kind, cls, items in (
        ("enum", "EnumerationType", "ownedLiterals"),
        ("units", "UnitsType", "ownedLiterals"),
        ("record", "RecordType", "ownedFields"),
    ):
        if is_a(element, cls):
            return kind, tuple(item.name for item in getattr(element, items))
    return "other", ()


def _differences(unit: EObject) -> list[str]:
    """Where the property set ``unit`` departs from the layout of OSATE's set of the same name."""
    name = unit.name
    table = osate_eras.table(ERA)
    osate_properties: list[str] = []
    while (found := table.property_name(name, len(osate_properties))) is not None:
        osate_properties.append(found.rpartition("::")[2].lower())
    problems = []
    ours = [prop.name.lower() for prop in unit.ownedProperties]
    if ours[: len(osate_properties)] != osate_properties:
        problems.append(f"{name}: properties {ours}, OSATE's start {osate_properties}")
    for info in era_catalogue(ERA).get(name.lower(), ()):
        layout = _layout(_at(unit, info.fragment or ""))
        osate = [n.lower() for n in info.names]
        if layout is None or layout[0] != info.kind or [n.lower() for n in layout[1][: len(osate)]] != osate:
            problems.append(
                f"{name} {info.fragment} ({info.table_name}): OSATE has {info.names}, ours {layout}"
            )
    return problems


def test_the_library_ships_osates_contributed_sets() -> None:
    contributed = {"ARINC429", "ARINC653", "Code_Generation_Properties", "Data_Model", "Physical", "SEI"}
    assert contributed <= set(SHIPPED)
    packages = {path.stem for path in library_files() if path.parent.name == "packages"}
    assert {"Base_Types", "PhysicalResources"} <= packages


@pytest.mark.parametrize("name", SHIPPED)
def test_library_set_keeps_osates_positions(name: str) -> None:
    assert _differences(_library_sets()[name.lower()]) == []


def test_the_layout_check_finds_a_moved_declaration_and_a_moved_literal(tmp_path: Path) -> None:
    arinc429 = tmp_path / "ARINC429.aadl"
    arinc429.write_text(
        "property set ARINC429 is\n  FirstBit : aadlinteger applies to (port);\n"
        "  WordID : aadlinteger applies to (port);\nend ARINC429;\n"
    )
    physical = tmp_path / "Physical.aadl"
    physical.write_text(
        "property set Physical is\n  Voltage : aadlreal units Physical::Voltage_Units applies to (all);\n"
        "  Voltage_Units : type units (uV, mV => uV * 1000);\nend Physical;\n"
    )
    model = read_files([arinc429, physical], include_library=False, warnings=[], check=False)
    units = {u.name: u for u in model.units}
    assert any("properties" in p for p in _differences(units["ARINC429"]))
    # OSATE's Voltage_Units is the set's second type; here the first and only one
    assert any("@ownedPropertyType.1" in p for p in _differences(units["Physical"]))
    library = _library_sets()
    assert _layout(_at(library["physical"], "@ownedPropertyType.0")) == ("other", ())
    deadline_type = _at(library["arinc653"], "@ownedProperty.17/@ownedPropertyType")
    assert _layout(deadline_type) == ("enum", ("soft", "hard"))
    assert _at(library["arinc653"], "@ownedProperty.0/@ownedPropertyType") is None  # a named type
