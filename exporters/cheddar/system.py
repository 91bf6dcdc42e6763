"""The intermediate Cheddar system the writer works from, and the index that builds it.

Reading the instance (:mod:`~rosaadl.exporters.cheddar.collect`) and writing XML
(:mod:`~rosaadl.exporters.cheddar.v3`, :mod:`~rosaadl.exporters.cheddar.v2`) meet here: a
:class:`CheddarSystem` lists the processors (with their cores), networks, address spaces,
tasks, resources, buffers, messages and dependencies, each with its Cheddar name and id and the
instance object that holds its fields (None for what the export makes up). ``imported`` marks
an entity read from a Cheddar file, which is written back as it was read.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from pyecore.ecore import EObject

from rosaadl.exporters.cheddar.context import ExportContext

__all__ = [
    "Core",
    "Processor",
    "AddressSpace",
    "Task",
    "SharedObject",
    "Network",
    "Dependency",
    "CheddarSystem",
    "Collection",
]


@dataclass
class Core:
    """A core unit: of a multi-core processor, or the one core of a mono-core processor."""

    name: str
    ident: str | None
    facts: EObject | None  # instance holding the core unit's facts (None: made up)
    imported: bool


@dataclass
class Processor:
    """A processor: mono-core, or multi-core (an SoC, or a processor with processor subcomponents)."""

    name: str
    ident: str | None
    instance: EObject | None
    imported: bool
    multi: bool
    cores: list[Core] = field(default_factory=list)


@dataclass
class AddressSpace:
    """An address space: a process, or one made for threads outside any process (``instance`` None)."""

    name: str
    ident: str | None
    instance: EObject | None
    cpu: str
    imported: bool


@dataclass
class Task:
    """A task: a thread, on processor ``cpu`` (and core ``core``), in address space ``space``."""

    name: str
    ident: str | None
    instance: EObject
    cpu: str
    core: str | None
    space: str | None
    task_type: str
    imported: bool


@dataclass
class SharedObject:
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
class Network:
    """A network: a bus (or a virtual bus that connections are bound to)."""

    name: str
    ident: str | None
    instance: EObject
    imported: bool
    tag: str = "generic_network"


@dataclass
class Dependency:
    """A dependency: its kind, its two ends as (entity kind, name) in Cheddar's order, its
    orientation and its extra fields (tag, text)."""

    kind: str
    first: tuple[str, str]  # (entity kind, name)
    second: tuple[str, str]
    orientation: str | None = None
    extras: list[tuple[str, str]] = field(default_factory=list)


@dataclass
class CheddarSystem:
    """The entities of the Cheddar model, in the order they are written, and what the file
    read had beyond them (its section order and the sections kept verbatim)."""

    processors: list[Processor] = field(default_factory=list)
    networks: list[Network] = field(default_factory=list)
    spaces: list[AddressSpace] = field(default_factory=list)
    tasks: list[Task] = field(default_factory=list)
    resources: list[SharedObject] = field(default_factory=list)
    buffers: list[SharedObject] = field(default_factory=list)
    messages: list[SharedObject] = field(default_factory=list)
    dependencies: list[Dependency] = field(default_factory=list)
    section_order: list[str] = field(default_factory=list)
    kept: list[tuple[str, str]] = field(default_factory=list)


@dataclass
class Collection:
    """The system being collected, and which entity each instance object has become."""

    ctx: ExportContext
    system: CheddarSystem = field(default_factory=CheddarSystem)
    cpu_of_processor: dict[int, tuple[Processor, Core | None]] = field(default_factory=dict)
    space_of_process: dict[int, AddressSpace] = field(default_factory=dict)
    task_of_thread: dict[int, Task] = field(default_factory=dict)
    shared_of_data: dict[int, SharedObject] = field(default_factory=dict)
    synthetic_spaces: dict[str, AddressSpace] = field(default_factory=dict)
    buffers_by_port: dict[int, tuple[EObject, SharedObject]] = field(default_factory=dict)
    messages_by_port: dict[tuple[int, int], SharedObject] = field(default_factory=dict)
    soc_ids: set[int] = field(default_factory=set)
