"""Cheddar 2 documents (DTD style, ``.xml``): processors with a scheduler element,
dependencies written as two names, and the reader of each section.

Cheddar 2 has no ids, core units or address-space scheduling parameters: a processor holds
``<scheduler>`` whose attributes carry preemption, quantum and user-defined scheduler files
(:mod:`~rosaadl.importers.cheddar.scheduling`); a dependency is
``<dependency from_type=... to_type=...>from to</dependency>``. Cheddar 2's reader does not
check location names, so undeclared processors and address spaces are warnings
(:meth:`~rosaadl.importers.cheddar.state.ReadState.lenient`). The entities that Cheddar 2 and 3
share (with the ``x``/``y`` positions of Cheddar 2's editor) are read by
:mod:`rosaadl.importers.cheddar.entities`.
"""

from __future__ import annotations

from lxml import etree

from rosaadl.importers.cheddar import entities
from rosaadl.importers.cheddar.connections import dependency
from rosaadl.importers.cheddar.scheduling import scheduler_element
from rosaadl.importers.cheddar.state import Entity, ReadState, SectionReader, entries
from rosaadl.importers.cheddar.values import associate, str_value
from rosaadl.importers.cheddar.vocabulary import (
    CP,
    V2_ADDRESS_SPACE_FIELDS,
    V2_BUFFER_FIELDS,
    V2_MESSAGE_FIELDS,
    V2_NETWORK_FIELDS,
    V2_RESOURCE_FIELDS,
    V2_TASK_FIELDS,
)

__all__ = ["SECTION_READERS"]


def processors(state: ReadState, section: etree._Element) -> None:
    """``<processor>`` entries: name, scheduler and network link."""
    for item in state.items(section, ("processor",), "processor"):
        present = state.index_children(item)
        entity = Entity("processor", state.name_of(item, present, "processor"), item)  # no ids in Cheddar 2
        state.register(state.processors, entity, "processor")
        instance = state.place(entity, state.root, "processor")
        consumed = {"name"}
        scheduler = present.get("scheduler")
        if scheduler is not None:
            consumed.add("scheduler")
            scheduler_element(state, instance, scheduler, processor=True)
        link = present.get("network_link")
        if link is not None:
            consumed.add("network_link")
            associate(instance, CP + "Network_Link", str_value(state.text(link)))
        state.leftovers(instance, item, "processor", present, consumed)


def dependencies(state: ReadState, section: etree._Element) -> None:
    """``<dependency from_type=... to_type=...>from to</dependency>``: task to task is a
    precedence, a task and a buffer a queueing-buffer dependency, a task and a message an
    asynchronous communication."""
    for index, item in enumerate(state.items(section, ("dependency",), "dependency")):
        from_type = (item.get("from_type") or "task").strip().lower()
        to_type = (item.get("to_type") or "task").strip().lower()
        for kind in (from_type, to_type):
            if kind not in ("task", "buffer", "message"):
                state.fail(item, f"dependency end type {kind!r}; expected task, buffer or message")
        words = state.text(item).split()
        if len(words) != 2:
            state.fail(item, "<dependency> must hold two names: from and to")
        tables = {"task": state.tasks, "buffer": state.buffers, "message": state.messages}
        ends = []
        for word, kind in zip(words, (from_type, to_type), strict=True):
            entity = tables[kind].get(word)
            if entity is None:
                state.fail(
                    item, f"{kind} {word!r} is not declared (expected one of: {state.known(tables[kind])})"
                )
            ends.append(entity)
        if from_type == "task" and to_type == "task":
            dependency(state, item, index, "PRECEDENCE_DEPENDENCY", ends[1], ends[0], None, [])
            continue
        if "task" not in (from_type, to_type):
            state.fail(item, "a dependency must have a task at one end")
        kind = (
            "QUEUEING_BUFFER_DEPENDENCY"
            if "buffer" in (from_type, to_type)
            else "ASYNCHRONOUS_COMMUNICATION_DEPENDENCY"
        )
        if from_type == "task":
            dependency(state, item, index, kind, ends[0], ends[1], "FROM_TASK_TO_OBJECT", [])
        else:
            dependency(state, item, index, kind, ends[1], ends[0], "FROM_OBJECT_TO_TASK", [])


#: The reader of each Cheddar 2 section (taken in the order of ``SECTIONS_V2``).
SECTION_READERS: dict[str, SectionReader] = {
    "processors": processors,
    "networks": entries(
        ("network",),
        "network",
        lambda state, item, _: entities.network(state, item, V2_NETWORK_FIELDS, "generic_network"),
    ),
    "address_spaces": entries(
        ("address_space",),
        "address space",
        lambda state, item, _: entities.address_space(state, item, V2_ADDRESS_SPACE_FIELDS),
    ),
    "tasks": entries(
        ("task",),
        "task",
        lambda state, item, index: entities.task(state, item, index, V2_TASK_FIELDS, "APERIODIC_TYPE"),
    ),
    "resources": entries(
        ("resource",),
        "resource",
        lambda state, item, index: entities.resource(state, item, index, V2_RESOURCE_FIELDS),
    ),
    "buffers": entries(
        ("buffer",),
        "buffer",
        lambda state, item, index: entities.buffer(state, item, index, V2_BUFFER_FIELDS),
    ),
    "messages": entries(
        ("message",), "message", lambda state, item, _: entities.message(state, item, V2_MESSAGE_FIELDS)
    ),
    "dependencies": dependencies,
}
