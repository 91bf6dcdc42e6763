"""Writing the intermediate system as a Cheddar 2 document (DTD style, ``.xml``).

Cheddar 2 has no ids, core units or multi-core processors: a processor holds a ``<scheduler>``
whose attributes carry its parameters, names are words (a name with a space cannot be
written), critical sections and buffer users are lines of words, and a dependency is two names
with their kinds. Only precedence, queueing-buffer and first-message asynchronous dependencies
exist; what Cheddar 2 cannot say is a problem that names Cheddar 3 as the way out.
"""

from __future__ import annotations

from lxml import etree
from pyecore.ecore import EObject

from rosaadl.exporters.cheddar.fields import (
    DEFAULT_SCHEDULER,
    aadl_scheduler,
    buffer_roles,
    critical_sections,
    fields,
    kept_fields,
    leaf,
    shared_fields,
    task_defaults,
)
from rosaadl.exporters.cheddar.system import (
    AddressSpace,
    Collection,
    Dependency,
    Network,
    Processor,
    SharedObject,
    Task,
)
from rosaadl.importers.cheddar.vocabulary import (
    CP,
    PREEMPTIVE_SCHEDULER,
    V2_ADDRESS_SPACE_FIELDS,
    V2_BUFFER_FIELDS,
    V2_MESSAGE_FIELDS,
    V2_NETWORK_FIELDS,
    V2_RESOURCE_FIELDS,
    V2_TASK_FIELDS,
)

__all__ = ["sections"]


def sections(c: Collection) -> dict[str, list[etree._Element]]:
    """The entries of each section; what Cheddar 2 cannot say is a problem in ``c.ctx``."""
    for processor in c.system.processors:
        if processor.multi:
            c.ctx.problem(processor.instance, "Cheddar 2 has no multi-core processors; export as Cheddar 3")
    named = [*c.system.processors, *c.system.spaces, *c.system.tasks, *c.system.resources, *c.system.buffers]
    for entity in [*named, *c.system.messages, *c.system.networks]:
        if len(entity.name.split()) != 1:
            c.ctx.problem(
                entity.instance,
                f"Cheddar 2 splits values at spaces: the name {entity.name!r} cannot be written",
            )
    return {
        "processors": [_processor(c, p) for p in c.system.processors if not p.multi],
        "networks": [_network(c, n) for n in c.system.networks],
        "address_spaces": [_space(c, s) for s in c.system.spaces],
        "tasks": [_task(c, t) for t in c.system.tasks],
        "buffers": [_buffer(c, b) for b in c.system.buffers],
        "resources": [_resource(c, r) for r in c.system.resources],
        "messages": [_message(c, m) for m in c.system.messages],
        "dependencies": [d for d in (_dependency(c, d) for d in c.system.dependencies) if d is not None],
    }


def _scheduler(
    c: Collection, element: etree._Element, owner: EObject | None, *, processor: bool, imported: bool
) -> None:
    props = c.ctx.props(owner) if owner is not None else None
    scheduler = props.get(CP + "Scheduler") if props is not None else None
    if scheduler is None and processor and owner is not None:
        scheduler = aadl_scheduler(c, owner)
    if scheduler is None:
        if imported or not processor:
            return
        scheduler = DEFAULT_SCHEDULER
    item = leaf(element, "scheduler", str(scheduler).upper())
    if props is None:
        return
    quantum = props.get(CP + "Scheduler_Quantum")
    if quantum is not None:
        text = c.ctx.time_text(owner, "Scheduler_Quantum", quantum)
        if text is not None:
            item.set("quantum", text)
    preemptive = props.get(PREEMPTIVE_SCHEDULER if processor else CP + "Preemptive")
    if preemptive is not None:
        item.set("is_preemptive", "PREEMPTIVE" if preemptive else "NOT_PREEMPTIVE")
    for prop, attribute in (
        ("Automaton_Name", "automaton_name"),
        ("User_Defined_Scheduler_File", "parametric_file_name"),
    ):
        value = props.get(CP + prop)
        if isinstance(value, str):
            item.set(attribute, value)


def _processor(c: Collection, processor: Processor) -> etree._Element:
    element = etree.Element("processor")
    leaf(element, "name", processor.name)
    owner = processor.cores[0].facts if processor.cores else processor.instance
    _scheduler(c, element, owner, processor=True, imported=processor.imported)
    link = (
        c.ctx.props(processor.instance).get(CP + "Network_Link") if processor.instance is not None else None
    )
    if isinstance(link, str):
        leaf(element, "network_link", link)
    elif not processor.imported:
        leaf(element, "network_link", "No_Network")
    kept_fields(c, element, processor.instance, ["processor"])
    return element


def _network(c: Collection, network: Network) -> etree._Element:
    element = etree.Element("network")
    leaf(element, "name", network.name)
    fields(c, element, network.instance, V2_NETWORK_FIELDS)
    kept_fields(c, element, network.instance, ["network"])
    return element


def _space(c: Collection, space: AddressSpace) -> etree._Element:
    element = etree.Element("address_space")
    leaf(element, "name", space.name)
    leaf(element, "cpu_name", space.cpu)
    defaults = None if space.imported else {f.tag: "0" for f in V2_ADDRESS_SPACE_FIELDS}
    fields(c, element, space.instance, V2_ADDRESS_SPACE_FIELDS, defaults)
    _scheduler(c, element, space.instance, processor=False, imported=space.imported)
    kept_fields(c, element, space.instance, ["address_space"])
    return element


def _positions(c: Collection, element: etree._Element, obj: EObject | None) -> None:
    if obj is None:
        return
    for prop, attribute in (("X_Position", "x"), ("Y_Position", "y")):
        value = c.ctx.props(obj).get(CP + prop)
        if isinstance(value, int):
            element.set(attribute, str(value))


def _task(c: Collection, task: Task) -> etree._Element:
    element = etree.Element("task", task_type=task.task_type)
    _positions(c, element, task.instance)
    leaf(element, "cpu_name", task.cpu)
    if task.space is not None:
        leaf(element, "address_space_name", task.space)
    leaf(element, "name", task.name)
    skip = () if task.task_type not in ("APERIODIC_TYPE",) or task.imported else ("period", "jitter")
    fields(c, element, task.instance, V2_TASK_FIELDS, task_defaults(c, task), skip)
    kept_fields(c, element, task.instance, ["task"])
    return element


def _resource(c: Collection, resource: SharedObject) -> etree._Element:
    element = etree.Element("resource")
    if resource.cpu is not None:
        leaf(element, "cpu_name", resource.cpu)
    if resource.space is not None:
        leaf(element, "address_space_name", resource.space)
    leaf(element, "name", resource.name)
    obj = resource.instance
    fields(c, element, obj, V2_RESOURCE_FIELDS[:1], None if resource.imported else {"state": "1"})
    leaf(element, "protocol", resource.protocol)
    sections = critical_sections(c, resource)
    if sections or not resource.imported or c.ctx.props(obj).has(CP + "Critical_Sections"):
        holder = etree.SubElement(element, "resource_used_by")
        for name, begin, end, sync in sections:
            if sync not in (None, "MUTEX"):
                c.ctx.problem(obj, f"Cheddar 2 has no {sync} critical sections")
            leaf(holder, "resource_user", f"{name} {begin} {end}")
    fields(c, element, obj, V2_RESOURCE_FIELDS[1:])
    kept_fields(c, element, obj, ["resource"])
    return element


def _buffer(c: Collection, buffer: SharedObject) -> etree._Element:
    element = etree.Element("buffer")
    _positions(c, element, buffer.instance)
    if buffer.cpu is not None:
        leaf(element, "cpu_name", buffer.cpu)
    if buffer.space is not None:
        leaf(element, "address_space_name", buffer.space)
    if buffer.imported:
        fields(c, element, buffer.instance, V2_BUFFER_FIELDS[:1])
        leaf(element, "name", buffer.name)
        fields(c, element, buffer.instance, V2_BUFFER_FIELDS[1:])
    else:
        leaf(element, "qs", buffer.values["queueing_system_type"])
        leaf(element, "name", buffer.name)
        leaf(element, "size", buffer.values["buffer_size"])
    roles = buffer_roles(c, buffer)
    if roles or not buffer.imported or c.ctx.props(buffer.instance).has(CP + "Buffer_Roles"):
        holder = etree.SubElement(element, "buffer_used_by")
        for role in roles:
            kind = role["role"]
            if kind not in ("QUEUING_PRODUCER", "QUEUING_CONSUMER"):
                c.ctx.problem(buffer.instance, f"Cheddar 2 has no {kind} buffer role")
                continue
            item = leaf(
                holder, "buffer_user", f"{role['task']} {role.get('size', '0')} {role.get('time', '0')}"
            )
            item.set("buffer_role", "producer" if kind == "QUEUING_PRODUCER" else "consumer")
    kept_fields(c, element, buffer.instance, ["buffer"])
    return element


def _message(c: Collection, message: SharedObject) -> etree._Element:
    element = etree.Element("message")
    _positions(c, element, message.instance)
    leaf(element, "name", message.name)
    shared_fields(c, element, message, V2_MESSAGE_FIELDS)
    kept_fields(c, element, message.instance, ["message"])
    return element


def _dependency(c: Collection, dependency: Dependency) -> etree._Element | None:
    kind = dependency.kind
    if kind == "PRECEDENCE_DEPENDENCY":
        sink, source = dependency.first[1], dependency.second[1]
        element = leaf(etree.Element("cheddar"), "dependency", f"{source} {sink}")
        element.set("from_type", "task")
        element.set("to_type", "task")
        return element
    if kind in ("QUEUEING_BUFFER_DEPENDENCY", "ASYNCHRONOUS_COMMUNICATION_DEPENDENCY"):
        task, thing = dependency.first, dependency.second
        if dependency.extras and dependency.extras != [
            ("asynchronous_communication_protocol_property", "FIRST_MESSAGE")
        ]:
            c.ctx.problems.append(
                f"dependency of {task[1]} on {thing[1]}: Cheddar 2 has no ALL_MESSAGES protocol"
            )
        if dependency.orientation == "FROM_OBJECT_TO_TASK":
            text, from_type, to_type = f"{thing[1]} {task[1]}", thing[0], "task"
        else:
            text, from_type, to_type = f"{task[1]} {thing[1]}", "task", thing[0]
        element = leaf(etree.Element("cheddar"), "dependency", text)
        element.set("from_type", from_type)
        element.set("to_type", to_type)
        return element
    c.ctx.problems.append(
        f"Cheddar 2 has no {kind} ({dependency.first[1]}, {dependency.second[1]}); export as Cheddar 3"
    )
    return None
