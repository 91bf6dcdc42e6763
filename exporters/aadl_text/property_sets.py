"""A property set as AADL text: its property types, definitions and constants, in that order.

Types are written out (``enumeration (a, b)``, ``units (ms, sec => ms * 1000)``, ``aadlinteger
0 .. 10 units Time_Units``, ``record (f: aadlstring;)``, ``list of ...``) or named; long
enumeration and unit lists and ``applies to`` owner lists are wrapped one item per line.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.exporters.aadl_text.context import UnitContext
from rosaadl.exporters.aadl_text.lexical import OWNER_RE, unit_file_name

__all__ = ["property_set", "type_text"]


def property_set(ctx: UnitContext, ps: EObject) -> None:
    """The whole property set."""
    unit_file_name(ps)
    name = ctx.ident(ps.name, "the property set", ps)
    ctx.where = [name]
    if ps.annexSubclauses:
        raise ctx.error("a property set cannot hold annex subclauses in AADL text", ps)
    ctx.emit(0, f"property set {name} is")
    groups = 0
    if ps.withs:
        ctx.emit_wrapped(1, "with ", [ctx.ident(w.strip(), "with clause", ps) for w in ps.withs], ";")
        groups += 1
    for items, write in (
        (ps.ownedPropertyTypes, _type_declaration),
        (ps.ownedProperties, _definition),
        (ps.ownedPropertyConstants, _constant),
    ):
        if not items:
            continue
        if groups:
            ctx.emit(1, "")
        groups += 1
        for item in items:
            write(ctx, item)
    ctx.emit(0, f"end {name};")


def _type_declaration(ctx: UnitContext, ptype: EObject) -> None:
    name = ctx.ident(ptype.name, "a property type", ptype)
    ctx.where.append(name)
    kind = ptype.eClass.name
    head = f"{name}: type "
    if kind == "EnumerationType" and ptype.ownedLiterals:
        literals = [ctx.ident(lit.name, "an enumeration literal", lit) for lit in ptype.ownedLiterals]
        ctx.emit_wrapped(1, head + "enumeration (", literals, ");")
    elif kind == "UnitsType" and len(ptype.ownedLiterals) > 2:
        ctx.emit_wrapped(1, head + "units (", _unit_literals(ctx, ptype), ");")
    else:
        ctx.emit(1, head + type_text(ctx, ptype) + ";")
    ctx.where.pop()


def _definition(ctx: UnitContext, prop: EObject) -> None:
    name = ctx.ident(prop.name, "a property", prop)
    ctx.where.append(name)
    text = f"{name}: " + ("inherit " if prop.inherit else "") + _type_ref(ctx, prop)
    if prop.defaultValue is not None:
        text += " => " + ctx.value(prop.defaultValue)
    owners = _owners(ctx, prop)
    ctx.emit_wrapped(1, f"{text} applies to (", owners, ");")
    ctx.where.pop()


def _constant(ctx: UnitContext, const: EObject) -> None:
    name = ctx.ident(const.name, "a property constant", const)
    ctx.where.append(name)
    if const.value is None:
        raise ctx.error("a property constant needs a value", const)
    ctx.emit(1, f"{name}: constant {_type_ref(ctx, const)} => {ctx.value(const.value)};")
    ctx.where.pop()


def _owners(ctx: UnitContext, prop: EObject) -> list[str]:
    owners = [" ".join((o or "").split()) for o in prop.appliesTo]
    if not owners:
        raise ctx.error("a property definition needs its 'applies to' owners (or 'all')", prop)
    if any(o.lower() == "all" for o in owners):
        if len(owners) > 1:
            raise ctx.error("'applies to (all)' cannot list other owners", prop)
        return ["all"]
    for owner in owners:
        if not OWNER_RE.match(owner):
            raise ctx.error(f"'applies to' owner {owner!r} is not a category or a classifier", prop)
    return [o.replace(" ::", "::").replace(":: ", "::") for o in owners]


def _type_ref(ctx: UnitContext, element: EObject, attribute: str = "type", owned: str = "ownedType") -> str:
    """A named type (qualified name) or a type written out."""
    owned_type = getattr(element, owned)
    if owned_type is not None:
        return type_text(ctx, owned_type)
    named = getattr(element, attribute)
    if not named:
        raise ctx.error("a type is missing", element)
    return ctx.qname(named, "property type name", element)


def _unit_literals(ctx: UnitContext, units: EObject) -> list[str]:
    out = []
    for i, lit in enumerate(units.ownedLiterals):
        name = ctx.ident(lit.name, "a unit literal", lit)
        if i == 0:
            if lit.baseUnit or lit.factor is not None:
                raise ctx.error(f"the first unit {name!r} is the base unit: it has no conversion", lit)
            out.append(name)
            continue
        if not lit.baseUnit or lit.factor is None:
            raise ctx.error(f"unit {name!r} needs a base unit and a factor", lit)
        if not model.is_a(lit.factor, "IntegerValue", "RealValue") or lit.factor.unit:
            raise ctx.error(f"the factor of unit {name!r} must be a number without unit", lit)
        base = ctx.ident(lit.baseUnit, "the base unit", lit)
        out.append(f"{name} => {base} * {ctx.value(lit.factor)}")
    return out


def type_text(ctx: UnitContext, ptype: EObject) -> str:
    """A property type written out (dispatch on the type's class)."""
    kind = ptype.eClass.name
    if kind == "AadlBoolean":
        return "aadlboolean"
    if kind == "AadlString":
        return "aadlstring"
    if kind == "EnumerationType":
        if not ptype.ownedLiterals:
            raise ctx.error("an enumeration type needs literals", ptype)
        literals = [ctx.ident(lit.name, "an enumeration literal", lit) for lit in ptype.ownedLiterals]
        return f"enumeration ({', '.join(literals)})"
    if kind == "UnitsType":
        if not ptype.ownedLiterals:
            raise ctx.error("a units type needs literals", ptype)
        return f"units ({', '.join(_unit_literals(ctx, ptype))})"
    if kind in ("AadlInteger", "AadlReal"):
        text = "aadlinteger" if kind == "AadlInteger" else "aadlreal"
        if ptype.range is not None:
            if not model.is_a(ptype.range, "RangeValue"):
                raise ctx.error("the range of a number type must be a range value", ptype)
            text += " " + ctx.value(ptype.range)
        if ptype.ownedUnitsType is not None:
            text += " " + type_text(ctx, ptype.ownedUnitsType)
        elif ptype.unitsType:
            text += " units " + ctx.qname(ptype.unitsType, "units type name", ptype)
        return text
    if kind == "RangeType":
        return "range of " + _type_ref(ctx, ptype, "numberType", "ownedNumberType")
    if kind in ("ClassifierType", "ReferenceType"):
        word = "classifier" if kind == "ClassifierType" else "reference"
        categories = [" ".join((c or "").split()) for c in ptype.categories]
        for category in categories:
            if not OWNER_RE.match(category):
                raise ctx.error(f"{word} type category {category!r} is not well-formed", ptype)
        return f"{word} ({', '.join(categories)})" if categories else word
    if kind == "RecordType":
        if not ptype.ownedFields:
            raise ctx.error("a record type needs fields", ptype)
        fields = [
            f"{ctx.ident(field.name, 'a record field', field)}: {_type_ref(ctx, field)};"
            for field in ptype.ownedFields
        ]
        return f"record ({' '.join(fields)})"
    if kind == "ListType":
        return "list of " + _type_ref(ctx, ptype, "elementType", "ownedElementType")
    raise ctx.error(f"a {kind} has no AADL text form", ptype)
