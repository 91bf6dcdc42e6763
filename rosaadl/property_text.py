"""Property expressions as AADL text: the one printer of property values.

:class:`ValuePrinter` turns a ``PropertyExpression`` of the model (``IntegerValue``,
``RangeValue``, ``ClassifierValue``, ...) into the AADL text of AS5506C 11.4: ``33333 us``,
``2319 us .. 2319 us``, ``classifier (P::T)``, ``(reference (a.b), reference (c))``,
``[f => 1;]``, ``not (a or b)``. What it does with the names in a value, and with a value that has
no AADL form, is up to its :class:`NameRules`:

* the AADL text writer (:mod:`rosaadl.exporters.aadl_text`) gives rules that check every name
  and raise a located :class:`~rosaadl.errors.ExportError` for anything that would not read back;
* :func:`format_value` (``rosaadl library show``, profile comparisons) prints the names as the
  model holds them, refuses nothing, and also prints instance references by their instance path
  (``reference (top.board.cpu1)``), which have no declarative AADL form.

:func:`format_real` and :func:`string_literal` are the literals of numbers and strings.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Protocol

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import ModelError

__all__ = [
    "NameRules",
    "LenientNames",
    "ValuePrinter",
    "format_value",
    "format_real",
    "string_literal",
    "SIGN_OPERATORS",
    "BOOLEAN_OPERATORS",
]

#: Unary sign operators as the model may spell them, and their AADL text.
SIGN_OPERATORS = {"-": "-", "minus": "-", "+": "+", "plus": "+"}
#: Boolean operators of property expressions (``not`` binds tighter than ``and``, ``and`` than ``or``).
BOOLEAN_OPERATORS = {"and": "and", "or": "or", "not": "not"}

_NUMBERS = ("IntegerValue", "RealValue")


def format_real(value: float) -> str:
    """An AADL real literal that reads back as exactly ``value``: ``1.0``, ``2.5e-3`` → ``0.0025``.

    Python's shortest round-trip ``repr`` is used, rewritten so that there are digits on both
    sides of the point (``1e-05`` → ``1.0e-5``). A value that is not a finite number raises
    :class:`~rosaadl.errors.ModelError`.
    """
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ModelError(f"{value!r} is not a number: it has no AADL real literal") from None
    if not math.isfinite(number):
        raise ModelError(f"{value!r} has no AADL real literal")
    text = repr(number)
    sign = ""
    if text.startswith("-"):
        sign, text = "-", text[1:]
    mantissa, _, exponent = text.partition("e")
    if "." not in mantissa:
        mantissa += ".0"
    if exponent:
        return f"{sign}{mantissa}e{int(exponent)}"
    return sign + mantissa


def string_literal(text: str) -> str:
    """An AADL string literal: ``"`` doubled as the standard says; a backslash, which begins an
    escape in OSATE's (and our reader's) string syntax, is written ``\\\\``."""
    return '"' + text.replace("\\", "\\\\").replace('"', '""') + '"'


class NameRules(Protocol):
    """What a :class:`ValuePrinter` does with names and with values that have no AADL form.

    Each name method returns the name as it is to be written (or raises); ``refuse`` is called
    with what is wrong with a value and either raises or returns, and then the printer goes on
    with the best text it can make.
    """

    def ident(self, name: str | None, what: str, element: EObject | None = None) -> str: ...

    def qname(self, text: str | None, what: str, element: EObject | None = None) -> str: ...

    def path(self, text: str | None, what: str, element: EObject | None = None) -> str: ...

    def classifier_ref(self, text: str | None, what: str, element: EObject | None = None) -> str: ...

    def refuse(self, message: str, element: EObject | None = None) -> None: ...


class LenientNames:
    """Names as the model holds them; nothing is refused (for showing a model to a user)."""

    def ident(self, name: str | None, what: str, element: EObject | None = None) -> str:
        return name or ""

    qname = path = classifier_ref = ident

    def refuse(self, message: str, element: EObject | None = None) -> None:
        return None


class ValuePrinter:
    """Prints property expressions as AADL text under ``names`` (see :class:`NameRules`).

    ``instance_references``: print an ``InstanceReferenceValue`` as ``reference (<instance
    path>)``; otherwise it is refused (declarative AADL text has no such value).
    """

    __slots__ = ("names", "instance_references")

    def __init__(self, names: NameRules | None = None, *, instance_references: bool = False) -> None:
        self.names: NameRules = names if names is not None else LenientNames()
        self.instance_references = instance_references

    def text(self, expr: EObject | None) -> str:
        """``expr`` as AADL text."""
        if expr is None:
            self.names.refuse("a property value is missing")
            return ""
        kind = expr.eClass.name
        printer = _PRINTERS.get(kind)
        if printer is None:
            self.names.refuse(f"a {kind} has no AADL text form", expr)
            return kind
        return printer(self, expr)

    # ----------------------------------------------------------------- one method per value class

    def _unit(self, expr: EObject) -> str:
        return " " + self.names.ident(expr.unit, "the unit", expr) if expr.unit else ""

    def _integer(self, expr: EObject) -> str:
        return f"{int(expr.value or 0)}{self._unit(expr)}"

    def _real(self, expr: EObject) -> str:
        try:
            text = format_real(expr.value or 0.0)
        except ModelError:
            self.names.refuse(f"the real value {expr.value!r} has no AADL literal", expr)
            text = repr(expr.value)
        return text + self._unit(expr)

    def _range(self, expr: EObject) -> str:
        if expr.minimum is None or expr.maximum is None:
            self.names.refuse("a range needs a minimum and a maximum", expr)
        text = f"{self._bound(expr.minimum)} .. {self._bound(expr.maximum)}"
        if expr.delta is not None:
            text += f" delta {self._bound(expr.delta)}"
        return text

    def _bound(self, expr: EObject | None) -> str:
        if expr is None:
            return ""
        kind = expr.eClass.name
        if not (
            kind in _NUMBERS
            or kind == "NamedValue"
            or (kind == "OperationValue" and (expr.operator or "").lower() in SIGN_OPERATORS)
        ):
            self.names.refuse(f"a range bound must be a number or a constant, not a {kind}", expr)
        return self.text(expr)

    def _boolean(self, expr: EObject) -> str:
        return "true" if expr.value else "false"

    def _string(self, expr: EObject) -> str:
        return string_literal(expr.value or "")

    def _named(self, expr: EObject) -> str:
        return self.names.qname(expr.name, "named value", expr)

    def _reference(self, expr: EObject) -> str:
        return f"reference ({self.names.path(expr.path, 'reference path', expr)})"

    def _instance_reference(self, expr: EObject) -> str:
        if not self.instance_references:
            self.names.refuse(f"a {expr.eClass.name} has no AADL text form", expr)
        target = expr.referencedInstanceObject
        return f"reference ({model.instance_path(target) if target is not None else '?'})"

    def _classifier(self, expr: EObject) -> str:
        return f"classifier ({self.names.classifier_ref(expr.classifier, 'classifier value', expr)})"

    def _list(self, expr: EObject) -> str:
        return "(" + ", ".join(self.text(item) for item in expr.ownedItems) + ")"

    def _record(self, expr: EObject) -> str:
        ident = self.names.ident
        fields = [
            f"{ident(field.name, 'a record field', field)} => {self.text(field.value)};"
            for field in expr.ownedFields
        ]
        return "[" + " ".join(fields) + "]"

    def _computed(self, expr: EObject) -> str:
        return f"compute ({self.names.ident(expr.function, 'the computed value function', expr)})"

    def _operation(self, expr: EObject) -> str:
        refuse = self.names.refuse
        operator = (expr.operator or "").strip().lower()
        operands = list(expr.ownedOperands)
        if operator in SIGN_OPERATORS:
            if len(operands) != 1:
                refuse(f"unary {operator!r} needs one operand", expr)
                return self._joined(expr, operands)
            operand = operands[0]
            kind = operand.eClass.name
            if kind != "NamedValue" and not (kind in _NUMBERS and (operand.value or 0) >= 0):
                refuse(f"a signed {kind} cannot be written in AADL", expr)
            return SIGN_OPERATORS[operator] + self.text(operand)
        if operator not in BOOLEAN_OPERATORS:
            refuse(f"unknown operator {expr.operator!r} (expected and, or, not, + or -)", expr)
            return self._joined(expr, operands)
        if operator == "not":
            if len(operands) != 1:
                refuse("'not' needs one operand", expr)
                return self._joined(expr, operands)
            return "not " + self._boolean_operand(operands[0], ("and", "or"))
        if len(operands) < 2:
            refuse(f"'{operator}' needs at least two operands", expr)
        # 'not' binds tighter than 'and', 'and' tighter than 'or'; an operand that would otherwise
        # merge into this operation (or bind wrongly) is parenthesised, so the tree is kept
        nested = ("and", "or") if operator == "and" else ("or",)
        return f" {operator} ".join(self._boolean_operand(op, nested) for op in operands)

    def _boolean_operand(self, expr: EObject, parenthesised: tuple[str, ...]) -> str:
        text = self.text(expr)
        if expr.eClass.name == "OperationValue" and (expr.operator or "").strip().lower() in parenthesised:
            return f"({text})"
        return text

    def _joined(self, expr: EObject, operands: list[EObject]) -> str:
        """An operation that has no AADL form, as near to one as it gets (lenient rules only)."""
        return f" {expr.operator} ".join(self.text(operand) for operand in operands)


_PRINTERS: dict[str, Callable[[ValuePrinter, EObject], str]] = {
    "IntegerValue": ValuePrinter._integer,
    "RealValue": ValuePrinter._real,
    "RangeValue": ValuePrinter._range,
    "BooleanValue": ValuePrinter._boolean,
    "StringValue": ValuePrinter._string,
    "NamedValue": ValuePrinter._named,
    "ReferenceValue": ValuePrinter._reference,
    "InstanceReferenceValue": ValuePrinter._instance_reference,
    "ClassifierValue": ValuePrinter._classifier,
    "ListValue": ValuePrinter._list,
    "RecordValue": ValuePrinter._record,
    "ComputedValue": ValuePrinter._computed,
    "OperationValue": ValuePrinter._operation,
}

_SHOW = ValuePrinter(LenientNames(), instance_references=True)


def format_value(expr: EObject | None) -> str:
    """A property value as AADL text for a reader (``33333 us``, ``2319 us .. 2319 us``,
    ``classifier (P::T)``); names as the model holds them, instance references by their path,
    ``""`` for no value. Never raises for a malformed value: it prints what is there."""
    return _SHOW.text(expr)
