"""The checks across the units of an AADL model, after every file is read.

:func:`check_names_and_values` resolves every name of the model with
:class:`rosaadl.resolution.Resolver` (classifiers, properties, ``with`` clauses, ...), then
checks each property value against its property's type with :class:`ValueChecker`: unit
literals, enumeration literals and record field names.  It returns located diagnostics; the
reader raises the errors among them together.
"""

from __future__ import annotations

from typing import Any

from pyecore.ecore import EObject

from rosaadl.bulk import stored_value
from rosaadl.errors import Diagnostic
from rosaadl.importers.aadl_text.values import MAX_NESTING
from rosaadl.model import is_a
from rosaadl.resolution import Resolver

__all__ = ["ValueChecker", "check_names_and_values"]

# the members that hold property associations, by class
_MEMBER_LISTS: dict[str, tuple[str, ...]] = {
    "AadlPackage": ("classifiers",),
    "ComponentType": ("features", "flowSpecifications", "modes", "modeTransitions"),
    "ComponentImplementation": (
        "subcomponents",
        "connections",
        "flowImplementations",
        "endToEndFlows",
        "callSequences",
        "modes",
        "modeTransitions",
    ),
    "FeatureGroupType": ("features",),
    "CallSequence": ("calls",),
}


def check_names_and_values(model: EObject, *, lenient: bool = False) -> list[Diagnostic]:
    """Name resolution (``rosaadl.resolution``) and the units and literals of every value; one
    diagnostic per place (a value checked at a place the resolver already reported is left out).
    ``lenient``: a classifier or package that is not found is a warning."""
    resolver = Resolver(model)
    diagnostics = list(resolver.check(lenient=lenient))
    seen = {(d.location.file, d.location.line, d.location.column) for d in diagnostics}
    for diagnostic in ValueChecker(resolver).run(model):
        key = (diagnostic.location.file, diagnostic.location.line, diagnostic.location.column)
        if key not in seen:
            diagnostics.append(diagnostic)
    return diagnostics


class ValueChecker:
    """Property values against their property's type: unit literals (a unit of the type's units;
    none where the type has no units; one on every number but 0 where it has), enumeration
    literals, record field names.  Values of unknown properties or types are left alone: the
    resolver reports those names."""

    def __init__(self, resolver: Any) -> None:
        self.resolver = resolver
        self.out: list[Diagnostic] = []

    def run(self, model: EObject) -> list[Diagnostic]:
        resolver = self.resolver
        for unit in model.units:
            if is_a(unit, "PropertySet"):
                for prop in unit.ownedProperties:
                    if prop.defaultValue is not None:
                        self.value(prop.defaultValue, resolver.resolved_type(prop), prop.name, prop, 0)
                for const in unit.ownedPropertyConstants:
                    if const.value is not None:
                        self.value(const.value, resolver.resolved_type(const), const.name, const, 0)
                continue
            stack: list[EObject] = [unit]
            while stack:
                element = stack.pop()
                # read as stored: pyecore's getter would keep an empty list on each element
                for pa in stored_value(element, "ownedPropertyAssociations", ()):
                    self.association(pa)
                for name in _MEMBER_LISTS.get(element.eClass.name, ()):
                    stack.extend(stored_value(element, name, ()))
        return self.out

    def association(self, pa: EObject) -> None:
        prop = self.resolver.association_property(pa)
        if prop is None:
            return  # unknown property: the resolver reports it
        ptype = self.resolver.resolved_type(prop)
        if ptype is None:
            return
        for modal in pa.ownedValues:
            if modal.value is not None:
                self.value(modal.value, ptype, pa.property, pa, 0)

    def error(self, element: EObject, message: str) -> None:
        self.out.append(Diagnostic("error", message, self.resolver.location(element)))

    def value(self, expr: EObject, ptype: EObject | None, prop: str, context: EObject, depth: int) -> None:
        if ptype is None or depth > MAX_NESTING:
            return
        resolver = self.resolver
        if is_a(ptype, "ListType"):
            element = resolver.element_type_once(ptype)
            if is_a(expr, "ListValue"):
                for item in expr.ownedItems:
                    self.value(item, element, prop, context, depth + 1)
            else:
                self.value(expr, element, prop, context, depth + 1)
            return
        if is_a(expr, "IntegerValue", "RealValue"):
            self.number(expr, ptype, prop)
        elif is_a(expr, "RangeValue"):
            inner = ptype
            if is_a(ptype, "RangeType"):
                inner = ptype.ownedNumberType or resolver.property_type(ptype.numberType, ptype)
            for bound in (expr.minimum, expr.maximum, expr.delta):
                if bound is not None:
                    self.value(bound, inner, prop, context, depth + 1)
        elif is_a(expr, "OperationValue") and expr.operator in ("-", "+"):
            for operand in expr.ownedOperands:
                self.value(operand, ptype, prop, context, depth + 1)
        elif is_a(expr, "RecordValue") and is_a(ptype, "RecordType"):
            self.record(expr, ptype, prop, context, depth)
        elif is_a(expr, "NamedValue") and is_a(ptype, "EnumerationType"):
            name = expr.name or ""
            if "::" in name or resolver.enumeration_literal(ptype, name) is not None:
                return
            if resolver.constant(name, context) is not None or resolver.property(name, context) is not None:
                return
            literals = ", ".join(lit.name for lit in ptype.ownedLiterals)
            self.error(expr, f"{name} is not a literal of the type of {prop} (expected one of: {literals})")
        elif is_a(expr, "NamedValue") and is_a(ptype, "UnitsType"):
            name = expr.name or ""
            if "::" not in name and resolver.unit_literal(ptype, name) is None:
                literals = ", ".join(lit.name for lit in ptype.ownedLiterals)
                self.error(expr, f"{name} is not a unit of {_type_name(ptype)} (expected one of: {literals})")

    def record(self, expr: EObject, ptype: EObject, prop: str, context: EObject, depth: int) -> None:
        fields = {(f.name or "").lower(): f for f in ptype.ownedFields}
        for field in expr.ownedFields:
            declared = fields.get((field.name or "").lower())
            if declared is None:
                names = ", ".join(f.name for f in ptype.ownedFields)
                self.error(field, f"{prop} has no field {field.name} (its fields: {names})")
            elif field.value is not None:
                self.value(field.value, self.resolver.resolved_type(declared), prop, context, depth + 1)

    def number(self, expr: EObject, ptype: EObject, prop: str) -> None:
        if not is_a(ptype, "NumberType", "RangeType", "UnitsType"):
            return
        resolver = self.resolver
        units = resolver.units_type(ptype)
        unit = expr.unit
        if unit:
            if units is None:
                self.error(expr, f"{prop} takes a number without unit, not one in {unit}")
            elif resolver.unit_literal(ptype, unit) is None:
                literals = ", ".join(lit.name for lit in units.ownedLiterals)
                self.error(
                    expr,
                    f"{unit} is not a unit of {_type_name(units)}, the units of {prop} "
                    f"(expected one of: {literals})",
                )
        elif units is not None and (expr.value or 0) != 0:
            literals = ", ".join(lit.name for lit in units.ownedLiterals)
            self.error(expr, f"{prop} needs a unit of {_type_name(units)} ({literals})")


def _type_name(ptype: EObject) -> str:
    if ptype.name:
        owner = ptype.eContainer()
        return f"{owner.name}::{ptype.name}" if is_a(owner, "PropertySet") else ptype.name
    return "its units type"
