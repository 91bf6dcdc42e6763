"""OSATE's own property sets, as the era tables and this project's library know them.

A value of a property of OSATE's sets (``Timing_Properties``, ``SEI``, ...) is written with
positional hrefs into OSATE's copy of the set. When the model does not declare the property
(after reading an ``.aaxl2`` file, say), its type comes from the library's declaration of the
set (:func:`library_property_types`) or from the era tables themselves (:func:`era_catalogue`:
every enumeration, units and record type of each set, found by probing the tables), searched
by the literal or field names a value uses (:func:`era_search`). A value that only exists in an
older layout of a set (a property OSATE has since renamed) is looked up in :func:`older_eras`.
"""

from __future__ import annotations

import functools
import logging
from types import MappingProxyType
from typing import Any

from rosaadl.errors import RosaadlError
from rosaadl.importers import osate_eras
from rosaadl.model import is_a

from .property_types import TypeBuilder, TypeInfo
from .vocabulary import ERA, OSATE_PACKAGES

__all__ = [
    "osate_set",
    "osate_unit",
    "library_property_types",
    "era_catalogue",
    "era_units",
    "older_eras",
    "era_search",
    "era_property",
]

log = logging.getLogger(__package__)


def osate_set(name: str | None) -> bool:
    """Is ``name`` one of the property sets OSATE ships (written as platform references)?"""
    return bool(name) and osate_eras.table(ERA).has_set(name or "")


def osate_unit(name: str | None) -> bool:
    return osate_set(name) or (name or "").lower() in OSATE_PACKAGES


@functools.cache
def library_property_types() -> MappingProxyType:
    """Qualified property name (lower case) → :class:`TypeInfo`, for OSATE's property sets as
    this project's library declares them (used when a model does not hold them, as after
    reading an ``.aaxl2`` file). Built once from the library's files; immutable."""
    from rosaadl.importers.aadl_text import library_files, read_files
    from rosaadl.resolution import Resolver

    files = [p for p in library_files() if osate_set(p.stem)]
    try:
        library = read_files(files, include_library=False, warnings=[])
    except RosaadlError as exc:  # the era tables still answer for OSATE's sets
        log.warning("the library's property sets do not read (%s); using the OSATE era tables only", exc)
        return MappingProxyType({})
    builder = TypeBuilder(Resolver(library))
    table: dict[str, TypeInfo | None] = {}
    for unit in library.units:
        if not is_a(unit, "PropertySet"):
            continue
        for prop in unit.ownedProperties:
            table[f"{unit.name}::{prop.name}".lower()] = builder.of_property(prop)
    return MappingProxyType(table)


def _probe_container(tab: Any, set_name: str, path: str) -> TypeInfo | None:
    """The enumeration, units or record type at ``path`` of an OSATE property set, per the era table."""
    first = tab.literal(set_name, f"{path}/@ownedLiteral.0") or tab.literal(set_name, f"{path}/@ownedField.0")
    if first is None:
        return None
    step = "@ownedField" if first.kind == "field" else "@ownedLiteral"
    names: list[str] = []
    while (entry := tab.literal(set_name, f"{path}/{step}.{len(names)}")) is not None:
        names.append(entry.name)
    kind = {"field": "record", "enum": "enum", "units": "units"}[first.kind]
    table_name = first.type_name.rpartition("::")[2]
    return TypeInfo(
        kind, set_name=first.property_set, table_name=table_name, fragment=path, names=tuple(names)
    )


@functools.cache
def era_catalogue(era: str = osate_eras.CURRENT_ERA) -> MappingProxyType:
    """Property set name (lower case) → the enumeration, units and record types of OSATE's copy of
    it in ``era``, read off the era tables (immutable, built once). Record types carry their
    fields' types where the tables know them: an anonymous field type, the units of its numbers,
    or an ``era`` marker for a named type (whose literals are then looked up by name)."""
    tab = osate_eras.table(era)
    catalogue: dict[str, tuple[TypeInfo, ...]] = {}
    nested = ("/@ownedElementType", "/@ownedUnitsType", "/@ownedNumberType")
    for set_name in tab.property_sets():
        count = 0
        while tab.property_name(set_name, count) is not None:
            count += 1
        bases = [f"@ownedPropertyType.{n}" for n in range(128)]
        bases += [f"@ownedProperty.{n}/@ownedPropertyType" for n in range(count)]
        bases += [f"@ownedPropertyConstant.{n}/@ownedPropertyType" for n in range(32)]
        queue = bases + [base + step for base in bases for step in nested]
        queue += [base + step + "/@ownedUnitsType" for base in bases for step in nested[::2]]
        found: list[TypeInfo] = []
        while queue:
            path = queue.pop()
            info = _probe_container(tab, set_name, path)
            if info is not None:
                found.append(info)
                if info.kind == "record":
                    queue += [f"{path}/@ownedField.{k}/@ownedPropertyType" for k in range(len(info.names))]
        found.sort(key=lambda i: i.fragment or "")
        by_name = {(i.table_name or "").lower(): i for i in found}
        linked = []
        for info in found:
            if info.kind == "record":
                fields: list[TypeInfo | None] = []
                for position, name in enumerate(info.names):
                    inner = by_name.get(f"{info.table_name}.{name}".lower())
                    if inner is None:
                        entry = tab.literal(set_name, f"{info.fragment}/@ownedField.{position}")
                        units = entry.units if entry is not None else None
                        if units:
                            inner = TypeInfo("number", inner=era_units(units, era))
                        else:  # a named type: its literals are looked up by name in the set
                            inner = TypeInfo("era", set_name=info.set_name, table_name=name, era=era)
                    fields.append(inner)
                info = TypeInfo(
                    "record",
                    info.set_name,
                    info.table_name,
                    info.fragment,
                    info.names,
                    fields=tuple(fields),
                    era=era,
                )
            linked.append(info)
        catalogue[set_name.lower()] = tuple(linked)
    return MappingProxyType(catalogue)


@functools.cache
def era_units(qualified: str | None, era: str = osate_eras.CURRENT_ERA) -> TypeInfo | None:
    """The units type ``Set::Name`` of OSATE's property sets in ``era``, as a :class:`TypeInfo`."""
    if not qualified:
        return None
    set_name, _, local = qualified.rpartition("::")
    tab = osate_eras.table(era)
    for path in [f"@ownedPropertyType.{n}" for n in range(128)]:
        info = _probe_container(tab, set_name, path)
        if info is not None and info.kind == "units" and (info.table_name or "").lower() == local.lower():
            return info
    return None


def older_eras(set_name: str) -> list[str]:
    """Older eras whose copy of ``set_name`` OSATE finds under the same URI as today's (the
    SEI-contributed sets), newest first: a value of a property OSATE has since renamed can
    still be written in the layout of the set that had it."""
    current = osate_eras.predeclared_uri(osate_eras.CURRENT_ERA, set_name)
    out = []
    for era in reversed(osate_eras.ERAS[:-1]):
        if osate_eras.table(era).has_set(set_name) and osate_eras.predeclared_uri(era, set_name) == current:
            out.append(era)
    return out


def era_search(
    kind: str, names: tuple[str, ...], sets: tuple[str, ...], era: str = osate_eras.CURRENT_ERA
) -> TypeInfo | None:
    """The one ``kind`` type (enum, units, record) of OSATE's sets holding every literal or field
    of ``names``, looking in ``sets`` in order (each set, then all sets); None when none or
    several do."""
    catalogue = era_catalogue(era)
    wanted = {n.lower() for n in names}
    for group in [(s,) for s in sets] + [tuple(catalogue)]:
        hits = [
            info
            for set_name in group
            for info in catalogue.get(set_name.lower(), ())
            if info.kind == kind and wanted <= {n.lower() for n in info.names}
        ]
        if len(hits) == 1:
            return hits[0]
        if len(hits) > 1:
            return None
    return None


def era_property(qualified: str) -> TypeInfo | None:
    """What the era tables tell of the type of a property of OSATE's sets not declared anywhere:
    its anonymous type when it has one, else the units of its numbers, else an ``era`` marker
    (enumeration literals and record fields are then found by name in the set's types)."""
    set_name, _, local = qualified.rpartition("::")
    if not osate_set(set_name):
        return None
    for info in era_catalogue().get(set_name.lower(), ()):
        if (info.table_name or "").lower() == local.lower():
            return info
    units = era_units(osate_eras.table(ERA).property_units(qualified))
    if units is not None:
        return TypeInfo("number", inner=units)
    return TypeInfo("era", set_name=set_name, table_name=local)
