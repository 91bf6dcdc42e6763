"""What both AADL → ROSMOD rule sets share: reading AADL property values, finding classifiers,
locating and reporting what cannot be mapped, and making ROSMOD objects.

The property readers take the values a holder carries itself (``own_property``): the
convention reads the declarative model written by the forward conversion, the best effort
reads the property values the instantiator resolved onto each instance object.
"""

from __future__ import annotations

import dataclasses
import logging
from decimal import Decimal, InvalidOperation
from functools import cache
from typing import Any

from pyecore.ecore import EObject

from rosaadl import metamodels
from rosaadl import model as _model
from rosaadl.errors import Diagnostic, Location
from rosaadl.properties import EnumLiteral, own_property
from rosaadl.transforms import rosmod_to_aadl as fwd
from rosaadl.transforms.engine import source_location
from rosaadl.units import Quantity

__all__ = [
    "log",
    "new",
    "add",
    "set_given",
    "enum_name",
    "text",
    "string",
    "integer",
    "seconds",
    "quantity_seconds",
    "settings",
    "scheduling_scheme",
    "Report",
    "declared_location",
    "declared_path",
    "qualify",
    "ClassifierIndex",
    "unique",
    "words",
]

#: one logger for the whole transformation, whichever module of it warns
log = logging.getLogger("rosaadl.transforms.aadl_to_rosmod")


# --------------------------------------------------------------------------- ROSMOD objects


def new(class_name: str, /, **values: Any) -> EObject:
    """A ``rosmod`` object; features given as None stay unset."""
    return _model.new(f"rosmod.{class_name}", **{k: v for k, v in values.items() if v is not None})


def add(owner: EObject, feature: str, items: list[EObject]) -> None:
    """Add ``items`` to a many-valued feature of ``owner``; nothing at all when there are none
    (pyecore would record even an empty change, and make the list on first read)."""
    if items:
        getattr(owner, feature).extend(items)


def set_given(obj: EObject, **values: Any) -> None:
    """Set the features whose value is not None (the others stay unset)."""
    for key, value in values.items():
        if value is not None:
            setattr(obj, key, value)


# --------------------------------------------------------------------------- property values


def enum_name(value: object) -> str:
    """The name of an enumeration literal (``threadGroup``); '' for none."""
    return str(getattr(value, "name", value) or "")


def text(holder: EObject, prop: str) -> str | None:
    value = own_property(holder, prop)
    return value if isinstance(value, str) else None


def string(value: Any) -> str | None:
    return value if isinstance(value, str) else None


def integer(holder: EObject, prop: str) -> int | None:
    value = own_property(holder, prop)
    if isinstance(value, Quantity):
        value = value.value
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    return int(value)


def quantity_seconds(value: Any) -> Decimal | None:
    """The seconds of an AADL time value, else None."""
    if isinstance(value, Quantity):
        return fwd.time_to_seconds(value.value, value.unit)
    return None


def seconds(holder: EObject, prop: str, text_prop: str | None = None) -> Decimal | None:
    """The seconds of a time property; its ROSMOD text (``text_prop``) when it has that value."""
    value = own_property(holder, prop)
    if not isinstance(value, Quantity):
        return None
    found = fwd.time_to_seconds(value.value, value.unit)
    written = text(holder, text_prop) if text_prop is not None and found is not None else None
    if written is not None:
        try:
            exact = Decimal(written)
        except InvalidOperation:
            return found
        if exact == found:
            return exact
    return found


def settings(holder: EObject, prop: str = fwd.SETTINGS) -> list[EObject]:
    """``ROSMOD_Properties::Settings`` (or ``prop``) as ROSMOD ``Property`` objects, in order."""
    value = own_property(holder, prop)
    out = []
    for item in value if isinstance(value, list) else []:
        if isinstance(item, dict):
            out.append(new("Property", key=string(item.get("Key")), value=string(item.get("Value"))))
    return out


@cache
def _schemes() -> frozenset[str]:
    enum = metamodels.load().rosmod.getEClassifier("SchedulingScheme")
    return frozenset(literal.name for literal in enum.eLiterals)


def scheduling_scheme(holder: EObject, prop: str = fwd.SCHEDULING_SCHEME) -> str | None:
    """The ROSMOD scheduling scheme (a literal of ``rosmod.SchedulingScheme``: FIFO, PFIFO,
    EDF) an enumeration property names, else None."""
    value = own_property(holder, prop)
    if isinstance(value, EnumLiteral) and value.name.upper() in _schemes():
        return value.name.upper()
    return None


# --------------------------------------------------------------------------- what cannot be mapped


class Report:
    """The warnings of one conversion: each logged, and appended to the caller's list."""

    def __init__(self, warnings: list[Diagnostic] | None) -> None:
        self.warnings = warnings

    def warn(self, message: str, location: Location) -> None:
        diag = Diagnostic("warning", message, location)
        log.warning("%s", diag)
        if self.warnings is not None:
            self.warnings.append(diag)


def declared_location(element: EObject | None, path: str | None = None) -> Location:
    """File, line and column of an element (nothing for None), with ``path`` as its path."""
    if element is None:
        return Location(path=path)
    return dataclasses.replace(source_location(element), path=path)


def declared_path(element: EObject | None) -> str | None:
    """``Pkg::Classifier.member`` for a declarative element."""
    if element is None:
        return None
    parts: list[str] = []
    current = element
    while current is not None and not _model.is_a(current, "AadlModel"):
        name = getattr(current, "name", None) if current.eClass.findEStructuralFeature("name") else None
        if name:
            parts.append(name)
        current = current.eContainer()
    parts.reverse()
    if len(parts) >= 2:
        return f"{parts[0]}::{'.'.join(parts[1:])}"
    return parts[0] if parts else None


# --------------------------------------------------------------------------- classifiers


def qualify(name: str, unit: EObject) -> str:
    """``Pkg::Name`` for a classifier name written inside ``unit`` (spaces removed)."""
    name = "".join(name.split())
    return name if "::" in name else f"{unit.name}::{name}"


class ClassifierIndex:
    """The classifiers of a model by lower-case qualified name (the first of a name wins)."""

    def __init__(self, model: EObject) -> None:
        self.classifiers: dict[str, EObject] = {}
        self.unit_of: dict[int, EObject] = {}
        for unit in model.units:
            if not _model.is_a(unit, "AadlPackage"):
                continue
            for classifier in unit.classifiers:
                self.classifiers.setdefault(f"{unit.name}::{classifier.name}".lower(), classifier)
                self.unit_of[id(classifier)] = unit

    def find(self, name: str | None, context: EObject) -> EObject | None:
        """The classifier ``name``, unqualified names looked up in the package of ``context``."""
        if not name:
            return None
        unit = context
        while unit is not None and not _model.is_a(unit, "AadlPackage"):
            unit = unit.eContainer()
        if unit is None:
            return self.classifiers.get("".join(name.split()).lower())
        return self.classifiers.get(qualify(name, unit).lower())

    def implementation(self, ctype: EObject) -> EObject | None:
        """The implementation of a component type: ``<type>.impl``, else the first of its package."""
        unit = self.unit_of.get(id(ctype))
        if unit is None:
            return None
        found = self.classifiers.get(f"{unit.name}::{ctype.name}.impl".lower())
        if found is not None:
            return found
        for classifier in unit.classifiers:
            if (
                _model.is_a(classifier, "ComponentImplementation")
                and (classifier.type or "").lower() == (ctype.name or "").lower()
            ):
                return classifier
        return None


# --------------------------------------------------------------------------- names


def unique(name: str, fallback: str, taken: set[str]) -> str:
    """``name``, else an identifier made of ``fallback``, numbered until not in ``taken`` (then taken)."""
    chosen = name if name not in taken else fwd.aadl_identifier(fallback.replace(".", "_"))
    base, count = chosen, 0
    while chosen in taken:
        count += 1
        chosen = f"{base}_{count}"
    taken.add(chosen)
    return chosen


def words(category: str) -> str:
    """``threadGroup`` → ``thread group``."""
    return "".join(f" {c.lower()}" if c.isupper() else c for c in category)
