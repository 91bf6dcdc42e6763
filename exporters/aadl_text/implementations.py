"""The sections of a component implementation as AADL text: subcomponents, calls, connections, flows.

An access connection whose category (``bus access``, ``data access``, ...) is not set in the
model takes it from the subcomponent or feature its ends name, found in the model the unit
belongs to (:func:`access_category`); when neither tells, ``access`` is written alone (our reader
accepts it; OSATE needs the category) and a warning is logged.
"""

from __future__ import annotations

import logging
import re
from collections.abc import Sequence

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.exporters.aadl_text.associations import element_with_properties, modal_item
from rosaadl.exporters.aadl_text.context import UnitContext
from rosaadl.exporters.aadl_text.lexical import (
    ACCESS_COMPONENT_CATEGORY,
    ACCESS_FEATURE_CATEGORY,
    CONNECTION_WORDS,
    ID,
    enum_name,
    literal,
)

__all__ = [
    "subcomponents",
    "call_sequences",
    "connections",
    "connection_end",
    "access_category",
    "flow_implementations",
]

log = logging.getLogger(__package__)  # the writer's one logger, rosaadl.exporters.aadl_text

_ELEMENT_IMPLEMENTATION_RE = re.compile(rf"{ID}(?:\s*::\s*{ID})*(?:\s*\.\s*{ID})?")
_PROCESSOR_SUBPROGRAM_RE = re.compile(rf"processor\s*\.\s*({ID})", re.I)
_SPECIAL_END_RE = re.compile(rf"(processor|self)\s*\.\s*({ID})", re.I)


def subcomponents(ctx: UnitContext, subs: Sequence[EObject]) -> None:
    """The ``subcomponents`` section (with arrays, prototype bindings, element implementations)."""
    if not subs:
        return
    ctx.emit(2, "subcomponents")
    for sub in subs:
        name = ctx.ident(sub.name, "a subcomponent", sub)
        ctx.where.append(name)
        text = f"{name}: " + ("refined to " if sub.refined else "") + literal(sub.category)
        if sub.classifier:
            text += " " + ctx.classifier_ref(sub.classifier, "subcomponent classifier", sub)
        if sub.prototypeBindings:
            if not sub.classifier:
                raise ctx.error("prototype bindings need a classifier", sub)
            text += " " + ctx.bindings(sub.prototypeBindings, sub)
        if sub.arrayDimensions:
            text += " " + ctx.array_dimensions(sub.arrayDimensions, sub)
        if sub.arrayElementBindings:
            if not sub.arrayDimensions:
                raise ctx.error("array element implementations need array dimensions", sub)
            refs = [_element_implementation(ctx, ref, sub) for ref in sub.arrayElementBindings]
            text += f" ({', '.join(refs)})"
        modal_item(ctx, text, sub)
        ctx.where.pop()


def _element_implementation(ctx: UnitContext, text: str, element: EObject) -> str:
    value = " ".join((text or "").split())
    match = _ELEMENT_IMPLEMENTATION_RE.match(value)
    if match is None:
        raise ctx.error(f"array element implementation {text!r} is not a classifier reference", element)
    ref = match.group(0).replace(" ", "")
    rest = value[match.end() :].strip()
    return f"{ref} {ctx.bindings(rest, element)}" if rest else ref


def call_sequences(ctx: UnitContext, sequences: Sequence[EObject]) -> None:
    """The ``calls`` section: ``name: { call: subprogram P::S; ... };``."""
    if not sequences:
        return
    ctx.emit(2, "calls")
    for seq in sequences:
        name = ctx.ident(seq.name, "a call sequence", seq)
        ctx.where.append(name)
        ctx.emit(3, f"{name}: {{")
        for call in seq.calls:
            call_name = ctx.ident(call.name, "a subprogram call", call)
            called = " ".join((call.called or "").split())
            processor = _PROCESSOR_SUBPROGRAM_RE.fullmatch(called)
            if processor:
                called = f"processor.{processor.group(1)}"
            else:
                called = ctx.classifier_ref(called, f"the subprogram called by {call_name!r}", call)
            element_with_properties(
                ctx, 4, f"{call_name}: subprogram {called}", call.ownedPropertyAssociations, ""
            )
        modal_item(ctx, "}", seq)
        ctx.where.pop()


def connections(ctx: UnitContext, impl: EObject) -> None:
    """The ``connections`` section."""
    if not impl.connections:
        return
    ctx.emit(2, "connections")
    for conn in impl.connections:
        label = conn.name or f"{conn.source} -> {conn.destination}"
        ctx.where.append(label)
        kind = enum_name(conn.kind)
        if kind == "accessConnection":
            category = access_category(ctx, conn, impl)
            words = f"{category} access" if category else "access"
        elif kind in CONNECTION_WORDS:
            words = CONNECTION_WORDS[kind]
        else:
            raise ctx.error(f"a {literal(conn.kind)} connection has no AADL text form", conn)
        text = f"{ctx.ident(conn.name, 'a connection', conn)}: " if conn.name else ""
        if conn.refined:
            if not conn.name:
                raise ctx.error("a refined connection needs the name of the connection it refines", conn)
            text += "refined to "
        text += words
        if conn.source or conn.destination:
            if not (conn.source and conn.destination):
                raise ctx.error("a connection needs both a source and a destination", conn)
            arrow = "<->" if conn.bidirectional else "->"
            source = connection_end(ctx, conn.source, "source", conn)
            destination = connection_end(ctx, conn.destination, "destination", conn)
            text += f" {source} {arrow} {destination}"
        elif not conn.refined:
            raise ctx.error("a connection needs a source and a destination", conn)
        modal_item(ctx, text, conn)
        ctx.where.pop()


def connection_end(ctx: UnitContext, text: str, what: str, element: EObject) -> str:
    """A connection end (or mode transition trigger): a path, ``processor.x`` or ``self.x``."""
    value = " ".join(text.split())
    special = _SPECIAL_END_RE.fullmatch(value)
    if special:
        return f"{special.group(1).lower()}.{special.group(2)}"
    return ctx.path(value, f"connection {what}", element)


# --------------------------------------------------------------------------- access categories


def access_category(ctx: UnitContext, conn: EObject, impl: EObject) -> str:
    """The category word of an access connection: as set, else from what its ends name."""
    given = enum_name(conn.accessCategory)
    if given and given != "abstract":  # 'abstract' is the unset value
        category = ACCESS_COMPONENT_CATEGORY.get(given)
        if category is None:
            raise ctx.error(f"{literal(conn.accessCategory)!r} is not an access category", conn)
        return category
    for end in (conn.source, conn.destination):
        category = _inferred_access_category(ctx, end or "", impl)
        if category:
            return category
    log.warning(
        "in %s: the category of access connection %r is not set and its ends do not resolve in the "
        "model; writing 'access' without a category (OSATE needs one)",
        " / ".join(ctx.where[:-1]),
        conn.name or f"{conn.source} -> {conn.destination}",
    )
    return ""


def _inferred_access_category(ctx: UnitContext, end: str, impl: EObject) -> str:
    parts = [p.strip() for p in end.split(".")]
    if len(parts) == 1:
        for sub in _chain(ctx, impl, "subcomponents"):
            if (sub.name or "").lower() == parts[0].lower():
                return ACCESS_COMPONENT_CATEGORY.get(enum_name(sub.category), "")
        own_type = _type_of(ctx, impl)
        if own_type is not None:
            return _feature_access_category(ctx, own_type, parts[0])
        return ""
    if len(parts) == 2:
        for sub in _chain(ctx, impl, "subcomponents"):
            if (sub.name or "").lower() == parts[0].lower():
                classifier = _resolve(ctx, sub.classifier, impl) if sub.classifier else None
                if classifier is None:
                    return ""
                if model.is_a(classifier, "ComponentImplementation"):
                    classifier = _type_of(ctx, classifier)
                if classifier is None:
                    return ""
                return _feature_access_category(ctx, classifier, parts[1])
    return ""


def _feature_access_category(ctx: UnitContext, classifier: EObject, name: str) -> str:
    for feature in _chain(ctx, classifier, "features"):
        if (feature.name or "").lower() == name.lower():
            return ACCESS_FEATURE_CATEGORY.get(enum_name(feature.category), "")
    return ""


def _resolve(ctx: UnitContext, ref: str | None, context: EObject) -> EObject | None:
    """The classifier ``ref`` names from ``context``, in the model the unit belongs to (cached)."""
    if not ref:
        return None
    text = ref.replace(" ", "")
    pkg_name, _, local = text.rpartition("::")
    if not pkg_name:
        owner = context.eContainer()
        while owner is not None and not model.is_a(owner, "AadlPackage"):
            owner = owner.eContainer()
        pkg_name = owner.name if owner is not None else ""
    key = f"{pkg_name}::{local}".lower()
    cache = ctx.classifier_cache
    if key in cache:
        return cache[key]
    found = None
    units = ctx.root.units if model.is_a(ctx.root, "AadlModel") else [ctx.root]
    for unit in units:
        if model.is_a(unit, "AadlPackage") and (unit.name or "").replace(" ", "").lower() == pkg_name.lower():
            for classifier in unit.classifiers:
                if (classifier.name or "").replace(" ", "").lower() == local.lower():
                    found = classifier
                    break
    cache[key] = found
    return found


def _type_of(ctx: UnitContext, impl: EObject) -> EObject | None:
    if impl.type:
        return _resolve(ctx, impl.type, impl)
    name = (impl.name or "").partition(".")[0]
    return _resolve(ctx, name, impl) if name else None


def _chain(ctx: UnitContext, classifier: EObject, feature: str) -> list[EObject]:
    """The ``feature`` items of a classifier and of the classifiers it extends (nearest first)."""
    out: list[EObject] = []
    seen: set[int] = set()
    current: EObject | None = classifier
    while current is not None and id(current) not in seen:
        seen.add(id(current))
        out.extend(getattr(current, feature, ()))
        current = _resolve(ctx, current.extended, current) if current.extended else None
    return out


# --------------------------------------------------------------------------- flows


def flow_implementations(ctx: UnitContext, impl: EObject) -> None:
    """The ``flows`` section of an implementation: flow implementations and end-to-end flows.
    (A property block of a flow implementation is written although OSATE's grammar has none.)"""
    if not (impl.flowImplementations or impl.endToEndFlows):
        return
    ctx.emit(2, "flows")
    for flow in impl.flowImplementations:
        name = ctx.ident(flow.name, "a flow implementation", flow)
        ctx.where.append(name)
        if not flow.elements:
            raise ctx.error("a flow implementation needs its flow elements", flow)
        elements = " -> ".join(ctx.path(e, "flow element", flow) for e in flow.elements)
        text = f"{name}: flow {enum_name(flow.kind)} {elements}"
        modal_item(ctx, text, flow)
        ctx.where.pop()
    for flow in impl.endToEndFlows:
        name = ctx.ident(flow.name, "an end-to-end flow", flow)
        ctx.where.append(name)
        text = f"{name}: " + ("refined to " if flow.refined else "") + "end to end flow"
        if flow.elements:
            text += " " + " -> ".join(ctx.path(e, "flow element", flow) for e in flow.elements)
        elif not flow.refined:
            raise ctx.error("an end-to-end flow needs its flow elements", flow)
        modal_item(ctx, text, flow)
        ctx.where.pop()
