"""What the Cheddar 3 and Cheddar 2 writers share: elements, field tables, kept fields, and the
values both write in their own syntax (offsets, schedulers, critical sections, buffer roles).

A field is written when the instance object has a value for its property (converted by
:meth:`~rosaadl.exporters.cheddar.context.ExportContext.text`), otherwise from ``defaults``, the
values Cheddar's editor writes for a new entity (entities made from AADL get them; imported ones
are written back with exactly the fields they had).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from lxml import etree
from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import ExportError, RosaadlError
from rosaadl.exporters.cheddar.hardware import in_soc
from rosaadl.exporters.cheddar.software import task_name
from rosaadl.exporters.cheddar.system import Collection, SharedObject, Task
from rosaadl.fileio import parse_xml_bytes
from rosaadl.importers.cheddar.vocabulary import (
    AADL_TO_SCHEDULER,
    CP,
    ENUMERATIONS,
    PERIOD,
    SCHEDULING,
    Field,
)

__all__ = [
    "DEFAULT_SCHEDULER",
    "leaf",
    "ref",
    "fields",
    "shared_fields",
    "kept_fields",
    "aadl_scheduler",
    "task_defaults",
    "critical_sections",
    "buffer_roles",
]

#: The scheduler of a processor whose model says none (a warning says so).
DEFAULT_SCHEDULER = "POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL"


def leaf(parent: etree._Element, tag: str, text: str) -> etree._Element:
    """A child ``<tag>text</tag>`` (text XML cannot carry is an :class:`ExportError`)."""
    element = etree.SubElement(parent, tag)
    try:
        element.text = text
    except ValueError:
        raise ExportError(
            f"<{tag}> would hold {text!r}, which XML cannot carry (control characters)"
        ) from None
    return element


def ref(parent: etree._Element, tag: str, target: str) -> etree._Element:
    """A child ``<tag ref="target"/>``."""
    element = etree.SubElement(parent, tag)
    try:
        element.set("ref", target)
    except ValueError:
        raise ExportError(f"<{tag}> would refer to {target!r}, which XML cannot carry") from None
    return element


def fields(
    c: Collection,
    element: etree._Element,
    obj: EObject | None,
    table: Iterable[Field],
    defaults: dict[str, str] | None = None,
    skip: Iterable[str] = (),
) -> None:
    """Write the table's fields ``obj`` has a value for (and the defaults for the others)."""
    props = c.ctx.props(obj) if obj is not None else None
    skipped = set(skip)
    for spec in table:
        if spec.tag in skipped:
            continue
        value = props.get(spec.prop) if props is not None else None
        if value is None:
            if defaults and spec.tag in defaults:
                leaf(element, spec.tag, defaults[spec.tag])
            continue
        if spec.kind == "offsets":
            offsets(c, element, obj, value)
            continue
        text = c.ctx.text(obj, spec, value)
        if text is not None:
            leaf(element, spec.tag, text)


def shared_fields(
    c: Collection, element: etree._Element, shared: SharedObject, table: Iterable[Field]
) -> None:
    """The fields of a buffer or message: its instance's when imported, else the values the
    export made for it."""
    if shared.imported:
        fields(c, element, shared.instance, table)
        return
    for spec in table:
        if spec.tag in shared.values:
            leaf(element, spec.tag, shared.values[spec.tag])


def kept_fields(c: Collection, element: etree._Element, obj: EObject | None, kinds: Iterable[str]) -> None:
    """The fields of ``kinds`` elements that the reader kept verbatim on ``obj``, written back."""
    if obj is None:
        return
    wanted = set(kinds)
    kept = c.ctx.props(obj).get(CP + "Unmodelled_Fields")
    if not isinstance(kept, list):
        return
    for item in kept:
        if not isinstance(item, dict) or str(item.get("Section", "")).lower() not in wanted:
            continue
        try:
            element.append(
                parse_xml_bytes(str(item.get("Xml", "")).encode("utf-8"), "<kept field>").getroot()
            )
        except RosaadlError as exc:
            c.ctx.problem(obj, f"a kept field is not XML: {exc.message}")


def offsets(c: Collection, element: etree._Element, obj: EObject, value: Any) -> None:
    """A task's ``Cheddar_Properties::Offsets`` in the style of the format written."""
    holder = etree.SubElement(element, "offsets")
    for record in value if isinstance(value, list) else []:
        if not isinstance(record, dict):
            continue
        activation = record.get("Activation")
        offset = c.ctx.time_text(obj, "Cheddar_Properties::Offsets", record.get("Offset_Value"))
        if offset is None or not isinstance(activation, int):
            continue
        if c.ctx.version == 3:
            item = etree.SubElement(holder, "offset_type")
            leaf(item, "offset_value", offset)
            leaf(item, "activation", str(activation))
        else:
            leaf(holder, "offset", f"{activation} {offset}")


def aadl_scheduler(c: Collection, owner: EObject) -> str | None:
    """The Cheddar scheduler of ``Scheduling_Protocol`` on a processor (or the processor or SoC
    around it), or None."""
    current = owner
    while current is not None and model.is_a(current, "ComponentInstance"):
        value = c.ctx.props(current).get(SCHEDULING)
        if value is not None:
            first = value[0] if isinstance(value, list) and value else value
            literal = AADL_TO_SCHEDULER.get(str(first).lower())
            if literal is None and str(first).upper() in ENUMERATIONS["scheduler"]:
                literal = str(first).upper()
            if literal is None:
                c.ctx.problem(owner, f"Scheduling_Protocol {first} has no Cheddar scheduler")
            return literal
        if current.category is None or current.category.name not in ("processor", "system"):
            break
        if (
            current.category.name == "system"
            and not in_soc(current, c.soc_ids)
            and id(current) not in c.soc_ids
        ):
            break
        current = current.eContainer()
    return None


def task_defaults(c: Collection, task: Task) -> dict[str, str]:
    """The fields Cheddar's editor writes for a task made from AADL, where the thread has no value."""
    if task.imported:
        return {}
    props = c.ctx.props(task.instance)
    defaults = {
        "start_time": "0",
        "blocking_time": "0",
        "policy": "SCHED_FIFO",
        "text_memory_size": "0",
        "stack_memory_size": "0",
        "criticality": "0",
        "context_switch_overhead": "0",
    }
    priority = props.get(CP + "Fixed_Priority")
    defaults["priority"] = str(priority) if isinstance(priority, int) and priority >= 0 else "1"
    period = props.get(PERIOD)
    if task.task_type not in ("APERIODIC_TYPE",) and period is not None:
        defaults["jitter"] = "0"
        deadline = c.ctx.time_text(task.instance, "Period", period)
        if deadline is not None:
            defaults["deadline"] = deadline
    return defaults


def critical_sections(c: Collection, resource: SharedObject) -> list[tuple[str, str, str, str | None]]:
    """(task, begin, end, synchronization) of each critical section of a resource."""
    if not resource.imported:
        return [(t, str(b), str(e), s) for t, b, e, s in resource.sections]
    value = c.ctx.props(resource.instance).get(CP + "Critical_Sections")
    sections = []
    for record in value if isinstance(value, list) else []:
        if not isinstance(record, dict):
            continue
        name = task_name(c, record.get("Task"))
        begin = c.ctx.time_text(resource.instance, "Critical_Sections", record.get("Task_Begin"))
        end = c.ctx.time_text(resource.instance, "Critical_Sections", record.get("Task_End"))
        sync = record.get("Synchronization")
        if name is None or begin is None or end is None:
            c.ctx.problem(resource.instance, "a critical section has no task, begin or end")
            continue
        sections.append((name, begin, end, str(sync).upper() if sync is not None else None))
    return sections


def buffer_roles(c: Collection, buffer: SharedObject) -> list[dict[str, str]]:
    """The roles of a buffer as (tag -> text) rows: task, role, size, time, timeout, ..."""
    if not buffer.imported:
        return buffer.roles
    value = c.ctx.props(buffer.instance).get(CP + "Buffer_Roles")
    roles: list[dict[str, str]] = []
    for record in value if isinstance(value, list) else []:
        if not isinstance(record, dict):
            continue
        name = task_name(c, record.get("Task"))
        if name is None or record.get("Role") is None:
            c.ctx.problem(buffer.instance, "a buffer role has no task or role")
            continue
        role: dict[str, str] = {"task": name, "role": str(record["Role"]).upper()}
        if isinstance(record.get("Size"), int):
            role["size"] = str(record["Size"])
        for key, tag in (("Time", "time"), ("Timeout", "timeout")):
            if record.get(key) is not None:
                text = c.ctx.time_text(buffer.instance, f"Buffer_Roles.{key}", record[key])
                if text is not None:
                    role[tag] = text
        if isinstance(record.get("Amplitude_Function"), str):
            role["amplitude_function"] = record["Amplitude_Function"]
        roles.append(role)
    return roles
