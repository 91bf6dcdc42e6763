"""The record lists inside Cheddar entities, in both file styles: a task's offsets, a resource's
critical sections and a buffer's roles.

Cheddar 3 writes them as elements (``<offset_type>``, and ``<task_name>`` / record pairs in
``<critical_sections>`` and ``<roles>``); Cheddar 2 as lines of words (``<offset>2 5</offset>``,
``<resource_user>task 1 3</resource_user>``, ``<buffer_user buffer_role="producer">``). Each
becomes a list of AADL record values (``Cheddar_Properties::Offsets``, ``Critical_Sections``,
``Buffer_Roles``) whose task fields refer to the thread instances.
"""

from __future__ import annotations

from lxml import etree
from pyecore.ecore import EObject

from rosaadl.importers.cheddar.document import children, local
from rosaadl.importers.cheddar.state import ReadState
from rosaadl.importers.cheddar.values import (
    int_value,
    named_value,
    record_value,
    reference_value,
    str_value,
)

__all__ = ["offsets", "critical_sections", "buffer_roles"]


def offsets(state: ReadState, element: etree._Element) -> list[EObject]:
    """``<offsets>`` of a task: (activation, offset value) records."""
    records = []
    for item in children(element):
        tag = local(item)
        if state.version == 3:
            if tag != "offset_type":
                state.fail(item, f"<{tag}> in <offsets>; expected <offset_type>")
            present = state.index_children(item)
            if set(present) - {"offset_value", "activation"} or len(present) != 2:
                state.fail(item, "<offset_type> must hold <offset_value> and <activation>")
            activation = state.natural(present["activation"])
            value = state.natural(present["offset_value"])
        else:
            if tag != "offset":
                state.fail(item, f"<{tag}> in <offsets>; expected <offset>")
            words = state.text(item).split()
            if len(words) != 2:
                state.fail(item, "<offset> must hold two numbers: activation and offset value")
            activation = state.natural(item, words[0])
            value = state.natural(item, words[1])
        records.append(
            record_value(
                [("Activation", int_value(activation)), ("Offset_Value", int_value(value, state.unit))]
            )
        )
    return records


def critical_sections(state: ReadState, element: etree._Element) -> list[EObject]:
    """``<critical_sections>`` (Cheddar 3) or ``<resource_used_by>`` (Cheddar 2) of a resource."""
    records = []
    if state.version == 2:
        for item in children(element):
            if local(item) != "resource_user":
                state.fail(item, f"<{local(item)}> in <resource_used_by>; expected <resource_user>")
            words = state.text(item).split()
            if len(words) != 3:
                state.fail(item, "<resource_user> must hold a task name, a begin and an end")
            task = state.task_reference(item, words[0])
            begin, end = state.natural(item, words[1]), state.natural(item, words[2])
            records.append(_critical_section(state, item, task, begin, end, None))
        return records
    for task_element, data in _pairs(state, element, "critical_section"):
        present = state.index_children(data)
        unknown = set(present) - {"task_begin", "task_end", "task_synchronization"}
        if unknown:
            state.fail(data, f"<critical_section> has unknown field <{sorted(unknown)[0]}>")
        for needed in ("task_begin", "task_end"):
            if needed not in present:
                state.fail(data, f"<critical_section> has no <{needed}>")
        task = state.task_reference(task_element, state.text(task_element))
        sync = present.get("task_synchronization")
        records.append(
            _critical_section(
                state,
                data,
                task,
                state.natural(present["task_begin"]),
                state.natural(present["task_end"]),
                state.literal(sync, "synchronization") if sync is not None else None,
            )
        )
    return records


def _critical_section(
    state: ReadState, element: etree._Element, task: EObject | str, begin: int, end: int, sync: str | None
) -> EObject:
    if begin > end:
        state.fail(element, f"the critical section begins ({begin}) after it ends ({end})")
    fields = [
        ("Task", reference_value(task)),
        ("Task_Begin", int_value(begin, state.unit)),
        ("Task_End", int_value(end, state.unit)),
    ]
    if sync is not None:
        fields.append(("Synchronization", named_value(sync)))
    return record_value(fields)


def buffer_roles(state: ReadState, element: etree._Element) -> list[EObject]:
    """``<roles>`` (Cheddar 3) or ``<buffer_used_by>`` (Cheddar 2) of a buffer."""
    records = []
    if state.version == 2:
        for item in children(element):
            if local(item) != "buffer_user":
                state.fail(item, f"<{local(item)}> in <buffer_used_by>; expected <buffer_user>")
            words = state.text(item).split()
            if len(words) != 3:
                state.fail(item, "<buffer_user> must hold a task name, a size and a time")
            role_text = (item.get("buffer_role") or "producer").strip().lower()
            if role_text not in ("producer", "consumer"):
                state.fail(item, f"buffer_role is {role_text!r}; expected producer or consumer")
            fields = [
                ("Task", reference_value(state.task_reference(item, words[0]))),
                ("Role", named_value("QUEUING_" + role_text.upper())),
                ("Size", int_value(state.natural(item, words[1]))),
                ("Time", int_value(state.natural(item, words[2]), state.unit)),
            ]
            records.append(record_value(fields))
        return records
    for task_element, data in _pairs(state, element, "buffer_role"):
        present = state.index_children(data)
        unknown = set(present) - {"the_role", "size", "time", "timeout", "amplitude_function"}
        if unknown:
            state.fail(data, f"<buffer_role> has unknown field <{sorted(unknown)[0]}>")
        if "the_role" not in present:
            state.fail(data, "<buffer_role> has no <the_role>")
        fields = [
            ("Task", reference_value(state.task_reference(task_element, state.text(task_element)))),
            ("Role", named_value(state.literal(present["the_role"], "buffer_role"))),
        ]
        if "size" in present:
            fields.append(("Size", int_value(state.natural(present["size"]))))
        for tag, name in (("time", "Time"), ("timeout", "Timeout")):
            if tag in present:
                fields.append((name, int_value(state.natural(present[tag]), state.unit)))
        if "amplitude_function" in present:
            fields.append(("Amplitude_Function", str_value(state.text(present["amplitude_function"]))))
        records.append(record_value(fields))
    return records


def _pairs(
    state: ReadState, element: etree._Element, record_tag: str
) -> list[tuple[etree._Element, etree._Element]]:
    """``<task_name>t</task_name><record>…</record>`` pairs of Cheddar 3's indexed tables."""
    items = children(element)
    result = []
    i = 0
    while i < len(items):
        first = items[i]
        if local(first) != "task_name":
            state.fail(first, f"<{local(first)}> in <{local(element)}>; expected <task_name>")
        if i + 1 >= len(items) or local(items[i + 1]) != record_tag:
            state.fail(first, f"<task_name> in <{local(element)}> must be followed by <{record_tag}>")
        result.append((first, items[i + 1]))
        i += 2
    return result
