"""Writing the intermediate system as a Cheddar 3 ADL document (``.xmlv3``).

Cheddar 3 gives every entity an ``id`` (its own when it was imported and is unique, else
``id_N``) and joins entities with ``ref`` attributes: a processor refers to its core units, a
dependency to its two ends. Core units and address spaces carry ``<scheduling_parameters>``
inside ``<scheduling>``, as Cheddar writes them, whichever style the file was read in.
Fields are written in the order of the field tables of
:mod:`~rosaadl.importers.cheddar.vocabulary` (Cheddar 3's writer order).
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
    ref,
    shared_fields,
    task_defaults,
)
from rosaadl.exporters.cheddar.system import (
    AddressSpace,
    Collection,
    Core,
    Dependency,
    Network,
    Processor,
    SharedObject,
    Task,
)
from rosaadl.importers.cheddar.vocabulary import (
    ADDRESS_SPACE_FIELDS,
    BUFFER_FIELDS,
    CORE_FIELDS,
    CP,
    DEPENDENCY_ENDS,
    MESSAGE_FIELDS,
    MESSAGE_TAGS,
    NETWORK_FIELDS,
    PREEMPTIVE_SCHEDULER,
    PRIORITY,
    PROCESSOR_FIELDS,
    RESOURCE_FIELDS,
    RESOURCE_TAGS,
    SCHEDULING_FIELDS,
    TASK_FIELDS,
    TASK_TYPE_TAGS,
)

__all__ = ["sections"]

#: The id of each entity, by (kind, Cheddar name).
Ids = dict[tuple[str, str], str]


def _assign_ids(c: Collection) -> Ids:
    """An id for every entity: its own (imported) when it is unique, else ``id_N``."""
    ids: Ids = {}
    taken: set[str] = set()
    wanted: list[tuple[tuple[str, str], str | None]] = []
    for processor in c.system.processors:
        for core in processor.cores:
            wanted.append((("core", core.name), core.ident))
    for network in c.system.networks:
        wanted.append((("network", network.name), network.ident))
    for processor in c.system.processors:
        wanted.append((("processor", processor.name), processor.ident))
    for space in c.system.spaces:
        wanted.append((("address_space", space.name), space.ident))
    for task in c.system.tasks:
        wanted.append((("task", task.name), task.ident))
    for kind, items in (
        ("resource", c.system.resources),
        ("buffer", c.system.buffers),
        ("message", c.system.messages),
    ):
        for item in items:
            wanted.append(((kind, item.name), item.ident))
    for _section, xml in c.system.kept:
        try:
            element = etree.fromstring(xml.encode())
        except etree.XMLSyntaxError:
            continue
        for node in element.iter():
            if isinstance(node.tag, str) and node.get("id"):
                taken.add(node.get("id"))
    owners: dict[str, tuple[str, str]] = {}
    for key, ident in wanted:
        if ident is None:
            continue
        if ident in owners and owners[ident] != key:
            if key[0] == "core" and owners[ident][0] == "core":
                continue
            c.ctx.problems.append(
                f"id {ident!r} is given to both {owners[ident][0]} {owners[ident][1]!r} "
                f"and {key[0]} {key[1]!r}"
            )
            continue
        owners[ident] = key
        taken.add(ident)
    counter = 0
    for key, ident in wanted:
        if key in ids:
            continue
        if ident is not None and owners.get(ident) == key:
            ids[key] = ident
            continue
        if ident is not None and key[0] == "core":
            ids[key] = ident
            continue
        counter += 1
        while f"id_{counter}" in taken:
            counter += 1
        ids[key] = f"id_{counter}"
        taken.add(f"id_{counter}")
    return ids


def sections(c: Collection) -> dict[str, list[etree._Element]]:
    """The entries of each section, with an id for every entity (problems go to ``c.ctx``)."""
    ids = _assign_ids(c)
    return {
        "core_units": _core_units(c, ids),
        "networks": [_network(c, ids, n) for n in c.system.networks],
        "processors": [_processor(c, ids, p) for p in c.system.processors],
        "address_spaces": [_space(c, ids, s) for s in c.system.spaces],
        "tasks": [_task(c, ids, t) for t in c.system.tasks],
        "resources": [_resource(c, ids, r) for r in c.system.resources],
        "buffers": [_buffer(c, ids, b) for b in c.system.buffers],
        "messages": [_message(c, ids, m) for m in c.system.messages],
        "dependencies": [_dependency(c, ids, d) for d in c.system.dependencies],
    }


def _scheduling(
    c: Collection, element: etree._Element, owner: EObject | None, *, processor: bool, imported: bool
) -> None:
    props = c.ctx.props(owner) if owner is not None else None
    scheduler = None
    if props is not None:
        scheduler = props.get(CP + "Scheduler")
        if scheduler is None and processor:
            scheduler = aadl_scheduler(c, owner)
    if processor:
        preemptive = props.get(PREEMPTIVE_SCHEDULER) if props is not None else None
    else:
        preemptive = props.get(CP + "Preemptive") if props is not None else None
    has_any = (
        scheduler is not None
        or preemptive is not None
        or (props is not None and any(props.has(f.prop) for f in SCHEDULING_FIELDS))
    )
    if imported and not has_any:
        return
    outer = etree.SubElement(element, "scheduling")
    params = etree.SubElement(outer, "scheduling_parameters")
    if scheduler is not None or not imported:
        default = DEFAULT_SCHEDULER if processor else "NO_SCHEDULING_PROTOCOL"
        if scheduler is None and processor and owner is not None:
            c.ctx.warn(owner, f"no Scheduling_Protocol; written with {default}")
        leaf(params, "scheduler_type", str(scheduler).upper() if scheduler is not None else default)
    quantum = SCHEDULING_FIELDS[0]
    fields(c, params, owner, [quantum], None if imported else {"quantum": "0"})
    if preemptive is not None or not imported:
        leaf(params, "preemptive_type", "NOT_PREEMPTIVE" if preemptive is False else "PREEMPTIVE")
    defaults = None if imported else {"capacity": "0", "period": "0", "priority": "0", "start_time": "0"}
    fields(c, params, owner, SCHEDULING_FIELDS[1:], defaults)
    kept_fields(c, params, owner, ["scheduling_parameters"])


def _core_units(c: Collection, ids: Ids) -> list[etree._Element]:
    items = []
    done: set[str] = set()
    for processor in c.system.processors:
        for core in processor.cores:
            ident = ids["core", core.name]
            if ident in done:
                continue
            done.add(ident)
            items.append(_core_unit(c, core, ident))
    return items


def _core_unit(c: Collection, core: Core, ident: str) -> etree._Element:
    element = etree.Element("core_unit", id=ident)
    leaf(element, "object_type", "CORE_OBJECT_TYPE")
    leaf(element, "name", core.name)
    owner = core.facts
    _scheduling(c, element, owner, processor=True, imported=core.imported)
    fields(c, element, owner, CORE_FIELDS, None if core.imported else {"speed": "1"})
    kept_fields(c, element, owner, ["core_unit"])
    return element


def _processor(c: Collection, ids: Ids, processor: Processor) -> etree._Element:
    tag = "multi_cores_processor" if processor.multi else "mono_core_processor"
    element = etree.Element(tag, id=ids["processor", processor.name])
    leaf(element, "object_type", "PROCESSOR_OBJECT_TYPE")
    leaf(element, "name", processor.name)
    if processor.multi:
        bound_to_core = any(t.core is not None and t.cpu == processor.name for t in c.system.tasks)
        kinds = {core.facts.classifier or "" for core in processor.cores if core.facts is not None}
        defaults = {
            "processor_type": "IDENTICAL_MULTICORES_TYPE" if len(kinds) <= 1 else "UNRELATED_MULTICORES_TYPE",
            "migration_type": "NO_MIGRATION_TYPE" if bound_to_core else "JOB_LEVEL_MIGRATION_TYPE",
        }
    else:
        defaults = {"processor_type": "MONOCORE_TYPE", "migration_type": "NO_MIGRATION_TYPE"}
    fields(c, element, processor.instance, PROCESSOR_FIELDS, None if processor.imported else defaults)
    if processor.multi:
        cores = etree.SubElement(element, "cores")
        for core in processor.cores:
            ref(cores, "core_unit", ids["core", core.name])
    else:
        ref(element, "core", ids["core", processor.cores[0].name])
    kept_fields(c, element, processor.instance, ["processor"])
    return element


def _network(c: Collection, ids: Ids, network: Network) -> etree._Element:
    element = etree.Element(network.tag, id=ids["network", network.name])
    leaf(element, "object_type", "NETWORK_OBJECT_TYPE")
    leaf(element, "name", network.name)
    defaults = None if network.imported else {"network_delay": "BOUNDED_DELAY"}
    fields(c, element, network.instance, NETWORK_FIELDS, defaults)
    kept_fields(c, element, network.instance, ["network"])
    return element


def _space(c: Collection, ids: Ids, space: AddressSpace) -> etree._Element:
    element = etree.Element("address_space", id=ids["address_space", space.name])
    leaf(element, "object_type", "ADDRESS_SPACE_OBJECT_TYPE")
    leaf(element, "name", space.name)
    leaf(element, "cpu_name", space.cpu)
    memory = ADDRESS_SPACE_FIELDS[:4]
    defaults = None if space.imported else {f.tag: "0" for f in memory}
    fields(c, element, space.instance, memory, defaults)
    _scheduling(c, element, space.instance, processor=False, imported=space.imported)
    fields(c, element, space.instance, ADDRESS_SPACE_FIELDS[4:])
    kept_fields(c, element, space.instance, ["address_space"])
    return element


def _task(c: Collection, ids: Ids, task: Task) -> etree._Element:
    element = etree.Element(TASK_TYPE_TAGS.get(task.task_type, "periodic_task"), id=ids["task", task.name])
    leaf(element, "object_type", "TASK_OBJECT_TYPE")
    leaf(element, "name", task.name)
    leaf(element, "task_type", task.task_type)
    leaf(element, "cpu_name", task.cpu)
    if task.space is not None:
        leaf(element, "address_space_name", task.space)
    if task.core is not None:
        leaf(element, "core_name", task.core)
    skip = () if task.task_type not in ("APERIODIC_TYPE",) or task.imported else ("period", "jitter")
    fields(c, element, task.instance, TASK_FIELDS, task_defaults(c, task), skip)
    kept_fields(c, element, task.instance, ["task"])
    return element


def _resource(c: Collection, ids: Ids, resource: SharedObject) -> etree._Element:
    element = etree.Element(
        RESOURCE_TAGS.get(resource.protocol, "np_resource"), id=ids["resource", resource.name]
    )
    leaf(element, "object_type", "RESOURCE_OBJECT_TYPE")
    leaf(element, "name", resource.name)
    obj = resource.instance
    fields(
        c,
        element,
        obj,
        RESOURCE_FIELDS[:3],
        None if resource.imported else {"state": "1", "size": "0", "address": "0"},
    )
    leaf(element, "protocol", resource.protocol)
    sections = critical_sections(c, resource)
    if sections or not resource.imported or c.ctx.props(obj).has(CP + "Critical_Sections"):
        holder = etree.SubElement(element, "critical_sections")
        for name, begin, end, sync in sections:
            leaf(holder, "task_name", name)
            section = etree.SubElement(holder, "critical_section")
            if sync is not None:
                leaf(section, "task_synchronization", sync)
            leaf(section, "task_begin", begin)
            leaf(section, "task_end", end)
    if resource.cpu is not None:
        leaf(element, "cpu_name", resource.cpu)
    if resource.space is not None:
        leaf(element, "address_space_name", resource.space)
    defaults = None
    if not resource.imported:
        priority = c.ctx.props(obj).get(PRIORITY)
        defaults = {
            "priority": "0",
            "priority_assignment": "MANUAL_ASSIGNMENT"
            if isinstance(priority, int)
            else "AUTOMATIC_ASSIGNMENT",
        }
    fields(c, element, obj, RESOURCE_FIELDS[3:], defaults)
    kept_fields(c, element, obj, ["resource"])
    return element


def _buffer(c: Collection, ids: Ids, buffer: SharedObject) -> etree._Element:
    element = etree.Element("buffer", id=ids["buffer", buffer.name])
    leaf(element, "object_type", "BUFFER_OBJECT_TYPE")
    leaf(element, "name", buffer.name)
    if buffer.cpu is not None:
        leaf(element, "cpu_name", buffer.cpu)
    if buffer.space is not None:
        leaf(element, "address_space_name", buffer.space)
    shared_fields(c, element, buffer, BUFFER_FIELDS)
    roles = buffer_roles(c, buffer)
    if roles or not buffer.imported or c.ctx.props(buffer.instance).has(CP + "Buffer_Roles"):
        holder = etree.SubElement(element, "roles")
        for role in roles:
            leaf(holder, "task_name", role["task"])
            item = etree.SubElement(holder, "buffer_role")
            leaf(item, "the_role", role["role"])
            for tag in ("size", "time", "timeout", "amplitude_function"):
                if tag in role:
                    leaf(item, tag, role[tag])
    kept_fields(c, element, buffer.instance, ["buffer"])
    return element


def _message_type(c: Collection, message: SharedObject) -> str:
    if not message.imported:
        return message.values["message_type"]
    value = c.ctx.props(message.instance).get(CP + "Message_Type")
    return str(value).upper() if value is not None else "APERIODIC_TYPE"


def _message(c: Collection, ids: Ids, message: SharedObject) -> etree._Element:
    kind = _message_type(c, message)
    element = etree.Element(MESSAGE_TAGS.get(kind, "aperiodic_message"), id=ids["message", message.name])
    leaf(element, "object_type", "MESSAGE_OBJECT_TYPE")
    leaf(element, "name", message.name)
    leaf(element, "message_type", kind)
    shared_fields(c, element, message, MESSAGE_FIELDS)
    kept_fields(c, element, message.instance, ["message"])
    return element


def _dependency(c: Collection, ids: Ids, dependency: Dependency) -> etree._Element:
    first_tag, _, orient_tag, second_tag, _, _ = DEPENDENCY_ENDS[dependency.kind]
    element = etree.Element("dependency")
    leaf(element, "type_of_dependency", dependency.kind)
    ref(element, first_tag, ids[dependency.first])
    if orient_tag is not None and dependency.orientation is not None:
        leaf(element, orient_tag, dependency.orientation)
    ref(element, second_tag, ids[dependency.second])
    for tag, text in dependency.extras:
        leaf(element, tag, text)
    return element
