"""Property associations and property values of AADL text into model objects.

:class:`ValueBuilder` turns ``properties`` sections (and the ``{ ... }`` blocks of members) into
``PropertyAssociation`` objects, and every value form into its ``PropertyExpression``: integers
(based ``16#FF#``, exponents ``1e3``, underscores; they must fit the metamodel's 64-bit
``ELong``), reals, strings (unescaped), named values, lists, records, ranges, references,
classifiers, computed values and the operations ``-``/``+`` on a named constant, ``not``,
``and`` and ``or``.  Literals out of range and values nested deeper than :data:`MAX_NESTING`
stop the reading with a located :class:`rosaadl.errors.AadlSyntaxError`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from lark import Token, Tree
from pyecore.ecore import EObject

from rosaadl.importers.aadl_text.factory import add, make, maker
from rosaadl.importers.aadl_text.legality import Legality
from rosaadl.importers.aadl_text.lexical import parse_integer, shown, unescape
from rosaadl.importers.aadl_text.tree import classifier_ref, mode_refs, path_text, position

__all__ = ["MAX_NESTING", "ValueBuilder"]

#: How deeply values and property types may nest (lists of lists, records, boolean terms).
MAX_NESTING = 64

_ELONG_MIN = -(2**63)
_ELONG_MAX = 2**63 - 1


class ValueBuilder:
    """Builds the property associations and values of one file (``rules``: its diagnostics)."""

    def __init__(self, rules: Legality) -> None:
        self.rules = rules
        # the most frequent objects, made with their features by position
        self.new_association = maker(
            "PropertyAssociation", "property", "append", "constant", "line", "column"
        )
        self.new_modal = maker("ModalPropertyValue", "value", "line", "column")
        self.new_integer = maker("IntegerValue", "value", "unit", "line", "column")
        self.new_real = maker("RealValue", "value", "unit", "line", "column")
        self.new_named = maker("NamedValue", "name", "line", "column")
        self.values = {
            "integer_value": self.integer_value,
            "real_value": self.real_value,
            "named_value": self.named_value,
            "signed_constant": self.signed_constant,
            "boolean_value": self.boolean_value,
            "string_value": self.string_value,
            "list_value": self.list_value,
            "record_value": self.record_value,
            "reference_value": self.reference_value,
            "classifier_value": self.classifier_value,
            "computed_value": self.computed_value,
            "or_value": self.operation_value,
            "and_value": self.operation_value,
            "not_value": self.operation_value,
            "range_value": self.range_value,
        }

    # ----------------------------------------------------------------- property associations

    def associations(self, nodes: Sequence[Tree]) -> list[EObject]:
        """The property associations of a ``properties`` section or a ``{ ... }`` block."""
        out = []
        new_association = self.new_association
        new_modal = self.new_modal
        for node in nodes:
            qname, append, constant, assignment, applies_to, in_binding = node.children
            first = qname.children[0]
            line, column = first.line, first.column
            pa = new_association(
                "::".join(qname.children),
                True if append is not None else None,
                True if constant is not None else None,
                line,
                column,
            )
            if assignment.data == "modal_property_value":
                modal = []
                for item in assignment.children:
                    value_node, in_modes = item.children
                    value_line, value_column = position(value_node)
                    value = self.value(value_node, line, column, 0)
                    mpv = new_modal(value, value_line, value_column)
                    if in_modes is not None:
                        add(mpv, "inModes", *mode_refs(in_modes))
                    modal.append(mpv)
                add(pa, "ownedValues", *modal)
            else:
                value_line, value_column = position(assignment)
                value = self.value(assignment, line, column, 0)
                add(pa, "ownedValues", new_modal(value, value_line, value_column))
            if applies_to is not None:
                add(pa, "appliesTo", *[path_text(p) for p in applies_to.children])
            if in_binding is not None:
                add(pa, "inBinding", *[classifier_ref(c) for c in in_binding.children])
            out.append(pa)
        return out

    # ----------------------------------------------------------------- values

    def value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        """The value of a value node (``line``/``column``: where an empty list or record is)."""
        if depth > MAX_NESTING:
            raise self.rules.fatal(f"a property value nested more than {MAX_NESTING} levels deep", node)
        return self.values[node.data](node, line, column, depth)

    def _number_position(self, sign: Tree | None, literal: Token) -> tuple[int, int]:
        if sign is not None:
            token = sign.children[0]
            return token.line, token.column
        return literal.line, literal.column

    def integer_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        sign, literal, unit = node.children
        number = int(literal) if len(literal) < 19 and literal.isdigit() else self._integer(literal)
        if sign is not None and sign.children[0] == "-":
            number = -number
        if not _ELONG_MIN <= number <= _ELONG_MAX:
            raise self.rules.fatal(
                f"integer {'-' if number < 0 else ''}{shown(literal)} does not fit in 64 bits (the range of "
                "an AADL integer is -2**63 .. 2**63-1)",
                sign if sign is not None else literal,
            )
        line, column = self._number_position(sign, literal)
        return self.new_integer(number, str(unit) if unit is not None else None, line, column)

    def _integer(self, literal: Token) -> int:
        """An AADL integer literal: ``1_000``, ``16#FF#``, ``2#1#e10``, ``1e3``."""
        try:
            return parse_integer(literal)
        except ValueError as exc:
            raise self.rules.fatal(str(exc), literal) from None

    def real_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        sign, literal, unit = node.children
        number = float(literal.replace("_", ""))
        if math.isinf(number):
            raise self.rules.fatal(
                f"real {shown(literal)} is out of range (larger than a 64-bit float)", literal
            )
        if sign is not None and sign.children[0] == "-":
            number = -number
        line, column = self._number_position(sign, literal)
        return self.new_real(number, str(unit) if unit is not None else None, line, column)

    def named_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        first = node.children[0]
        return self.new_named("::".join(node.children), first.line, first.column)

    def signed_constant(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        sign, named = node.children
        token = sign.children[0]
        op = make("OperationValue", operator=str(token), line=token.line, column=token.column)
        add(op, "ownedOperands", self.named_value(named, line, column, depth))
        return op

    def boolean_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        token = node.children[0]
        return make("BooleanValue", value=token.lower() == "true", line=token.line, column=token.column)

    def string_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        token = node.children[0]
        return make("StringValue", value=unescape(token), line=token.line, column=token.column)

    def list_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        items = [self.value(item, line, column, depth + 1) for item in node.children]
        if items:
            line, column = items[0].line, items[0].column
        value = make("ListValue", line=line, column=column)
        if items:
            add(value, "ownedItems", *items)
        return value

    def record_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        fields = []
        for field in node.children:
            name, item = field.children
            fields.append(
                make(
                    "FieldValue",
                    name=str(name),
                    value=self.value(item, name.line, name.column, depth + 1),
                    line=name.line,
                    column=name.column,
                )
            )
        if fields:
            line, column = fields[0].line, fields[0].column
        value = make("RecordValue", line=line, column=column)
        if fields:
            add(value, "ownedFields", *fields)
        return value

    def reference_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        referenced = node.children[0]
        line, column = position(referenced)
        return make("ReferenceValue", path=path_text(referenced), line=line, column=column)

    def classifier_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        ref = node.children[0]
        first = ref.children[0]
        return make("ClassifierValue", classifier=classifier_ref(ref), line=first.line, column=first.column)

    def computed_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        token = node.children[0]
        return make("ComputedValue", function=str(token), line=token.line, column=token.column)

    def operation_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        operator = node.data[:-6]  # or_value / and_value / not_value
        operands = []
        for item in node.children:
            # "(a or b)" reads as a one-element list; as an operand it can only be the expression
            while item.data == "list_value" and len(item.children) == 1:
                item = item.children[0]
            operands.append(self.value(item, line, column, depth + 1))
        line, column = position(node)
        value = make("OperationValue", operator=operator, line=line, column=column)
        add(value, "ownedOperands", *operands)
        return value

    def range_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        lower, upper, delta = node.children
        minimum = self.value(lower, line, column, depth + 1)
        return make(
            "RangeValue",
            minimum=minimum,
            maximum=self.value(upper, line, column, depth + 1),
            delta=self.value(delta, line, column, depth + 1) if delta is not None else None,
            line=minimum.line,
            column=minimum.column,
        )
