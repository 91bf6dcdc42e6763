"""Connection instances: one under construction (:class:`ConnectionInfo`) and its completion.

A :class:`ConnectionInfo` (OSATE's ConnectionInfo) collects the hops of a semantic connection as
the walk of :mod:`.connections` follows declared connections; :func:`add_connection` (OSATE's
addConnectionInstance) turns a complete one into a ``ConnectionInstance``: duplicates skipped,
the two directions of an access connection merged into one bidirectional instance, the name
relative to its container, one ``ConnectionReference`` per hop, and the system operation modes
it exists in (:func:`.modes.connection_modes`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from pyecore.ecore import EObject

from .mirrors import (
    ACCESS,
    ComponentMirror,
    ConnectionRecord,
    FeatureMirror,
    component_path,
    end_path,
    enum_literal,
)
from .modes import connection_modes

if TYPE_CHECKING:
    from .declared import DeclaredConnection
    from .instantiator import Instantiator

__all__ = [
    "ConnectionInfo",
    "add_connection",
    "attach",
    "connection_name",
    "remove_connection",
    "same_feature",
]


class ConnectionInfo:
    """A connection instance under construction (OSATE's ConnectionInfo)."""

    __slots__ = (
        "connections",
        "opposites",
        "contexts",
        "sources",
        "destinations",
        "src",
        "bidirectional",
        "complete",
        "across",
        "src_to_match",
        "dst_to_match",
        "container",
        "mode_transition",
    )

    def __init__(self, src: Any) -> None:
        self.connections: list[DeclaredConnection] = []
        self.opposites: list[bool] = []
        self.contexts: list[ComponentMirror] = []
        self.sources: list[Any] = []
        self.destinations: list[Any] = []
        self.src = src
        self.bidirectional = True
        self.complete = False
        self.across = False
        self.src_to_match: tuple[str, ...] = ()
        self.dst_to_match: tuple[str, ...] = ()
        self.container: ComponentMirror | None = None
        self.mode_transition = False

    def clone(self) -> ConnectionInfo:
        other = ConnectionInfo(self.src)
        other.connections = list(self.connections)
        other.opposites = list(self.opposites)
        other.contexts = list(self.contexts)
        other.sources = list(self.sources)
        other.destinations = list(self.destinations)
        other.bidirectional = self.bidirectional
        other.complete = self.complete
        other.across = self.across
        other.src_to_match = self.src_to_match
        other.dst_to_match = self.dst_to_match
        other.container = self.container
        other.mode_transition = self.mode_transition
        return other

    def add_segment(
        self, conn: DeclaredConnection, from_end: Any, to_end: Any, ci: ComponentMirror, opposite: bool
    ) -> tuple[bool, bool]:
        """Add a hop (``opposite``: followed from its destination); returns (keep, valid): whether
        the hop continues the feature group members the connection went through, and whether
        the directions of its ends allow it."""
        src_ref = conn.dst if opposite else conn.src
        dst_ref = conn.src if opposite else conn.dst
        going_up = dst_ref.ctx_kind != "sub" and (src_ref.end_kind == "sub" or src_ref.ctx_kind == "sub")
        going_down = src_ref.ctx_kind != "sub" and (dst_ref.end_kind == "sub" or dst_ref.ctx_kind == "sub")
        keep = True
        valid = True
        if from_end is not None:
            self.sources.append(from_end)
            if isinstance(from_end, FeatureMirror):
                direction = from_end.direction
                self.bidirectional &= direction == "in out"
                if going_up or not going_down:
                    valid &= direction in ("out", "in out")
                else:
                    valid &= direction in ("in", "in out")
        self.bidirectional &= conn.bidir
        if to_end is not None:
            self.destinations.append(to_end)
            if isinstance(to_end, FeatureMirror):
                direction = to_end.direction
                self.bidirectional &= direction == "in out"
                if going_up:
                    valid &= direction in ("out", "in out")
                else:
                    valid &= direction in ("in", "in out")
        if valid:
            if conn.across:
                i = len(self.connections)
                to_match = conn.dst.next if opposite else conn.src.next
                while keep and i > 0 and to_match:
                    i -= 1
                    previous = self.connections[i]
                    if not previous.same_fg:
                        end = previous.src.end if self.opposites[i] else previous.dst.end
                        keep = to_match[0] == end
                        to_match = to_match[1:]
                self.src_to_match = to_match
                self.across = True
                self.dst_to_match = conn.src.next if opposite else conn.dst.next
                self.container = ci
            elif self.across and self.dst_to_match and not conn.same_fg:
                end = conn.dst.end if opposite else conn.src.end
                keep = self.dst_to_match[0] == end
                self.dst_to_match = self.dst_to_match[1:]
        self.connections.append(conn)
        self.opposites.append(opposite)
        self.contexts.append(ci)
        return keep, valid


def add_connection(st: Instantiator, info: ConnectionInfo, dst: Any) -> EObject | None:
    """OSATE's addConnectionInstance: skip duplicates, merge the two directions of an access
    connection, name the instance relative to its container, make its references."""
    count = len(info.connections)
    if not info.mode_transition and (len(info.sources) != count or len(info.destinations) != count):
        st.warn(
            f"connection from {end_path(info.sources[0] if info.sources else info.src)} to "
            f"{end_path(dst)} could not be instantiated",
            component_path(info.container or st.root),
        )
        return None
    container = info.container or st.root
    decls = [c.decl for c in info.connections]
    for record in container.conn_index.get((id(info.src), id(dst)), ()):
        if len(record.decls) == count and (
            all(a is b for a, b in zip(record.decls, decls, strict=True))
            or all(a is b for a, b in zip(record.decls, reversed(decls), strict=True))
        ):
            return None
    for record in container.conn_index.get((id(dst), id(info.src)), ()):
        if record.kind == "accessConnection":
            record.obj.bidirectional = True
            if not st.legacy:
                record.obj.name = record.obj.name.replace("->", "<->")
            return record.obj
    factory = st.factory
    kind = _connection_kind(info.src, dst)
    conni = factory.new(
        "ConnectionInstance",
        name=connection_name(container, info.src, dst),
        complete=True if info.across else None,
        kind=enum_literal("ConnectionKind", kind),
        source=info.src.obj,
        destination=dst if isinstance(dst, EObject) else dst.obj,
    )
    refs = []
    source = info.src
    for conn, context, destination in zip(info.connections, info.contexts, info.destinations, strict=False):
        resolved = _resolve_feature(source, destination)
        refs.append(
            factory.new(
                "ConnectionReference",
                connection=conn.name,
                context=context.obj,
                source=source.obj if source is not None else None,
                destination=resolved.obj if resolved is not None else None,
            )
        )
        source = resolved
    factory.extend(conni, "connectionReferences", refs)
    record = ConnectionRecord(conni, info.src, dst, decls, kind, list(info.contexts))
    if not connection_modes(st, record, info):
        st.warn(
            f"connection {conni.name} was removed because it is not active in any system operation mode",
            component_path(container),
        )
        return None
    attach(st, container, record)
    return conni


def connection_name(container: ComponentMirror, src: Any, dst: Any) -> str:
    """``src -> dst``, each end's path relative to the container's."""
    container_path = component_path(container)

    def relative(path: str) -> str:
        if path.startswith(container_path + "."):
            return path[len(container_path) + 1 :]
        return path

    return f"{relative(end_path(src))} -> {relative(end_path(dst))}"


def attach(st: Instantiator, container: ComponentMirror, record: ConnectionRecord) -> None:
    """Add a connection instance to its container (object and mirror)."""
    st.factory.extend(container.obj, "connectionInstances", [record.obj])
    container.connections.append(record)
    container.conn_index.setdefault((id(record.src), id(record.dst)), []).append(record)


def remove_connection(container: ComponentMirror, record: ConnectionRecord) -> None:
    """Take a connection instance out of its container (object and mirror)."""
    container.obj.connectionInstances.remove(record.obj)
    container.connections.remove(record)
    bucket = container.conn_index.get((id(record.src), id(record.dst)), [])
    if record in bucket:
        bucket.remove(record)


def same_feature(a: FeatureMirror, b: FeatureMirror) -> bool:
    """Same name and array index."""
    return a.key == b.key and a.index == b.index


def _resolve_feature(orig: Any, root: Any) -> Any:
    """OSATE's resolveFeatureInstance: narrow a feature group destination to the member that
    matches the source it came from."""
    if not isinstance(orig, FeatureMirror) or not isinstance(root, FeatureMirror):
        return root
    if not root.children:
        return root
    parent: FeatureMirror = root
    if orig.parent is not None:
        if orig.parent.parent is not None:
            resolved = _resolve_feature(orig.parent, root)
            if isinstance(resolved, FeatureMirror):
                parent = resolved
        for fi in parent.children:
            if same_feature(orig, fi):
                return fi
    return root


def _connection_kind(src: Any, dst: Any) -> str:
    def category(end: Any) -> str:
        return end.category if isinstance(end, FeatureMirror) else ""

    s, d = category(src), category(dst)
    src_ci = isinstance(src, ComponentMirror)
    dst_ci = isinstance(dst, ComponentMirror)
    if (src_ci and d in ACCESS) or (s in ACCESS and dst_ci) or (s in ACCESS and d in ACCESS):
        return "accessConnection"
    if s == "parameter" or d == "parameter":
        return "parameterConnection"
    if s == "featureGroup" or d == "featureGroup":
        return "featureGroupConnection"
    if s == "abstractFeature" or d == "abstractFeature":
        return "featureConnection"
    return "portConnection"
