"""Cheddar 3 ADL documents (``.xmlv3``): ids and refs, core units and processors, dependency
records, and the reader of each section.

Cheddar 3 gives every entity an ``id`` and joins entities with ``ref`` attributes; its reader
checks that ids are unique and that every ``ref`` resolves to an entity of the right kind, and
so does this one. A mono-core processor refers to one core unit (its facts go on the processor
instance); a multi-core processor refers to several, each a ``processor`` subcomponent. The
entities that Cheddar 2 and 3 share are read by :mod:`rosaadl.importers.cheddar.entities`.
"""

from __future__ import annotations

from typing import Any

from lxml import etree
from pyecore.ecore import EObject

from rosaadl.importers.cheddar import entities
from rosaadl.importers.cheddar.connections import dependency
from rosaadl.importers.cheddar.document import canonical_xml, children, local
from rosaadl.importers.cheddar.scheduling import scheduling_parameters
from rosaadl.importers.cheddar.state import ReadState, SectionReader, entries
from rosaadl.importers.cheddar.values import associate, named_value, str_value
from rosaadl.importers.cheddar.vocabulary import (
    ADDRESS_SPACE_FIELDS,
    BUFFER_FIELDS,
    CORE_FIELDS,
    CP,
    DEPENDENCY_ENDS,
    MESSAGE_FIELDS,
    MESSAGE_TAGS,
    NETWORK_FIELDS,
    NETWORK_TAGS,
    PROCESSOR_FIELDS,
    RESOURCE_FIELDS,
    RESOURCE_TAGS,
    TASK_FIELDS,
    TASK_TAG_TYPES,
)

__all__ = ["SECTION_READERS", "collect_ids", "ref", "keep_unreferenced_cores", "core_facts"]


def collect_ids(state: ReadState, sections: dict[str, list[etree._Element]]) -> None:
    """Record the id of every entry of every section; an empty or repeated id is an error."""
    for name, elements in sections.items():
        for section in elements:
            for item in children(section):
                identifier = item.get("id")
                if identifier is None:
                    continue
                identifier = identifier.strip()
                if not identifier:
                    state.fail(item, "the id attribute is empty")
                if identifier in state.ids:
                    first = state.ids[identifier][1]
                    state.fail(item, f"id {identifier!r} is used twice (first at line {first.sourceline})")
                state.ids[identifier] = (name, item)


def ref(state: ReadState, element: etree._Element, kind: str) -> Any:
    """The target of a ``ref`` attribute: the entity of ``kind`` it names, or for ``kind``
    ``core`` the id of a core unit."""
    target = element.get("ref")
    if target is None or not target.strip():
        state.fail(element, f"<{local(element)}> has no ref attribute")
    target = target.strip()
    if kind == "core":
        if target not in state.cores:
            if target in state.ids:
                state.fail(element, f"ref {target!r} is not a core unit")
            state.fail(element, f"ref {target!r} does not resolve to any id of the file")
        return target
    entity = state.by_id.get(target)
    if entity is None or entity.kind != kind:
        if target in state.ids:
            state.fail(element, f"ref {target!r} is a {state.ids[target][0]} entry, expected a {kind}")
        state.fail(element, f"ref {target!r} does not resolve to any id of the file")
    return entity


def keep_unreferenced_cores(state: ReadState, sections: list[etree._Element]) -> None:
    """Keep verbatim (with a warning) the entries of ``<core_units>`` no processor refers to."""
    for section in sections:
        for item in children(section):
            identifier = (item.get("id") or "").strip()
            if local(item) == "core_unit" and identifier in state.used_cores:
                continue
            state.warn(item, f"<{local(item)}> {identifier!r} belongs to no processor; kept as it is")
            state.kept.append(("core_units", canonical_xml(item)))


def core_units(state: ReadState, section: etree._Element) -> None:
    """Index the core units by id; their facts are read with the processor that uses them."""
    for item in children(section):
        if local(item) != "core_unit":
            continue  # memories and other entries: kept with the unreferenced cores
        identifier = (item.get("id") or "").strip()
        if not identifier:
            state.fail(item, "the core unit has no id attribute")
        state.cores[identifier] = item


def core_facts(state: ReadState, owner: EObject, identifier: str, as_processor_core: bool) -> None:
    """Store a core unit's facts on ``owner`` (a mono-core processor or a core instance)."""
    element = state.cores[identifier]
    present = state.index_children(element)
    name = state.name_of(element, present, "core unit")
    consumed = {"name", "object_type"}
    if as_processor_core:
        associate(owner, CP + "Core_Name", str_value(name))
        associate(owner, CP + "Core_Id", str_value(identifier))
    else:
        associate(owner, CP + "Cheddar_Name", str_value(name))
        associate(owner, CP + "Cheddar_Id", str_value(identifier))
    parameters = present.get("scheduling")
    if parameters is not None:
        consumed.add("scheduling")
        scheduling_parameters(state, owner, parameters, processor=True)
    state.fields(owner, element, CORE_FIELDS, present, consumed)
    state.leftovers(owner, element, "core_unit", present, consumed)


def processors(state: ReadState, section: etree._Element) -> None:
    """Mono-core processors (one instance holding its core's facts) and multi-core ones (one
    ``processor`` subcomponent per core unit)."""
    for item in state.items(section, ("mono_core_processor", "multi_cores_processor"), "processor"):
        tag = local(item)
        present = state.index_children(item)
        entity = state.declare(item, present, "processor", state.processors, "processor")
        instance = state.place(entity, state.root, "processor")
        consumed = {"name", "object_type"}
        state.fields(instance, item, PROCESSOR_FIELDS, present, consumed)
        if tag == "mono_core_processor":
            core = present.get("core")
            if core is None:
                state.fail(item, "the mono-core processor has no <core ref=...>")
            consumed.add("core")
            identifier = ref(state, core, "core")
            state.used_cores.add(identifier)
            core_facts(state, instance, identifier, as_processor_core=True)
        else:
            cores = present.get("cores")
            if cores is None:
                state.fail(item, "the multi-core processor has no <cores>")
            consumed.add("cores")
            refs = children(cores)
            if not refs:
                state.fail(cores, "the multi-core processor has no core unit")
            for reference in refs:
                if local(reference) != "core_unit":
                    state.fail(reference, f"<{local(reference)}> in <cores>; expected <core_unit ref=...>")
                identifier = ref(state, reference, "core")
                state.used_cores.add(identifier)
                core_name = state.name_of(
                    state.cores[identifier], state.index_children(state.cores[identifier]), "core unit"
                )
                core = state.instance(instance, core_name, "processor")
                core_facts(state, core, identifier, as_processor_core=False)
        state.leftovers(instance, item, "processor", present, consumed)


def dependencies(state: ReadState, section: etree._Element) -> None:
    """Dependency records: their kind, the two ends as refs, the orientation and the extras."""
    for index, item in enumerate(state.items(section, ("dependency",), "dependency")):
        present = state.index_children(item)
        kind_element = present.get("type_of_dependency")
        if kind_element is None:
            state.fail(item, "the dependency has no <type_of_dependency>")
        kind = state.literal(kind_element, "dependency_type")
        if kind not in DEPENDENCY_ENDS:
            state.fail(kind_element, f"unknown dependency type {kind}")
        first_tag, first_kind, orient_tag, second_tag, second_kind, extras = DEPENDENCY_ENDS[kind]
        allowed = {"type_of_dependency", first_tag, second_tag} | {e[0] for e in extras}
        if orient_tag:
            allowed.add(orient_tag)
        for tag, child in present.items():
            if tag not in allowed:
                state.fail(child, f"<{tag}> does not belong to a {kind}")
        ends = []
        for tag, end_kind in ((first_tag, first_kind), (second_tag, second_kind)):
            if tag not in present:
                state.fail(item, f"the {kind} has no <{tag} ref=...>")
            ends.append(ref(state, present[tag], end_kind))
        orientation = None
        if orient_tag:
            if orient_tag not in present:
                state.fail(item, f"the {kind} has no <{orient_tag}>")
            orientation = state.literal(present[orient_tag], "orientation")
        extra_values = [
            (prop, named_value(state.literal(present[tag], enum)))
            for tag, prop, enum in extras
            if tag in present
        ]
        dependency(state, item, index, kind, ends[0], ends[1], orientation, extra_values)


#: The reader of each Cheddar 3 section (taken in the order of ``SECTIONS_V3``).
SECTION_READERS: dict[str, SectionReader] = {
    "core_units": core_units,
    "processors": processors,
    "networks": entries(
        NETWORK_TAGS,
        "network",
        lambda state, item, _: entities.network(state, item, NETWORK_FIELDS, local(item)),
    ),
    "address_spaces": entries(
        ("address_space",),
        "address space",
        lambda state, item, _: entities.address_space(state, item, ADDRESS_SPACE_FIELDS),
    ),
    "tasks": entries(
        tuple(TASK_TAG_TYPES),
        "task",
        lambda state, item, index: entities.task(
            state, item, index, TASK_FIELDS, TASK_TAG_TYPES[local(item)]
        ),
    ),
    "resources": entries(
        tuple(RESOURCE_TAGS.values()),
        "resource",
        lambda state, item, index: entities.resource(state, item, index, RESOURCE_FIELDS),
    ),
    "buffers": entries(
        ("buffer",), "buffer", lambda state, item, index: entities.buffer(state, item, index, BUFFER_FIELDS)
    ),
    "messages": entries(
        tuple(MESSAGE_TAGS.values()),
        "message",
        lambda state, item, _: entities.message(state, item, MESSAGE_FIELDS),
    ),
    "dependencies": dependencies,
}
