"""AADL instances as Cheddar XML: Cheddar 3 ADL (``.xmlv3``, default) or Cheddar 2 (``cheddar_format=2``).

What becomes what (the inverse of :mod:`rosaadl.importers.cheddar`, plus the AADL
conventions Ocarina and OSATE's Cheddar plugin use):

* top-level ``processor`` instances → processors; one with ``processor`` subcomponents (an
  SoC with cores, possibly in clusters) → ``multi_cores_processor`` whose core units are
  its innermost processors; a plain processor → ``mono_core_processor`` with one core unit;
  ``Scheduling_Protocol`` → the core's scheduler (RMS / Rate_Monotonic_Protocol →
  RATE_MONOTONIC_PROTOCOL, EDF → EARLIEST_DEADLINE_FIRST_PROTOCOL, ...);
* ``process`` instances → address spaces (threads outside any process get one per processor);
* ``thread`` instances → tasks by ``Dispatch_Protocol`` (periodic, sporadic, aperiodic, ...),
  ``Actual_Processor_Binding`` → ``cpu_name`` (and ``core_name`` when bound to a core),
  the upper bound of ``Compute_Execution_Time`` → capacity, ``Dispatch_Offset`` →
  start_time, ``Dispatch_Jitter`` → jitter, ``Priority`` (or Ocarina's
  ``Cheddar_Properties::Fixed_Priority``) → priority;
* ``data`` with ``Concurrency_Control_Protocol`` → a resource whose critical sections are
  the whole execution of the threads that access it (so Cheddar serialises them — the
  ROSMOD callback queue of a component); ``Priority_Inheritance`` → pip_resource,
  ``Priority_Ceiling`` → pcp_resource, ``Protected_Access``/``Maximum_Priority`` → ipcp;
* port connections between threads → a buffer per receiving port with QUEUEING_BUFFER
  dependencies (event ports: PRECEDENCE dependencies); connections bound to a bus
  (``Actual_Connection_Binding``) or between processors → a message per sending port with
  ASYNCHRONOUS_COMMUNICATION dependencies, and the buses → networks;
* entities imported from Cheddar (they carry ``Cheddar_Properties::Cheddar_Name``) are
  written back exactly as they were read: same names, ids, fields and order.

Names are ``Cheddar_Name`` or the dotted instance path below the root. Times are written in
``time_unit`` (``us`` by default, or ``ms``); a time that is not a whole number of that
unit is an :class:`ExportError` listing every such value, never a silent rounding.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Iterable
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

from lxml import etree
from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.bulk import gc_paused
from rosaadl.errors import Diagnostic, ExportError, Location, RosaadlError
from rosaadl.fileio import atomic_write_bytes, parse_xml_bytes
from rosaadl.importers.cheddar import (
    AADL_TO_RESOURCE_PROTOCOL,
    AADL_TO_SCHEDULER,
    ADDRESS_SPACE_FIELDS,
    BUFFER_FIELDS,
    CORE_FIELDS,
    CP,
    DEPENDENCY_ENDS,
    DISPATCH_TO_TASK_TYPE,
    ENUMERATIONS,
    MESSAGE_FIELDS,
    MESSAGE_TAGS,
    NETWORK_FIELDS,
    PROCESSOR_FIELDS,
    RESOURCE_FIELDS,
    RESOURCE_TAGS,
    SCHEDULING_FIELDS,
    SECTIONS_V2,
    TASK_FIELDS,
    TASK_TYPE_TAGS,
    TIME_UNITS,
    V2_ADDRESS_SPACE_FIELDS,
    V2_BUFFER_FIELDS,
    V2_MESSAGE_FIELDS,
    V2_NETWORK_FIELDS,
    V2_RESOURCE_FIELDS,
    V2_TASK_FIELDS,
    Field,
)
from rosaadl.properties import EnumLiteral, Range, Reference, python_value
from rosaadl.units import Quantity

__all__ = ["dumps_cheddar", "write_cheddar", "structure_problems", "EXPORT_SECTIONS_V3"]

log = logging.getLogger(__name__)

#: Section order of a Cheddar 3 file written from scratch (Cheddar's writer order).
EXPORT_SECTIONS_V3 = (
    "core_units",
    "networks",
    "processors",
    "address_spaces",
    "tasks",
    "resources",
    "buffers",
    "messages",
    "dependencies",
)
_DEFAULT_SCHEDULER = "POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL"
_TIME_KINDS = ("time", "capacity")


# --------------------------------------------------------------------------- property access


class _Props:
    """The property values an instance object holds, by qualified and by short name."""

    __slots__ = ("obj", "_by_name")

    def __init__(self, obj: EObject) -> None:
        self.obj = obj
        self._by_name: dict[str, EObject] = {}
        for assoc in obj.ownedPropertyAssociations:
            # instance objects hold resolved values: no applies-to (instance-model.md)
            modal = assoc.ownedValues
            if not modal:
                continue
            name = (assoc.property or "").lower()
            if len(modal) == 1:
                value = modal[0].value
            else:  # the value outside any mode
                value = next((m.value for m in modal if not m.inModes), modal[0].value)
            self._by_name[name] = value
            short = name.rpartition("::")[2]
            self._by_name.setdefault("::" + short, value)

    def raw(self, name: str) -> EObject | None:
        key = name.lower()
        value = self._by_name.get(key)
        if value is None and "::" in key:
            # an association written without its property set (``Period``)
            value = self._by_name.get(key.rpartition("::")[2])
        if value is None and "::" not in key:
            value = self._by_name.get("::" + key)
        return value

    def get(self, name: str) -> Any:
        value = self.raw(name)
        return python_value(value) if value is not None else None

    def has(self, name: str) -> bool:
        return self.raw(name) is not None


def _is_component(obj: EObject) -> bool:
    return obj.eClass.name in ("ComponentInstance", "SystemInstance")


def _instances(obj: EObject) -> list[EObject]:
    """``obj`` and the component and connection instances below it, in a fixed order: each
    component, then its subcomponents (depth first), then the connections it owns."""
    out: list[EObject] = []
    stack: list[tuple[EObject, bool]] = [(obj, False)]
    while stack:
        current, done = stack.pop()
        if done:
            out.extend(current.connectionInstances)
            continue
        out.append(current)
        stack.append((current, True))
        stack.extend((child, False) for child in reversed(current.componentInstances))
    return out


# --------------------------------------------------------------------------- the intermediate system


@dataclass
class _Core:
    name: str
    ident: str | None
    facts: EObject | None  # instance holding the core unit's facts (None: made up)
    imported: bool
    scheduler_owner: EObject | None = None  # where to read Scheduling_Protocol for a made-up core


@dataclass
class _Processor:
    name: str
    ident: str | None
    instance: EObject | None
    imported: bool
    multi: bool
    cores: list[_Core] = field(default_factory=list)


@dataclass
class _Space:
    name: str
    ident: str | None
    instance: EObject | None
    cpu: str
    imported: bool


@dataclass
class _Task:
    name: str
    ident: str | None
    instance: EObject
    cpu: str
    core: str | None
    space: str | None
    task_type: str
    imported: bool


@dataclass
class _Shared:
    """A resource, buffer or message (imported, or made from the AADL model)."""

    kind: str  # resource | buffer | message
    name: str
    ident: str | None
    instance: EObject | None
    cpu: str | None
    space: str | None
    imported: bool
    protocol: str = "NO_PROTOCOL"
    sections: list[tuple[str, int, int, str | None]] = field(default_factory=list)  # task, begin, end, sync
    roles: list[dict[str, Any]] = field(default_factory=list)
    values: dict[str, Any] = field(default_factory=dict)  # tag -> text for made-up entities


@dataclass
class _Network:
    name: str
    ident: str | None
    instance: EObject
    imported: bool
    tag: str = "generic_network"


@dataclass
class _Dependency:
    kind: str
    first: tuple[str, str]  # (entity kind, name)
    second: tuple[str, str]
    orientation: str | None = None
    extras: list[tuple[str, str]] = field(default_factory=list)


@dataclass
class _System:
    processors: list[_Processor] = field(default_factory=list)
    networks: list[_Network] = field(default_factory=list)
    spaces: list[_Space] = field(default_factory=list)
    tasks: list[_Task] = field(default_factory=list)
    resources: list[_Shared] = field(default_factory=list)
    buffers: list[_Shared] = field(default_factory=list)
    messages: list[_Shared] = field(default_factory=list)
    dependencies: list[_Dependency] = field(default_factory=list)
    section_order: list[str] = field(default_factory=list)
    kept: list[tuple[str, str]] = field(default_factory=list)


# --------------------------------------------------------------------------- reading the instance


class _Collector:
    """Turns a system instance into the entities of a Cheddar model."""

    def __init__(self, root: EObject, unit: str, version: int, diagnostics: list[Diagnostic]) -> None:
        self.root = root
        self.unit = unit
        self.version = version
        self.diagnostics = diagnostics
        self.problems: list[str] = []
        self.time_problems: list[str] = []
        self.cache: dict[int, _Props] = {}
        self.everything = _instances(root)
        self.order = {id(obj): i for i, obj in enumerate(self.everything)}
        self.system = _System()
        self.cpu_of_processor: dict[int, tuple[_Processor, _Core | None]] = {}
        self.space_of_process: dict[int, _Space] = {}
        self.task_of_thread: dict[int, _Task] = {}
        self.shared_of_data: dict[int, _Shared] = {}
        self.synthetic_spaces: dict[str, _Space] = {}
        self.buffers_by_port: dict[int, tuple[EObject, _Shared]] = {}
        self.messages_by_port: dict[tuple[int, int], _Shared] = {}
        self.soc_ids: set[int] = set()

    # ------------------------------------------------------------------ helpers

    def props(self, obj: EObject) -> _Props:
        found = self.cache.get(id(obj))
        if found is None:
            found = self.cache[id(obj)] = _Props(obj)
        return found

    def path(self, obj: EObject) -> str:
        full = model.instance_path(obj)
        prefix = model.instance_path(self.root) + "."
        return full[len(prefix) :] if full.startswith(prefix) else full

    def name(self, obj: EObject) -> str:
        own = self.props(obj).get(CP + "Cheddar_Name")
        return own if isinstance(own, str) and own != "" else self.path(obj)

    def imported(self, obj: EObject) -> bool:
        return self.props(obj).has(CP + "Cheddar_Name")

    def ident(self, obj: EObject, prop: str = CP + "Cheddar_Id") -> str | None:
        value = self.props(obj).get(prop)
        return value if isinstance(value, str) and value else None

    def warn(self, obj: EObject | None, message: str) -> None:
        where = Location(path=model.instance_path(obj)) if obj is not None else Location()
        diagnostic = Diagnostic("warning", message, where)
        self.diagnostics.append(diagnostic)
        log.warning("%s", diagnostic)

    def problem(self, obj: EObject | None, message: str) -> None:
        where = model.instance_path(obj) if obj is not None else model.instance_path(self.root)
        self.problems.append(f"{where}: {message}")

    def time_text(self, obj: EObject, prop: str, value: Any) -> str | None:
        """A time value as a whole number of ``self.unit`` (problems are collected)."""
        if isinstance(value, Range):
            value = value.maximum
        if isinstance(value, Quantity):
            if value.unit is None:
                self.time_problems.append(
                    f"{model.instance_path(obj)}: {prop} = {value.value} has no time unit"
                )
                return None
            try:
                converted = value.to(self.unit)
            except RosaadlError as exc:
                self.time_problems.append(f"{model.instance_path(obj)}: {prop}: {exc.message}")
                return None
            exact = Fraction(converted) if not isinstance(converted, float) else Fraction(str(converted))
            if exact.denominator != 1:
                self.time_problems.append(
                    f"{model.instance_path(obj)}: {prop} = {value} is not a whole number of {self.unit} "
                    f"({float(exact):g} {self.unit})"
                )
                return None
            if exact < 0:
                self.time_problems.append(f"{model.instance_path(obj)}: {prop} = {value} is negative")
                return None
            return str(int(exact))
        if isinstance(value, int) and not isinstance(value, bool):
            self.time_problems.append(f"{model.instance_path(obj)}: {prop} = {value} has no time unit")
            return None
        self.problem(obj, f"{prop} is not a time value ({value!r})")
        return None

    def text(self, obj: EObject, spec: Field, value: Any) -> str | None:
        """The XML text of one field value (None when it cannot be written)."""
        kind = spec.kind
        if kind in _TIME_KINDS:
            return self.time_text(obj, spec.prop, value)
        if kind == "int":
            if isinstance(value, Quantity):
                value = value.value
            if isinstance(value, bool) or not isinstance(value, int):
                self.problem(obj, f"{spec.prop} is not a whole number ({value!r})")
                return None
            if value < 0:
                self.problem(obj, f"{spec.prop} = {value} is negative; Cheddar takes natural numbers")
                return None
            return str(value)
        if kind == "real":
            number = value.value if isinstance(value, Quantity) else value
            if not isinstance(number, (int, float)) or isinstance(number, bool):
                self.problem(obj, f"{spec.prop} is not a number ({value!r})")
                return None
            return str(int(number)) if float(number).is_integer() else repr(float(number))
        if kind == "bool":
            return "TRUE" if value else "FALSE"
        if kind == "preemptive":
            return "PREEMPTIVE" if value else "NOT_PREEMPTIVE"
        if kind.startswith("enum:"):
            return str(value).upper()
        if isinstance(value, EnumLiteral):
            return value.name
        return str(value)

    # ------------------------------------------------------------------ entities

    def collect(self) -> _System:
        props = self.props(self.root)
        order = props.get(CP + "Section_Order")
        if isinstance(order, list):
            self.system.section_order = [str(s).lower() for s in order]
        kept = props.get(CP + "Unmodelled_Elements")
        if isinstance(kept, list):
            for item in kept:
                if (
                    isinstance(item, dict)
                    and isinstance(item.get("Section"), str)
                    and isinstance(item.get("Xml"), str)
                ):
                    self.system.kept.append((item["Section"].lower(), item["Xml"]))
        everything = self.everything
        socs = self.soc_ids = self.socs()
        for obj in everything:
            if id(obj) in socs:
                self.processor(obj)
            elif _is_component(obj) and obj.category is not None:
                category = obj.category.name
                if (
                    category == "processor"
                    and not self.inside(obj, "processor")
                    and not self.in_soc(obj, socs)
                ):
                    self.processor(obj)
        for obj in everything:
            if _is_component(obj) and obj.category is not None and obj.category.name == "bus":
                self.network(obj)
        for obj in everything:
            if _is_component(obj) and obj.category is not None and obj.category.name == "process":
                self.space(obj)
        threads = [
            o
            for o in everything
            if _is_component(o) and o.category is not None and o.category.name == "thread"
        ]
        for thread in self.by_section_index(threads):
            self.task(thread)
        datas = [
            o for o in everything if _is_component(o) and o.category is not None and o.category.name == "data"
        ]
        for data in self.by_section_index(datas):
            self.data(data)
        connections = [o for o in everything if o.eClass.name == "ConnectionInstance"]
        imported_deps = [c for c in connections if self.props(c).has(CP + "Dependency_Type")]
        for connection in self.by_section_index(imported_deps):
            self.imported_dependency(connection)
        for connection in connections:
            if (
                not self.props(connection).has(CP + "Dependency_Type")
                and connection.kind is not None
                and connection.kind.name == "portConnection"
            ):
                self.port_connection(connection)
        return self.system

    def inside(self, obj: EObject, category: str) -> bool:
        current = obj.eContainer()
        while current is not None and _is_component(current):
            if current.category is not None and current.category.name == category:
                return True
            current = current.eContainer()
        return False

    def by_section_index(self, objects: list[EObject]) -> list[EObject]:
        def key(obj: EObject) -> tuple[int, int, int]:
            index = self.props(obj).get(CP + "Section_Index")
            if isinstance(index, int) and not isinstance(index, bool):
                return (0, index, self.order[id(obj)])
            return (1, 0, self.order[id(obj)])

        return sorted(objects, key=key)

    def processor(self, obj: EObject) -> None:
        cores = self.leaf_processors(obj)
        imported = self.imported(obj)
        entity = _Processor(self.name(obj), self.ident(obj), obj, imported, multi=bool(cores))
        if cores:
            for core in cores:
                made = _Core(self.name(core), self.ident(core), core, self.imported(core))
                entity.cores.append(made)
                self.cpu_of_processor[id(core)] = (entity, made)
            for middle in _instances(obj):
                if (
                    middle is not obj
                    and _is_component(middle)
                    and id(middle) not in self.cpu_of_processor
                    and middle.category is not None
                    and middle.category.name in ("processor", "virtual processor", "system")
                ):
                    self.cpu_of_processor[id(middle)] = (entity, None)
        else:
            props = self.props(obj)
            core_name = props.get(CP + "Core_Name")
            if isinstance(core_name, str):
                entity.cores.append(_Core(core_name, self.ident(obj, CP + "Core_Id"), obj, True))
            else:
                entity.cores.append(_Core(f"core_unit_{entity.name}", None, obj, False))
            for inner in _instances(obj):
                if (
                    inner is not obj
                    and _is_component(inner)
                    and inner.category is not None
                    and inner.category.name == "virtual processor"
                ):
                    self.cpu_of_processor[id(inner)] = (entity, None)
        self.cpu_of_processor[id(obj)] = (entity, None)
        self.system.processors.append(entity)

    def leaf_processors(self, obj: EObject) -> list[EObject]:
        """The cores of a processor or SoC system: its innermost processors, in order."""
        found = []
        for child in obj.componentInstances:
            if child.category is None:
                continue
            if child.category.name == "processor" or (
                child.category.name == "system" and obj.category.name == "system"
            ):
                inner = self.leaf_processors(child)
                found.extend(inner if inner or child.category.name == "system" else [child])
        return found

    def socs(self) -> set[int]:
        """Systems that are multi-core SoCs: below them only processors (at least two), in
        processor-only subsystems (clusters) or not, and memories. The outermost one counts."""
        memo: dict[int, tuple[bool, int]] = {}

        def shape(obj: EObject) -> tuple[bool, int]:
            found = memo.get(id(obj))
            if found is not None:
                return found
            only, count = True, 0
            for child in obj.componentInstances:
                category = child.category.name if child.category is not None else ""
                if category == "processor":
                    count += 1
                elif category == "system":
                    inner_only, inner_count = shape(child)
                    only = only and inner_only
                    count += inner_count
                elif category != "memory":
                    only = False
            memo[id(obj)] = (only, count)
            return only, count

        chosen: set[int] = set()
        for obj in self.everything:
            if obj is self.root or not _is_component(obj) or obj.category is None:
                continue
            if obj.category.name != "system" or self.imported(obj):
                continue
            only, count = shape(obj)
            if only and count >= 2 and not self.in_soc(obj, chosen):
                chosen.add(id(obj))
        return chosen

    @staticmethod
    def in_soc(obj: EObject, socs: set[int]) -> bool:
        current = obj.eContainer()
        while current is not None:
            if id(current) in socs:
                return True
            current = current.eContainer()
        return False

    def network(self, obj: EObject) -> None:
        kind = self.props(obj).get(CP + "Network_Kind")
        tag = str(kind).lower() if kind is not None else "generic_network"
        self.system.networks.append(_Network(self.name(obj), self.ident(obj), obj, self.imported(obj), tag))

    def binding_target(self, obj: EObject) -> EObject | str | None:
        """The processor (or core) ``obj`` is bound to, following containers and virtual processors."""
        current = obj
        seen = 0
        while current is not None and _is_component(current):
            value = self.props(current).get("Deployment_Properties::Actual_Processor_Binding")
            if value is not None:
                target = value[0] if isinstance(value, list) and value else value
                if isinstance(target, Reference):
                    return target.path
                if isinstance(target, EObject):
                    if id(target) in self.cpu_of_processor:
                        return target
                    if (
                        target.category is not None
                        and target.category.name == "virtual processor"
                        and seen < 16
                    ):
                        seen += 1
                        current = target
                        continue
                    return target
                return None
            current = current.eContainer()
        return None

    def cpu_names(self, target: EObject | str | None) -> tuple[str | None, str | None]:
        """(cpu_name, core_name) of a binding target."""
        if target is None:
            return None, None
        if isinstance(target, str):
            return target, None
        found = self.cpu_of_processor.get(id(target))
        if found is None:
            # bound inside a virtual processor's container chain: find the processor around it
            current = target.eContainer()
            while current is not None and id(current) not in self.cpu_of_processor:
                current = current.eContainer()
            if current is None:
                return None, None
            found = self.cpu_of_processor[id(current)]
        processor, core = found
        return processor.name, core.name if core is not None else None

    def space(self, obj: EObject) -> None:
        cpu, _ = self.cpu_names(self.binding_target(obj))
        imported = self.imported(obj)
        if cpu is None:
            threads = [
                t
                for t in _instances(obj)
                if _is_component(t) and t.category is not None and t.category.name == "thread"
            ]
            cpus = []
            for thread in threads:
                name, _ = self.cpu_names(self.binding_target(thread))
                if name is not None and name not in cpus:
                    cpus.append(name)
            if not cpus:
                if imported:
                    self.problem(obj, "the address space is bound to no processor")
                return
            cpu = cpus[0]
        entity = _Space(self.name(obj), self.ident(obj), obj, cpu, imported)
        self.space_of_process[id(obj)] = entity
        self.system.spaces.append(entity)

    def space_for(self, thread: EObject, cpu: str) -> _Space:
        """The address space of a thread: its process (split by processor when needed)."""
        current = thread.eContainer()
        while current is not None and _is_component(current):
            if current.category is not None and current.category.name == "process":
                break
            current = current.eContainer()
        if current is not None and _is_component(current):
            space = self.space_of_process.get(id(current))
            if space is not None and (space.cpu == cpu or space.imported):
                return space
            if space is not None:
                key = f"{space.name}_on_{cpu}"
                base = space
            else:
                key = self.path(current)
                base = None
            made = self.synthetic_spaces.get(key)
            if made is None:
                made = _Space(key, None, None, cpu, False)
                self.synthetic_spaces[key] = made
                self.system.spaces.append(made)
                if base is not None:
                    self.warn(
                        current,
                        f"its threads run on several processors; address space {key!r} holds those on {cpu}",
                    )
            return made
        key = f"{cpu}.address_space"
        made = self.synthetic_spaces.get(key)
        if made is None:
            made = _Space(key, None, None, cpu, False)
            self.synthetic_spaces[key] = made
            self.system.spaces.append(made)
        return made

    def task(self, thread: EObject) -> None:
        props = self.props(thread)
        imported = self.imported(thread)
        cpu, core = self.cpu_names(self.binding_target(thread))
        if cpu is None:
            self.problem(thread, "the thread is bound to no processor (set Actual_Processor_Binding)")
            return
        if core is None:
            own_core = props.get(CP + "Core_Name")
            if isinstance(own_core, str):
                core = own_core
        task_type = props.get(CP + "Task_Type")
        if task_type is None:
            dispatch = props.get("Thread_Properties::Dispatch_Protocol")
            if dispatch is None:
                dispatch = EnumLiteral("Periodic" if props.has("Timing_Properties::Period") else "Aperiodic")
                self.warn(thread, f"no Dispatch_Protocol; written as a {str(dispatch).lower()} task")
            task_type = DISPATCH_TO_TASK_TYPE.get(str(dispatch).lower())
            if task_type is None:
                self.problem(thread, f"Dispatch_Protocol {dispatch} has no Cheddar task kind")
                return
        task_type = str(task_type).upper()
        if imported:
            space_name = None
            container = thread.eContainer()
            if container is not None and id(container) in self.space_of_process:
                space_name = self.space_of_process[id(container)].name
            lost = props.get(CP + "Address_Space_Name")
            if isinstance(lost, str):
                space_name = lost
        else:
            space_name = self.space_for(thread, cpu).name
            if not props.has("Timing_Properties::Compute_Execution_Time"):
                # a thread with no execution time (a ROS spinner the profile did not measure) has
                # nothing for Cheddar to schedule: it is left out, and said so
                self.warn(
                    thread,
                    "not exported as a task: Compute_Execution_Time is not set, so Cheddar "
                    "would have no capacity for it",
                )
                return
            if task_type in ("PERIODIC_TYPE", "SPORADIC_TYPE") and not props.has("Timing_Properties::Period"):
                self.problem(thread, "Period is not set (a periodic or sporadic task needs one)")
        entity = _Task(
            self.name(thread), self.ident(thread), thread, cpu, core, space_name, task_type, imported
        )
        self.task_of_thread[id(thread)] = entity
        self.system.tasks.append(entity)

    def task_name(self, target: Any) -> str | None:
        if isinstance(target, Reference):
            return target.path
        if isinstance(target, EObject):
            found = self.task_of_thread.get(id(target))
            return found.name if found is not None else self.name(target)
        return None

    def location_of(self, data: EObject) -> tuple[str | None, str | None]:
        """(cpu_name, address space name) of an imported resource, buffer or message."""
        props = self.props(data)
        space_name = None
        cpu = None
        container = data.eContainer()
        if container is not None and id(container) in self.space_of_process:
            space = self.space_of_process[id(container)]
            space_name, cpu = space.name, space.cpu
        lost = props.get(CP + "Address_Space_Name")
        if isinstance(lost, str):
            space_name = lost
        own_cpu = props.get(CP + "Cpu_Name")
        if isinstance(own_cpu, str):
            cpu = own_cpu
        return cpu, space_name

    def data(self, data: EObject) -> None:
        props = self.props(data)
        role = props.get(CP + "Data_Role")
        role = str(role).lower() if role is not None else None
        if role is None and props.has("Thread_Properties::Concurrency_Control_Protocol"):
            role = "resource"
        if role is None:
            return
        imported = self.imported(data)
        if role == "message":
            entity = _Shared("message", self.name(data), self.ident(data), data, None, None, imported)
            self.shared_of_data[id(data)] = entity
            self.system.messages.append(entity)
            return
        if role == "buffer":
            cpu, space = self.location_of(data)
            entity = _Shared("buffer", self.name(data), self.ident(data), data, cpu, space, imported)
            self.shared_of_data[id(data)] = entity
            self.system.buffers.append(entity)
            return
        if role != "resource":
            self.problem(data, f"Cheddar_Properties::Data_Role {role} is not a Cheddar entity")
            return
        protocol = props.get(CP + "Resource_Protocol")
        if protocol is None:
            ccp = props.get("Thread_Properties::Concurrency_Control_Protocol")
            protocol = AADL_TO_RESOURCE_PROTOCOL.get(str(ccp).lower()) if ccp is not None else "NO_PROTOCOL"
            if protocol is None:
                self.problem(data, f"Concurrency_Control_Protocol {ccp} has no Cheddar protocol")
                return
        if imported:
            cpu, space = self.location_of(data)
            entity = _Shared(
                "resource", self.name(data), self.ident(data), data, cpu, space, True, str(protocol).upper()
            )
        else:
            entity = self.made_resource(data, str(protocol).upper())
            if entity is None:
                return
        self.shared_of_data[id(data)] = entity
        self.system.resources.append(entity)

    def made_resource(self, data: EObject, protocol: str) -> _Shared | None:
        """A resource for a shared data component: its users hold it for their whole execution."""
        users = self.users_of(data)
        if not users:
            self.warn(data, "shared data with Concurrency_Control_Protocol that no thread uses; not written")
            return None
        cpus = {self.task_of_thread[id(u)].cpu for u in users if id(u) in self.task_of_thread}
        if len(cpus) != 1:
            self.problem(
                data,
                "threads on several processors share it; a Cheddar resource lives on one processor "
                f"({', '.join(sorted(cpus)) or 'none bound'})",
            )
            return None
        cpu = cpus.pop()
        container = data.eContainer()
        space = None
        while container is not None and _is_component(container):
            if id(container) in self.space_of_process and self.space_of_process[id(container)].cpu == cpu:
                space = self.space_of_process[id(container)].name
                break
            container = container.eContainer()
        if space is None:
            space = self.task_of_thread[id(users[0])].space
        entity = _Shared("resource", self.name(data), None, data, cpu, space, False, protocol)
        for user in users:
            task = self.task_of_thread[id(user)]
            cet = self.props(user).get("Timing_Properties::Compute_Execution_Time")
            end = self.time_text(user, "Compute_Execution_Time", cet) if cet is not None else None
            if end is None:
                continue
            entity.sections.append((task.name, 1, int(end), None))
        return entity

    def users_of(self, data: EObject) -> list[EObject]:
        """Threads that access ``data``: through access connections, else those beside it."""
        users: list[EObject] = []
        for connection in self.everything:
            if connection.eClass.name != "ConnectionInstance":
                continue
            ends = [connection.source, connection.destination]
            if not any(self.component(e) is data for e in ends if e is not None):
                continue
            for end in ends:
                thread = self.thread_of(end)
                if thread is not None and thread not in users:
                    users.append(thread)
        if not users and data.eContainer() is not None:
            for obj in _instances(data.eContainer()):
                if (
                    _is_component(obj)
                    and obj.category is not None
                    and obj.category.name == "thread"
                    and obj not in users
                ):
                    users.append(obj)
        return [u for u in sorted(users, key=lambda o: self.order[id(o)]) if id(u) in self.task_of_thread]

    @staticmethod
    def component(end: EObject | None) -> EObject | None:
        current = end
        while current is not None and not _is_component(current):
            current = current.eContainer()
        return current

    def thread_of(self, end: EObject | None) -> EObject | None:
        component = self.component(end)
        if component is not None and component.category is not None and component.category.name == "thread":
            return component
        return None

    def imported_dependency(self, connection: EObject) -> None:
        props = self.props(connection)
        kind = str(props.get(CP + "Dependency_Type")).upper()
        if kind not in DEPENDENCY_ENDS:
            self.problem(connection, f"Dependency_Type {kind} is not a Cheddar dependency")
            return
        first_tag, first_kind, orient_tag, second_tag, second_kind, extras = DEPENDENCY_ENDS[kind]
        source, destination = connection.source, connection.destination
        if first_kind == "task" and second_kind == "task":
            src, dst = self.thread_of(source), self.thread_of(destination)
            if (
                src is None
                or dst is None
                or id(src) not in self.task_of_thread
                or id(dst) not in self.task_of_thread
            ):
                self.problem(connection, "a task-to-task dependency must join two exported threads")
                return
            src_name, dst_name = self.task_of_thread[id(src)].name, self.task_of_thread[id(dst)].name
            if kind in ("PRECEDENCE_DEPENDENCY", "TIME_TRIGGERED_COMMUNICATION_DEPENDENCY"):
                first, second = ("task", dst_name), ("task", src_name)
            else:
                first, second = ("task", src_name), ("task", dst_name)
            dependency = _Dependency(kind, first, second)
        else:
            thread = self.thread_of(source) or self.thread_of(destination)
            thing = self.component(destination if self.thread_of(source) is not None else source)
            if thread is None or thing is None or id(thread) not in self.task_of_thread:
                self.problem(connection, "the dependency must join a thread and a data component")
                return
            shared = self.shared_of_data.get(id(thing))
            object_kind = first_kind if first_kind != "task" else second_kind
            if shared is None or shared.kind != object_kind:
                self.problem(connection, f"the {kind} must join a thread and a {object_kind}")
                return
            task_end = ("task", self.task_of_thread[id(thread)].name)
            thing_end = (object_kind, shared.name)
            first, second = (task_end, thing_end) if first_kind == "task" else (thing_end, task_end)
            orientation = None
            if orient_tag is not None:
                orientation = (
                    "FROM_TASK_TO_OBJECT" if self.thread_of(source) is not None else "FROM_OBJECT_TO_TASK"
                )
            dependency = _Dependency(kind, first, second, orientation)
        for tag, prop, _enum in extras:
            value = props.get(prop)
            if value is not None:
                dependency.extras.append((tag, str(value).upper()))
        self.system.dependencies.append(dependency)

    # ------------------------------------------------------------------ port connections

    def port_connection(self, connection: EObject) -> None:
        src_thread, dst_thread = self.thread_of(connection.source), self.thread_of(connection.destination)
        if src_thread is None or dst_thread is None:
            return
        src, dst = self.task_of_thread.get(id(src_thread)), self.task_of_thread.get(id(dst_thread))
        if src is None or dst is None:
            return
        feature = connection.source
        category = (
            feature.category.name if feature.eClass.name == "FeatureInstance" and feature.category else ""
        )
        if category == "eventPort":
            self.system.dependencies.append(
                _Dependency("PRECEDENCE_DEPENDENCY", ("task", dst.name), ("task", src.name))
            )
            return
        bus = self.connection_bus(connection)
        if bus is None and src.cpu == dst.cpu:
            self.pending_buffer(connection, src, dst)
        else:
            self.pending_message(connection, src, dst, bus)

    def connection_bus(self, connection: EObject) -> EObject | None:
        value = self.props(connection).get("Deployment_Properties::Actual_Connection_Binding")
        targets = value if isinstance(value, list) else [value] if value is not None else []
        for target in targets:
            if isinstance(target, EObject) and target.category is not None:
                if target.category.name == "bus":
                    return target
                if target.category.name == "virtual bus":
                    below = self.props(target).get("Deployment_Properties::Actual_Connection_Binding")
                    below = below[0] if isinstance(below, list) and below else below
                    if (
                        isinstance(below, EObject)
                        and below.category is not None
                        and below.category.name == "bus"
                    ):
                        return below
                    if not any(n.instance is target for n in self.system.networks):
                        self.system.networks.append(_Network(self.name(target), None, target, False))
                    return target
        return None

    def pending_buffer(self, connection: EObject, src: _Task, dst: _Task) -> None:
        key = id(connection.destination)
        found = self.buffers_by_port.get(key)
        if found is None:
            port = connection.destination
            size = self.props(port).get("Communication_Properties::Queue_Size")
            size = size if isinstance(size, int) and not isinstance(size, bool) and size > 0 else 1
            buffer = _Shared("buffer", self.path(port), None, None, dst.cpu, dst.space, False)
            buffer.values = {
                "queueing_system_type": "QS_PP1",
                "buffer_size": str(size),
                "buffer_initial_data_size": "0",
            }
            buffer.roles.append(self.role(dst, "QUEUING_CONSUMER"))
            self.buffers_by_port[key] = (port, buffer)
            self.system.buffers.append(buffer)
            self.system.dependencies.append(
                _Dependency(
                    "QUEUEING_BUFFER_DEPENDENCY",
                    ("task", dst.name),
                    ("buffer", buffer.name),
                    "FROM_OBJECT_TO_TASK",
                )
            )
        else:
            buffer = found[1]
        if not any(r["task"] == src.name and r["role"] == "QUEUING_PRODUCER" for r in buffer.roles):
            buffer.roles.insert(
                sum(1 for r in buffer.roles if r["role"] == "QUEUING_PRODUCER"),
                self.role(src, "QUEUING_PRODUCER"),
            )
            self.system.dependencies.append(
                _Dependency(
                    "QUEUEING_BUFFER_DEPENDENCY",
                    ("task", src.name),
                    ("buffer", buffer.name),
                    "FROM_TASK_TO_OBJECT",
                )
            )

    def role(self, task: _Task, role: str) -> dict[str, Any]:
        cet = self.props(task.instance).get("Timing_Properties::Compute_Execution_Time")
        capacity = self.time_text(task.instance, "Compute_Execution_Time", cet) if cet is not None else "1"
        time = capacity if role == "QUEUING_PRODUCER" else "1"
        return {"task": task.name, "role": role, "size": "1", "time": time or "1", "timeout": "0"}

    def pending_message(self, connection: EObject, src: _Task, dst: _Task, bus: EObject | None) -> None:
        port = connection.source
        key = (id(port), id(bus) if bus is not None else 0)
        message = self.messages_by_port.get(key)
        if message is None:
            name = self.path(port)
            if any(k[0] == id(port) for k in self.messages_by_port):
                name = f"{name}@{self.name(bus) if bus is not None else 'local'}"
            message = _Shared("message", name, None, None, None, None, False)
            props = self.props(src.instance)
            period = props.get("Timing_Properties::Period")
            periodic = src.task_type in ("PERIODIC_TYPE",) and period is not None
            size = self.props(port).get("Memory_Properties::Data_Size")
            size_bytes = "0"
            if isinstance(size, Quantity) and size.unit:
                try:
                    size_bytes = str(math.ceil(Fraction(str(size.to("Bytes")))))
                except RosaadlError:
                    size_bytes = "0"
            message.values = {
                "message_type": "PERIODIC_TYPE" if periodic else "APERIODIC_TYPE",
                "deadline": "0",
                "size": size_bytes,
                "response_time": "0",
                "communication_time": "0",
            }
            if periodic:
                message.values["period"] = self.time_text(src.instance, "Period", period) or "0"
                message.values["jitter"] = "0"
            self.messages_by_port[key] = message
            self.system.messages.append(message)
            self.system.dependencies.append(
                _Dependency(
                    "ASYNCHRONOUS_COMMUNICATION_DEPENDENCY",
                    ("task", src.name),
                    ("message", message.name),
                    "FROM_TASK_TO_OBJECT",
                    [("asynchronous_communication_protocol_property", "FIRST_MESSAGE")],
                )
            )
        self.system.dependencies.append(
            _Dependency(
                "ASYNCHRONOUS_COMMUNICATION_DEPENDENCY",
                ("task", dst.name),
                ("message", message.name),
                "FROM_OBJECT_TO_TASK",
                [("asynchronous_communication_protocol_property", "FIRST_MESSAGE")],
            )
        )


# --------------------------------------------------------------------------- writing XML


def _leaf(parent: etree._Element, tag: str, text: str) -> etree._Element:
    element = etree.SubElement(parent, tag)
    try:
        element.text = text
    except ValueError:
        raise ExportError(
            f"<{tag}> would hold {text!r}, which XML cannot carry (control characters)"
        ) from None
    return element


def _ref(parent: etree._Element, tag: str, target: str) -> etree._Element:
    element = etree.SubElement(parent, tag)
    try:
        element.set("ref", target)
    except ValueError:
        raise ExportError(f"<{tag}> would refer to {target!r}, which XML cannot carry") from None
    return element


class _Writer:
    def __init__(self, collector: _Collector, system: _System) -> None:
        self.c = collector
        self.s = system
        self.version = collector.version
        self.ids: dict[tuple[str, str], str] = {}
        self.core_ids: dict[str, str] = {}

    # ------------------------------------------------------------------ ids

    def assign_ids(self) -> None:
        taken: set[str] = set()
        wanted: list[tuple[tuple[str, str], str | None]] = []
        for processor in self.s.processors:
            for core in processor.cores:
                wanted.append((("core", core.name), core.ident))
        for network in self.s.networks:
            wanted.append((("network", network.name), network.ident))
        for processor in self.s.processors:
            wanted.append((("processor", processor.name), processor.ident))
        for space in self.s.spaces:
            wanted.append((("address_space", space.name), space.ident))
        for task in self.s.tasks:
            wanted.append((("task", task.name), task.ident))
        for kind, items in (
            ("resource", self.s.resources),
            ("buffer", self.s.buffers),
            ("message", self.s.messages),
        ):
            for item in items:
                wanted.append(((kind, item.name), item.ident))
        for _section, xml in self.s.kept:
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
                self.c.problems.append(
                    f"id {ident!r} is given to both {owners[ident][0]} {owners[ident][1]!r} "
                    f"and {key[0]} {key[1]!r}"
                )
                continue
            owners[ident] = key
            taken.add(ident)
        counter = 0
        for key, ident in wanted:
            if key in self.ids:
                continue
            if ident is not None and owners.get(ident) == key:
                self.ids[key] = ident
                continue
            if ident is not None and key[0] == "core":
                self.ids[key] = ident
                continue
            counter += 1
            while f"id_{counter}" in taken:
                counter += 1
            self.ids[key] = f"id_{counter}"
            taken.add(f"id_{counter}")

    def ident(self, kind: str, name: str) -> str:
        return self.ids[(kind, name)]

    # ------------------------------------------------------------------ document

    def document(self) -> etree._Element:
        root = etree.Element("cheddar")
        sections: dict[str, etree._Element] = {}
        known = EXPORT_SECTIONS_V3 if self.version == 3 else SECTIONS_V2
        content = self.sections()
        order = [s for s in self.s.section_order if self.version == 3 or s != "core_units"]
        wanted = [name for name in known if content.get(name)] + [s for s, _ in self.s.kept]
        for name in wanted:
            if name in order:
                continue
            # a section the file did not have: before the first later one, in Cheddar's order
            rank = known.index(name) if name in known else len(known)
            position = next(
                (i for i, s in enumerate(order) if s in known and known.index(s) > rank), len(order)
            )
            order.insert(position, name)
        for name in order:
            if name in sections:
                etree.SubElement(root, name)  # a repeated section stays, empty
                continue
            sections[name] = etree.SubElement(root, name)
        for name, items in content.items():
            if items:
                sections[name].extend(items)
        for section, xml in self.s.kept:
            try:
                element = parse_xml_bytes(xml.encode("utf-8"), "<kept element>").getroot()
            except RosaadlError as exc:
                self.c.problems.append(f"a kept element of section {section} is not XML: {exc.message}")
                continue
            sections[section].append(element)
        return root

    def sections(self) -> dict[str, list[etree._Element]]:
        if self.version == 3:
            return {
                "core_units": self.core_units(),
                "networks": [self.network(n) for n in self.s.networks],
                "processors": [self.processor(p) for p in self.s.processors],
                "address_spaces": [self.space(s) for s in self.s.spaces],
                "tasks": [self.task(t) for t in self.s.tasks],
                "resources": [self.resource(r) for r in self.s.resources],
                "buffers": [self.buffer(b) for b in self.s.buffers],
                "messages": [self.message(m) for m in self.s.messages],
                "dependencies": [self.dependency(d) for d in self.s.dependencies],
            }
        for processor in self.s.processors:
            if processor.multi:
                self.c.problem(
                    processor.instance, "Cheddar 2 has no multi-core processors; export as Cheddar 3"
                )
        named = [*self.s.processors, *self.s.spaces, *self.s.tasks, *self.s.resources, *self.s.buffers]
        for entity in [*named, *self.s.messages, *self.s.networks]:
            if len(entity.name.split()) != 1:
                self.c.problem(
                    entity.instance,
                    f"Cheddar 2 splits values at spaces: the name {entity.name!r} cannot be written",
                )
        return {
            "processors": [self.v2_processor(p) for p in self.s.processors if not p.multi],
            "networks": [self.v2_network(n) for n in self.s.networks],
            "address_spaces": [self.v2_space(s) for s in self.s.spaces],
            "tasks": [self.v2_task(t) for t in self.s.tasks],
            "buffers": [self.v2_buffer(b) for b in self.s.buffers],
            "resources": [self.v2_resource(r) for r in self.s.resources],
            "messages": [self.v2_message(m) for m in self.s.messages],
            "dependencies": [
                d for d in (self.v2_dependency(d) for d in self.s.dependencies) if d is not None
            ],
        }

    # ------------------------------------------------------------------ shared pieces

    def fields(
        self,
        element: etree._Element,
        obj: EObject | None,
        table: Iterable[Field],
        defaults: dict[str, str] | None = None,
        skip: Iterable[str] = (),
    ) -> None:
        """Write the table's fields ``obj`` has a value for (and the defaults for the others)."""
        props = self.c.props(obj) if obj is not None else None
        skipped = set(skip)
        for spec in table:
            if spec.tag in skipped:
                continue
            value = props.get(spec.prop) if props is not None else None
            if value is None:
                if defaults and spec.tag in defaults:
                    _leaf(element, spec.tag, defaults[spec.tag])
                continue
            if spec.kind == "offsets":
                self.offsets(element, obj, value)
                continue
            text = self.c.text(obj, spec, value)
            if text is not None:
                _leaf(element, spec.tag, text)

    def kept_fields(self, element: etree._Element, obj: EObject | None, kinds: Iterable[str]) -> None:
        if obj is None:
            return
        wanted = set(kinds)
        kept = self.c.props(obj).get(CP + "Unmodelled_Fields")
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
                self.c.problem(obj, f"a kept field is not XML: {exc.message}")

    def offsets(self, element: etree._Element, obj: EObject, value: Any) -> None:
        offsets = etree.SubElement(element, "offsets")
        for record in value if isinstance(value, list) else []:
            if not isinstance(record, dict):
                continue
            activation = record.get("Activation")
            offset = self.c.time_text(obj, "Cheddar_Properties::Offsets", record.get("Offset_Value"))
            if offset is None or not isinstance(activation, int):
                continue
            if self.version == 3:
                item = etree.SubElement(offsets, "offset_type")
                _leaf(item, "offset_value", offset)
                _leaf(item, "activation", str(activation))
            else:
                _leaf(offsets, "offset", f"{activation} {offset}")

    def scheduling(
        self, element: etree._Element, owner: EObject | None, *, processor: bool, imported: bool
    ) -> None:
        props = self.c.props(owner) if owner is not None else None
        scheduler = None
        if props is not None:
            scheduler = props.get(CP + "Scheduler")
            if scheduler is None and processor:
                scheduler = self.aadl_scheduler(owner)
        if processor:
            preemptive = (
                props.get("Deployment_Properties::Preemptive_Scheduler") if props is not None else None
            )
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
            default = _DEFAULT_SCHEDULER if processor else "NO_SCHEDULING_PROTOCOL"
            if scheduler is None and processor and owner is not None:
                self.c.warn(owner, f"no Scheduling_Protocol; written with {default}")
            _leaf(params, "scheduler_type", str(scheduler).upper() if scheduler is not None else default)
        quantum = SCHEDULING_FIELDS[0]
        self.fields(params, owner, [quantum], None if imported else {"quantum": "0"})
        if preemptive is not None or not imported:
            _leaf(params, "preemptive_type", "NOT_PREEMPTIVE" if preemptive is False else "PREEMPTIVE")
        defaults = None if imported else {"capacity": "0", "period": "0", "priority": "0", "start_time": "0"}
        self.fields(params, owner, SCHEDULING_FIELDS[1:], defaults)
        self.kept_fields(params, owner, ["scheduling_parameters"])

    def aadl_scheduler(self, owner: EObject) -> str | None:
        current = owner
        while current is not None and _is_component(current):
            value = self.c.props(current).get("Deployment_Properties::Scheduling_Protocol")
            if value is not None:
                first = value[0] if isinstance(value, list) and value else value
                literal = AADL_TO_SCHEDULER.get(str(first).lower())
                if literal is None and str(first).upper() in ENUMERATIONS["scheduler"]:
                    literal = str(first).upper()
                if literal is None:
                    self.c.problem(owner, f"Scheduling_Protocol {first} has no Cheddar scheduler")
                return literal
            if current.category is None or current.category.name not in ("processor", "system"):
                break
            if (
                current.category.name == "system"
                and not self.c.in_soc(current, self.c.soc_ids)
                and id(current) not in self.c.soc_ids
            ):
                break
            current = current.eContainer()
        return None

    # ------------------------------------------------------------------ Cheddar 3 entities

    def core_units(self) -> list[etree._Element]:
        items = []
        done: set[str] = set()
        for processor in self.s.processors:
            for core in processor.cores:
                ident = self.ident("core", core.name)
                if ident in done:
                    continue
                done.add(ident)
                items.append(self.core_unit(processor, core, ident))
        return items

    def core_unit(self, processor: _Processor, core: _Core, ident: str) -> etree._Element:
        element = etree.Element("core_unit", id=ident)
        _leaf(element, "object_type", "CORE_OBJECT_TYPE")
        _leaf(element, "name", core.name)
        owner = core.facts
        self.scheduling(element, owner, processor=True, imported=core.imported)
        self.fields(element, owner, CORE_FIELDS, None if core.imported else {"speed": "1"})
        self.kept_fields(element, owner, ["core_unit"])
        return element

    def processor(self, processor: _Processor) -> etree._Element:
        tag = "multi_cores_processor" if processor.multi else "mono_core_processor"
        element = etree.Element(tag, id=self.ident("processor", processor.name))
        _leaf(element, "object_type", "PROCESSOR_OBJECT_TYPE")
        _leaf(element, "name", processor.name)
        if processor.multi:
            bound_to_core = any(t.core is not None and t.cpu == processor.name for t in self.s.tasks)
            kinds = {core.facts.classifier or "" for core in processor.cores if core.facts is not None}
            defaults = {
                "processor_type": "IDENTICAL_MULTICORES_TYPE"
                if len(kinds) <= 1
                else "UNRELATED_MULTICORES_TYPE",
                "migration_type": "NO_MIGRATION_TYPE" if bound_to_core else "JOB_LEVEL_MIGRATION_TYPE",
            }
        else:
            defaults = {"processor_type": "MONOCORE_TYPE", "migration_type": "NO_MIGRATION_TYPE"}
        self.fields(element, processor.instance, PROCESSOR_FIELDS, None if processor.imported else defaults)
        if processor.multi:
            cores = etree.SubElement(element, "cores")
            for core in processor.cores:
                _ref(cores, "core_unit", self.ident("core", core.name))
        else:
            _ref(element, "core", self.ident("core", processor.cores[0].name))
        self.kept_fields(element, processor.instance, ["processor"])
        return element

    def network(self, network: _Network) -> etree._Element:
        element = etree.Element(network.tag, id=self.ident("network", network.name))
        _leaf(element, "object_type", "NETWORK_OBJECT_TYPE")
        _leaf(element, "name", network.name)
        defaults = None if network.imported else {"network_delay": "BOUNDED_DELAY"}
        self.fields(element, network.instance, NETWORK_FIELDS, defaults)
        self.kept_fields(element, network.instance, ["network"])
        return element

    def space(self, space: _Space) -> etree._Element:
        element = etree.Element("address_space", id=self.ident("address_space", space.name))
        _leaf(element, "object_type", "ADDRESS_SPACE_OBJECT_TYPE")
        _leaf(element, "name", space.name)
        _leaf(element, "cpu_name", space.cpu)
        memory = ADDRESS_SPACE_FIELDS[:4]
        defaults = None if space.imported else {f.tag: "0" for f in memory}
        self.fields(element, space.instance, memory, defaults)
        self.scheduling(element, space.instance, processor=False, imported=space.imported)
        self.fields(element, space.instance, ADDRESS_SPACE_FIELDS[4:])
        self.kept_fields(element, space.instance, ["address_space"])
        return element

    def task_defaults(self, task: _Task) -> dict[str, str]:
        if task.imported:
            return {}
        props = self.c.props(task.instance)
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
        period = props.get("Timing_Properties::Period")
        if task.task_type not in ("APERIODIC_TYPE",) and period is not None:
            defaults["jitter"] = "0"
            deadline = self.c.time_text(task.instance, "Period", period)
            if deadline is not None:
                defaults["deadline"] = deadline
        return defaults

    def task(self, task: _Task) -> etree._Element:
        element = etree.Element(
            TASK_TYPE_TAGS.get(task.task_type, "periodic_task"), id=self.ident("task", task.name)
        )
        _leaf(element, "object_type", "TASK_OBJECT_TYPE")
        _leaf(element, "name", task.name)
        _leaf(element, "task_type", task.task_type)
        _leaf(element, "cpu_name", task.cpu)
        if task.space is not None:
            _leaf(element, "address_space_name", task.space)
        if task.core is not None:
            _leaf(element, "core_name", task.core)
        skip = () if task.task_type not in ("APERIODIC_TYPE",) or task.imported else ("period", "jitter")
        self.fields(element, task.instance, TASK_FIELDS, self.task_defaults(task), skip)
        self.kept_fields(element, task.instance, ["task"])
        return element

    def critical_sections(self, resource: _Shared) -> list[tuple[str, str, str, str | None]]:
        if not resource.imported:
            return [(t, str(b), str(e), s) for t, b, e, s in resource.sections]
        value = self.c.props(resource.instance).get(CP + "Critical_Sections")
        sections = []
        for record in value if isinstance(value, list) else []:
            if not isinstance(record, dict):
                continue
            name = self.c.task_name(record.get("Task"))
            begin = self.c.time_text(resource.instance, "Critical_Sections", record.get("Task_Begin"))
            end = self.c.time_text(resource.instance, "Critical_Sections", record.get("Task_End"))
            sync = record.get("Synchronization")
            if name is None or begin is None or end is None:
                self.c.problem(resource.instance, "a critical section has no task, begin or end")
                continue
            sections.append((name, begin, end, str(sync).upper() if sync is not None else None))
        return sections

    def resource(self, resource: _Shared) -> etree._Element:
        element = etree.Element(
            RESOURCE_TAGS.get(resource.protocol, "np_resource"), id=self.ident("resource", resource.name)
        )
        _leaf(element, "object_type", "RESOURCE_OBJECT_TYPE")
        _leaf(element, "name", resource.name)
        obj = resource.instance
        self.fields(
            element,
            obj,
            RESOURCE_FIELDS[:3],
            None if resource.imported else {"state": "1", "size": "0", "address": "0"},
        )
        _leaf(element, "protocol", resource.protocol)
        sections = self.critical_sections(resource)
        if sections or not resource.imported or self.c.props(obj).has(CP + "Critical_Sections"):
            holder = etree.SubElement(element, "critical_sections")
            for name, begin, end, sync in sections:
                _leaf(holder, "task_name", name)
                section = etree.SubElement(holder, "critical_section")
                if sync is not None:
                    _leaf(section, "task_synchronization", sync)
                _leaf(section, "task_begin", begin)
                _leaf(section, "task_end", end)
        if resource.cpu is not None:
            _leaf(element, "cpu_name", resource.cpu)
        if resource.space is not None:
            _leaf(element, "address_space_name", resource.space)
        defaults = None
        if not resource.imported:
            priority = self.c.props(obj).get("Thread_Properties::Priority")
            defaults = {
                "priority": "0",
                "priority_assignment": "MANUAL_ASSIGNMENT"
                if isinstance(priority, int)
                else "AUTOMATIC_ASSIGNMENT",
            }
        self.fields(element, obj, RESOURCE_FIELDS[3:], defaults)
        self.kept_fields(element, obj, ["resource"])
        return element

    def roles(self, buffer: _Shared) -> list[dict[str, str]]:
        if not buffer.imported:
            return buffer.roles
        value = self.c.props(buffer.instance).get(CP + "Buffer_Roles")
        roles = []
        for record in value if isinstance(value, list) else []:
            if not isinstance(record, dict):
                continue
            name = self.c.task_name(record.get("Task"))
            if name is None or record.get("Role") is None:
                self.c.problem(buffer.instance, "a buffer role has no task or role")
                continue
            role: dict[str, str] = {"task": name, "role": str(record["Role"]).upper()}
            if isinstance(record.get("Size"), int):
                role["size"] = str(record["Size"])
            for key, tag in (("Time", "time"), ("Timeout", "timeout")):
                if record.get(key) is not None:
                    text = self.c.time_text(buffer.instance, f"Buffer_Roles.{key}", record[key])
                    if text is not None:
                        role[tag] = text
            if isinstance(record.get("Amplitude_Function"), str):
                role["amplitude_function"] = record["Amplitude_Function"]
            roles.append(role)
        return roles

    def buffer(self, buffer: _Shared) -> etree._Element:
        element = etree.Element("buffer", id=self.ident("buffer", buffer.name))
        _leaf(element, "object_type", "BUFFER_OBJECT_TYPE")
        _leaf(element, "name", buffer.name)
        if buffer.cpu is not None:
            _leaf(element, "cpu_name", buffer.cpu)
        if buffer.space is not None:
            _leaf(element, "address_space_name", buffer.space)
        if buffer.imported:
            self.fields(element, buffer.instance, BUFFER_FIELDS)
        else:
            for spec in BUFFER_FIELDS:
                _leaf(element, spec.tag, buffer.values[spec.tag])
        roles = self.roles(buffer)
        if roles or not buffer.imported or self.c.props(buffer.instance).has(CP + "Buffer_Roles"):
            holder = etree.SubElement(element, "roles")
            for role in roles:
                _leaf(holder, "task_name", role["task"])
                item = etree.SubElement(holder, "buffer_role")
                _leaf(item, "the_role", role["role"])
                for tag in ("size", "time", "timeout", "amplitude_function"):
                    if tag in role:
                        _leaf(item, tag, role[tag])
        self.kept_fields(element, buffer.instance, ["buffer"])
        return element

    def message_type(self, message: _Shared) -> str:
        if not message.imported:
            return message.values["message_type"]
        value = self.c.props(message.instance).get(CP + "Message_Type")
        return str(value).upper() if value is not None else "APERIODIC_TYPE"

    def message(self, message: _Shared) -> etree._Element:
        kind = self.message_type(message)
        element = etree.Element(
            MESSAGE_TAGS.get(kind, "aperiodic_message"), id=self.ident("message", message.name)
        )
        _leaf(element, "object_type", "MESSAGE_OBJECT_TYPE")
        _leaf(element, "name", message.name)
        _leaf(element, "message_type", kind)
        if message.imported:
            self.fields(element, message.instance, MESSAGE_FIELDS)
        else:
            for spec in MESSAGE_FIELDS:
                if spec.tag in message.values:
                    _leaf(element, spec.tag, message.values[spec.tag])
        self.kept_fields(element, message.instance, ["message"])
        return element

    def dependency(self, dependency: _Dependency) -> etree._Element:
        first_tag, _, orient_tag, second_tag, _, _ = DEPENDENCY_ENDS[dependency.kind]
        element = etree.Element("dependency")
        _leaf(element, "type_of_dependency", dependency.kind)
        _ref(element, first_tag, self.ident(*dependency.first))
        if orient_tag is not None and dependency.orientation is not None:
            _leaf(element, orient_tag, dependency.orientation)
        _ref(element, second_tag, self.ident(*dependency.second))
        for tag, text in dependency.extras:
            _leaf(element, tag, text)
        return element

    # ------------------------------------------------------------------ Cheddar 2 entities

    def v2_scheduler(
        self, element: etree._Element, owner: EObject | None, *, processor: bool, imported: bool
    ) -> None:
        props = self.c.props(owner) if owner is not None else None
        scheduler = props.get(CP + "Scheduler") if props is not None else None
        if scheduler is None and processor and owner is not None:
            scheduler = self.aadl_scheduler(owner)
        if scheduler is None:
            if imported or not processor:
                return
            scheduler = _DEFAULT_SCHEDULER
        item = _leaf(element, "scheduler", str(scheduler).upper())
        if props is None:
            return
        quantum = props.get(CP + "Scheduler_Quantum")
        if quantum is not None:
            text = self.c.time_text(owner, "Scheduler_Quantum", quantum)
            if text is not None:
                item.set("quantum", text)
        preemptive = props.get(
            "Deployment_Properties::Preemptive_Scheduler" if processor else CP + "Preemptive"
        )
        if preemptive is not None:
            item.set("is_preemptive", "PREEMPTIVE" if preemptive else "NOT_PREEMPTIVE")
        for prop, attribute in (
            ("Automaton_Name", "automaton_name"),
            ("User_Defined_Scheduler_File", "parametric_file_name"),
        ):
            value = props.get(CP + prop)
            if isinstance(value, str):
                item.set(attribute, value)

    def v2_processor(self, processor: _Processor) -> etree._Element:
        element = etree.Element("processor")
        _leaf(element, "name", processor.name)
        owner = processor.cores[0].facts if processor.cores else processor.instance
        self.v2_scheduler(element, owner, processor=True, imported=processor.imported)
        link = (
            self.c.props(processor.instance).get(CP + "Network_Link")
            if processor.instance is not None
            else None
        )
        if isinstance(link, str):
            _leaf(element, "network_link", link)
        elif not processor.imported:
            _leaf(element, "network_link", "No_Network")
        self.kept_fields(element, processor.instance, ["processor"])
        return element

    def v2_network(self, network: _Network) -> etree._Element:
        element = etree.Element("network")
        _leaf(element, "name", network.name)
        self.fields(element, network.instance, V2_NETWORK_FIELDS)
        self.kept_fields(element, network.instance, ["network"])
        return element

    def v2_space(self, space: _Space) -> etree._Element:
        element = etree.Element("address_space")
        _leaf(element, "name", space.name)
        _leaf(element, "cpu_name", space.cpu)
        defaults = None if space.imported else {f.tag: "0" for f in V2_ADDRESS_SPACE_FIELDS}
        self.fields(element, space.instance, V2_ADDRESS_SPACE_FIELDS, defaults)
        self.v2_scheduler(element, space.instance, processor=False, imported=space.imported)
        self.kept_fields(element, space.instance, ["address_space"])
        return element

    def positions(self, element: etree._Element, obj: EObject | None) -> None:
        if obj is None:
            return
        for prop, attribute in (("X_Position", "x"), ("Y_Position", "y")):
            value = self.c.props(obj).get(CP + prop)
            if isinstance(value, int):
                element.set(attribute, str(value))

    def v2_task(self, task: _Task) -> etree._Element:
        element = etree.Element("task", task_type=task.task_type)
        self.positions(element, task.instance)
        _leaf(element, "cpu_name", task.cpu)
        if task.space is not None:
            _leaf(element, "address_space_name", task.space)
        _leaf(element, "name", task.name)
        skip = () if task.task_type not in ("APERIODIC_TYPE",) or task.imported else ("period", "jitter")
        self.fields(element, task.instance, V2_TASK_FIELDS, self.task_defaults(task), skip)
        self.kept_fields(element, task.instance, ["task"])
        return element

    def v2_resource(self, resource: _Shared) -> etree._Element:
        element = etree.Element("resource")
        if resource.cpu is not None:
            _leaf(element, "cpu_name", resource.cpu)
        if resource.space is not None:
            _leaf(element, "address_space_name", resource.space)
        _leaf(element, "name", resource.name)
        obj = resource.instance
        self.fields(element, obj, V2_RESOURCE_FIELDS[:1], None if resource.imported else {"state": "1"})
        _leaf(element, "protocol", resource.protocol)
        sections = self.critical_sections(resource)
        if sections or not resource.imported or self.c.props(obj).has(CP + "Critical_Sections"):
            holder = etree.SubElement(element, "resource_used_by")
            for name, begin, end, sync in sections:
                if sync not in (None, "MUTEX"):
                    self.c.problem(obj, f"Cheddar 2 has no {sync} critical sections")
                _leaf(holder, "resource_user", f"{name} {begin} {end}")
        self.fields(element, obj, V2_RESOURCE_FIELDS[1:])
        self.kept_fields(element, obj, ["resource"])
        return element

    def v2_buffer(self, buffer: _Shared) -> etree._Element:
        element = etree.Element("buffer")
        self.positions(element, buffer.instance)
        if buffer.cpu is not None:
            _leaf(element, "cpu_name", buffer.cpu)
        if buffer.space is not None:
            _leaf(element, "address_space_name", buffer.space)
        if buffer.imported:
            self.fields(element, buffer.instance, V2_BUFFER_FIELDS[:1])
            _leaf(element, "name", buffer.name)
            self.fields(element, buffer.instance, V2_BUFFER_FIELDS[1:])
        else:
            _leaf(element, "qs", buffer.values["queueing_system_type"])
            _leaf(element, "name", buffer.name)
            _leaf(element, "size", buffer.values["buffer_size"])
        roles = self.roles(buffer)
        if roles or not buffer.imported or self.c.props(buffer.instance).has(CP + "Buffer_Roles"):
            holder = etree.SubElement(element, "buffer_used_by")
            for role in roles:
                kind = role["role"]
                if kind not in ("QUEUING_PRODUCER", "QUEUING_CONSUMER"):
                    self.c.problem(buffer.instance, f"Cheddar 2 has no {kind} buffer role")
                    continue
                item = _leaf(
                    holder, "buffer_user", f"{role['task']} {role.get('size', '0')} {role.get('time', '0')}"
                )
                item.set("buffer_role", "producer" if kind == "QUEUING_PRODUCER" else "consumer")
        self.kept_fields(element, buffer.instance, ["buffer"])
        return element

    def v2_message(self, message: _Shared) -> etree._Element:
        element = etree.Element("message")
        self.positions(element, message.instance)
        _leaf(element, "name", message.name)
        if message.imported:
            self.fields(element, message.instance, V2_MESSAGE_FIELDS)
        else:
            for spec in V2_MESSAGE_FIELDS:
                if spec.tag in message.values:
                    _leaf(element, spec.tag, message.values[spec.tag])
        self.kept_fields(element, message.instance, ["message"])
        return element

    def v2_dependency(self, dependency: _Dependency) -> etree._Element | None:
        kind = dependency.kind
        if kind == "PRECEDENCE_DEPENDENCY":
            sink, source = dependency.first[1], dependency.second[1]
            element = _leaf(etree.Element("cheddar"), "dependency", f"{source} {sink}")
            element.set("from_type", "task")
            element.set("to_type", "task")
            return element
        if kind in ("QUEUEING_BUFFER_DEPENDENCY", "ASYNCHRONOUS_COMMUNICATION_DEPENDENCY"):
            task, thing = dependency.first, dependency.second
            if dependency.extras and dependency.extras != [
                ("asynchronous_communication_protocol_property", "FIRST_MESSAGE")
            ]:
                self.c.problems.append(
                    f"dependency of {task[1]} on {thing[1]}: Cheddar 2 has no ALL_MESSAGES protocol"
                )
            if dependency.orientation == "FROM_OBJECT_TO_TASK":
                text, from_type, to_type = f"{thing[1]} {task[1]}", thing[0], "task"
            else:
                text, from_type, to_type = f"{task[1]} {thing[1]}", "task", thing[0]
            element = _leaf(etree.Element("cheddar"), "dependency", text)
            element.set("from_type", from_type)
            element.set("to_type", to_type)
            return element
        self.c.problems.append(
            f"Cheddar 2 has no {kind} ({dependency.first[1]}, {dependency.second[1]}); export as Cheddar 3"
        )
        return None


# --------------------------------------------------------------------------- structure check


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


# --------------------------------------------------------------------------- public API


def _system_instance(source: EObject, root: str | None) -> EObject:
    if not isinstance(source, EObject):
        raise ExportError(
            f"cannot export {type(source).__name__} to Cheddar; expected an AadlModel or a SystemInstance"
        )
    if model.is_a(source, "SystemInstance"):
        return source
    if model.is_a(source, "AadlModel"):
        instances = list(source.instances)
        if root is not None:
            wanted = root.lower()
            for instance in instances:
                if (instance.name or "").lower() == wanted or (instance.classifier or "").lower() == wanted:
                    return instance
            names = ", ".join(i.name for i in instances) or "none"
            raise ExportError(f"no system instance {root!r} in the model (instances: {names})")
        if len(instances) == 1:
            return instances[0]
        if not instances:
            raise ExportError("the model holds no system instance; instantiate a system implementation first")
        names = ", ".join(i.name for i in instances)
        raise ExportError(f"the model holds several system instances ({names}); choose one with root=")
    raise ExportError(
        f"cannot export a {source.eClass.name} to Cheddar; expected an AadlModel or a SystemInstance"
    )


def dumps_cheddar(
    source: EObject,
    *,
    root: str | None = None,
    cheddar_format: int = 3,
    time_unit: str = "us",
    diagnostics: list[Diagnostic] | None = None,
) -> bytes:
    """A system instance (or the one in an ``AadlModel``) as Cheddar XML bytes.

    ``cheddar_format`` is 3 (Cheddar 3 ADL) or 2 (Cheddar 2); ``time_unit`` is ``us`` or
    ``ms``. Problems (unbound threads, missing capacities, times that are not whole numbers
    of ``time_unit``, what the format cannot say) raise one :class:`ExportError` listing them
    all, with instance paths. Warnings go to ``diagnostics`` (and the log).
    """
    if cheddar_format not in (2, 3):
        raise ExportError(f"cheddar_format must be 2 or 3, not {cheddar_format!r}")
    if time_unit not in TIME_UNITS:
        raise ExportError(f"time_unit must be one of {', '.join(TIME_UNITS)}, not {time_unit!r}")
    instance = _system_instance(source, root)
    found = diagnostics if diagnostics is not None else []
    collector = _Collector(instance, time_unit, cheddar_format, found)
    with gc_paused():
        system = collector.collect()
        writer = _Writer(collector, system)
        if cheddar_format == 3:
            writer.assign_ids()
        try:
            document = writer.document()
        except ValueError as exc:  # lxml refuses text XML cannot carry (ids, names)
            raise ExportError(
                f"a value cannot be written in XML: {exc}", Location(path=instance.name)
            ) from None
    if collector.time_problems:
        unique = list(dict.fromkeys(collector.time_problems))
        shown = unique[:20]
        more = len(unique) - len(shown)
        raise ExportError(
            f"times that are not whole numbers of {time_unit} (not rounded; export with another time unit "
            "or fix the model):\n  " + "\n  ".join(shown) + (f"\n  ... and {more} more" if more > 0 else ""),
            Location(path=model.instance_path(instance)),
        )
    if collector.problems:
        unique = list(dict.fromkeys(collector.problems))
        shown = unique[:20]
        more = len(unique) - len(shown)
        raise ExportError(
            "the model cannot be written as Cheddar XML:\n  "
            + "\n  ".join(shown)
            + (f"\n  ... and {more} more" if more > 0 else ""),
            Location(path=model.instance_path(instance)),
        )
    problems = structure_problems(document, cheddar_format)
    if problems:
        raise ExportError(
            "the Cheddar model would not load in Cheddar:\n  " + "\n  ".join(problems[:20]),
            Location(path=model.instance_path(instance)),
        )
    etree.indent(document, space=" ")
    body = etree.tostring(document, encoding="utf-8")
    return b'<?xml version="1.0" encoding="utf-8"?>\n' + body + b"\n"


def write_cheddar(
    source: EObject,
    path: str | Path,
    *,
    root: str | None = None,
    cheddar_format: int = 3,
    time_unit: str = "us",
    diagnostics: list[Diagnostic] | None = None,
) -> Path:
    """Write :func:`dumps_cheddar`'s document to ``path`` atomically (nothing is written on error)."""
    data = dumps_cheddar(
        source, root=root, cheddar_format=cheddar_format, time_unit=time_unit, diagnostics=diagnostics
    )
    target = Path(path)
    atomic_write_bytes(target, data)
    return target
