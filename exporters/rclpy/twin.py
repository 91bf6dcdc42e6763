"""The workload twin of a generated node: what each emulated dispatch publishes.

With the node parameter ``rosaadl.emulate`` true, each dispatch of a thread whose user block
still holds the generated skeleton burns the thread's ``Compute_Execution_Time`` as CPU time of
its own OS thread (``time.thread_time_ns``, so time waiting for the GIL is not counted; the upper
bound by default, ``rosaadl.emulate_cet`` = ``min``/``max``/``uniform``), then publishes one
message on each of its out ports, carrying the port's ``Data_Size`` in the message's first
``uint8[]`` field (``sensor_msgs/Image.data``), else its first ``string``
(``std_msgs/String.data``).  A type with neither is published as its default message, and the
node says so once.

The out ports of a thread group or process that no thread handles (a ROSMOD component's
publishers) are sent by one thread of the component: the first periodic thread of its callback
group, else its first dispatching thread (the model does not say which callback of a ROSMOD
component publishes).

Each emulated dispatch also calls the services the thread requires (its own required subprogram
accesses, and those of the component it sends for, as above) with a default request, through the
generated ``call_…`` method, when the service is up and the previous call of that client has been
answered: the servers' dispatches then run, and publish in turn, as in the model (a ROSMOD
component with no timer whose publishers are sent from its service callbacks; without the calls
nothing would ever dispatch it).

The twin's call is the last line of each dispatch's generated skeleton, inside its user block:
a user who writes the callback replaces it.  A block kept from a generator without the twin
(the skeleton less that line) takes the new skeleton when regenerated.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rosaadl.exporters.rclpy.nodes import NodeClass, PortPlan, ThreadPlan
    from rosaadl.exporters.rclpy.preservation import Content

__all__ = ["assign_twin_outputs", "sender_of", "payload_note", "skeleton_before_twin"]


def sender_of(container: ThreadPlan, threads: list[ThreadPlan]) -> ThreadPlan | None:
    """The thread whose emulated dispatch publishes the out ports of ``container`` (a thread
    group's or process's own ports): the first periodic thread of its callback group, else the
    first dispatching one; None when no thread of the group dispatches."""
    mates = [t for t in threads if t is not container and t.group is container.group and t.dispatches]
    periodic = [t for t in mates if t.timer == "periodic"]
    chosen = periodic or mates
    return chosen[0] if chosen else None


def assign_twin_outputs(cls: NodeClass) -> None:
    """Fill ``twin_outputs`` and ``twin_calls`` of every dispatching thread of ``cls``: its own out
    ports and clients, then those of the components it sends for (see :func:`sender_of`)."""
    for thread in cls.threads:
        if thread.dispatches:
            thread.twin_outputs = list(thread.outputs)
            thread.twin_calls = list(thread.clients)
    for container in cls.threads:
        if container.container and (container.outputs or container.clients):
            sender = sender_of(container, cls.threads)
            if sender is not None:
                sender.twin_outputs.extend(container.outputs)
                sender.twin_calls.extend(container.clients)


def payload_note(port: PortPlan) -> str:
    """``pub_msg: sensor_msgs/msg/Image, Data_Size 921000 B`` (a comment of the generated code)."""
    size = "no Data_Size" if port.data_size is None else f"Data_Size {port.data_size} B"
    return f"{port.name}: {port.msg.full_name}, {size}"


def skeleton_before_twin(old: Content, new: Content) -> bool:
    """Whether the kept block ``old`` is the skeleton a generator without the twin wrote: the new
    default ``new`` less its ``self.emulate(...)`` line (a block holding code of its own is kept
    as it is)."""
    before = [text for _, text in new if not text.lstrip().startswith("self.emulate(")]
    return len(before) < len(new) and [text for _, text in old] == before
