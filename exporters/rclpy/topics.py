"""Topics and services from an instance's connections.

Ports joined by port connection instances (from ultimate source to ultimate destination, as the
instantiator makes them) form one *topic*; subprogram access features joined by access
connections form one *service*.  A topic is named, in this order, by ``ROS_Properties::Topic_Name``
on one of its connections, on a feature along the connections (the process ports a thread port
is connected through), or on an end; otherwise it is ``/<node>/<port>`` after the publishing
node and the process port the data leaves it by.  Explicit names are kept as written (two
groups naming ``/tf`` are one ROS topic); derived names are made unique.

Inside a node, the code uses a *local* (relative) name for each port: the name of the process
port it is connected through, or ``<thread>/<port>`` when it is connected to nothing outside
its thread; the launch files remap local names to the topic names.
"""

from __future__ import annotations

import logging
from collections.abc import Iterable
from dataclasses import dataclass, field

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import Diagnostic, Location
from rosaadl.exporters.rclpy import naming
from rosaadl.exporters.rclpy.instances import connections, enum_name, owner_component, process_of, prop

__all__ = [
    "Topology",
    "Group",
    "normalize_ros_name",
    "enum_name",
    "owner_component",
    "process_of",
]

log = logging.getLogger(__name__)

_PORTS = frozenset({"dataPort", "eventPort", "eventDataPort"})
_SERVICE_ACCESS = frozenset({"subprogramAccess", "subprogramGroupAccess"})


def normalize_ros_name(text: str, *, allow_private: bool = True) -> str | None:
    """A ROS topic or service name from a written one (``/usb_cam/image_raw``), tokens sanitised."""
    raw = (text or "").strip()
    if not raw:
        return None
    prefix = ""
    if raw.startswith("~") and allow_private:
        prefix, raw = "~/", raw[1:].lstrip("/")
    elif raw.startswith("/"):
        prefix = "/"
    # Tokens with no letter or digit at all ("..", "-") carry no name: they are dropped.
    tokens = [naming.topic_token(t) for t in raw.split("/") if any(c.isalnum() for c in t)]
    if not tokens:
        return None
    return prefix + "/".join(tokens)


@dataclass
class Group:
    """A topic or a service: the features it joins and its ROS name."""

    kind: str  # "topic" | "service"
    ends: list[EObject] = field(default_factory=list)
    connections: list[EObject] = field(default_factory=list)
    name: str | None = None
    explicit: bool = False


class _UnionFind:
    def __init__(self) -> None:
        self.parent: dict[int, int] = {}

    def find(self, key: int) -> int:
        parent = self.parent.setdefault(key, key)
        while parent != key:
            grand = self.parent.setdefault(parent, parent)
            self.parent[key] = grand
            key, parent = parent, grand
        return key

    def union(self, a: int, b: int) -> None:
        ra, rb = self.find(a), self.find(b)
        if ra != rb:
            self.parent[rb] = ra


class Topology:
    """Topics, services and shared data of one system instance (see the module docstring)."""

    def __init__(self, root: EObject) -> None:
        self.root = root
        self.diagnostics: list[Diagnostic] = []
        self._objects: dict[int, EObject] = {}
        self._uf = _UnionFind()
        self._outward: dict[int, list[EObject]] = {}
        self._data_links: dict[int, list[EObject]] = {}
        self._connections: list[EObject] = []
        self._ends: set[int] = set()
        self._connections.extend(connections(root))
        for conn in self._connections:
            self._add_connection(conn)

    # ------------------------------------------------------------------ building

    def _remember(self, obj: EObject) -> int:
        self._objects[id(obj)] = obj
        return id(obj)

    def _add_connection(self, conn: EObject) -> None:
        source, destination = conn.source, conn.destination
        if source is None or destination is None:
            return
        self._ends.add(id(source))
        self._ends.add(id(destination))
        for ref in conn.connectionReferences:
            a, b = ref.source, ref.destination
            if a is None or b is None:
                continue
            self._outward.setdefault(id(a), []).append(b)
            self._outward.setdefault(id(b), []).append(a)
        kind = enum_name(conn.kind)
        if kind == "portConnection":
            self._uf.union(self._remember(source), self._remember(destination))
        elif kind == "accessConnection":
            ends = [source, destination]
            data = [e for e in ends if model.is_a(e, "ComponentInstance")]
            features = [e for e in ends if model.is_a(e, "FeatureInstance")]
            if data and features:
                thread = owner_component(features[0])
                if thread is not None:
                    self._data_links.setdefault(id(thread), []).append(data[0])
            elif len(features) == 2 and all(enum_name(f.category) in _SERVICE_ACCESS for f in features):
                self._uf.union(self._remember(source), self._remember(destination))

    # ------------------------------------------------------------------ questions

    def is_end(self, feature: EObject) -> bool:
        """``feature`` is the ultimate source or destination of a connection instance."""
        return id(feature) in self._ends

    def reached(self, feature: EObject) -> bool:
        """``feature`` is on the way of a connection instance (an end, or a feature it passes)."""
        return id(feature) in self._ends or id(feature) in self._outward

    def shared_data(self, thread: EObject) -> list[EObject]:
        """The data components a thread accesses through access connections."""
        return list(self._data_links.get(id(thread), ()))

    def local_feature(self, feature: EObject, process: EObject) -> EObject | None:
        """The feature of ``process`` that ``feature`` (of a thread inside it) is connected through."""
        outer = self.outer_feature(feature, process)
        return outer if owner_component(outer) is process else None

    def outer_feature(self, feature: EObject, process: EObject) -> EObject:
        """The outermost feature inside ``process`` (the process's own feature when it gets there,
        else a thread group's) that ``feature`` is connected through, going outward."""
        owner = owner_component(feature)
        if owner is process:
            return feature
        best, best_depth = feature, _depth(owner, process)
        seen = {id(feature)}
        frontier = [(feature, owner)]
        while frontier:
            current, current_owner = frontier.pop(0)
            for other in self._outward.get(id(current), ()):
                if id(other) in seen:
                    continue
                seen.add(id(other))
                other_owner = owner_component(other) if model.is_a(other, "FeatureInstance") else None
                if other_owner is None or not _is_ancestor(other_owner, current_owner):
                    continue
                if other_owner is process:
                    return other
                depth = _depth(other_owner, process)
                if depth < best_depth:
                    best, best_depth = other, depth
                frontier.append((other, other_owner))
        return best

    def typed_peer(self, feature: EObject) -> EObject | None:
        """The nearest feature joined to ``feature`` by connection references that has a
        classifier (the thread group or process port typing an untyped thread port)."""
        seen = {id(feature)}
        frontier = [feature]
        while frontier:
            current = frontier.pop(0)
            for other in self._outward.get(id(current), ()):
                if id(other) in seen or not model.is_a(other, "FeatureInstance"):
                    continue
                seen.add(id(other))
                if other.classifier:
                    return other
                frontier.append(other)
        return None

    def groups(self, kind: str, features: Iterable[EObject], node_names: dict[int, str]) -> dict[int, Group]:
        """Group ``features`` (every port or every service access of the nodes) and name the groups.

        Returns ``id(feature) -> Group``.  ``node_names`` maps ``id(process)`` to its ROS node name,
        for derived names.
        """
        features = list(features)
        for feature in features:  # a process port the connection only passes (see _end_through)
            end = None if self.is_end(feature) else self._end_through(feature)
            if end is not None:
                self._uf.union(self._remember(end), self._remember(feature))
        by_root: dict[int, Group] = {}
        order: list[Group] = []
        result: dict[int, Group] = {}
        for feature in features:
            root = self._uf.find(id(feature))
            group = by_root.get(root)
            if group is None:
                group = Group(kind=kind)
                by_root[root] = group
                order.append(group)
            group.ends.append(feature)
            result[id(feature)] = group
        wanted = "portConnection" if kind == "topic" else "accessConnection"
        for conn in self._connections:
            if enum_name(conn.kind) != wanted or conn.source is None:
                continue
            group = result.get(id(conn.source)) or result.get(id(conn.destination))
            if group is not None:
                group.connections.append(conn)
        self._name_groups(order, node_names)
        return result

    def _end_through(self, feature: EObject) -> EObject | None:
        """The nearest end of a connection instance that passes ``feature`` (None: none passes it).

        A node's implicit thread (a process with no thread, e.g. a ROSMOD component with only
        publishers, a thread group of ports) uses the process's own ports, which its connections
        only pass: they run from the thread group's ports inside.  Such a port belongs to the
        topic of the connection passing it, so its node publishes where the subscribers listen.
        """
        seen = {id(feature)}
        frontier = [feature]
        while frontier:
            current = frontier.pop(0)
            for other in self._outward.get(id(current), ()):
                if id(other) in seen:
                    continue
                if self.is_end(other):
                    return other
                seen.add(id(other))
                frontier.append(other)
        return None

    # ------------------------------------------------------------------ naming

    def _name_groups(self, order: list[Group], node_names: dict[int, str]) -> None:
        taken = naming.NameTable()
        for group in order:
            explicit = self._explicit_name(group)
            if explicit is not None:
                group.name, group.explicit = explicit, True
                taken.reserve(explicit)
        for group in order:
            if group.name is not None:
                continue
            if not group.connections:
                continue  # not connected: the node's own (relative) name is used
            end = self._naming_end(group)
            process = process_of(end)
            local = self.local_feature(end, process) if process is not None else None
            port_name = (local or end).name or ""
            if process is not None and id(process) in node_names:
                owner = node_names[id(process)]
            else:
                owner = naming.topic_token((owner_component(end) or end).name or "")
            group.name = taken.unique(f"/{owner}/{naming.topic_token(port_name)}")

    def _naming_end(self, group: Group) -> EObject:
        for conn in group.connections:
            if conn.source is not None:
                return conn.source
        return group.ends[0]

    def _explicit_name(self, group: Group) -> str | None:
        candidates: list[EObject] = list(group.connections)
        for conn in group.connections:
            for ref in conn.connectionReferences:
                candidates.extend(e for e in (ref.source, ref.destination) if e is not None)
        for end in group.ends:
            candidates.append(end)
            process = process_of(end)
            if process is not None:
                local = self.local_feature(end, process)
                if local is not None:
                    candidates.append(local)
        found: list[tuple[EObject, str]] = []
        seen: set[int] = set()
        for obj in candidates:
            if id(obj) in seen:
                continue
            seen.add(id(obj))
            value = prop(obj, "Topic_Name")
            if isinstance(value, str) and value.strip():
                found.append((obj, value))
        if not found:
            return None
        obj, value = found[0]
        name = normalize_ros_name(value)
        if name is None:
            return None
        others = sorted({normalize_ros_name(v) or "" for _, v in found[1:]} - {name})
        if others:
            self._warn(f"Topic_Name {name!r} used; other names on the same connection ignored: {others}", obj)
        return name

    def _warn(self, message: str, obj: EObject) -> None:
        path = model.instance_path(obj) if model.is_a(obj, "InstanceObject") else None
        self.diagnostics.append(Diagnostic("warning", message, Location(path=path)))
        log.warning("%s: %s", path, message)


def _depth(component: EObject | None, ancestor: EObject) -> int:
    depth = 0
    current = component
    while current is not None and current is not ancestor:
        depth += 1
        current = current.eContainer()
    return depth


def _is_ancestor(candidate: EObject, obj: EObject | None) -> bool:
    current = obj.eContainer() if obj is not None else None
    while current is not None:
        if current is candidate:
            return True
        current = current.eContainer()
    return False
