"""The units of an ``AadlModel`` by name, and where each element stands among them.

:class:`UnitIndex` reads the packages and property sets of a model once, case-insensitively as
AADL names are: the classifiers of each package and the properties, property types and constants
of each property set, by name. It answers which unit holds an element, the qualified name of an
element (``Pkg::T.impl``, ``Set::Name``) and its location (file of its unit, line, column, model
path) for diagnostics. A second unit of the same name is kept aside as a duplicate.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.errors import Location
from rosaadl.model import is_a

from .names import lower, squeeze

__all__ = ["UnitIndex", "feature_value", "visible_packages"]

#: The kinds of property set members, as :meth:`UnitIndex.set_members` keys them.
SET_MEMBER_KINDS = ("property", "type", "constant")


class UnitIndex:
    """The packages and property sets of one model, with their members, by lower-case name."""

    def __init__(self, model: EObject) -> None:
        #: units by lower-case name (the first of each name)
        self.by_name: dict[str, EObject] = {}
        #: units whose name an earlier unit already has
        self.duplicates: list[EObject] = []
        # by id(package): classifiers by lower-case name; by id(property set): members by kind
        self._classifiers: dict[int, dict[str, EObject]] = {}
        self._members: dict[int, dict[str, dict[str, EObject]]] = {}
        self._unit_of: dict[int, EObject | None] = {}
        for unit in getattr(model, "units", ()):
            key = lower(unit.name)
            if not key:
                continue
            if key in self.by_name:
                self.duplicates.append(unit)
                continue
            self.by_name[key] = unit
            if is_a(unit, "AadlPackage"):
                table: dict[str, EObject] = {}
                for classifier in unit.classifiers:
                    table.setdefault(lower(classifier.name), classifier)
                self._classifiers[id(unit)] = table
            elif is_a(unit, "PropertySet"):
                members: dict[str, dict[str, EObject]] = {kind: {} for kind in SET_MEMBER_KINDS}
                for prop in unit.ownedProperties:
                    members["property"].setdefault(lower(prop.name), prop)
                for ptype in unit.ownedPropertyTypes:
                    members["type"].setdefault(lower(ptype.name), ptype)
                for const in unit.ownedPropertyConstants:
                    members["constant"].setdefault(lower(const.name), const)
                self._members[id(unit)] = members

    def unit(self, name: str | None) -> EObject | None:
        """The package or property set called ``name`` (case-insensitive, spaces ignored)."""
        return self.by_name.get(squeeze(name).lower())

    def classifiers(self, package: EObject | None) -> dict[str, EObject]:
        """The classifiers of a package by lower-case name (empty for anything else)."""
        return self._classifiers.get(id(package), {})

    def set_members(self, unit: EObject | None) -> dict[str, dict[str, EObject]] | None:
        """The members of a property set by kind then lower-case name; None for anything else."""
        return self._members.get(id(unit))

    def unit_of(self, element: EObject | None) -> EObject | None:
        """The package or property set that contains ``element`` (itself for a unit)."""
        if element is None:
            return None
        key = id(element)
        if key in self._unit_of:
            return self._unit_of[key]
        current = element
        found = None
        while current is not None:
            if is_a(current, "ModelUnit"):
                found = current
                break
            current = current.eContainer()
        self._unit_of[key] = found
        return found

    def qualified_name(self, element: EObject) -> str:
        """``Pkg::T.impl`` for a classifier, ``Set::Name`` for a property/type/constant."""
        unit = self.unit_of(element)
        name = getattr(element, "name", None) or ""
        if unit is None or unit is element:
            return name
        owner = element.eContainer()
        if owner is unit:
            return f"{unit.name}::{name}"
        return f"{self.qualified_name(owner)}.{name}" if owner is not None else name

    def location(self, element: EObject | None, path: str | None = None) -> Location:
        """file:line:column of an element (from its unit's ``sourceFile``) and a model path."""
        if element is None:
            return Location(path=path)
        unit = self.unit_of(element)
        file = getattr(unit, "sourceFile", None) if unit is not None else None
        line = feature_value(element, "line")
        column = feature_value(element, "column")
        return Location(
            file=file or None,
            line=line or None,
            column=column or None,
            path=path if path is not None else self._element_path(element),
        )

    def _element_path(self, element: EObject) -> str:
        parts = []
        current = element
        while current is not None and not is_a(current, "ModelUnit", "AadlModel"):
            name = getattr(current, "name", None)
            if name:
                parts.append(name)
            current = current.eContainer()
        unit = current if current is not None and is_a(current, "ModelUnit") else None
        text = ".".join(reversed(parts))
        if unit is not None:
            return f"{unit.name}::{text}" if text else str(unit.name)
        return text


def visible_packages(unit: EObject) -> list[str]:
    """The names a unit's ``with`` clauses (public then private) make visible, as written."""
    withs = list(getattr(unit, "withs", ()) or ())
    withs.extend(getattr(unit, "privateWiths", ()) or ())
    return withs


def feature_value(obj: EObject, name: str) -> object:
    """The value of feature ``name`` of ``obj``, or None when its class has no such feature."""
    if obj.eClass.findEStructuralFeature(name) is None:
        return None
    return getattr(obj, name)
