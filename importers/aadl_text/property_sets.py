"""Property sets of AADL text into model objects: property definitions, types and constants.

:class:`PropertySetBuilder` builds a ``PropertySet`` with its ``with`` clauses, property types
(``aadlboolean``, ``aadlstring``, enumerations, units, integer and real types with their range
and units, ``range of``, classifier and reference types, records and lists, nested as written),
property definitions (``inherit``, default value, ``applies to``) and constants.  A type written
out where it is used becomes an owned type, a named one stays a name (``Set::Type``).  A type
without a name of its own is located where its text starts, which the tree does not say: it is
found in the source text after the keywords before it.
"""

from __future__ import annotations

from typing import Any

from lark import Token, Tree
from pyecore.ecore import EObject

from rosaadl.importers.aadl_text.factory import add, make
from rosaadl.importers.aadl_text.legality import Legality
from rosaadl.importers.aadl_text.lexical import SourceText
from rosaadl.importers.aadl_text.tree import owner_text, position
from rosaadl.importers.aadl_text.values import MAX_NESTING, ValueBuilder

__all__ = ["PropertySetBuilder"]


class PropertySetBuilder:
    """Builds the property sets of one file."""

    def __init__(self, source: SourceText, rules: Legality, values: ValueBuilder) -> None:
        self.source = source
        self.rules = rules
        self.values = values

    def property_set(self, node: Tree, filename: str) -> EObject:
        children = node.children
        name = children[0]
        rules = self.rules
        rules.end_name(name, children[-1], "property set", children[-1])
        pset = make("PropertySet", name=str(name), line=name.line, column=name.column, sourceFile=filename)
        withs: list[str] = []
        types = []
        properties = []
        constants = []
        names: dict[str, int] = {}
        after = self.source.after
        value = self.values.value
        for item in children[1:-1]:
            kind = item.data
            if kind == "property_definition":
                prop_name, inherit, ptype, default, owners = item.children
                type_pos = after(prop_name.end_pos, ":", "inherit")
                prop = make(
                    "Property",
                    name=str(prop_name),
                    inherit=True if inherit is not None else None,
                    defaultValue=value(default, prop_name.line, prop_name.column, 0)
                    if default is not None
                    else None,
                    line=prop_name.line,
                    column=prop_name.column,
                    **self.type_reference(ptype, "type", "ownedType", 0, type_pos),
                )
                if owners.data == "all_owners":
                    add(prop, "appliesTo", "all")
                else:
                    add(prop, "appliesTo", *[owner_text(o) for o in owners.children])
                rules.declare(names, prop_name, "property")
                properties.append(prop)
            elif kind == "property_type_declaration":
                type_name, ptype = item.children
                if ptype.data == "qname":
                    raise rules.fatal(
                        f"property type {type_name} must be written out (aadlinteger, enumeration (...), "
                        f"...), not named as {'::'.join(ptype.children)}",
                        ptype,
                    )
                type_pos = after(type_name.end_pos, ":", "type")
                declared = self.property_type(ptype, 0, type_pos, type_name)
                rules.declare(names, type_name, "property type")
                types.append(declared)
            elif kind == "property_constant":
                const_name, ptype, constant_value = item.children
                type_pos = after(const_name.end_pos, ":", "constant")
                const = make(
                    "PropertyConstant",
                    name=str(const_name),
                    value=value(constant_value, const_name.line, const_name.column, 0),
                    line=const_name.line,
                    column=const_name.column,
                    **self.type_reference(ptype, "type", "ownedType", 0, type_pos),
                )
                rules.declare(names, const_name, "property constant")
                constants.append(const)
            else:  # with_clause
                withs.extend("::".join(q.children) for q in item.children)
        if withs:
            add(pset, "withs", *withs)
        if types:
            add(pset, "ownedPropertyTypes", *types)
        if properties:
            add(pset, "ownedProperties", *properties)
        if constants:
            add(pset, "ownedPropertyConstants", *constants)
        return pset

    def type_reference(self, ptype: Tree, named: str, owned: str, depth: int, pos: int) -> dict[str, Any]:
        """``{named: "Set::Type"}`` for a named type, ``{owned: PropertyType}`` for one written out
        (``pos``: where its text starts)."""
        if ptype.data == "qname":
            return {named: "::".join(ptype.children)}
        return {owned: self.property_type(ptype, depth + 1, pos)}

    def property_type(self, node: Tree, depth: int, pos: int, name: Token | None = None) -> EObject:
        """A property type written out, starting at ``pos``; ``name`` for ``name: type ...``."""
        if depth > MAX_NESTING:
            raise self.rules.fatal(f"a property type nested more than {MAX_NESTING} levels deep", node)
        kind = node.data
        if name is not None:
            line, column = name.line, name.column
            named = {"name": str(name), "line": line, "column": column}
        else:
            line, column = self.source.line_column(pos)
            named = {"line": line, "column": column}
        if kind == "boolean_type":
            return make("AadlBoolean", **named)
        if kind == "string_type":
            return make("AadlString", **named)
        if kind == "enumeration_type":
            ptype = make("EnumerationType", **named)
            literals = []
            seen: dict[str, int] = {}
            for token in node.children:
                literal = make("EnumerationLiteral", name=str(token), line=token.line, column=token.column)
                self.rules.declare(seen, token, "enumeration literal")
                literals.append(literal)
            add(ptype, "ownedLiterals", *literals)
            return ptype
        if kind == "units_type":
            return self.units_type(node, named)
        if kind == "integer_type" or kind == "real_type":
            range_node, units = node.children
            unit_values: dict[str, Any] = {}
            if units is not None:
                if units.data == "units_ref":
                    unit_values["unitsType"] = "::".join(units.children[0].children)
                else:
                    unit_values["ownedUnitsType"] = self.units_type(units, None)
            return make(
                "AadlInteger" if kind == "integer_type" else "AadlReal",
                range=self.values.value(range_node, line, column, depth + 1)
                if range_node is not None
                else None,
                **named,
                **unit_values,
            )
        if kind == "range_type":
            inner = node.children[0]
            if inner.data not in ("qname", "integer_type", "real_type"):
                raise self.rules.fatal("'range of' needs a number type (aadlinteger or aadlreal)", inner)
            inner_pos = self.source.after(pos, "range", "of")
            number = self.type_reference(inner, "numberType", "ownedNumberType", depth, inner_pos)
            return make("RangeType", **named, **number)
        if kind == "classifier_type" or kind == "reference_type":
            ptype = make("ClassifierType" if kind == "classifier_type" else "ReferenceType", **named)
            categories = [owner_text(o) for o in node.children if o is not None]
            if categories:
                add(ptype, "categories", *categories)
            return ptype
        if kind == "record_type":
            return self.record_type(node, named, depth)
        if kind == "list_type":
            inner_pos = self.source.after(pos, "list", "of")
            inner = self.type_reference(node.children[0], "elementType", "ownedElementType", depth, inner_pos)
            return make("ListType", **named, **inner)
        raise self.rules.fatal(f"unexpected property type {kind}", node)  # the grammar has no other

    def record_type(self, node: Tree, named: dict[str, Any], depth: int) -> EObject:
        ptype = make("RecordType", **named)
        fields = []
        seen: dict[str, int] = {}
        for field in node.children:
            field_name, field_type = field.children
            record_field = make(
                "RecordField",
                name=str(field_name),
                line=field_name.line,
                column=field_name.column,
                **self.type_reference(
                    field_type, "type", "ownedType", depth, self.source.after(field_name.end_pos, ":")
                ),
            )
            self.rules.declare(seen, field_name, "record field")
            fields.append(record_field)
        add(ptype, "ownedFields", *fields)
        return ptype

    def units_type(self, node: Tree, named: dict[str, Any] | None) -> EObject:
        children = node.children
        base = children[0]
        if named is None:
            line, column = position(node)
            named = {"line": line, "column": column}
        ptype = make("UnitsType", **named)
        literals = [make("UnitLiteral", name=str(base), line=base.line, column=base.column)]
        seen: dict[str, int] = {}
        self.rules.declare(seen, base, "unit")
        for conversion in children[1:]:
            name, unit_base, factor = conversion.children
            literal = make(
                "UnitLiteral",
                name=str(name),
                baseUnit=str(unit_base),
                factor=self.values.value(factor, name.line, name.column, 0),
                line=name.line,
                column=name.column,
            )
            self.rules.unit_base(seen, name, unit_base)
            self.rules.declare(seen, name, "unit")
            literals.append(literal)
        add(ptype, "ownedLiterals", *literals)
        return ptype
