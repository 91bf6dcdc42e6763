"""Property associations as AADL text: ``Name => value applies to a.b in binding (P::C);``.

A unit's, a classifier's, or an element's property block (``x: ... { A => 1; };``, inline when
one short association, else one per line). Values are printed by the context's
:class:`~rosaadl.property_text.ValuePrinter`; modal values in parentheses,
``(v1 in modes (a), v2)``, the form OSATE reads.
"""

from __future__ import annotations

from collections.abc import Sequence

from pyecore.ecore import EObject

from rosaadl.exporters.aadl_text.context import INDENT, LINE_LENGTH, UnitContext

__all__ = ["element_with_properties", "modal_item", "property_association", "association_parts"]


def element_with_properties(
    ctx: UnitContext, level: int, text: str, assocs: Sequence[EObject], suffix: str
) -> None:
    """``text {assoc; ...}suffix;``: inline for one short association, else one per line."""
    if not assocs:
        ctx.emit(level, f"{text}{suffix};")
        return
    rendered = [association_parts(ctx, a) for a in assocs]
    if len(rendered) == 1:
        head, tail = rendered[0]
        one = f"{head} {tail};" if tail else f"{head};"
        line = f"{text} {{ {one} }}{suffix};"
        if len(INDENT * level) + len(line) <= LINE_LENGTH:
            ctx.emit(level, line)
            return
    ctx.emit(level, f"{text} {{")
    for parts in rendered:
        _emit_association(ctx, level + 1, parts)
    ctx.emit(level, f"}}{suffix};")


def modal_item(ctx: UnitContext, text: str, element: EObject) -> None:
    """A section item with its property block and ``in modes`` (subcomponents, connections, ...)."""
    suffix = ctx.in_modes(element.inModes, element)
    element_with_properties(ctx, 3, text, element.ownedPropertyAssociations, suffix)


def property_association(ctx: UnitContext, level: int, assoc: EObject) -> None:
    """One association of a ``properties`` section."""
    _emit_association(ctx, level, association_parts(ctx, assoc))


def _emit_association(ctx: UnitContext, level: int, parts: tuple[str, str]) -> None:
    """One line; when too long, ``applies to``/``in binding`` go on a line of their own."""
    head, tail = parts
    line = f"{head} {tail};" if tail else f"{head};"
    if not tail or len(INDENT * level) + len(line) <= LINE_LENGTH:
        ctx.emit(level, line)
    else:
        ctx.emit(level, head)
        ctx.emit(level + 1, f"{tail};")


def association_parts(ctx: UnitContext, assoc: EObject) -> tuple[str, str]:
    """``Name => value`` and what follows it (``applies to ...``, ``in binding (...)``)."""
    prop = ctx.qname(assoc.property, "property name", assoc)
    ctx.where.append(prop)
    arrow = "+=>" if assoc.append else "=>"
    constant = "constant " if assoc.constant else ""
    values = list(assoc.ownedValues)
    if not values:
        raise ctx.error("a property association needs a value", assoc)
    if len(values) == 1 and not values[0].inModes:
        value = ctx.value(values[0].value)
    else:
        modal = [v for v in values if v.inModes]
        default = [v for v in values if not v.inModes]
        if len(default) > 1:
            raise ctx.error("a modal property value can have only one value without 'in modes'", assoc)
        items = [ctx.value(v.value) + ctx.in_modes(v.inModes, v) for v in modal]
        items += [ctx.value(v.value) for v in default]
        value = f"({', '.join(items)})"
    tail = []
    if assoc.appliesTo:
        paths = [ctx.path(p, "'applies to' path", assoc) for p in assoc.appliesTo]
        tail.append("applies to " + ", ".join(paths))
    if assoc.inBinding:
        refs = [ctx.classifier_ref(c, "'in binding' classifier", assoc) for c in assoc.inBinding]
        tail.append(f"in binding ({', '.join(refs)})")
    ctx.where.pop()
    return f"{prop} {arrow} {constant}{value}", " ".join(tail)
