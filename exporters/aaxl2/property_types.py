"""What writing a property value needs to know of its type: :class:`TypeInfo`.

:class:`TypeBuilder` turns the property types of a declarative model into :class:`TypeInfo`
(the kind of type; for units, enumeration and record types the property set declaring it, its
name as the era tables know it and its era-neutral path in the set, which is what a positional
href into the set is made of). The era tables' own view of OSATE's sets is :mod:`.osate_sets`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from pyecore.ecore import EObject

from rosaadl.importers import osate_eras
from rosaadl.model import is_a

__all__ = ["TypeInfo", "TypeBuilder", "unit_of", "type_fragment", "type_table_name"]


@dataclass(frozen=True)
class TypeInfo:
    """What writing a value needs to know of its property type (from any declarative model).

    ``kind``: ``units``, ``enum``, ``record``, ``list``, ``range``, ``number`` or ``other``.
    For units, enumeration and record types: ``set_name`` (the property set declaring it),
    ``table_name`` (its name as the era tables know it: the type's name, or the property's for
    an anonymous type, ``Record.Field`` for a field's type), ``fragment`` (its era-neutral path
    in the set) and ``names`` (literals or fields, in order). ``inner``: the element type of a
    list, the number type of a range, the units of a number; ``fields``: the field types.
    """

    kind: str
    set_name: str | None = None
    table_name: str | None = None
    fragment: str | None = None
    names: tuple[str, ...] = ()
    inner: TypeInfo | None = None
    fields: tuple[TypeInfo | None, ...] = ()
    era: str = osate_eras.CURRENT_ERA

    def index(self, name: str) -> int | None:
        wanted = name.lower()
        for position, item in enumerate(self.names):
            if item.lower() == wanted:
                return position
        return None

    @property
    def units(self) -> TypeInfo | None:
        info: TypeInfo | None = self
        for _ in range(8):
            if info is None or info.kind == "units":
                return info
            info = info.inner
        return None

    @property
    def element(self) -> TypeInfo | None:
        """The type of a list's elements (itself for anything else)."""
        return self.inner if self.kind == "list" else self

    @property
    def base(self) -> TypeInfo | None:
        """The innermost non-list type (what a named value or record is checked against)."""
        info: TypeInfo | None = self
        for _ in range(8):
            if info is None or info.kind != "list":
                return info
            info = info.inner
        return None


def unit_of(element: EObject | None) -> EObject | None:
    """The package or property set that holds ``element`` (None for a detached element)."""
    while element is not None and not is_a(element, "ModelUnit"):
        element = element.eContainer()
    return element


def type_fragment(ptype: EObject) -> str | None:
    """The era-neutral path of a property type in its property set (``@ownedPropertyType.3``,
    ``@ownedProperty.4/@ownedPropertyType/@ownedField.1/@ownedPropertyType``)."""
    owner = ptype.eContainer()
    if owner is None:
        return None
    feature = ptype.eContainmentFeature().name
    if is_a(owner, "PropertySet"):
        lists = {
            "ownedPropertyTypes": "@ownedPropertyType",
            "ownedProperties": "@ownedProperty",
            "ownedPropertyConstants": "@ownedPropertyConstant",
        }
        step = lists.get(feature)
        if step is None:
            return None
        items = getattr(owner, feature)
        position = next(i for i, item in enumerate(items) if item is ptype)
        return f"{step}.{position}"
    head = type_fragment(owner)
    if head is None:
        return None
    if feature == "ownedFields":
        position = next(i for i, item in enumerate(owner.ownedFields) if item is ptype)
        return f"{head}/@ownedField.{position}"
    step = {
        "ownedType": "@ownedPropertyType",
        "ownedUnitsType": "@ownedUnitsType",
        "ownedNumberType": "@ownedNumberType",
        "ownedElementType": "@ownedElementType",
    }.get(feature)
    return f"{head}/{step}" if step else None


def type_table_name(ptype: EObject) -> str | None:
    """The name the era tables give a type: its own, its property's, or ``Record.Field``."""
    owner = ptype.eContainer()
    if owner is None:
        return None
    if is_a(owner, "PropertySet"):
        return ptype.name
    if is_a(owner, "Property", "PropertyConstant"):
        return owner.name
    if is_a(owner, "RecordField"):
        record = owner.eContainer()
        head = type_table_name(record) if record is not None else None
        return f"{head}.{owner.name}" if head else None
    return type_table_name(owner)


class TypeBuilder:
    """Turns property types of a declarative model into :class:`TypeInfo` (cached per type)."""

    def __init__(self, resolver: Any) -> None:
        self.resolver = resolver
        self.cache: dict[int, TypeInfo | None] = {}

    def of_property(self, prop: EObject | None) -> TypeInfo | None:
        if prop is None:
            return None
        return self.of_type(self.resolver.resolved_type(prop), 0)

    def of_type(self, ptype: EObject | None, depth: int) -> TypeInfo | None:
        if ptype is None or depth > 12:
            return None
        key = id(ptype)
        if key in self.cache:
            return self.cache[key]
        self.cache[key] = None  # cyclic type names end here
        info = self._build(ptype, depth)
        self.cache[key] = info
        return info

    def _named(self, ptype: EObject, kind: str, names: tuple[str, ...], fields=()) -> TypeInfo:
        unit = unit_of(ptype)
        return TypeInfo(
            kind,
            set_name=unit.name if unit is not None else None,
            table_name=type_table_name(ptype),
            fragment=type_fragment(ptype),
            names=names,
            fields=fields,
        )

    def _build(self, ptype: EObject, depth: int) -> TypeInfo | None:
        resolver = self.resolver
        kind = ptype.eClass.name
        if kind == "UnitsType":
            return self._named(ptype, "units", tuple(lit.name or "" for lit in ptype.ownedLiterals))
        if kind == "EnumerationType":
            return self._named(ptype, "enum", tuple(lit.name or "" for lit in ptype.ownedLiterals))
        if kind == "RecordType":
            names = tuple(f.name or "" for f in ptype.ownedFields)
            fields = tuple(self.of_type(resolver.resolved_type(f), depth + 1) for f in ptype.ownedFields)
            return self._named(ptype, "record", names, fields)
        if kind == "ListType":
            inner = ptype.ownedElementType
            if inner is None:
                inner = resolver.property_type(ptype.elementType, ptype)
            return TypeInfo("list", inner=self.of_type(inner, depth + 1))
        if kind == "RangeType":
            inner = ptype.ownedNumberType
            if inner is None:
                inner = resolver.property_type(ptype.numberType, ptype)
            return TypeInfo("range", inner=self.of_type(inner, depth + 1))
        if kind in ("AadlInteger", "AadlReal"):
            units = ptype.ownedUnitsType
            if units is None and ptype.unitsType:
                units = resolver.property_type(ptype.unitsType, ptype)
            return TypeInfo("number", inner=self.of_type(units, depth + 1))
        return TypeInfo("other")
