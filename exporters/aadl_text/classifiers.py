"""Classifiers as AADL text: component types and implementations, feature group types.

:func:`classifier` writes the header (``thread implementation T.i extends U.i (bindings)``), the
sections in the standard's order (prototypes, features, flows, modes for a type; subcomponents,
calls, connections, flows, modes for an implementation, see :mod:`.implementations`), the
property block, the annex subclauses and ``end``. The features, flow specifications, modes and
annex texts of classifiers are here too.
"""

from __future__ import annotations

from collections.abc import Sequence

from pyecore.ecore import EObject

from rosaadl.exporters.aadl_text.associations import element_with_properties, modal_item, property_association
from rosaadl.exporters.aadl_text.context import UnitContext
from rosaadl.exporters.aadl_text.implementations import (
    call_sequences,
    connection_end,
    connections,
    flow_implementations,
    subcomponents,
)
from rosaadl.exporters.aadl_text.lexical import (
    DIRECTED,
    ID_RE,
    IMPL_NAME_RE,
    OPTIONALLY_DIRECTED,
    enum_name,
    literal,
)
from rosaadl.resolution import feature_category_word

__all__ = ["classifier", "annex_text"]


def classifier(ctx: UnitContext, cl: EObject) -> None:
    """One classifier of a package section, from its header to its ``end``."""
    kind = cl.eClass.name  # dispatch on the written kind
    if kind == "ComponentImplementation":
        name = _implementation_name(ctx, cl)
        header = f"{literal(cl.category)} implementation {name}"
    elif kind == "ComponentType":
        name = ctx.ident(cl.name, f"the {literal(cl.category)} type", cl)
        ctx.where.append(name)
        header = f"{literal(cl.category)} {name}"
    elif kind == "FeatureGroupType":
        name = ctx.ident(cl.name, "the feature group type", cl)
        ctx.where.append(name)
        header = f"feature group {name}"
    else:
        raise ctx.error(f"cannot write a {kind} in a package", cl)
    if cl.extended:
        header += " extends " + ctx.classifier_ref(cl.extended, "extended classifier", cl)
    if cl.prototypeBindings:
        header += " " + ctx.bindings(cl.prototypeBindings, cl)
    ctx.emit(1, header)
    _prototypes(ctx, cl)
    if kind == "ComponentType":
        _features(ctx, cl.features)
        _flow_specifications(ctx, cl.flowSpecifications)
        _modes(ctx, cl)
    elif kind == "ComponentImplementation":
        subcomponents(ctx, cl.subcomponents)
        call_sequences(ctx, cl.callSequences)
        connections(ctx, cl)
        flow_implementations(ctx, cl)
        _modes(ctx, cl)
    else:
        _features(ctx, cl.features)
        if cl.inverseOf:
            ctx.emit(2, "inverse of " + ctx.classifier_ref(cl.inverseOf, "inverse feature group type", cl))
    if cl.ownedPropertyAssociations:
        ctx.emit(2, "properties")
        for assoc in cl.ownedPropertyAssociations:
            property_association(ctx, 3, assoc)
    for annex in cl.annexSubclauses:
        _annex_subclause(ctx, 2, annex)
    ctx.emit(1, f"end {name};")
    ctx.where.pop()


def _implementation_name(ctx: UnitContext, impl: EObject) -> str:
    """``Type.impl``: checked against the type the implementation names."""
    raw = " ".join((impl.name or "").split())
    type_name = (impl.type or "").strip().rpartition("::")[2].strip()
    match = IMPL_NAME_RE.match(raw)
    if match is None and type_name and ID_RE.match(raw):
        match = IMPL_NAME_RE.match(f"{type_name}.{raw}")
    if match is None:
        ctx.where.append(raw or "?")
        raise ctx.error(
            f"the {literal(impl.category)} implementation has {impl.name!r}: expected 'Type.impl' "
            "(two AADL identifiers joined by a dot)",
            impl,
        )
    name = f"{match.group(1)}.{match.group(2)}"
    ctx.where.append(name)
    ctx.ident(match.group(1), "the implementation's type", impl)
    ctx.ident(match.group(2), "the implementation", impl)
    if type_name and type_name.lower() != match.group(1).lower():
        raise ctx.error(f"the implementation is named {name!r} but implements type {impl.type!r}", impl)
    return name


def _prototypes(ctx: UnitContext, cl: EObject) -> None:
    if not cl.prototypes:
        return
    ctx.emit(2, "prototypes")
    for proto in cl.prototypes:
        name = ctx.ident(proto.name, "a prototype", proto)
        ctx.where.append(name)
        text = (proto.text or "").strip().removesuffix(";").strip()
        text = ctx.opaque(text, "prototype", proto)
        refined = "refined to " if proto.refined else ""
        ctx.emit(3, f"{name}: {refined}{text};")
        ctx.where.pop()


# --------------------------------------------------------------------------- features


def _features(ctx: UnitContext, features: Sequence[EObject]) -> None:
    if not features:
        return
    ctx.emit(2, "features")
    for feature in features:
        _feature(ctx, feature)


def _feature(ctx: UnitContext, f: EObject) -> None:
    name = ctx.ident(f.name, "a feature", f)
    ctx.where.append(name)
    category = enum_name(f.category)
    # the category's words, except that an abstract feature is declared with the word 'feature'
    words = "feature" if category == "abstractFeature" else feature_category_word(category)
    parts = [f"{name}:"]
    if f.refined:
        parts.append("refined to")
    if category in DIRECTED:
        parts.append(literal(f.direction) or "in")
    elif category in OPTIONALLY_DIRECTED:
        direction = enum_name(f.direction)  # 'in out' is the default: no word
        if direction in ("in", "out"):
            parts.append(direction)
    else:
        parts.append(literal(f.access) or "provides")
    parts.append(words)
    if f.inverse:
        if category != "featureGroup":
            raise ctx.error("only a feature group can be 'inverse of' its type", f)
        parts.append("inverse of")
    if f.classifier:
        parts.append(_feature_classifier(ctx, f.classifier, f))
    text = " ".join(parts)
    if f.arrayDimensions:
        if len(f.arrayDimensions) > 1:
            raise ctx.error("a feature array has one dimension in AADL", f)
        text += " " + ctx.array_dimensions(f.arrayDimensions, f)
    element_with_properties(ctx, 3, text, f.ownedPropertyAssociations, "")
    ctx.where.pop()


def _feature_classifier(ctx: UnitContext, text: str, element: EObject) -> str:
    value = " ".join(text.split())
    if value.lower().startswith("prototype "):
        return "prototype " + ctx.ident(value[10:].strip(), "the prototype reference", element)
    return ctx.classifier_ref(value, "feature classifier", element)


# --------------------------------------------------------------------------- flows and modes


def _flow_specifications(ctx: UnitContext, flows: Sequence[EObject]) -> None:
    if not flows:
        return
    ctx.emit(2, "flows")
    for flow in flows:
        name = ctx.ident(flow.name, "a flow specification", flow)
        ctx.where.append(name)
        kind = enum_name(flow.kind)
        text = f"{name}: " + ("refined to " if flow.refined else "") + f"flow {kind}"
        if kind == "source":
            ends = [flow.outEnd] if flow.outEnd else []
        elif kind == "sink":
            ends = [flow.inEnd] if flow.inEnd else []
        else:
            ends = [flow.inEnd, flow.outEnd] if (flow.inEnd or flow.outEnd) else []
            if ends and not all(ends):
                raise ctx.error("a flow path needs both an in end and an out end", flow)
        if not ends and not flow.refined:
            raise ctx.error(f"a flow {kind} needs its end feature", flow)
        if ends:
            text += " " + " -> ".join(ctx.path(e, "flow end", flow) for e in ends)
        modal_item(ctx, text, flow)
        ctx.where.pop()


def _modes(ctx: UnitContext, cl: EObject) -> None:
    if not (cl.modes or cl.modeTransitions):
        return
    ctx.emit(2, "requires modes" if cl.requiresModes else "modes")
    for mode in cl.modes:
        name = ctx.ident(mode.name, "a mode", mode)
        ctx.where.append(name)
        text = f"{name}: " + ("initial " if mode.initial else "") + "mode"
        element_with_properties(ctx, 3, text, mode.ownedPropertyAssociations, "")
        ctx.where.pop()
    for tr in cl.modeTransitions:
        label = tr.name or f"{tr.source} -> {tr.destination}"
        ctx.where.append(label)
        text = f"{ctx.ident(tr.name, 'a mode transition', tr)}: " if tr.name else ""
        source = ctx.ident(tr.source, "the transition's source mode", tr)
        destination = ctx.ident(tr.destination, "the transition's destination mode", tr)
        if not tr.triggers:
            raise ctx.error("a mode transition needs at least one trigger", tr)
        triggers = ", ".join(connection_end(ctx, t or "", "trigger", tr) for t in tr.triggers)
        text += f"{source} -[ {triggers} ]-> {destination}"
        element_with_properties(ctx, 3, text, tr.ownedPropertyAssociations, "")
        ctx.where.pop()


# --------------------------------------------------------------------------- annexes


def annex_text(ctx: UnitContext, annex: EObject) -> str:
    """The annex text in its ``{** **}`` delimiters, or ``none``."""
    text = annex.text
    if text is None:
        return "none"
    delimited = text.startswith("{**") and text.endswith("**}") and len(text) >= 6
    inner = text[3:-3] if delimited else text
    if "**}" in inner:
        raise ctx.error("annex text cannot contain '**}'", annex)
    return "{**" + inner + "**}"


def _annex_subclause(ctx: UnitContext, level: int, annex: EObject) -> None:
    name = ctx.ident(annex.name, "an annex subclause", annex)
    ctx.where.append(f"annex {name}")
    text = annex_text(ctx, annex)
    ctx.emit(level, f"annex {name} {text}{ctx.in_modes(annex.inModes, annex)};")
    ctx.where.pop()
