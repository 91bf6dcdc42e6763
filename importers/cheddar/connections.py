"""Cheddar dependencies as connection instances between the threads and the data components.

A task-to-task dependency (precedence, time-triggered communication, remote procedure call)
is a port connection between an ``out`` and an ``in`` event port of the two threads; a
dependency between a task and a resource, buffer or message is an access connection from
a ``requires data access`` feature of the thread, oriented as the dependency is (both ways when
it has no orientation). The kind and extras are kept in ``Cheddar_Properties::Dependency_Type``
and its companions, and the record's place in ``Section_Index``.
"""

from __future__ import annotations

from lxml import etree
from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.importers.cheddar.state import Entity, ReadState
from rosaadl.importers.cheddar.values import associate, int_value, named_value
from rosaadl.importers.cheddar.vocabulary import CP

__all__ = ["dependency", "feature"]


def dependency(
    state: ReadState,
    element: etree._Element,
    index: int,
    kind: str,
    first: Entity,
    second: Entity,
    orientation: str | None,
    extras: list[tuple[str, EObject]],
) -> None:
    """A Cheddar dependency as a connection instance (see Cheddar_Properties::Dependency_Type)."""
    bidirectional = False
    if first.kind == "task" and second.kind == "task":
        # precedence: sink first in the record; the connection goes source -> sink
        if kind in ("PRECEDENCE_DEPENDENCY", "TIME_TRIGGERED_COMMUNICATION_DEPENDENCY"):
            source_task, sink_task = second, first
        else:  # remote procedure call: client -> server
            source_task, sink_task = first, second
        stem = {
            "PRECEDENCE_DEPENDENCY": "precedence",
            "TIME_TRIGGERED_COMMUNICATION_DEPENDENCY": "time_triggered",
        }.get(kind, "rpc")
        source = feature(
            state, source_task.instance, (stem, "out"), f"{stem}_out", "event port", direction="out"
        )
        destination = feature(
            state, sink_task.instance, (stem, "in"), f"{stem}_in", "event port", direction="in"
        )
        connection_kind = "portConnection"
        ends = (source_task.instance, sink_task.instance)
    else:
        task, thing = (first, second) if first.kind == "task" else (second, first)
        access_feature = feature(
            state,
            task.instance,
            ("access", id(thing.instance)),
            thing.instance.name,
            "data access",
            access="requires",
        )
        if orientation == "FROM_OBJECT_TO_TASK":
            source, destination = thing.instance, access_feature
        else:
            source, destination = access_feature, thing.instance
        bidirectional = orientation is None
        connection_kind = "accessConnection"
        ends = (task.instance, thing.instance)
    owner = _common_owner(*ends)
    arrow = " <-> " if bidirectional else " -> "
    name = _relative_path(source, owner) + arrow + _relative_path(destination, owner)
    connection = model.new(
        "ConnectionInstance",
        name=name,
        kind=connection_kind,
        complete=True,
        bidirectional=bidirectional,
        source=source,
        destination=destination,
    )
    owner.connectionInstances.append(connection)
    associate(connection, CP + "Section_Index", int_value(index))
    associate(connection, CP + "Dependency_Type", named_value(kind))
    for prop, value in extras:
        associate(connection, prop, value)


def feature(
    state: ReadState,
    thread: EObject,
    key: tuple,
    name: str,
    category: str,
    *,
    direction: str | None = None,
    access: str | None = None,
) -> EObject:
    """The thread's feature for ``key`` (made on first use, with a name unique on the thread)."""
    found = state.features.get((id(thread), key))
    if found is not None:
        return found
    taken = {f.name.lower() for f in thread.featureInstances}
    candidate, n = name, 1
    while candidate.lower() in taken:
        n += 1
        candidate = f"{name}_{n}"
    made = model.new(
        "FeatureInstance",
        name=candidate,
        feature=candidate,
        category=category,
        direction=direction,
        access=access,
    )
    thread.featureInstances.append(made)
    state.features[(id(thread), key)] = made
    return made


def _common_owner(a: EObject, b: EObject) -> EObject:
    """The innermost component that holds both ``a`` and ``b`` (where the connection goes)."""
    chain = []
    current = a.eContainer()
    while current is not None:
        chain.append(current)
        current = current.eContainer()
    current = b.eContainer()
    while current is not None:
        if current in chain:
            return current
        current = current.eContainer()
    return chain[-1]


def _relative_path(obj: EObject, owner: EObject) -> str:
    """The dotted path of ``obj`` below ``owner`` (a connection end as the connection names it)."""
    parts = []
    current = obj
    while current is not None and current is not owner:
        parts.append(model.instance_segment(current))
        current = current.eContainer()
    return ".".join(reversed(parts))
