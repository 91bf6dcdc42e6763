"""The structure check: what Cheddar's own reader would reject in a document.

Every exported document passes this check before it is written (a failure is an export
error, never a file Cheddar cannot open); the tests use it on every export too.
"""

from __future__ import annotations

from collections.abc import Iterable

from lxml import etree

from rosaadl.fileio import parse_xml_bytes
from rosaadl.importers.cheddar.vocabulary import DEPENDENCY_ENDS

__all__ = ["structure_problems"]


def structure_problems(document: etree._Element | bytes, cheddar_format: int = 3) -> list[str]:
    """What Cheddar's reader would reject in a document: duplicate ids, ``ref`` attributes that
    do not resolve to an entity of the right kind, and names that do not resolve.

    Cheddar 3's reader resolves ``cpu_name``, ``address_space_name`` and ``core_name`` of
    tasks, resources and buffers (and checks that a task's processor is its address space's),
    the ``cpu_name`` of address spaces and the task names of critical sections and buffer
    roles. Cheddar 2's reader resolves only the names of dependencies, critical sections and
    buffer users; its location names are not checked. ``l1_cache_system_name`` names a cache
    that Cheddar does not look up when reading.
    """
    root = (
        document if isinstance(document, etree._Element) else parse_xml_bytes(document, "<cheddar>").getroot()
    )
    problems: list[str] = []
    tree = root.getroottree()

    def where(element: etree._Element) -> str:
        return tree.getpath(element)

    def local(element: etree._Element) -> str:
        return etree.QName(element).localname.lower()

    sections = {local(s): s for s in root if isinstance(s.tag, str)}

    def names(section: str, tags: Iterable[str] | None = None) -> dict[str, etree._Element]:
        found: dict[str, etree._Element] = {}
        element = sections.get(section)
        if element is None:
            return found
        allowed = set(tags) if tags is not None else None
        for item in element:
            if not isinstance(item.tag, str) or (allowed is not None and local(item) not in allowed):
                continue
            name = item.findtext("name")
            if name is None:
                problems.append(f"{where(item)}: no <name>")
                continue
            name = " ".join(name.split()) if cheddar_format == 2 else name.strip()
            if name in found:
                problems.append(f"{where(item)}: name {name!r} is used twice in <{section}>")
            found[name] = item
        return found

    processors = names("processors")
    spaces = names("address_spaces")
    tasks = names("tasks")
    if cheddar_format == 3:
        ids: dict[str, etree._Element] = {}
        for element in root.iter():
            if isinstance(element.tag, str) and element.get("id") is not None:
                ident = element.get("id")
                if ident in ids:
                    problems.append(f"{where(element)}: id {ident!r} is also the id of {where(ids[ident])}")
                ids[ident] = element
        kinds = {
            "core": ("core_unit",),
            "core_unit": ("core_unit",),
        }
        dependency_kinds = {
            "task": "_task",
            "buffer": "buffer",
            "message": "_message",
            "resource": "_resource",
        }
        for element in root.iter():
            if not isinstance(element.tag, str) or element.get("ref") is None:
                continue
            target = ids.get(element.get("ref"))
            if target is None:
                problems.append(f"{where(element)}: ref {element.get('ref')!r} does not resolve")
                continue
            tag = local(element)
            expected = kinds.get(tag)
            if expected is None and local(element.getparent()) == "dependency":
                kind_text = (element.getparent().findtext("type_of_dependency") or "").strip().upper()
                ends = DEPENDENCY_ENDS.get(kind_text)
                if ends is not None:
                    end_kind = ends[1] if tag == ends[0] else ends[4] if tag == ends[3] else None
                    if end_kind is not None:
                        suffix = dependency_kinds[end_kind]
                        if not local(target).endswith(suffix):
                            problems.append(
                                f"{where(element)}: ref {element.get('ref')!r} is not a {end_kind}"
                            )
                continue
            if expected is not None and local(target) not in expected:
                problems.append(
                    f"{where(element)}: ref {element.get('ref')!r} is a <{local(target)}>, not a core unit"
                )
        cores_of: dict[str, set[str]] = {}
        core_names = {
            (c.findtext("name") or "").strip(): c for c in sections.get("core_units", etree.Element("x"))
        }
        for name, processor in processors.items():
            refs = [
                r.get("ref") for r in processor.iter() if isinstance(r.tag, str) and r.get("ref") is not None
            ]
            cores_of[name] = {(ids[r].findtext("name") or "").strip() for r in refs if r in ids}
        for space in spaces.values():
            cpu = (space.findtext("cpu_name") or "").strip()
            if cpu not in processors:
                problems.append(f"{where(space)}: cpu_name {cpu!r} is not a processor")
        for section in ("tasks", "resources", "buffers"):
            holder = sections.get(section)
            if holder is None:
                continue
            for item in holder:
                if not isinstance(item.tag, str):
                    continue
                cpu = (item.findtext("cpu_name") or "").strip()
                space = (item.findtext("address_space_name") or "").strip()
                if cpu not in processors:
                    problems.append(f"{where(item)}: cpu_name {cpu!r} is not a processor")
                if space not in spaces:
                    problems.append(f"{where(item)}: address_space_name {space!r} is not an address space")
                elif cpu in processors and (spaces[space].findtext("cpu_name") or "").strip() != cpu:
                    problems.append(f"{where(item)}: its address space {space!r} is on another processor")
                core = item.findtext("core_name")
                if core is not None and core.strip() and core.strip() not in core_names:
                    problems.append(f"{where(item)}: core_name {core.strip()!r} is not a core unit")
                elif (
                    core is not None
                    and core.strip()
                    and cpu in cores_of
                    and core.strip() not in cores_of[cpu]
                ):
                    problems.append(f"{where(item)}: core {core.strip()!r} is not a core of {cpu!r}")
                for holder_tag in ("critical_sections", "roles"):
                    for name_element in item.findall(f"{holder_tag}/task_name"):
                        if (name_element.text or "").strip() not in tasks:
                            problems.append(
                                f"{where(name_element)}: task {name_element.text!r} is not declared"
                            )
    else:
        buffers = names("buffers")
        messages = names("messages")
        for resource in sections.get("resources", etree.Element("x")):
            for user in resource.iter("resource_user"):
                words = (user.text or "").split()
                if not words or words[0] not in tasks:
                    problems.append(f"{where(user)}: task {words[0] if words else ''!r} is not declared")
        for buffer in sections.get("buffers", etree.Element("x")):
            for user in buffer.iter("buffer_user"):
                words = (user.text or "").split()
                if not words or words[0] not in tasks:
                    problems.append(f"{where(user)}: task {words[0] if words else ''!r} is not declared")
        tables = {"task": tasks, "buffer": buffers, "message": messages}
        for dependency in sections.get("dependencies", etree.Element("x")):
            if not isinstance(dependency.tag, str):
                continue
            words = (dependency.text or "").split()
            kinds = (dependency.get("from_type", "task"), dependency.get("to_type", "task"))
            if len(words) != 2:
                problems.append(f"{where(dependency)}: expected two names")
                continue
            for word, kind in zip(words, kinds, strict=True):
                if word not in tables.get(kind, {}):
                    problems.append(f"{where(dependency)}: {kind} {word!r} is not declared")
    return problems
