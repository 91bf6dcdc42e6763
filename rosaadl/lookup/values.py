"""Property values as the lookup gives them: normalised copies, ``+=>`` and modal values.

A value found by the lookup order (:class:`~.order.Found`) becomes new value elements,
``[(expression, in modes)]``, made by :class:`ValueBuilder`:

* units and enumeration literals take their declared spelling, constants their value,
  classifier values their qualified name;
* a named property (``Deadline => Period``) takes the value the element has for it (a
  :class:`NoValue` when it has none, or when it depends on itself);
* ``reference (a.b)`` paths become ``InstanceReferenceValue`` where the caller resolves them,
  else they stay ``ReferenceValue`` and a warning is recorded;
* an appending association (``+=>``) gives one list: the items of the values it appends to, then
  its own;
* ``in modes`` are kept, or one value is selected for a mode (:func:`select_modal`).

The resolution work for each expression is done once (a compiled *template* per expression, type
and context); the copies are made per element with the lookup's :class:`~.factory.Factory`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.errors import Diagnostic, Location, ModelError
from rosaadl.resolution import Resolver
from rosaadl.units import standard_units

from .associations import ModalValues
from .factory import Factory
from .keys import PropertyKeys
from .order import Evaluate, Found

__all__ = ["NoValue", "Reference", "ValueBuilder", "select_modal"]

_STANDARD_UNITS = standard_units()

#: resolves a ``reference (path)`` from an anchor (a component node) to an instance object
Reference = Callable[[Any, str], "EObject | None"]
#: makes one copy of a value: (anchor, evaluate, reference) -> expression
_Make = Callable[[Any, Any, Any], EObject]


class NoValue(ModelError):
    """A value names a property (``Deadline => Period``) that has no value for the object (or
    depends on itself). The lookup turns it into "no value"; one that escapes is a located
    model error like any other."""


class ValueBuilder:
    """Makes the value elements of found values (see the module docstring); warnings about
    references that do not resolve go to ``diagnostics``."""

    def __init__(
        self, resolver: Resolver, keys: PropertyKeys, factory: Factory, diagnostics: list[Diagnostic]
    ) -> None:
        self.resolver = resolver
        self.keys = keys
        self.factory = factory
        self.diagnostics = diagnostics
        self._eval_stack: list[tuple[int, str]] = []
        self._templates: dict[tuple[int, int, int], _Make] = {}
        # the keys of the templates are ids: keep their objects alive as long as the templates
        self._template_keep: list[tuple[EObject, EObject | None, EObject | None]] = []

    def build(
        self,
        found: Found,
        key: str,
        *,
        evaluate: Evaluate | None = None,
        reference: Reference | None = None,
        in_mode: str | None = None,
        keep_modes: bool = True,
    ) -> list[tuple[EObject, list[str]]]:
        """New value elements for a found value: ``[(expression, in modes)]``.

        Units and enumeration literals take their declared spelling, constants their value,
        named properties (``Deadline => Period``) the value ``evaluate`` gives for them (a
        :class:`NoValue` when it has none), and ``reference (...)`` paths become
        ``InstanceReferenceValue`` where ``reference`` resolves them (else they stay
        ``ReferenceValue`` and a warning is recorded).
        """
        prop = self.keys.definitions.get(key)
        ptype = self.resolver.resolved_type(prop) if prop is not None else None
        top_pa, top_values, top_anchor = found.parts[0]
        context = top_pa if top_pa is not None else prop
        selected = select_modal(top_values, in_mode) if not keep_modes else top_values
        below: list[tuple[EObject, EObject | None, Any]] = []
        if len(found.parts) > 1 and top_pa is not None and top_pa.append:
            for pa, values, anchor in reversed(found.parts[1:]):
                ctx = pa if pa is not None else prop
                for expr, _modes in select_modal(values, in_mode)[:1]:
                    below.append((expr, ctx, anchor))
        factory = self.factory
        result = []
        for expr, modes in selected:
            made = self.template(expr, ptype, context)(top_anchor, evaluate, reference)
            if below:
                items: list[EObject] = []
                for lower, ctx, anchor in below:
                    copy = self.template(lower, ptype, ctx)(anchor, evaluate, reference)
                    items.extend(_list_items(copy))
                items.extend(_list_items(made))
                made = factory.new("ListValue")
                factory.extend(made, "ownedItems", items)
            result.append((made, list(modes) if keep_modes else []))
        return result

    def template(self, expr: EObject, ptype: EObject | None, context: EObject | None) -> _Make:
        """A function that makes a normalised copy of ``expr`` (cached per expression, type and
        context): the resolution work is done once, the copies are made per instance object."""
        key = (id(expr), id(ptype), id(context))
        make = self._templates.get(key)
        if make is None:
            make = self._compile(expr, ptype, context, ())
            self._templates[key] = make
            self._template_keep.append((expr, ptype, context))
        return make

    def _compile(
        self, expr: EObject, ptype: EObject | None, context: EObject | None, constants: tuple[int, ...]
    ) -> _Make:
        """The template of ``expr`` (by value class); ``constants`` are the constants whose
        value is being compiled, so that a constant defined by itself stays a name."""
        kind = expr.eClass.name
        resolver = self.resolver
        factory = self.factory
        if kind in ("IntegerValue", "RealValue"):
            unit = expr.unit
            if unit:
                unit = resolver.unit_literal(ptype, unit) or _STANDARD_UNITS.spelling(unit)
                return _maker_of(factory, kind, value=expr.value, unit=unit)
            return _maker_of(factory, kind, value=expr.value)
        if kind == "RangeValue":
            inner = ptype
            if inner is not None and _model.is_a(inner, "RangeType"):
                inner = inner.ownedNumberType or resolver.property_type(inner.numberType, inner)
            parts = [
                (name, self._compile(part, inner, context, constants))
                for name, part in (
                    ("minimum", expr.minimum),
                    ("maximum", expr.maximum),
                    ("delta", expr.delta),
                )
                if part is not None
            ]

            def make_range(anchor, evaluate, reference):
                made = factory.new("RangeValue")
                for name, make in parts:
                    factory.set(made, name, make(anchor, evaluate, reference))
                return made

            return make_range
        if kind == "BooleanValue":
            return _maker_of(factory, kind, value=bool(expr.value))
        if kind == "StringValue":
            return _maker_of(factory, kind, value=expr.value)
        if kind == "NamedValue":
            return self._compile_named(expr, ptype, context, constants)
        if kind == "ReferenceValue":
            path = expr.path or ""

            def make_reference(anchor, evaluate, reference):
                target = reference(anchor, path) if reference is not None else None
                if target is not None:
                    return factory.new("InstanceReferenceValue", referencedInstanceObject=target)
                if reference is not None:
                    self.diagnostics.append(
                        Diagnostic(
                            "warning",
                            f"reference ({path}) does not resolve to an instance object",
                            self._where(context, anchor),
                        )
                    )
                return factory.new("ReferenceValue", path=path)

            return make_reference
        if kind == "InstanceReferenceValue":
            return _maker_of(factory, kind, referencedInstanceObject=expr.referencedInstanceObject)
        if kind == "ClassifierValue":
            name = expr.classifier
            found = resolver.classifier(name, context) if context is not None else None
            qualified = resolver.qualified_name(found) if found is not None else name
            return _maker_of(factory, kind, classifier=qualified)
        if kind == "ListValue":
            inner = resolver.element_type_once(ptype)
            items = [self._compile(item, inner, context, constants) for item in expr.ownedItems]
            return _maker_of_many(factory, kind, "ownedItems", items)
        if kind == "RecordValue":
            fields = []
            for fv in expr.ownedFields:
                ftype = resolver.record_field_type(ptype, fv.name)
                make = self._compile(fv.value, ftype, context, constants) if fv.value is not None else None
                fields.append((fv.name, make))

            def make_record(anchor, evaluate, reference):
                made = factory.new("RecordValue")
                values = []
                for name, make in fields:
                    field_value = factory.new("FieldValue", name=name)
                    if make is not None:
                        factory.set(field_value, "value", make(anchor, evaluate, reference))
                    values.append(field_value)
                factory.extend(made, "ownedFields", values)
                return made

            return make_record
        if kind == "ComputedValue":
            return _maker_of(factory, kind, function=expr.function)
        if kind == "OperationValue":
            operator = expr.operator
            operands = [self._compile(o, ptype, context, constants) for o in expr.ownedOperands]
            return _maker_of_many(factory, kind, "ownedOperands", operands, operator=operator)
        raise ModelError(f"unknown property value kind {kind}")

    def _compile_named(
        self, expr: EObject, ptype: EObject | None, context: EObject | None, constants: tuple[int, ...]
    ) -> _Make:
        resolver = self.resolver
        factory = self.factory
        name = expr.name or ""

        if "::" not in name:
            literal = resolver.enumeration_literal(ptype, name)
            if literal is not None:
                return _maker_of(factory, "NamedValue", name=literal)
        const = resolver.constant(name, context) if context is not None else resolver.constant(name)
        if const is not None and const.value is not None and id(const) not in constants:
            return self._compile(
                const.value, resolver.resolved_type(const) or ptype, const, (*constants, id(const))
            )
        prop = resolver.property(name, context) if context is not None else resolver.property(name)
        if prop is not None:
            key = self.keys.key(prop)
            fallback = name

            def make_property(anchor, evaluate, reference):
                if evaluate is None:
                    return factory.new("NamedValue", name=fallback)
                marker = (id(anchor), key)
                if marker in self._eval_stack:
                    raise NoValue(f"{self.keys.display_name(key)} depends on itself")
                self._eval_stack.append(marker)
                try:
                    found = evaluate(key)
                    if found is None:
                        raise NoValue(f"{self.keys.display_name(key)} has no value here")
                    values = self.build(found, key, evaluate=evaluate, reference=reference, keep_modes=False)
                finally:
                    self._eval_stack.pop()
                if not values:
                    raise NoValue(f"{self.keys.display_name(key)} has no value here")
                return values[0][0]

            return make_property
        return _maker_of(factory, "NamedValue", name=name)

    def _where(self, context: EObject | None, anchor: Any) -> Location:
        path = None
        obj = getattr(anchor, "obj", None)
        if obj is not None and _model.is_a(obj, "InstanceObject"):
            path = _model.instance_path(obj)
        if context is not None and _model.is_a(context, "Element"):
            return self.resolver.location(context, path=path)
        return Location(path=path)

    def association(
        self,
        obj: EObject,
        key: str,
        found: Found,
        *,
        evaluate: Evaluate | None = None,
        reference: Reference | None = None,
    ) -> EObject | None:
        """A new ``PropertyAssociation`` for an instance object holding a found value, or None when
        the value names a property that has no value there (``Deadline => Period`` without a
        ``Period``)."""
        try:
            values = self.build(found, key, evaluate=evaluate, reference=reference)
        except NoValue:
            return None
        factory = self.factory
        modal = []
        for expr, modes in values:
            mpv = factory.new("ModalPropertyValue")
            factory.set(mpv, "value", expr)
            if modes:
                factory.extend(mpv, "inModes", modes)
            modal.append(mpv)
        association = factory.new("PropertyAssociation", property=self.keys.display_name(key))
        factory.extend(association, "ownedValues", modal)
        return association


def _maker_of(factory: Factory, kind: str, **values: Any) -> _Make:
    """The template of a value of class ``kind`` with fixed ``values`` (a number, a string, ...)."""
    return lambda anchor, evaluate, reference: factory.new(kind, **values)


def _maker_of_many(factory: Factory, kind: str, feature: str, parts: list[_Make], **values: Any) -> _Make:
    """The template of a value of class ``kind`` holding the values ``parts`` make in ``feature``
    (a list's items, an operation's operands)."""

    def make(anchor, evaluate, reference):
        made = factory.new(kind, **values)
        factory.extend(made, feature, [part(anchor, evaluate, reference) for part in parts])
        return made

    return make


def select_modal(values: ModalValues, in_mode: str | None) -> ModalValues:
    """The value for mode ``in_mode`` (none: the value without ``in modes``, else the first)."""
    if not values:
        return []
    if in_mode is not None:
        wanted = in_mode.lower()
        for expr, modes in values:
            if any(m.lower() == wanted for m in modes):
                return [(expr, modes)]
    for expr, modes in values:
        if not modes:
            return [(expr, modes)]
    return [values[0]]


def _list_items(expr: EObject) -> list[EObject]:
    """The items of a list value (detached from it), or the value itself."""
    if not _model.is_a(expr, "ListValue"):
        return [expr]
    items = list(expr.ownedItems)
    expr.ownedItems.clear()
    return items
