"""The types of property values, and the literals they declare.

A property, constant, record field or list element has a type, owned (``aadlinteger units
Time_Units``) or named (``AADL_Project::Time``). These functions follow named types through the
resolver's property type lookup: the element type of a list, the type of a record field, the
units of a number or range type, and the declared spelling of an enumeration literal or a unit
(``periodic`` is ``Periodic``, ``MS`` is ``ms``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from pyecore.ecore import EObject

from rosaadl.model import is_a

from .index import feature_value
from .names import lower

if TYPE_CHECKING:
    from .resolver import Resolver

__all__ = [
    "declared_type",
    "element_type",
    "element_type_once",
    "enumeration_literal",
    "record_field_type",
    "unit_literal",
    "units_type",
]

# named types are followed at most this deep (a type that names itself ends there)
_MAX_DEPTH = 16


def declared_type(resolver: Resolver, holder: EObject) -> EObject | None:
    """The ``PropertyType`` of a property, constant, record field or list element (the holder
    itself when it is a type), following a named type one step; None when unknown."""
    if is_a(holder, "PropertyType"):
        return holder
    owned = feature_value(holder, "ownedType")
    return owned if owned is not None else resolver.property_type(feature_value(holder, "type"), holder)


def element_type(resolver: Resolver, ptype: EObject | None) -> EObject | None:
    """The element type of a list type (recursively), else the type itself."""
    seen = 0
    while ptype is not None and is_a(ptype, "ListType") and seen < _MAX_DEPTH:
        ptype = element_type_once(resolver, ptype)
        seen += 1
    return ptype


def element_type_once(resolver: Resolver, ptype: EObject | None) -> EObject | None:
    """The element type of a list type (one level); any other type unchanged."""
    if ptype is not None and is_a(ptype, "ListType"):
        inner = ptype.ownedElementType
        return inner if inner is not None else resolver.property_type(ptype.elementType, ptype)
    return ptype


def record_field_type(resolver: Resolver, ptype: EObject | None, name: str | None) -> EObject | None:
    """The type of field ``name`` of a record type (lists looked through)."""
    ptype = element_type(resolver, ptype)
    if ptype is None or not is_a(ptype, "RecordType"):
        return None
    wanted = lower(name)
    for record_field in ptype.ownedFields:
        if lower(record_field.name) == wanted:
            return resolver.resolved_type(record_field)
    return None


def units_type(resolver: Resolver, ptype: EObject | None) -> EObject | None:
    """The ``UnitsType`` of a number, range or units type (None when unit-less)."""
    depth = 0
    while ptype is not None and depth < _MAX_DEPTH:
        depth += 1
        if is_a(ptype, "UnitsType"):
            return ptype
        if is_a(ptype, "RangeType"):
            inner = ptype.ownedNumberType
            ptype = inner if inner is not None else resolver.property_type(ptype.numberType, ptype)
            continue
        if is_a(ptype, "NumberType"):
            if ptype.ownedUnitsType is not None:
                return ptype.ownedUnitsType
            if ptype.unitsType:
                ptype = resolver.property_type(ptype.unitsType, ptype)
                continue
            return None
        if is_a(ptype, "ListType"):
            ptype = element_type(resolver, ptype)
            continue
        return None
    return None


def enumeration_literal(resolver: Resolver, ptype: EObject | None, name: str) -> str | None:
    """The declared spelling of enumeration literal ``name`` of ``ptype`` (lists looked through)."""
    ptype = element_type(resolver, ptype)
    if ptype is None or not is_a(ptype, "EnumerationType"):
        return None
    return _declared_spelling(ptype.ownedLiterals, name)


def unit_literal(resolver: Resolver, ptype: EObject | None, name: str) -> str | None:
    """The declared spelling of unit ``name`` in the units of ``ptype``."""
    units = units_type(resolver, ptype)
    if units is None:
        return None
    return _declared_spelling(units.ownedLiterals, name)


def _declared_spelling(literals: list[EObject], name: str) -> str | None:
    wanted = lower(name)
    for literal in literals:
        if lower(literal.name) == wanted:
            return literal.name
    return None
