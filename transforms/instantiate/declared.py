"""Declared connections, resolved once per implementation for the semantic connection walk.

Each connection declaration of an implementation (its own and inherited, refinements applied)
becomes a :class:`DeclaredConnection` whose two :class:`ConnectionEnd` say what the end names:
a feature of the implementation, a subcomponent, a feature of a subcomponent, a member of one of
its own feature groups, or a processor/self feature. A connection whose end names nothing is
reported once and left out.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.resolution import split_path

from .mirrors import ComponentMirror, enum_name, literal

if TYPE_CHECKING:
    from .instantiator import Instantiator

__all__ = ["ConnectionEnd", "DeclaredConnection", "declared_connections", "outgoing_by_context"]


@dataclass(eq=False)
class ConnectionEnd:
    """One end of a declared connection, resolved against its implementation."""

    ctx_kind: str | None  # None, "sub" or "fg"
    ctx: str  # lower-case context name
    end_kind: str  # "feature", "sub", "internal" or "unknown"
    end: str  # lower-case end name
    next: tuple[str, ...] = ()  # the names after the end (members of a feature group)
    feature: EObject | None = None
    category: str = ""  # feature category name of the end feature
    sub_category: str = ""  # declared category of the end (or context) subcomponent
    ctx_category: str = ""
    owner_is_subprogram_type: bool = False


@dataclass(eq=False)
class DeclaredConnection:
    """A connection declaration with its resolved ends."""

    decl: EObject
    name: str
    kind: str  # ConnectionKind name (portConnection, accessConnection, ...)
    bidir: bool
    src: ConnectionEnd
    dst: ConnectionEnd
    modes: tuple[str, ...]  # lower-case names of the modes it exists in
    same_fg: bool = False  # a feature group connection between groups of one type

    @property
    def across(self) -> bool:
        """Does it connect two subcomponents (rather than go up or down)?"""
        return (self.src.ctx_kind == "sub" or self.src.end_kind == "sub") and (
            self.dst.ctx_kind == "sub" or self.dst.end_kind == "sub"
        )


def declared_connections(st: Instantiator, ci: ComponentMirror | None) -> list[DeclaredConnection]:
    """The connections declared by the implementation of ``ci`` (computed once per implementation)."""
    if ci is None or ci.node.impl is None:
        return []
    impl = ci.node.impl
    key = id(impl)
    cached = st.declared.get(key)
    if cached is not None:
        return cached
    resolver = st.resolver
    subs = {(s.name or "").lower(): s for s in resolver.subcomponents(impl)}
    own_features = {(f.name or "").lower(): f for f in resolver.features(impl)}
    result = []
    for decl in resolver.connections(impl):
        source, destination = resolver.connection_ends(decl)
        src = _end(st, source, subs, own_features)
        dst = _end(st, destination, subs, own_features)
        kind = enum_name(resolver.effective_attribute(decl, "kind") or decl.kind)
        bidir = any(bool(e.bidirectional) for e in resolver.refinement_chain(decl))
        modes = tuple(m.lower() for m in (resolver.effective_attribute(decl, "inModes") or ()))
        conn = DeclaredConnection(decl, decl.name or "", kind, bidir, src, dst, modes)
        if kind == "featureGroupConnection" and src.feature is not None and dst.feature is not None:
            a = resolver.feature_classifier(src.feature)
            b = resolver.feature_classifier(dst.feature)
            conn.same_fg = a is not None and a is b
        if src.end_kind == "unknown" or dst.end_kind == "unknown":
            st.warn(
                f"connection {decl.name}: end {source if src.end_kind == 'unknown' else destination} "
                "does not name a feature or subcomponent; not instantiated",
                resolver.qualified_name(impl),
                decl,
            )
            continue
        result.append(conn)
    st.declared[key] = result
    return result


def outgoing_by_context(st: Instantiator, ci: ComponentMirror) -> dict[str, list[DeclaredConnection]]:
    """The connections of an implementation that leave each subcomponent (by its name)."""
    impl = ci.node.impl
    key = id(impl)
    table = st.outgoing.get(key)
    if table is None:
        table = {}
        for conn in declared_connections(st, ci):
            contexts = []
            if conn.src.ctx_kind == "sub":
                contexts.append(conn.src.ctx)
            if conn.bidir and conn.dst.ctx_kind == "sub" and conn.dst.ctx not in contexts:
                contexts.append(conn.dst.ctx)
            for context in contexts:
                table.setdefault(context, []).append(conn)
        st.outgoing[key] = table
    return table


def _end(st: Instantiator, text: str, subs: dict, own_features: dict) -> ConnectionEnd:
    resolver = st.resolver
    segments = [s.key for s in split_path(text)]
    if not segments:
        return ConnectionEnd(None, "", "unknown", "")
    first = segments[0]
    if first in ("processor", "self") and len(segments) >= 2:
        return ConnectionEnd(None, "", "internal", segments[1])
    if len(segments) == 1:
        feature = own_features.get(first)
        if feature is not None:
            return ConnectionEnd(None, "", "feature", first, (), feature, enum_name(feature.category))
        sub = subs.get(first)
        if sub is not None:
            return ConnectionEnd(None, "", "sub", first, sub_category=literal(sub.category))
        return ConnectionEnd(None, "", "unknown", first)
    sub = subs.get(first)
    if sub is not None:
        classifier = resolver.subcomponent_classifier(sub)
        features = {(f.name or "").lower(): f for f in resolver.features(classifier)}
        feature = features.get(segments[1])
        owner_sub = (
            classifier is not None
            and enum_name(classifier.category) == "subprogram"
            and _model.is_a(classifier, "ComponentType")
        )
        category = enum_name(feature.category) if feature is not None else ""
        return ConnectionEnd(
            "sub",
            first,
            "feature",
            segments[1],
            tuple(segments[2:]),
            feature,
            category,
            ctx_category=literal(sub.category),
            owner_is_subprogram_type=bool(owner_sub),
        )
    group = own_features.get(first)
    if group is not None and enum_name(group.category) == "featureGroup":
        fgt = resolver.feature_classifier(group)
        feature = None
        if fgt is not None and _model.is_a(fgt, "FeatureGroupType"):
            members, _ = resolver.feature_group_features(fgt)
            feature = next((f for f in members if (f.name or "").lower() == segments[1]), None)
        category = enum_name(feature.category) if feature is not None else ""
        return ConnectionEnd("fg", first, "feature", segments[1], tuple(segments[2:]), feature, category)
    return ConnectionEnd(None, "", "unknown", first)
