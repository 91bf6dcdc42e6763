"""Semantic connections: OSATE's algorithm, from ultimate source to ultimate destination.

Each declared connection is a hop. A connection instance starts at a thread, device, processor
or shared data/bus component, or at a feature nothing inside continues
(:func:`instantiate_connections`), and the walk (:func:`_append`) goes up through the
enclosing implementations, across once, and down into the destination's, cloning the
:class:`~.connection_instances.ConnectionInfo` at every fork; where it ends,
:func:`.feature_group_matching.finalize` makes the instance(s). Ports that trigger a mode
transition also make mode transition connections. Only first array elements are walked; the
other elements get theirs from :mod:`.arrays`.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from rosaadl.resolution import split_path

from .connection_instances import ConnectionInfo, add_connection, same_feature
from .declared import ConnectionEnd, DeclaredConnection, declared_connections, outgoing_by_context
from .feature_group_matching import finalize
from .mirrors import ACCESS, ENDING, PORTS, SHARED, ComponentMirror, FeatureMirror, component_path, end_path

if TYPE_CHECKING:
    from .instantiator import Instantiator

__all__ = ["instantiate_connections"]


def instantiate_connections(st: Instantiator) -> None:
    """Every semantic connection instance of the system (between first array elements)."""
    root = st.root
    for ci in st.components:
        if ci is root:
            _external_connections(st, root)
        elif all(i <= 1 for a in _lineage(ci) for i in a.index):
            _start_connections(st, ci)


def _lineage(ci: ComponentMirror) -> Iterable[ComponentMirror]:
    current: ComponentMirror | None = ci
    while current is not None and current.parent is not None:
        yield current
        current = current.parent


def _start_connections(st: Instantiator, ci: ComponentMirror) -> None:
    """The connections that start at ``ci`` or at one of its features."""
    category = ci.category
    parent = ci.parent
    parent_conns = declared_connections(st, parent)
    if not parent_conns:
        return
    sub_key = ci.sub_key
    if category in SHARED:
        for conn in parent_conns:
            src_is = conn.src.end_kind == "sub" and conn.src.end == sub_key
            dst_is = conn.dst.end_kind == "sub" and conn.dst.end == sub_key
            if src_is or (conn.bidir and dst_is):
                _append(st, ConnectionInfo(ci), conn, parent, dst_is)
    outside = outgoing_by_context(st, parent).get(sub_key, [])
    if not outside:
        return
    inside = declared_connections(st, ci)
    has_outgoing_subs = any(_has_outgoing_feature(child) for child in ci.children)
    ending = category in ENDING
    previous: FeatureMirror | None = None
    for fi in ci.features:
        if previous is not None and previous.key == fi.key:
            continue
        if not _has_outgoing_features(fi):
            continue
        outgoing = [
            c
            for c in outside
            if (c.src.ctx_kind == "sub" and c.src.ctx == sub_key and c.src.end == fi.key)
            or (c.bidir and c.dst.ctx_kind == "sub" and c.dst.ctx == sub_key and c.dst.end == fi.key)
        ]
        if not outgoing:
            continue
        has_access, has_port, has_group = _feature_info(fi)
        look_inside = has_outgoing_subs and (not ending or has_access)
        connected_inside = look_inside and _is_connection_end(inside, fi.key)
        destination_inside = look_inside and _is_destination(inside, fi.key)
        for conn in outgoing:
            if (not destination_inside and not (conn.bidir and connected_inside)) or (
                ending and (has_group or has_port)
            ):
                previous = fi
                opposite = not (conn.src.ctx == sub_key and conn.src.end == fi.key) and (
                    conn.bidir and conn.dst.ctx == sub_key and conn.dst.end == fi.key
                )
                _append(st, ConnectionInfo(fi), conn, parent, opposite)


def _has_outgoing_feature(ci: ComponentMirror) -> bool:
    for fi in ci.features:
        if fi.category in PORTS and fi.outgoing:
            return True
        if fi.category in ACCESS or fi.category == "featureGroup":
            return True
        if fi.category == "abstractFeature" and fi.outgoing:
            return True
    return ci.category in SHARED


def _external_connections(st: Instantiator, root: ComponentMirror) -> None:
    """The connections that start at a feature of the system itself."""
    conns = declared_connections(st, root)
    if not conns:
        return
    for fi in root.features:
        _incoming(st, fi, root, conns)
        for contained in fi.children:
            _incoming(st, contained, root, conns)


def _incoming(
    st: Instantiator, fi: FeatureMirror, root: ComponentMirror, conns: list[DeclaredConnection]
) -> None:
    if not fi.incoming or fi.index > 1:
        return
    parent_key = fi.parent.key if fi.parent is not None else None
    selected = []
    for conn in conns:
        for end in (conn.src, conn.dst) if conn.bidir else (conn.src,):
            if end.end_kind != "feature" or end.end != fi.key:
                continue
            if end.ctx_kind is None and fi.parent is None or end.ctx_kind == "fg" and end.ctx == parent_key:
                selected.append(conn)
    for conn in selected:
        opposite = not (conn.src.end_kind == "feature" and conn.src.end == fi.key) and (
            conn.bidir and conn.dst.end == fi.key
        )
        _append(st, ConnectionInfo(fi), conn, root, opposite)


def _append(
    st: Instantiator, info: ConnectionInfo, conn: DeclaredConnection, ci: ComponentMirror, opposite: bool
) -> None:
    """Follow hop ``conn`` (declared in ``ci``; ``opposite``: from its destination) and go on."""
    did_transition = _mode_transition_connections(st, ci, info, conn)
    from_ref = conn.dst if opposite else conn.src
    to_ref = conn.src if opposite else conn.dst
    to_ci = ci.child(to_ref.ctx) if to_ref.ctx_kind == "sub" else None
    final_component = to_ref.ctx_kind == "sub" and to_ref.ctx_category in ENDING
    pushed = popped = downed = None

    if to_ref.category == "parameter" and (
        (from_ref.end_kind == "sub" and from_ref.sub_category == "data") or from_ref.category == "dataAccess"
    ):
        return
    if to_ref.category == "dataAccess" and to_ref.owner_is_subprogram_type:
        return
    if to_ref.ctx_kind == "sub" and to_ci is None:
        if to_ref.ctx_category != "subprogram":
            st.warn(f"no component instance for subcomponent {to_ref.ctx}", component_path(ci), conn.decl)
        return
    dst_empty = to_ci is not None and not to_ci.children

    from_end: Any = None
    if from_ref.end_kind != "sub":
        from_ci = ci.child(from_ref.ctx) if from_ref.ctx_kind == "sub" else None
        if from_ref.ctx_kind == "sub" and from_ci is None:
            if from_ref.ctx_category != "subprogram":
                st.warn(
                    f"no component instance for subcomponent {from_ref.ctx}", component_path(ci), conn.decl
                )
            return
        if from_ref.ctx_kind == "fg":
            group = ci.feature(from_ref.ctx)
            from_end = group.child(from_ref.end) if group is not None else None
            if from_end is not None:
                if st.up:
                    top = st.up[-1]
                    if not info.dst_to_match and not same_feature(top, from_end):
                        return
                    popped = st.up.pop()
                else:
                    st.down.append(from_end)
                    downed = from_end
        else:
            from_end = (from_ci or ci).feature(from_ref.end)
    else:
        from_end = ci.child(from_ref.end)

    to_end: Any = None
    if to_ref.end_kind != "sub":
        if to_ref.ctx_kind == "fg":
            group = ci.feature(to_ref.ctx)
            to_end = group.child(to_ref.end) if group is not None else None
            if to_end is not None:
                st.up.append(to_end)
                pushed = to_end
        else:
            to_end = (to_ci or ci).feature(to_ref.end)
    else:
        to_end = ci.child(to_ref.end)

    try:
        if (
            isinstance(from_end, FeatureMirror)
            and from_end.category in PORTS
            and isinstance(to_end, FeatureMirror)
            and to_end.parent is None
            and to_end.owner is ci
            and ci.category in ENDING
        ):
            return
        keep, valid = info.add_segment(conn, from_end, to_end, ci, opposite)
        if not keep:
            return
        if not valid:
            st.warn(
                f"connection from {end_path(info.src)} via {conn.name} has no valid direction; "
                "no connection instance created",
                component_path(ci),
                conn.decl,
            )
            return
        if to_ref.end_kind == "sub":
            target = ci.child(to_ref.end)
            if target is None:
                st.warn(
                    f"connection to {to_ref.end} could not be instantiated", component_path(ci), conn.decl
                )
            else:
                info.complete = True
                finalize(st, st.root, info, target)
        elif to_ref.end_kind == "internal":
            st.warn(f"connection to {to_ref.end} could not be instantiated", component_path(ci), conn.decl)
        elif to_ref.category == "parameter" or dst_empty:
            holder = to_ci or ci
            target = holder.feature(to_ref.end)
            if target is None:
                st.warn(f"destination feature {to_ref.end} not found", component_path(holder), conn.decl)
            else:
                info.complete = True
                finalize(st, ci, info, target)
        elif to_ref.ctx_kind != "sub":
            _going_up(st, info, conn, ci, to_ref, did_transition)
        else:
            _going_down(st, info, conn, ci, to_ref, to_ci, final_component)
    finally:
        if pushed is not None and st.up:
            st.up.pop()
        if popped is not None and not st.down:
            st.up.append(popped)
        if downed is not None and st.down:
            st.down.pop()


def _going_up(
    st: Instantiator,
    info: ConnectionInfo,
    conn: DeclaredConnection,
    ci: ComponentMirror,
    to_ref: ConnectionEnd,
    did_transition: bool,
) -> None:
    """The hop reached a feature of ``ci``: continue with the connections of its parent."""
    to_key = to_ref.ctx if to_ref.ctx_kind == "fg" else to_ref.end
    if ci.parent is None:
        finalize(st, ci, info, ci.feature(to_key))
        return
    next_ci = ci.parent
    parent_conns = declared_connections(st, next_ci)
    dst_fi = ci.feature(to_key)
    if dst_fi is None:
        return
    sub_key = ci.sub_key
    conns = [
        c
        for c in parent_conns
        if (c.src.ctx_kind == "sub" and c.src.ctx == sub_key and c.src.end == dst_fi.key)
        or (c.bidir and c.dst.ctx_kind == "sub" and c.dst.ctx == sub_key and c.dst.end == dst_fi.key)
    ]
    if not conns:
        if st.legacy and not did_transition:
            finalize(st, ci, info, dst_fi)
        elif not did_transition:
            # a feature nothing continues outside (often an unused provided access): OSATE
            # warned about it until its connection rework, which drops it silently
            st.warn(
                f"could not continue connection from {end_path(info.src)} through "
                f"{end_path(dst_fi)}; no connection instance created",
                component_path(ci),
                conn.decl,
                severity="info",
            )
        return
    for next_conn in conns:
        clone = info.clone()
        opposite = False
        if next_conn.bidir and next_conn.dst.end_kind == "feature":
            nd = next_conn.dst
            next_dst = next_ci.feature(nd.end) if nd.ctx_kind is None else None
            if next_dst is None and nd.ctx_kind == "sub":
                sub_ci = next_ci.child(nd.ctx)
                next_dst = sub_ci.feature(nd.end) if sub_ci is not None else None
            if next_dst is not None:
                opposite = ci.feature(to_key) is next_dst
        _append(st, clone, next_conn, next_ci, opposite)


def _going_down(
    st: Instantiator,
    info: ConnectionInfo,
    conn: DeclaredConnection,
    ci: ComponentMirror,
    to_ref: ConnectionEnd,
    to_ci: ComponentMirror,
    final: bool,
) -> None:
    """The hop reached a feature of subcomponent ``to_ci``: continue with its connections."""
    target = to_ci.feature(to_ref.end)
    if target is None:
        st.warn(
            f"could not find feature {to_ref.end} of subcomponent {to_ref.ctx}; "
            "no connection instance created",
            component_path(ci),
            conn.decl,
        )
        return
    if to_ci.node.impl is None:
        info.complete = True
        finalize(st, ci, info, target)
        return
    ignored = False
    inner = []
    for c in declared_connections(st, to_ci):
        matches = (
            (c.src.ctx_kind is None and c.src.end_kind == "feature" and c.src.end == to_ref.end)
            or (
                c.bidir and c.dst.ctx_kind is None and c.dst.end_kind == "feature" and c.dst.end == to_ref.end
            )
            or (c.src.ctx_kind == "fg" and c.src.ctx == to_ref.end)
            or (c.bidir and c.dst.ctx_kind == "fg" and c.dst.ctx == to_ref.end)
        )
        if not matches:
            continue
        if c.kind == "accessConnection":
            if c.src.ctx_category == "subprogram" or c.dst.ctx_category == "subprogram":
                ignored = True
                continue
        elif c.kind == "parameterConnection" or final:
            ignored = True
            continue
        inner.append(c)
    if not inner:
        if st.resolver.subcomponents(to_ci.node.impl):
            info.complete = True
            finalize(st, ci, info, target)
        return
    if ignored:
        clone = info.clone()
        clone.complete = True
        finalize(st, ci, clone, target)
    for next_conn in inner:
        clone = info.clone()
        nd = next_conn.dst
        opposite = (nd.ctx_kind is None and nd.end_kind == "feature" and nd.end == to_ref.end) or (
            nd.ctx_kind == "fg" and nd.ctx == to_ref.end
        )
        _append(st, clone, next_conn, to_ci, opposite)


def _mode_transition_connections(
    st: Instantiator, ci: ComponentMirror, info: ConnectionInfo, conn: DeclaredConnection
) -> bool:
    """Mode transition connections where hop ``conn`` reaches a port of ``ci`` that triggers a
    mode transition of its parent; whether there was one."""
    if conn.kind not in ("portConnection", "featureGroupConnection"):
        return False
    dst = conn.dst
    if dst.ctx_kind == "sub" or ci.parent is None or ci.sub is None:
        return False
    parent = ci.parent
    done = False
    for mti, transition in parent.transitions:
        for trigger in transition.triggers:
            segments = [s.key for s in split_path(trigger)]
            if len(segments) == 2 and segments[0] == ci.sub_key and segments[1] == dst.end:
                clone = info.clone()
                clone.mode_transition = True
                add_connection(st, clone, mti)
                done = True
    return done


def _has_outgoing_features(fi: FeatureMirror) -> bool:
    if not fi.children:
        return fi.direction != "in"
    return any(_has_outgoing_features(child) for child in fi.children)


def _feature_info(fi: FeatureMirror) -> tuple[bool, bool, bool]:
    """(has access, has port, has feature group) of a feature or the members of a feature group."""
    if fi.category == "featureGroup":
        members = fi.children
        return (
            any(m.category in ACCESS for m in members),
            any(m.category in PORTS for m in members),
            any(m.category == "featureGroup" for m in members),
        )
    return fi.category in ACCESS, fi.category in PORTS, False


def _is_connection_end(conns: list[DeclaredConnection], key: str) -> bool:
    return any(
        _names_own_feature(end, key)
        for conn in conns
        if conn.kind != "parameterConnection"
        for end in (conn.src, conn.dst)
    )


def _is_destination(conns: list[DeclaredConnection], key: str) -> bool:
    return any(
        _names_own_feature(end, key)
        for conn in conns
        if conn.kind != "parameterConnection"
        for end in ((conn.dst, conn.src) if conn.bidir else (conn.dst,))
    )


def _names_own_feature(end: ConnectionEnd, key: str) -> bool:
    """Does ``end`` name feature ``key`` of the implementation itself (or a member of it, a group)?"""
    return (end.ctx_kind is None and end.end_kind == "feature" and end.end == key) or (
        end.ctx_kind == "fg" and end.ctx == key
    )
