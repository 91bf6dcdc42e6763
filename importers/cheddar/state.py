"""What the Cheddar reader knows while it reads one document, and its primitive steps.

:class:`ReadState` is the one state object the reading modules share: the file's name, time
unit and strictness, the format (2 or 3), the entities read so far by kind and by id, what is
kept verbatim, and the instances waiting to be attached. Its methods are the steps every entity
reader takes: locate and report a problem (:meth:`~ReadState.fail`, :meth:`~ReadState.lenient`),
read a field's text as a value, make a uniquely named instance, store a field table, keep the
fields nobody read, and resolve the name of a processor, an address space or a task following
the rule of the file's format (Cheddar 3: an error; Cheddar 2: an unresolved reference).
"""

from __future__ import annotations

import logging
import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import NoReturn

from lxml import etree
from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import Diagnostic, ImportFormatError, Location, UsageError
from rosaadl.fileio import element_path
from rosaadl.importers.cheddar.document import canonical_xml, children, local
from rosaadl.importers.cheddar.values import (
    aadl_identifier,
    associate,
    bool_value,
    int_value,
    list_value,
    named_value,
    real_value,
    record_value,
    reference_value,
    str_value,
)
from rosaadl.importers.cheddar.vocabulary import BINDING, CP, ENUMERATIONS, TIME_UNITS, Field

__all__ = ["Entity", "ReadState", "SectionReader", "entries", "same_target"]

log = logging.getLogger("rosaadl.importers.cheddar")

_MAX_INT = 2**63 - 1
_INT_RE = re.compile(r"^[+]?[0-9]+$")
_NEG_RE = re.compile(r"^-[0-9]+$")


@dataclass
class Entity:
    """What the reader knows about one Cheddar entity while building the model."""

    kind: str
    name: str
    element: etree._Element
    instance: EObject | None = None
    cheddar_id: str | None = None
    cpu: EObject | str | None = None  # processor instance (or unresolved name)


class ReadState:
    """The reader's state for one document (see the module docstring)."""

    def __init__(
        self, filename: str, time_unit: str, strict: bool, diagnostics: list[Diagnostic] | None
    ) -> None:
        if time_unit not in TIME_UNITS:
            raise UsageError(f"time_unit must be one of {', '.join(TIME_UNITS)}, not {time_unit!r}")
        self.filename = filename
        self.unit = time_unit
        self.strict = strict
        self.diagnostics = diagnostics if diagnostics is not None else []
        self.version = 3
        self.ids: dict[str, tuple[str, etree._Element]] = {}
        self.cores: dict[str, etree._Element] = {}  # id -> core_unit element
        self.used_cores: set[str] = set()
        self.processors: dict[str, Entity] = {}
        self.address_spaces: dict[str, Entity] = {}
        self.tasks: dict[str, Entity] = {}
        self.resources: dict[str, Entity] = {}
        self.buffers: dict[str, Entity] = {}
        self.messages: dict[str, Entity] = {}
        self.networks: dict[str, Entity] = {}
        self.by_id: dict[str, Entity] = {}
        self.warnings: dict[str, list] = {}  # message -> [first element, count]
        self.kept: list[tuple[str, str]] = []
        self.names: dict[int, set[str]] = {}
        self.features: dict[tuple, EObject] = {}
        self.kept_fields: dict[int, tuple[EObject, list[EObject]]] = {}
        self.pending: list[tuple[EObject, EObject]] = []
        self.root: EObject | None = None

    # ------------------------------------------------------------------ diagnostics

    def where(self, element: etree._Element) -> Location:
        """File, line and element path of ``element``."""
        return Location(file=self.filename, line=element.sourceline, path=element_path(element))

    def fail(self, element: etree._Element, message: str) -> NoReturn:
        raise ImportFormatError(message, self.where(element))

    def warn(self, element: etree._Element, message: str) -> None:
        """Note a warning; the same message again only counts (see :meth:`report_warnings`)."""
        record = self.warnings.setdefault(message, [element, 0])
        record[1] += 1

    def report_warnings(self) -> None:
        """Report each warning once, at its first element, with the times it was met when
        more than one ("(1000 times)"): a file repeating a problem gets one line for it."""
        for message, (element, count) in self.warnings.items():
            times = f" ({count} times)" if count > 1 else ""
            diagnostic = Diagnostic("warning", message + times, self.where(element))
            self.diagnostics.append(diagnostic)
            log.warning("%s", diagnostic)
        self.warnings.clear()

    def lenient(self, element: etree._Element, message: str) -> None:
        """A problem Cheddar's own reader tolerates: a warning, or an error when strict."""
        if self.strict:
            self.fail(element, message)
        self.warn(element, message)

    # ------------------------------------------------------------------ text values

    def text(self, element: etree._Element) -> str:
        """A field's text, trimmed (Cheddar 2 also folds inner whitespace, as its reader does)."""
        if children(element):
            self.fail(element, f"<{local(element)}> must hold a value, not elements")
        text = element.text or ""
        return " ".join(text.split()) if self.version == 2 else text.strip()

    def natural(self, element: etree._Element, text: str | None = None) -> int:
        """A field's text (or ``text``) as a natural number that fits Cheddar's 64-bit integers."""
        raw = self.text(element) if text is None else text
        if _NEG_RE.match(raw):
            self.fail(element, f"<{local(element)}> is {raw}; expected a natural number (0 or more)")
        if not _INT_RE.match(raw):
            self.fail(element, f"<{local(element)}> is {raw!r}; expected a whole number")
        value = int(raw)
        if value > _MAX_INT:
            self.fail(element, f"<{local(element)}> is {raw}; the number is too large")
        return value

    def value(self, element: etree._Element, kind: str, text: str | None = None) -> EObject:
        """The property value for one field's text."""
        raw = self.text(element) if text is None else text
        if kind == "int":
            return int_value(self.natural(element, raw))
        if kind == "time":
            return int_value(self.natural(element, raw), self.unit)
        if kind == "real":
            try:
                number = float(raw)
            except ValueError:
                self.fail(element, f"<{local(element)}> is {raw!r}; expected a number")
            if number != number or number in (float("inf"), float("-inf")) or number < 0:
                self.fail(element, f"<{local(element)}> is {raw!r}; expected a finite number, 0 or more")
            return real_value(number)
        if kind == "bool":
            upper = raw.upper()
            if upper not in ("TRUE", "FALSE"):
                self.fail(element, f"<{local(element)}> is {raw!r}; expected TRUE or FALSE")
            return bool_value(upper == "TRUE")
        if kind == "preemptive":
            upper = raw.upper()
            if upper not in ENUMERATIONS["preemptive"]:
                self.fail(element, f"<{local(element)}> is {raw!r}; expected PREEMPTIVE or NOT_PREEMPTIVE")
            return bool_value(upper == "PREEMPTIVE")
        if kind.startswith("enum:"):
            return named_value(self.literal(element, kind[5:], raw))
        return str_value(raw)

    def literal(self, element: etree._Element, enumeration: str, raw: str | None = None) -> str:
        """A literal of ``enumeration`` in upper case (an unknown one is a lenient problem)."""
        text = (self.text(element) if raw is None else raw).upper()
        known = ENUMERATIONS[enumeration]
        if not text:
            self.fail(element, f"<{local(element)}> is empty; expected one of {', '.join(known)}")
        if text not in known:
            self.lenient(
                element, f"<{local(element)}> is {text}, not a value Cheddar knows ({', '.join(known)})"
            )
        return text

    # ------------------------------------------------------------------ model helpers

    def instance(self, parent: EObject, name: str, category: str) -> EObject:
        """A new component instance for ``parent``, with a name unique among its siblings.

        It is attached to ``parent`` when the next one is made (or the section ends): filling
        a detached object is much cheaper in pyecore (every change notifies up the containers).
        """
        self.attach()
        taken = self.names.get(id(parent))
        if taken is None:
            taken = self.names[id(parent)] = {c.name.lower() for c in parent.componentInstances}
        base = aadl_identifier(name)
        candidate, n = base, 1
        while candidate.lower() in taken:
            n += 1
            candidate = f"{base}_{n}"
        taken.add(candidate.lower())
        obj = model.new("ComponentInstance", name=candidate, category=category)
        self.pending.append((parent, obj))
        return obj

    def attach(self) -> None:
        """Attach the instances made since the last call to their parents."""
        for parent, obj in self.pending:
            parent.componentInstances.append(obj)
        self.pending.clear()

    def fields(
        self,
        owner: EObject,
        element: etree._Element,
        table: Iterable[Field],
        present: dict[str, etree._Element],
        consumed: set[str],
        special: Callable[[Field, etree._Element], None] | None = None,
    ) -> None:
        """Store the fields of ``table`` found in ``present`` on ``owner``, in table order."""
        for spec in table:
            child = present.get(spec.tag)
            if child is None:
                continue
            consumed.add(spec.tag)
            if spec.kind in ("capacity", "offsets"):
                if special is None:
                    self.fail(child, f"internal: no reader for <{spec.tag}>")
                special(spec, child)
                continue
            associate(owner, spec.prop, self.value(child, spec.kind))

    def index_children(
        self, element: etree._Element, repeatable: Iterable[str] = ()
    ) -> dict[str, etree._Element]:
        """The element's children by lower-case tag; a repeated simple field is an error."""
        found: dict[str, etree._Element] = {}
        allowed = set(repeatable)
        for child in children(element):
            tag = local(child)
            if tag in found and tag not in allowed:
                self.fail(child, f"<{tag}> is given twice in <{local(element)}>")
            found.setdefault(tag, child)
        return found

    def leftovers(
        self,
        owner: EObject,
        element: etree._Element,
        kind: str,
        present: dict[str, etree._Element],
        consumed: set[str],
    ) -> None:
        """Fields nobody read: kept verbatim on ``owner`` (Unmodelled_Fields), with a warning.

        Each is kept with the element it belongs to (``kind``: ``task``, ``core_unit``,
        ``scheduling_parameters``, ``processor``, ...), since a mono-core processor instance
        holds the fields of three Cheddar elements.
        """
        for child in children(element):
            tag = local(child)
            if tag in consumed:
                continue
            if self.strict:
                self.fail(child, f"<{kind}> field <{tag}> is not modelled by rosaadl")
            self.warn(child, f"<{kind}> field <{tag}> is not modelled by rosaadl; kept as it is")
            kept = self.kept_fields.setdefault(id(owner), (owner, []))[1]
            kept.append(
                record_value([("Section", str_value(kind)), ("Xml", str_value(canonical_xml(child)))])
            )

    def identity(self, owner: EObject, entity: Entity, index: int | None = None) -> None:
        """``Cheddar_Name``, ``Cheddar_Id`` and ``Section_Index`` of an entity's instance."""
        associate(owner, CP + "Cheddar_Name", str_value(entity.name))
        if entity.cheddar_id is not None:
            associate(owner, CP + "Cheddar_Id", str_value(entity.cheddar_id))
        if index is not None:
            associate(owner, CP + "Section_Index", int_value(index))

    def declare(
        self,
        item: etree._Element,
        present: dict[str, etree._Element],
        kind: str,
        table: dict[str, Entity],
        what: str,
    ) -> Entity:
        """The entity ``item`` declares (its name and id), registered in ``table``."""
        entity = Entity(kind, self.name_of(item, present, what), item)
        entity.cheddar_id = (item.get("id") or "").strip() or None
        self.register(table, entity, what)
        return entity

    def place(self, entity: Entity, parent: EObject, category: str, index: int | None = None) -> EObject:
        """The entity's instance under ``parent``, with its Cheddar name, id and place in its section."""
        instance = self.instance(parent, entity.name, category)
        entity.instance = instance
        self.identity(instance, entity, index)
        return instance

    def register(self, table: dict[str, Entity], entity: Entity, what: str) -> None:
        """Record ``entity`` by name in ``table`` (and by id); a name used twice is an error."""
        if not entity.name:
            self.fail(entity.element, f"the {what} has no <name>")
        key = entity.name
        if key in table:
            self.fail(entity.element, f"{what} name {entity.name!r} is used twice")
        table[key] = entity
        if entity.cheddar_id is not None:
            self.by_id[entity.cheddar_id] = entity

    def name_of(self, element: etree._Element, present: dict[str, etree._Element], what: str) -> str:
        """The entity's ``<name>``, which must be there and not empty."""
        child = present.get("name")
        if child is None:
            self.fail(element, f"the {what} has no <name>")
        name = self.text(child)
        if not name:
            self.fail(child, f"the {what}'s <name> is empty")
        return name

    def processor_of(self, element: etree._Element, name: str) -> EObject | str:
        """The processor instance called ``name``; unknown names follow the format's rule."""
        entity = self.processors.get(name)
        if entity is not None:
            return entity.instance
        if self.version == 3:
            self.fail(
                element,
                f"processor {name!r} is not declared (expected one of: {self.known(self.processors)})",
            )
        self.lenient(element, f"processor {name!r} is not declared; kept as an unresolved reference")
        return name

    @staticmethod
    def known(table: dict[str, Entity]) -> str:
        """The first names of ``table``, for an error message."""
        names = list(table)
        return ", ".join(names[:10]) + (", ..." if len(names) > 10 else "") if names else "none"

    def bind(self, owner: EObject, target: EObject | str) -> None:
        """``Actual_Processor_Binding`` of ``owner`` (an instance or an unresolved name)."""
        associate(owner, BINDING, list_value([reference_value(target)]))

    def location(
        self, item: etree._Element, present: dict[str, etree._Element], what: str
    ) -> tuple[EObject, EObject | str, str | None]:
        """Where an entity goes: (parent instance, processor, unresolved address-space name)."""
        cpu_element = present.get("cpu_name")
        if cpu_element is None or not self.text(cpu_element):
            self.fail(item, f"the {what} has no <cpu_name> (every {what} must name its processor)")
        cpu = self.processor_of(cpu_element, self.text(cpu_element))
        space_element = present.get("address_space_name")
        space_name = self.text(space_element) if space_element is not None else ""
        if not space_name:
            if self.version == 3:
                self.fail(item, f"the {what} has no <address_space_name> (Cheddar 3 needs one)")
            return self.root, cpu, None
        space = self.address_spaces.get(space_name)
        if space is None:
            if self.version == 3:
                self.fail(
                    space_element,
                    f"address space {space_name!r} is not declared "
                    f"(expected one of: {self.known(self.address_spaces)})",
                )
            self.lenient(
                space_element,
                f"address space {space_name!r} is not declared; the {what} goes under the system",
            )
            return self.root, cpu, space_name
        if self.version == 3 and not same_target(space.cpu, cpu):
            self.fail(
                cpu_element,
                f"the {what} is on processor {self.text(cpu_element)!r} but its address space "
                f"{space_name!r} is on {space.cpu.name if isinstance(space.cpu, EObject) else space.cpu!r}",
            )
        return space.instance, cpu, None

    def task_reference(self, element: etree._Element, name: str) -> EObject | str:
        """The thread instance of task ``name``; unknown names follow the format's rule."""
        entity = self.tasks.get(name)
        if entity is not None:
            return entity.instance
        if self.version == 3:
            self.fail(element, f"task {name!r} is not declared (expected one of: {self.known(self.tasks)})")
        self.lenient(element, f"task {name!r} is not declared; kept as an unresolved reference")
        return name

    def items(self, section: etree._Element, tags: Iterable[str], what: str) -> Iterable[etree._Element]:
        """The entries of ``section`` with one of ``tags``; the others are kept verbatim."""
        allowed = set(tags)
        for item in children(section):
            if local(item) in allowed:
                yield item
            else:
                self.lenient(item, f"<{local(item)}> is not a {what}; kept as it is")
                self.kept.append((local(section), canonical_xml(item)))


def same_target(a: object, b: object) -> bool:
    """Do two binding targets (instances, or unresolved names) name the same processor?"""
    return a is b or (isinstance(a, str) and a == b)


#: Reads one section of a document into the model.
SectionReader = Callable[[ReadState, etree._Element], None]


def entries(
    tags: Iterable[str], what: str, read: Callable[[ReadState, etree._Element, int], None]
) -> SectionReader:
    """The reader of a section of entities: each entry with one of ``tags`` is read with ``read``
    (with its place among them); the others are kept verbatim."""
    allowed = tuple(tags)

    def read_section(state: ReadState, section: etree._Element) -> None:
        for index, item in enumerate(state.items(section, allowed, what)):
            read(state, item, index)

    return read_section
