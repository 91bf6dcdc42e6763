"""Where a semantic connection ends: feature group ends matched member by member.

When the walk of :mod:`.connections` reaches the ultimate destination, :func:`finalize` (OSATE's
finalizeConnectionInstance) makes the connection instance. When an end is a feature group, the
connection is narrowed to the members it went through (the feature group members pushed on the
instantiator's ``up``/``down`` stacks, or named by the hops), or expanded to one connection
instance per pair of corresponding members: by name, or by position between a feature group type
and its inverse, or (``Classifier_Matching_Rule => Subset``) by the leaves of the source that
the destination names.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from pyecore.ecore import EObject

from rosaadl import model as _model

from .connection_instances import ConnectionInfo, add_connection
from .mirrors import ComponentMirror, FeatureMirror, end_path

if TYPE_CHECKING:
    from .instantiator import Instantiator

__all__ = ["find_member", "finalize"]


def finalize(st: Instantiator, parent: ComponentMirror | None, info: ConnectionInfo, dst: Any) -> None:
    """Make the connection instance(s) of ``info`` ending at ``dst`` (declared in ``parent``)."""
    if dst is None:
        return
    up_fi = None
    if isinstance(dst, FeatureMirror):
        dst_fi = dst
        if dst_fi.category == "featureGroup" and st.up:
            up_fi = st.up.pop()
            if up_fi.parent is dst_fi:
                dst_fi = up_fi
            elif up_fi.parent is not None and _fg_inverse(st, up_fi.parent, dst_fi) and dst_fi.children:
                dst_fi = _at_same_position(dst_fi, up_fi)
        try:
            if isinstance(info.src, FeatureMirror):
                if not info.src.children and not dst_fi.children:
                    add_connection(st, info, dst_fi)
                else:
                    _balance(st, parent, info, info.src, dst_fi)
            elif isinstance(info.src, ComponentMirror):
                if not dst_fi.children:
                    add_connection(st, info, dst_fi)
                else:
                    _balance(st, parent, info, info.src, dst_fi)
        finally:
            if up_fi is not None:
                st.up.append(up_fi)
    elif isinstance(dst, ComponentMirror) and isinstance(info.src, FeatureMirror):
        if not info.src.children:
            add_connection(st, info, dst)
        else:
            _balance(st, parent, info, info.src, dst)


def _fg_inverse(st: Instantiator, a: FeatureMirror, b: FeatureMirror) -> bool:
    """Are two feature group instances inverse of each other (both with members)?"""
    ta, tb = a.fgt, b.fgt
    if ta is None or tb is None:
        return False
    resolver = st.resolver
    if not resolver.feature_group_features(ta)[0] or not resolver.feature_group_features(tb)[0]:
        return False
    if bool(resolver.effective_attribute(a.decl, "inverse")) == bool(
        resolver.effective_attribute(b.decl, "inverse")
    ):
        return _fgt_inverse(st, ta, tb)
    return ta is tb


def _fgt_inverse(st: Instantiator, ta: EObject, tb: EObject) -> bool:
    inv_a = st.resolver.classifier(ta.inverseOf, ta) if ta.inverseOf else None
    inv_b = st.resolver.classifier(tb.inverseOf, tb) if tb.inverseOf else None
    return inv_a is tb or inv_b is ta


def _balance(
    st: Instantiator, parent: ComponentMirror | None, info: ConnectionInfo, src: Any, dst: Any
) -> None:
    """Narrow the ends to the feature group members the connection went through, then expand."""
    if st.up:
        for up_fi in reversed(list(st.up)):
            if not isinstance(dst, FeatureMirror):
                break
            if info.dst_to_match:
                name = info.dst_to_match[0]
                dst = dst.child(name)
                info.dst_to_match = info.dst_to_match[1:]
            elif up_fi.parent is not None and _fg_inverse(st, up_fi.parent, dst):
                dst = _at_same_position(dst, up_fi)
            elif isinstance(src, FeatureMirror):
                # OSATE matches the source by name here
                src = dst.child(up_fi.key)
            if dst is None or src is None:
                return
    elif st.down:
        for down_fi in list(st.down):
            if not isinstance(src, FeatureMirror):
                break
            if info.src_to_match:
                name = info.src_to_match[0]
                src = src.child(name)
                info.src_to_match = info.src_to_match[1:]
            elif down_fi.parent is not None and _fg_inverse(st, src, down_fi.parent):
                src = _at_same_position(src, down_fi)
            else:
                src = src.child(down_fi.key)
            if src is None:
                return
        info.src = src
    if isinstance(src, ComponentMirror) and isinstance(dst, ComponentMirror):
        return
    if isinstance(src, ComponentMirror) or isinstance(dst, ComponentMirror):
        add_connection(st, info, dst)
    else:
        _expand(st, parent, info, src, dst, info.src_to_match, info.dst_to_match)


def _expand(
    st: Instantiator,
    parent: ComponentMirror | None,
    info: ConnectionInfo,
    src: FeatureMirror,
    dst: FeatureMirror,
    src_match: tuple[str, ...],
    dst_match: tuple[str, ...],
) -> None:
    """One connection instance per pair of corresponding members of ``src`` and ``dst``."""
    old = info.src
    try:
        if src_match:
            for fi in src.children:
                if fi.key == src_match[0]:
                    _expand(st, parent, info, fi, dst, src_match[1:], dst_match)
                    break
            return
        if dst_match:
            for fi in dst.children:
                if fi.key == dst_match[0]:
                    _expand(st, parent, info, src, fi, src_match, dst_match[1:])
                    break
            return
        if not src.children and not dst.children:
            if info.across:
                if src.outgoing and dst.incoming:
                    info.src = src
                    add_connection(st, info, dst)
            else:
                up_only = _up_only(info, src, dst)
                if (up_only and src.outgoing and dst.outgoing) or (
                    not up_only and src.incoming and dst.incoming
                ):
                    info.src = src
                    add_connection(st, info, dst)
        elif not src.children:
            target = find_member(info, dst, at_destination=True)
            if target is not None and ((info.across and target.incoming) or target.outgoing):
                _expand(st, parent, info, src, target, src_match, dst_match)
            elif src.category == "featureGroup":
                up_only = _up_only(info, src, dst)
                for element in dst.children:
                    if (up_only and element.outgoing) or (not up_only and element.incoming):
                        _expand(st, parent, info, src, element, src_match, dst_match)
            else:
                info.src = src
                add_connection(st, info, dst)
        elif not dst.children:
            target = find_member(info, src, at_destination=False)
            if target is not None and ((info.across and target.outgoing) or target.incoming):
                _expand(st, parent, info, target, dst, src_match, dst_match)
            elif dst.category == "featureGroup" or info.src_to_match:
                down_only = not info.across and not _up_only(info, src, dst)
                for element in src.children:
                    if (down_only and element.incoming) or (not down_only and element.outgoing):
                        _expand(st, parent, info, element, dst, src_match, dst_match)
            else:
                info.src = src
                add_connection(st, info, dst)
        elif _subset_match(st, info):
            for element in dst.children:
                if (info.across and element.incoming) or element.outgoing:
                    match = _find_leaf(src, element.key)
                    if match is not None:
                        _expand(st, parent, info, match, element, src_match, dst_match)
        else:
            for a, b in zip(src.children, dst.children, strict=False):
                _expand(st, parent, info, a, b, src_match, dst_match)
            if len(src.children) != len(dst.children):
                st.warn("connected feature groups do not have the same number of features", end_path(src))
    finally:
        info.src = old


def _subset_match(st: Instantiator, info: ConnectionInfo) -> bool:
    """Does a hop of the connection say ``Classifier_Matching_Rule => Subset``?"""
    lookup = st.lookup
    key = lookup.property_key("Modeling_Properties::Classifier_Matching_Rule")
    for conn in info.connections:
        for member in st.resolver.refinement_chain(conn.decl):
            for pa in lookup.holder_associations(member).get(key, ()):
                for mv in pa.ownedValues:
                    value = mv.value
                    if _model.is_a(value, "NamedValue") and (value.name or "").lower() == "subset":
                        return True
    return False


def _at_same_position(group: FeatureMirror, member: FeatureMirror) -> FeatureMirror:
    """The member of ``group`` at the position ``member`` has among its siblings (``group``
    itself when it has no member there): how a feature group type and its inverse correspond."""
    siblings = member.parent.children if member.parent is not None else member.owner.features
    position = next((i for i, other in enumerate(siblings) if other is member), -1)
    return group.children[position] if 0 <= position < len(group.children) else group


def _up_only(info: ConnectionInfo, src: FeatureMirror, dst: FeatureMirror) -> bool:
    """Does the connection only go up (its destination's owner encloses its source's)?"""
    if info.across:
        return False
    target = dst.owner
    current: ComponentMirror | None = src.owner
    while current is not None:
        if current is target:
            return True
        current = current.parent
    return False


def _find_leaf(group: FeatureMirror, key: str) -> FeatureMirror | None:
    stack = list(reversed(group.children))
    while stack:
        fi = stack.pop()
        if not fi.children and fi.key == key:
            return fi
        stack.extend(reversed(fi.children))
    return None


def find_member(info: ConnectionInfo, group: FeatureMirror, *, at_destination: bool) -> FeatureMirror | None:
    """OSATE's findDestinationFeatureInstance (``at_destination``) and
    findSourceFeatureInstance: the member of feature group ``group``, at that end of the
    connection, that corresponds to the leaf feature the connection reached the other end's
    feature group through.

    Walking the connection's steps from the other end (sources and destinations pairwise,
    backwards for the source end), the step whose near end is the feature group that holds
    the previous step's far end tells the member: the leaf of ``group`` with its name, or else
    (a feature group type and the inverse that names its features differently) the member at
    its position in that feature group.
    """
    steps = list(zip(info.sources, info.destinations, strict=False))
    if not at_destination:
        steps.reverse()
    target: Any = None
    for src, dst in steps:
        near, far = (src, dst) if at_destination else (dst, src)
        if isinstance(target, FeatureMirror) and target.parent is near:
            found = _find_leaf(group, target.key)
            if found is None:
                position = near.children.index(target)
                if position < len(group.children):
                    found = group.children[position]
            return found
        target = far
    return None
