"""Property values as Python values: numbers with units, ranges, enumerations, references, lists, records.

:func:`python_value` decodes a ``PropertyExpression`` model element; :func:`own_property` and
:func:`property_value` read the associations held by one element (an instance object carries
its resolved values, so for instances this *is* the AADL lookup). The full declarative lookup
(type, implementation, extends chains, ``inherit``, defaults, ``applies to``) lives with the AADL
reader, which builds on these helpers.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from pyecore.ecore import EObject

from rosaadl.arguments import checked
from rosaadl.errors import Location, ModelError
from rosaadl.units import Quantity

__all__ = [
    "Range",
    "EnumLiteral",
    "Reference",
    "python_value",
    "property_name_matches",
    "own_association",
    "own_property",
    "property_value",
]


@dataclass(frozen=True)
class Range:
    """An AADL range value ``min .. max [delta d]``."""

    minimum: Any
    maximum: Any
    delta: Any = None


@dataclass(frozen=True)
class EnumLiteral:
    """An enumeration literal or property-constant name as written (``Periodic``, ``SCHED_FIFO``)."""

    name: str

    def __eq__(self, other: object) -> bool:
        if isinstance(other, str):
            return self.name.lower() == other.lower()
        if isinstance(other, EnumLiteral):
            return self.name.lower() == other.name.lower()
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self.name.lower())

    def __str__(self) -> str:
        return self.name


@dataclass(frozen=True)
class Reference:
    """A declarative ``reference (a.b.c)`` path that is not (yet) resolved to an instance."""

    path: str


def python_value(expr: EObject | None) -> Any:
    """Decode a ``PropertyExpression`` into Python: Quantity / int / float / bool / str / Range /
    EnumLiteral / Reference / instance object / list / dict."""
    if expr is None:
        return None
    kind = expr.eClass.name
    if kind in ("IntegerValue", "RealValue"):
        value = expr.value
        return Quantity(value, expr.unit) if expr.unit else value
    if kind == "RangeValue":
        return Range(python_value(expr.minimum), python_value(expr.maximum), python_value(expr.delta))
    if kind == "BooleanValue":
        return bool(expr.value)
    if kind == "StringValue":
        return expr.value or ""
    if kind == "NamedValue":
        return EnumLiteral(expr.name)
    if kind == "ReferenceValue":
        return Reference(expr.path)
    if kind == "InstanceReferenceValue":
        return expr.referencedInstanceObject
    if kind == "ClassifierValue":
        return expr.classifier
    if kind == "ListValue":
        return [python_value(item) for item in expr.ownedItems]
    if kind == "RecordValue":
        return {field.name: python_value(field.value) for field in expr.ownedFields}
    if kind == "ComputedValue":
        return ("compute", expr.function)
    if kind == "OperationValue":
        return (expr.operator, [python_value(o) for o in expr.ownedOperands])
    raise ModelError(f"unknown property value kind {kind}")


def property_name_matches(written: str, wanted: str) -> bool:
    """``Timing_Properties::Period`` matches ``Period`` and vice versa; case-insensitive as in AADL."""
    a, b = written.lower(), wanted.lower()
    if a == b:
        return True
    return a.rpartition("::")[2] == b.rpartition("::")[2] and ("::" not in a or "::" not in b)


def own_association(obj: EObject, name: str, *, in_mode: str | None = None) -> EObject | None:
    """The last association of property ``name`` held directly by ``obj`` with no ``applies to``."""
    found = None
    feature = obj.eClass.findEStructuralFeature("ownedPropertyAssociations")
    if feature is None:
        return None
    for assoc in obj.ownedPropertyAssociations:
        if assoc.appliesTo:
            continue
        if property_name_matches(assoc.property or "", name):
            found = assoc
    return found


def _modal_value(assoc: EObject, in_mode: str | None) -> EObject | None:
    default = None
    for modal in assoc.ownedValues:
        if not modal.inModes:
            default = modal.value
        elif in_mode is not None and any(m.lower() == in_mode.lower() for m in modal.inModes):
            return modal.value
    if default is None and assoc.ownedValues:
        default = assoc.ownedValues[0].value
    return default


def own_property(obj: EObject, name: str, *, in_mode: str | None = None) -> Any:
    """The Python value of property ``name`` held directly by ``obj`` (None when absent)."""
    assoc = own_association(obj, name, in_mode=in_mode)
    if assoc is None:
        return None
    return python_value(_modal_value(assoc, in_mode))


@checked
def property_value(obj: EObject, name: str, default: Any = None, *, required: bool = False) -> Any:
    """Property value of an instance object (its resolved associations); ``required`` raises a
    located :class:`ModelError` naming the instance path when the property is missing."""
    value = own_property(obj, name)
    if value is None:
        if required:
            from rosaadl.model import instance_path

            raise ModelError(f"property {name} is not set", Location(path=instance_path(obj)))
        return default
    return value
