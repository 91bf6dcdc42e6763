"""Port connections between threads as Cheddar buffers, messages and dependencies.

A connection between two threads on one processor, bound to no bus, becomes a buffer per
receiving port (``QUEUEING_BUFFER`` dependencies from each sender and to the receiver); one
bound to a bus (``Actual_Connection_Binding``) or between processors a message per sending
port and bus (``ASYNCHRONOUS_COMMUNICATION`` dependencies, first message); an event port
connection a ``PRECEDENCE`` dependency. The buses (and virtual buses) are the networks.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import RosaadlError
from rosaadl.exporters.cheddar.context import thread_of
from rosaadl.exporters.cheddar.system import Collection, Dependency, Network, SharedObject, Task
from rosaadl.importers.cheddar.vocabulary import CET, CONNECTION_BINDING, DATA_SIZE, PERIOD, QUEUE_SIZE
from rosaadl.units import Quantity

__all__ = ["port_connection"]

_ASYNCHRONOUS = "ASYNCHRONOUS_COMMUNICATION_DEPENDENCY"
_FIRST_MESSAGE = (("asynchronous_communication_protocol_property", "FIRST_MESSAGE"),)


def port_connection(c: Collection, connection: EObject) -> None:
    """A port connection between two exported threads, as Cheddar sees it."""
    src_thread, dst_thread = thread_of(connection.source), thread_of(connection.destination)
    if src_thread is None or dst_thread is None:
        return
    src, dst = c.task_of_thread.get(id(src_thread)), c.task_of_thread.get(id(dst_thread))
    if src is None or dst is None:
        return
    feature = connection.source
    category = feature.category.name if model.is_a(feature, "FeatureInstance") and feature.category else ""
    if category == "eventPort":
        c.system.dependencies.append(
            Dependency("PRECEDENCE_DEPENDENCY", ("task", dst.name), ("task", src.name))
        )
        return
    bus = _connection_bus(c, connection)
    if bus is None and src.cpu == dst.cpu:
        _pending_buffer(c, connection, src, dst)
    else:
        _pending_message(c, connection, src, dst, bus)


def _connection_bus(c: Collection, connection: EObject) -> EObject | None:
    """The bus (or virtual bus) the connection is bound to, or None."""
    value = c.ctx.props(connection).get(CONNECTION_BINDING)
    targets = value if isinstance(value, list) else [value] if value is not None else []
    for target in targets:
        if isinstance(target, EObject) and target.category is not None:
            if target.category.name == "bus":
                return target
            if target.category.name == "virtual bus":
                below = c.ctx.props(target).get(CONNECTION_BINDING)
                below = below[0] if isinstance(below, list) and below else below
                if isinstance(below, EObject) and below.category is not None and below.category.name == "bus":
                    return below
                if not any(n.instance is target for n in c.system.networks):
                    c.system.networks.append(Network(c.ctx.name(target), None, target, False))
                return target
    return None


def _pending_buffer(c: Collection, connection: EObject, src: Task, dst: Task) -> None:
    """The buffer of the receiving port, with the sender as a producer."""
    key = id(connection.destination)
    found = c.buffers_by_port.get(key)
    if found is None:
        port = connection.destination
        size = c.ctx.props(port).get(QUEUE_SIZE)
        size = size if isinstance(size, int) and not isinstance(size, bool) and size > 0 else 1
        buffer = SharedObject("buffer", c.ctx.path(port), None, None, dst.cpu, dst.space, False)
        buffer.values = {
            "queueing_system_type": "QS_PP1",
            "buffer_size": str(size),
            "buffer_initial_data_size": "0",
        }
        buffer.roles.append(_role(c, dst, "QUEUING_CONSUMER"))
        c.buffers_by_port[key] = (port, buffer)
        c.system.buffers.append(buffer)
        _depends(c, "QUEUEING_BUFFER_DEPENDENCY", dst, ("buffer", buffer.name), "FROM_OBJECT_TO_TASK")
    else:
        buffer = found[1]
    if not any(r["task"] == src.name and r["role"] == "QUEUING_PRODUCER" for r in buffer.roles):
        buffer.roles.insert(
            sum(1 for r in buffer.roles if r["role"] == "QUEUING_PRODUCER"),
            _role(c, src, "QUEUING_PRODUCER"),
        )
        _depends(c, "QUEUEING_BUFFER_DEPENDENCY", src, ("buffer", buffer.name), "FROM_TASK_TO_OBJECT")


def _role(c: Collection, task: Task, role: str) -> dict[str, Any]:
    """A buffer role of ``task``: producers write for their whole capacity."""
    cet = c.ctx.props(task.instance).get(CET)
    capacity = c.ctx.time_text(task.instance, "Compute_Execution_Time", cet) if cet is not None else "1"
    time = capacity if role == "QUEUING_PRODUCER" else "1"
    return {"task": task.name, "role": role, "size": "1", "time": time or "1", "timeout": "0"}


def _pending_message(c: Collection, connection: EObject, src: Task, dst: Task, bus: EObject | None) -> None:
    """The message of the sending port on ``bus``, with the receiver's dependency."""
    port = connection.source
    key = (id(port), id(bus) if bus is not None else 0)
    message = c.messages_by_port.get(key)
    if message is None:
        name = c.ctx.path(port)
        if any(k[0] == id(port) for k in c.messages_by_port):
            name = f"{name}@{c.ctx.name(bus) if bus is not None else 'local'}"
        message = SharedObject("message", name, None, None, None, None, False)
        props = c.ctx.props(src.instance)
        period = props.get(PERIOD)
        periodic = src.task_type in ("PERIODIC_TYPE",) and period is not None
        size = c.ctx.props(port).get(DATA_SIZE)
        size_bytes = "0"
        if isinstance(size, Quantity) and size.unit:
            try:
                size_bytes = str(math.ceil(Fraction(str(size.to("Bytes")))))
            except RosaadlError:
                size_bytes = "0"
        message.values = {
            "message_type": "PERIODIC_TYPE" if periodic else "APERIODIC_TYPE",
            "deadline": "0",
            "size": size_bytes,
            "response_time": "0",
            "communication_time": "0",
        }
        if periodic:
            message.values["period"] = c.ctx.time_text(src.instance, "Period", period) or "0"
            message.values["jitter"] = "0"
        c.messages_by_port[key] = message
        c.system.messages.append(message)
        _depends(c, _ASYNCHRONOUS, src, ("message", message.name), "FROM_TASK_TO_OBJECT", _FIRST_MESSAGE)
    _depends(c, _ASYNCHRONOUS, dst, ("message", message.name), "FROM_OBJECT_TO_TASK", _FIRST_MESSAGE)


def _depends(
    c: Collection,
    kind: str,
    task: Task,
    thing: tuple[str, str],
    orientation: str,
    extras: tuple[tuple[str, str], ...] = (),
) -> None:
    """A dependency of ``task`` on a buffer or message (``thing``: its kind and name)."""
    c.system.dependencies.append(Dependency(kind, ("task", task.name), thing, orientation, list(extras)))
