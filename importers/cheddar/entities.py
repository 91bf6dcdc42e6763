"""Cheddar entities as AADL instances: address spaces, tasks, resources, buffers, messages and
networks, in either file style.

Each function reads one entry of its section and makes its instance (see the package
docstring for what becomes what): an address space is a ``process`` bound to its processor; a
task a ``thread`` in its address space's process, bound to its processor or core, with its
timing in the standard properties; resources, buffers and messages ``data`` instances with a
``Cheddar_Properties::Data_Role``; a network a ``bus``. The field tables of
:mod:`~rosaadl.importers.cheddar.vocabulary` say which property holds each simple field; the
fields nobody reads are kept verbatim. Where the two styles differ (the records inside an
entity, schedulers, drawing positions), the entity asks the matching reader.
"""

from __future__ import annotations

from collections.abc import Callable

from lxml import etree
from pyecore.ecore import EObject

from rosaadl.importers.cheddar import records
from rosaadl.importers.cheddar.document import local
from rosaadl.importers.cheddar.scheduling import scheduler_element, scheduling_parameters
from rosaadl.importers.cheddar.state import Entity, ReadState, same_target
from rosaadl.importers.cheddar.values import (
    associate,
    int_value,
    list_value,
    named_value,
    range_value,
    str_value,
)
from rosaadl.importers.cheddar.vocabulary import (
    AADL_TO_RESOURCE_PROTOCOL,
    CCP,
    CET,
    CP,
    DISPATCH,
    DISPATCH_TO_TASK_TYPE,
    RESOURCE_PROTOCOL_TO_AADL,
    RESOURCE_TAGS,
    TASK_TYPE_TO_DISPATCH,
    Field,
)
from rosaadl.properties import own_property

__all__ = ["address_space", "task", "resource", "buffer", "message", "network", "positions"]


def address_space(state: ReadState, item: etree._Element, table: tuple[Field, ...]) -> None:
    """An address space: a ``process`` instance bound to its processor, with its memory and scheduler."""
    present = state.index_children(item)
    entity = state.declare(item, present, "address_space", state.address_spaces, "address space")
    instance = state.place(entity, state.root, "process")
    consumed = {"name", "object_type", "cpu_name"}
    cpu = present.get("cpu_name")
    if cpu is None or not state.text(cpu):
        state.fail(item, "the address space has no <cpu_name>")
    entity.cpu = state.processor_of(cpu, state.text(cpu))
    state.bind(instance, entity.cpu)
    state.fields(instance, item, table, present, consumed)
    scheduling = present.get("scheduling")
    if scheduling is not None and state.version == 3:
        consumed.add("scheduling")
        scheduling_parameters(state, instance, scheduling, processor=False)
    scheduler = present.get("scheduler")
    if scheduler is not None and state.version == 2:
        consumed.add("scheduler")
        scheduler_element(state, instance, scheduler, processor=False)
    state.leftovers(instance, item, "address_space", present, consumed)


def task(
    state: ReadState, item: etree._Element, index: int, table: tuple[Field, ...], default_type: str
) -> None:
    """A task: a ``thread`` in its address space's process (or under the root), bound to its
    processor or core, with its kind as ``Dispatch_Protocol`` and its fields from ``table``."""
    present = state.index_children(item)
    entity = state.declare(item, present, "task", state.tasks, "task")
    parent, cpu, lost_space = state.location(item, present, "task")
    instance = state.place(entity, parent, "thread", index)
    entity.cpu = cpu
    consumed = {"name", "object_type", "cpu_name", "address_space_name", "task_type", "core_name"}
    kind_element = present.get("task_type")
    task_type = default_type
    if kind_element is not None:
        task_type = state.literal(kind_element, "task_type")
    elif state.version == 2 and item.get("task_type") is not None:
        task_type = state.literal(item, "task_type", item.get("task_type"))
    dispatch = TASK_TYPE_TO_DISPATCH.get(task_type, "Aperiodic")
    associate(instance, DISPATCH, named_value(dispatch))
    if DISPATCH_TO_TASK_TYPE[dispatch.lower()] != task_type:
        associate(instance, CP + "Task_Type", named_value(task_type))
    target = cpu
    core_element = present.get("core_name")
    core_name = state.text(core_element) if core_element is not None else None
    if core_name and isinstance(cpu, EObject) and cpu.componentInstances:
        core = next(
            (c for c in cpu.componentInstances if own_property(c, CP + "Cheddar_Name") == core_name), None
        )
        if core is None:
            state.fail(core_element, f"core {core_name!r} is not a core of processor {cpu.name!r}")
        target = core
        core_name = None
    state.bind(instance, target)
    if core_name is not None:
        if (
            core_name
            and isinstance(cpu, EObject)
            and own_property(cpu, CP + "Core_Name") not in (None, core_name)
        ):
            state.fail(core_element, f"core {core_name!r} is not the core of processor {cpu.name!r}")
        associate(instance, CP + "Core_Name", str_value(core_name))
    if lost_space is not None:
        associate(instance, CP + "Address_Space_Name", str_value(lost_space))
    state.fields(instance, item, table, present, consumed, _task_special(state, instance))
    if state.version == 2:
        positions(state, instance, item)
    if (
        task_type in ("PERIODIC_TYPE", "SPORADIC_TYPE")
        and "period" in present
        and state.natural(present["period"]) == 0
    ):
        state.fail(present["period"], "the period of a periodic or sporadic task must be greater than 0")
    state.leftovers(instance, item, "task", present, consumed)


def _task_special(state: ReadState, instance: EObject) -> Callable[[Field, etree._Element], None]:
    def special(spec: Field, element: etree._Element) -> None:
        if spec.kind == "capacity":
            value = state.natural(element)
            associate(instance, CET, range_value(int_value(value, state.unit), int_value(value, state.unit)))
        elif spec.kind == "offsets":
            associate(instance, spec.prop, list_value(records.offsets(state, element)))

    return special


def _shared_object(
    state: ReadState, item: etree._Element, index: int, kind: str, table: dict[str, Entity], role: str
) -> tuple[Entity, EObject, dict[str, etree._Element], set[str]]:
    """Common part of resources and buffers: name, id, location, Data_Role."""
    present = state.index_children(item, ("task_name",))
    entity = state.declare(item, present, kind, table, kind)
    parent, cpu, lost_space = state.location(item, present, kind)
    instance = state.place(entity, parent, "data", index)
    entity.cpu = cpu
    associate(instance, CP + "Data_Role", named_value(role))
    space_cpu = None
    if parent is not state.root:
        space_cpu = next(s.cpu for s in state.address_spaces.values() if s.instance is parent)
    if not same_target(space_cpu, cpu):
        cpu_name = cpu if isinstance(cpu, str) else own_property(cpu, CP + "Cheddar_Name") or cpu.name
        associate(instance, CP + "Cpu_Name", str_value(cpu_name))
    if lost_space is not None:
        associate(instance, CP + "Address_Space_Name", str_value(lost_space))
    consumed = {"name", "object_type", "cpu_name", "address_space_name"}
    return entity, instance, present, consumed


def resource(state: ReadState, item: etree._Element, index: int, table: tuple[Field, ...]) -> None:
    """A resource: a ``data`` instance with ``Concurrency_Control_Protocol`` and its critical sections."""
    entity, instance, present, consumed = _shared_object(
        state, item, index, "resource", state.resources, "Resource"
    )
    protocol_element = present.get("protocol")
    protocol = "NO_PROTOCOL"
    if protocol_element is not None:
        consumed.add("protocol")
        protocol = state.literal(protocol_element, "resource_protocol")
    elif state.version == 3:
        for literal, tag in RESOURCE_TAGS.items():
            if tag == local(item):
                protocol = literal
    aadl = RESOURCE_PROTOCOL_TO_AADL.get(protocol, "None_Specified")
    associate(instance, CCP, named_value(aadl))
    if AADL_TO_RESOURCE_PROTOCOL[aadl.lower()] != protocol:
        associate(instance, CP + "Resource_Protocol", named_value(protocol))
    state.fields(instance, item, table, present, consumed)
    sections = present.get("critical_sections" if state.version == 3 else "resource_used_by")
    if sections is not None:
        consumed.add(local(sections))
        associate(instance, CP + "Critical_Sections", list_value(records.critical_sections(state, sections)))
    state.leftovers(instance, item, "resource", present, consumed)


def buffer(state: ReadState, item: etree._Element, index: int, table: tuple[Field, ...]) -> None:
    """A buffer: a ``data`` instance with its size and queueing system, and its roles."""
    entity, instance, present, consumed = _shared_object(
        state, item, index, "buffer", state.buffers, "Buffer"
    )
    state.fields(instance, item, table, present, consumed)
    roles = present.get("roles" if state.version == 3 else "buffer_used_by")
    if roles is not None:
        consumed.add(local(roles))
        associate(instance, CP + "Buffer_Roles", list_value(records.buffer_roles(state, roles)))
    if state.version == 2:
        positions(state, instance, item)
    state.leftovers(instance, item, "buffer", present, consumed)


def message(state: ReadState, item: etree._Element, table: tuple[Field, ...]) -> None:
    """A message: a ``data`` instance under the root with its type and fields."""
    present = state.index_children(item)
    entity = state.declare(item, present, "message", state.messages, "message")
    instance = state.place(entity, state.root, "data")
    associate(instance, CP + "Data_Role", named_value("Message"))
    consumed = {"name", "object_type", "message_type"}
    kind_element = present.get("message_type")
    if kind_element is not None:
        message_type = state.literal(kind_element, "message_type")
    elif state.version == 3:
        message_type = "PERIODIC_TYPE" if local(item) == "periodic_message" else "APERIODIC_TYPE"
    else:
        message_type = "PERIODIC_TYPE" if "period" in present else "APERIODIC_TYPE"
    associate(instance, CP + "Message_Type", named_value(message_type))
    state.fields(instance, item, table, present, consumed)
    if state.version == 2:
        positions(state, instance, item)
    state.leftovers(instance, item, "message", present, consumed)


def network(state: ReadState, item: etree._Element, table: tuple[Field, ...], tag: str) -> None:
    """A network: a ``bus`` instance (its kind in ``Network_Kind`` when not a generic network)."""
    present = state.index_children(item)
    entity = state.declare(item, present, "network", state.networks, "network")
    instance = state.place(entity, state.root, "bus")
    if tag != "generic_network":
        associate(instance, CP + "Network_Kind", named_value(tag.upper()))
    consumed = {"name", "object_type"}
    state.fields(instance, item, table, present, consumed)
    state.leftovers(instance, item, "network", present, consumed)


def positions(state: ReadState, instance: EObject, item: etree._Element) -> None:
    """The ``x``/``y`` attributes (Cheddar's editor) as ``X_Position``/``Y_Position``."""
    for attribute, prop in (("x", "X_Position"), ("y", "Y_Position")):
        if item.get(attribute) is not None:
            associate(instance, CP + prop, int_value(state.natural(item, item.get(attribute).strip())))
