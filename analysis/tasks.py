"""The neutral task model shared by the scheduling analyses, and its extraction from an instance.

A :class:`TaskSet` holds :class:`Task` s, the :class:`Processor` s (with their cores) that run
them and the shared :class:`Resource` s they lock. Every time is an exact number in one time
unit (``TaskSet.time_unit``, microseconds by default): an ``int`` or a ``Fraction``, never a
float, so that utilisations, bounds and simulated schedules are exact.

Names follow Cheddar, whose numbers the analyses reproduce: *capacity* is the worst-case
execution time, a larger *priority* number is a higher priority, schedulers carry Cheddar's
protocol names (:class:`Scheduler`), and a task's *offset* is its first release (Cheddar's
``start_time``, AADL's ``Dispatch_Offset``).

:func:`taskset_from_instance` reads an instance model that follows ``docs/instance-model.md``:
threads with ``Period``, ``Compute_Execution_Time`` (its upper bound), ``Deadline`` (default
``Period``), ``Priority``, ``Dispatch_Protocol``, ``Dispatch_Offset`` and ``Dispatch_Jitter``,
bound with ``Actual_Processor_Binding`` to processors (directly, to a core of a multi-core
processor, or through virtual processors); the scheduler comes from
``Deployment_Properties::Scheduling_Protocol`` (else ``Cheddar_Properties::Scheduler``) and
``Preemptive_Scheduler``; data components with a ``Concurrency_Control_Protocol`` (refined by
``Cheddar_Properties::Resource_Protocol``) become resources, their ``Priority`` the ceiling,
and their ``Cheddar_Properties::Critical_Sections`` (execution units ``Task_Begin`` ..
``Task_End``, 1-based and inclusive) the tasks' critical sections;
``Cheddar_Properties::Bound_On_Data_Blocking_Time`` is a task's given blocking. Problems (a
missing period, a zero period, a binding to something that is not a processor) become located
:class:`~rosaadl.errors.Diagnostic` s naming the instance path, never exceptions.
"""

from __future__ import annotations

import enum
import logging
import math
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field, replace
from decimal import Decimal
from fractions import Fraction
from typing import Any

from rosaadl.errors import Diagnostic, Location, ModelError

__all__ = [
    "Time",
    "exact_time",
    "Scheduler",
    "Protocol",
    "Dispatch",
    "CriticalSection",
    "Resource",
    "Processor",
    "Task",
    "TaskSet",
    "time_base",
    "taskset_from_instance",
]

log = logging.getLogger(__name__)

Time = int | Fraction


def exact_time(value: Any, what: str = "time") -> Time:
    """``value`` as an exact time: ``int`` or ``Fraction`` (a whole ``Fraction`` becomes ``int``).

    Accepts ``int``, ``Fraction``, ``Decimal`` and decimal text (``"0.5"``); refuses floats,
    whose binary rounding would leak into utilisations and schedules.
    """
    if isinstance(value, bool):
        raise ModelError(f"{what}: expected a number, got {value!r}")
    if isinstance(value, int):
        return value
    if isinstance(value, Fraction):
        return value.numerator if value.denominator == 1 else value
    if isinstance(value, Decimal):
        return exact_time(Fraction(value), what)
    if isinstance(value, str):
        try:
            return exact_time(Fraction(value.strip()), what)
        except (ValueError, ZeroDivisionError):
            raise ModelError(f"{what}: {value!r} is not a number") from None
    if isinstance(value, float):
        raise ModelError(f"{what}: {value!r} is a float; times are exact (use int or Fraction)")
    raise ModelError(f"{what}: expected a number, got {type(value).__name__}")


def time_base(values: Iterable[Time]) -> int:
    """The least common multiple of the denominators of ``values``: multiplying every time by it
    gives integers (the discrete time base of the simulation and of non-preemptive blocking)."""
    base = 1
    for value in values:
        if type(value) is not int and isinstance(value, Fraction):
            base = math.lcm(base, value.denominator)
    return base


def _written(quantity: Any) -> str:
    """A property value as written (``0.001 ps``), for messages."""
    value, unit = getattr(quantity, "value", quantity), getattr(quantity, "unit", None)
    return f"{value} {unit}" if unit else str(value)


class Scheduler(str, enum.Enum):
    """Scheduling protocols, with Cheddar's names as values."""

    FIXED_PRIORITY = "POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL"  # priorities as given
    RATE_MONOTONIC = "RATE_MONOTONIC_PROTOCOL"
    DEADLINE_MONOTONIC = "DEADLINE_MONOTONIC_PROTOCOL"
    EARLIEST_DEADLINE_FIRST = "EARLIEST_DEADLINE_FIRST_PROTOCOL"
    LEAST_LAXITY_FIRST = "LEAST_LAXITY_FIRST_PROTOCOL"

    @property
    def fixed_priority(self) -> bool:
        return self in (Scheduler.FIXED_PRIORITY, Scheduler.RATE_MONOTONIC, Scheduler.DEADLINE_MONOTONIC)

    @classmethod
    def from_name(cls, name: str) -> Scheduler | None:
        """The scheduler for an AADL or Cheddar protocol name (case-insensitive), else None."""
        return _SCHEDULER_NAMES.get(name.strip().lower().replace("-", "_").replace(" ", "_"))


_SCHEDULER_NAMES: dict[str, Scheduler] = {
    "posix_1003_highest_priority_first_protocol": Scheduler.FIXED_PRIORITY,
    "highest_priority_first": Scheduler.FIXED_PRIORITY,
    "hpf": Scheduler.FIXED_PRIORITY,
    "fixed_priority": Scheduler.FIXED_PRIORITY,
    "fixedpriority": Scheduler.FIXED_PRIORITY,
    "fp": Scheduler.FIXED_PRIORITY,
    "rate_monotonic_protocol": Scheduler.RATE_MONOTONIC,
    "rate_monotonic": Scheduler.RATE_MONOTONIC,
    "rms": Scheduler.RATE_MONOTONIC,
    "rm": Scheduler.RATE_MONOTONIC,
    "deadline_monotonic_protocol": Scheduler.DEADLINE_MONOTONIC,
    "deadline_monotonic": Scheduler.DEADLINE_MONOTONIC,
    "dms": Scheduler.DEADLINE_MONOTONIC,
    "dm": Scheduler.DEADLINE_MONOTONIC,
    "earliest_deadline_first_protocol": Scheduler.EARLIEST_DEADLINE_FIRST,
    "earliest_deadline_first": Scheduler.EARLIEST_DEADLINE_FIRST,
    "edf": Scheduler.EARLIEST_DEADLINE_FIRST,
    "least_laxity_first_protocol": Scheduler.LEAST_LAXITY_FIRST,
    "least_runtime_laxity_first_protocol": Scheduler.LEAST_LAXITY_FIRST,
    "least_laxity_first": Scheduler.LEAST_LAXITY_FIRST,
    "llf": Scheduler.LEAST_LAXITY_FIRST,
}


class Protocol(str, enum.Enum):
    """Resource access protocols, with Cheddar's names as values."""

    NONE = "NO_PROTOCOL"
    PIP = "PRIORITY_INHERITANCE_PROTOCOL"
    PCP = "PRIORITY_CEILING_PROTOCOL"
    IPCP = "IMMEDIATE_PRIORITY_CEILING_PROTOCOL"

    @classmethod
    def from_name(cls, name: str) -> Protocol | None:
        """The protocol for an AADL ``Concurrency_Control_Protocol`` literal or a Cheddar name."""
        return _PROTOCOL_NAMES.get(name.strip().lower().replace("-", "_").replace(" ", "_"))


_PROTOCOL_NAMES: dict[str, Protocol] = {
    "no_protocol": Protocol.NONE,
    "none": Protocol.NONE,
    "none_specified": Protocol.NONE,
    "semaphore": Protocol.NONE,
    "spin_lock": Protocol.NONE,
    "priority_inheritance_protocol": Protocol.PIP,
    "priority_inheritance": Protocol.PIP,
    "pip": Protocol.PIP,
    "priority_ceiling_protocol": Protocol.PCP,
    "priority_ceiling": Protocol.PCP,
    "pcp": Protocol.PCP,
    "immediate_priority_ceiling_protocol": Protocol.IPCP,
    "immediate_priority_ceiling": Protocol.IPCP,
    "ipcp": Protocol.IPCP,
    "maximum_priority": Protocol.IPCP,
    "interrupt_masking": Protocol.IPCP,
    "protected_access": Protocol.IPCP,
}


class Dispatch(str, enum.Enum):
    """AADL dispatch protocols (``Thread_Properties::Dispatch_Protocol``)."""

    PERIODIC = "Periodic"
    SPORADIC = "Sporadic"
    APERIODIC = "Aperiodic"
    TIMED = "Timed"
    HYBRID = "Hybrid"
    BACKGROUND = "Background"

    @property
    def recurrent(self) -> bool:
        """Released periodically (sporadic tasks at their minimum inter-arrival time)."""
        return self in (Dispatch.PERIODIC, Dispatch.SPORADIC, Dispatch.HYBRID)

    @classmethod
    def from_name(cls, name: str) -> Dispatch | None:
        wanted = name.strip().lower().removesuffix("_type")
        for member in cls:
            if member.value.lower() == wanted:
                return member
        return None


@dataclass(frozen=True)
class CriticalSection:
    """``resource`` is held from ``start`` to ``end`` units of the task's *execution* (0 = at once)."""

    resource: str
    start: Time
    end: Time

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", exact_time(self.start, "critical section start"))
        object.__setattr__(self, "end", exact_time(self.end, "critical section end"))
        if not 0 <= self.start < self.end:
            raise ModelError(
                f"critical section on {self.resource!r}: expected 0 <= start < end, "
                f"got {self.start}..{self.end}"
            )


@dataclass(frozen=True)
class Resource:
    """A shared resource (AADL shared data): access protocol and ceiling priority (None = computed
    as the highest priority of the tasks that use it)."""

    name: str
    protocol: Protocol = Protocol.NONE
    ceiling: int | None = None
    path: str = ""

    def __post_init__(self) -> None:
        if not self.name:
            raise ModelError("a resource needs a name")
        if not self.path:
            object.__setattr__(self, "path", self.name)


@dataclass(frozen=True)
class Processor:
    """A processor and its scheduler; ``cores`` names the cores of a partitioned multi-core
    processor (empty = one core, the processor itself)."""

    name: str
    scheduler: Scheduler = Scheduler.FIXED_PRIORITY
    preemptive: bool = True
    cores: tuple[str, ...] = ()
    path: str = ""

    def __post_init__(self) -> None:
        if not self.name:
            raise ModelError("a processor needs a name")
        object.__setattr__(self, "cores", tuple(self.cores))
        if len(set(self.cores)) != len(self.cores):
            raise ModelError(f"processor {self.name!r}: duplicate core names", Location(path=self.path))
        if not self.path:
            object.__setattr__(self, "path", self.name)

    @property
    def domains(self) -> tuple[str, ...]:
        """Core names to analyse separately ("" for a single-core processor)."""
        return self.cores or ("",)


@dataclass(frozen=True)
class Task:
    """A task (an AADL thread, a Cheddar task). ``deadline`` defaults to ``period``; ``period``
    is None for a task released once (aperiodic, background)."""

    name: str
    period: Time | None
    capacity: Time
    deadline: Time | None = None
    priority: int = 0
    offset: Time = 0
    jitter: Time = 0
    blocking: Time = 0
    dispatch: Dispatch = Dispatch.PERIODIC
    processor: str = ""
    core: str = ""
    address_space: str = ""
    critical_sections: tuple[CriticalSection, ...] = ()
    path: str = ""

    def __post_init__(self) -> None:
        where = Location(path=self.path or self.name)
        if not self.name:
            raise ModelError("a task needs a name")
        set_ = object.__setattr__
        try:
            if self.period is not None:
                set_(self, "period", exact_time(self.period, "period"))
            set_(self, "capacity", exact_time(self.capacity, "capacity"))
            deadline = self.deadline if self.deadline is not None else self.period
            if deadline is not None:
                set_(self, "deadline", exact_time(deadline, "deadline"))
            for name in ("offset", "jitter", "blocking"):
                set_(self, name, exact_time(getattr(self, name), name))
        except ModelError as exc:
            raise ModelError(f"task {self.name}: {exc.message}", where) from None
        if isinstance(self.priority, bool) or not isinstance(self.priority, int):
            raise ModelError(f"task {self.name}: priority must be an integer", where)
        if self.period is not None and self.period <= 0:
            raise ModelError(f"task {self.name}: period must be positive, got {self.period}", where)
        if self.capacity <= 0:
            raise ModelError(f"task {self.name}: capacity must be positive, got {self.capacity}", where)
        if self.deadline is not None and self.deadline <= 0:
            raise ModelError(f"task {self.name}: deadline must be positive, got {self.deadline}", where)
        for name in ("offset", "jitter", "blocking"):
            if getattr(self, name) < 0:
                raise ModelError(f"task {self.name}: {name} must not be negative", where)
        if self.dispatch.recurrent and self.period is None:
            raise ModelError(f"task {self.name}: a {self.dispatch.value} task needs a period", where)
        set_(self, "critical_sections", tuple(self.critical_sections))
        _check_sections(self, where)
        if not self.path:
            set_(self, "path", self.name)

    @property
    def utilization(self) -> Fraction:
        """C / T (0 for a task without period)."""
        return Fraction(self.capacity) / self.period if self.period is not None else Fraction(0)

    def outermost_section(self, section: CriticalSection) -> Time:
        """Length of the task's outermost critical section around ``section`` (its own length
        when it is not nested): how long the task may hold a resource once it locked it."""
        return max(
            s.end - s.start
            for s in self.critical_sections
            if s.start <= section.start <= section.end <= s.end
        )

    @property
    def resources(self) -> tuple[str, ...]:
        """Names of the resources the task locks, in first-use order."""
        seen: dict[str, None] = {}
        for section in self.critical_sections:
            seen.setdefault(section.resource, None)
        return tuple(seen)


def _check_sections(task: Task, where: Location) -> None:
    opened: list[CriticalSection] = []
    for section in sorted(task.critical_sections, key=lambda s: (s.start, -s.end)):
        if section.end > task.capacity:
            raise ModelError(
                f"task {task.name}: critical section on {section.resource!r} ends at {section.end}, "
                f"after the capacity {task.capacity}",
                where,
            )
        while opened and opened[-1].end <= section.start:
            opened.pop()
        if opened and section.end > opened[-1].end:
            raise ModelError(
                f"task {task.name}: critical sections on {opened[-1].resource!r} and "
                f"{section.resource!r} overlap without nesting",
                where,
            )
        if any(o.resource == section.resource for o in opened):
            raise ModelError(f"task {task.name}: {section.resource!r} is locked twice (nested)", where)
        opened.append(section)


@dataclass(frozen=True)
class TaskSet:
    """Tasks, processors and resources in one time unit, with the diagnostics of their extraction."""

    tasks: tuple[Task, ...]
    processors: tuple[Processor, ...] = ()
    resources: tuple[Resource, ...] = ()
    time_unit: str = "us"
    diagnostics: tuple[Diagnostic, ...] = ()
    _processor_index: dict[str, Processor] = field(
        default_factory=dict, init=False, repr=False, compare=False
    )
    _resource_index: dict[str, Resource] = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "tasks", tuple(self.tasks))
        object.__setattr__(self, "processors", tuple(self.processors))
        object.__setattr__(self, "resources", tuple(self.resources))
        object.__setattr__(self, "diagnostics", tuple(self.diagnostics))
        for kind, items, index in (
            ("processor", self.processors, self._processor_index),
            ("resource", self.resources, self._resource_index),
        ):
            for item in items:
                if item.name in index:
                    raise ModelError(f"duplicate {kind} name {item.name!r}", Location(path=item.path))
                index[item.name] = item
        names: set[str] = set()
        for task in self.tasks:
            where = Location(path=task.path)
            if task.name in names:
                raise ModelError(f"duplicate task name {task.name!r}", where)
            names.add(task.name)
            processor = self._processor_index.get(task.processor)
            if processor is None:
                raise ModelError(f"task {task.name}: unknown processor {task.processor!r}", where)
            if task.core and task.core not in processor.cores:
                raise ModelError(
                    f"task {task.name}: processor {processor.name!r} has no core {task.core!r}", where
                )
            if processor.cores and not task.core:
                raise ModelError(
                    f"task {task.name}: processor {processor.name!r} has cores "
                    f"({', '.join(processor.cores)}); a partitioned task needs one",
                    where,
                )
            for section in task.critical_sections:
                if section.resource not in self._resource_index:
                    raise ModelError(f"task {task.name}: unknown resource {section.resource!r}", where)

    # ------------------------------------------------------------------ construction helpers

    @classmethod
    def uniprocessor(
        cls,
        tasks: Iterable[Task],
        scheduler: Scheduler = Scheduler.FIXED_PRIORITY,
        *,
        preemptive: bool = True,
        resources: Iterable[Resource] = (),
        processor: str = "cpu",
        time_unit: str = "us",
    ) -> TaskSet:
        """One processor called ``processor`` running all ``tasks``."""
        placed = tuple(replace(t, processor=processor, core="") for t in tasks)
        return cls(
            placed,
            (Processor(processor, scheduler, preemptive),),
            tuple(resources),
            time_unit,
        )

    def replace_tasks(self, tasks: Iterable[Task]) -> TaskSet:
        """The same processors, resources and diagnostics with other tasks."""
        return TaskSet(tuple(tasks), self.processors, self.resources, self.time_unit, self.diagnostics)

    def with_priorities(self, priorities: Mapping[str, int]) -> TaskSet:
        """A copy where the named tasks get new priorities."""
        return self.replace_tasks(
            replace(t, priority=priorities[t.name]) if t.name in priorities else t for t in self.tasks
        )

    # ------------------------------------------------------------------ queries

    def processor(self, name: str) -> Processor:
        try:
            return self._processor_index[name]
        except KeyError:
            raise ModelError(f"no processor {name!r}") from None

    def resource(self, name: str) -> Resource:
        try:
            return self._resource_index[name]
        except KeyError:
            raise ModelError(f"no resource {name!r}") from None

    def task(self, name: str) -> Task:
        for task in self.tasks:
            if task.name == name:
                return task
        raise ModelError(f"no task {name!r}")

    def tasks_on(self, processor: str, core: str = "") -> tuple[Task, ...]:
        """Tasks of one scheduling domain (a processor, or one core of a multi-core processor)."""
        return tuple(t for t in self.tasks if t.processor == processor and t.core == core)

    def domains(self) -> Iterator[tuple[Processor, str, tuple[Task, ...]]]:
        """(processor, core, tasks) for every core of every processor, in declaration order."""
        for processor in self.processors:
            for core in processor.domains:
                yield processor, core, self.tasks_on(processor.name, core)

    def ceiling(self, resource: str) -> int | None:
        """The resource's ceiling: as given, else the highest priority of the tasks using it."""
        declared = self.resource(resource).ceiling
        if declared is not None:
            return declared
        users = [t.priority for t in self.tasks if resource in t.resources]
        return max(users) if users else None

    def times(self) -> Iterator[Time]:
        """Every time value of the set (for :func:`time_base`)."""
        for task in self.tasks:
            for value in (task.period, task.capacity, task.deadline, task.offset, task.jitter, task.blocking):
                if value is not None:
                    yield value
            for section in task.critical_sections:
                yield section.start
                yield section.end


# =============================================================================== from an instance

_TIME_PROPERTIES = (
    "Period",
    "Compute_Execution_Time",
    "Deadline",
    "Dispatch_Offset",
    "Dispatch_Jitter",
    "Cheddar_Properties::Bound_On_Data_Blocking_Time",
)


class _Extractor:
    """Reads one instance model into a TaskSet, collecting located diagnostics."""

    def __init__(self, root: Any, time_unit: str) -> None:
        from rosaadl.units import standard_units

        self.root = root
        self.time_unit = time_unit
        self.units = standard_units()
        if not self.units.knows(time_unit) or self.units.type_of(time_unit) != "Time_Units":
            raise ModelError(
                f"unknown time unit {time_unit!r} (expected one of ps, ns, us, ms, sec, min, hr)"
            )
        self.diagnostics: list[Diagnostic] = []
        self.processors: dict[int, Processor] = {}  # id(processor instance) -> Processor
        # id(thread instance) -> [(resource, start, end, data instance)]
        self.sections: dict[int, list[tuple[str, Time, Time, Any]]] = {}

    # ------------------------------------------------------------------ helpers

    def diag(self, severity: str, message: str, obj: Any) -> None:
        from rosaadl.model import instance_path

        self.diagnostics.append(Diagnostic(severity, message, Location(path=instance_path(obj))))

    def path(self, obj: Any) -> str:
        from rosaadl.model import instance_path

        return instance_path(obj)

    def value(self, obj: Any, name: str) -> Any:
        from rosaadl.properties import own_property

        try:
            return own_property(obj, name)
        except ModelError as exc:
            self.diag("error", f"property {name}: {exc.message}", obj)
            return None

    def time(self, obj: Any, name: str, quantity: Any) -> Time | None:
        """A time quantity converted exactly to the set's unit (None after a diagnostic)."""
        from rosaadl.properties import Range
        from rosaadl.units import Quantity

        if isinstance(quantity, Range):
            quantity = quantity.maximum
        if not isinstance(quantity, Quantity):
            self.diag("error", f"{name} is not a time value (got {quantity!r})", obj)
            return None
        if quantity.unit is None:
            self.diag("error", f"{name} = {quantity.value} has no time unit", obj)
            return None
        if not self.units.knows(quantity.unit) or self.units.type_of(quantity.unit) != "Time_Units":
            self.diag("error", f"{name} has unit {quantity.unit!r}, which is not a time unit", obj)
            return None
        raw = quantity.value
        if isinstance(raw, bool) or not isinstance(raw, (int, float)):
            self.diag("error", f"{name} is not a number", obj)
            return None
        if isinstance(raw, float):
            if not math.isfinite(raw):
                self.diag("error", f"{name} is not finite", obj)
                return None
            number = Fraction(repr(raw))  # the decimal as written, not its binary rounding
        else:
            number = Fraction(raw)
        return exact_time(number * self.units.factor(quantity.unit, self.time_unit))

    # ------------------------------------------------------------------ processors

    def category(self, obj: Any) -> str:
        value = getattr(obj, "category", None)
        return getattr(value, "name", str(value or ""))

    def processor_of(self, target: Any, thread: Any) -> tuple[Processor, str] | None:
        """(processor, core) for a binding target: a processor, a core of a multi-core processor,
        or a virtual processor (followed to the processor it runs on)."""
        seen: set[int] = set()
        current = target
        while current is not None and self.category(current) == "virtualProcessor":
            if id(current) in seen:
                self.diag("error", "virtual processors are bound in a cycle", thread)
                return None
            seen.add(id(current))
            bound = self.binding_targets(current)
            if bound:
                current = bound[0]
                continue
            parent = current.eContainer()
            while parent is not None and self.category(parent) == "virtualProcessor":
                parent = parent.eContainer()
            current = parent
        if current is None or self.category(current) != "processor":
            what = self.category(current) if current is not None else "nothing"
            self.diag(
                "error",
                f"Actual_Processor_Binding refers to {self.path(target)} ({what}), not a processor",
                thread,
            )
            return None
        outer = current.eContainer()
        if outer is not None and self.category(outer) == "processor":
            processor = self.processor(outer)
            return processor, current.name + "".join(f"[{i}]" for i in current.index)
        processor = self.processor(current)
        if processor.cores:
            migration = self.value(current, "Cheddar_Properties::Migration_Type")
            if isinstance(migration, str) and migration.upper() not in ("", "NO_MIGRATION_TYPE"):
                reason = f"its scheduling is global ({migration}), which the analyses do not cover"
            else:
                reason = "partitioned analysis needs a binding to one of its cores"
            self.diag(
                "error",
                f"bound to the multi-core processor {processor.path} as a whole; {reason}",
                thread,
            )
            return None
        return processor, ""

    def processor(self, obj: Any) -> Processor:
        known = self.processors.get(id(obj))
        if known is not None:
            return known
        cores = tuple(
            child.name + "".join(f"[{i}]" for i in child.index)
            for child in obj.componentInstances
            if self.category(child) == "processor"
        )
        scheduler = self.scheduler(obj)
        preemptive = self.value(obj, "Preemptive_Scheduler")
        path = self.path(obj)
        name = path
        processor = Processor(
            name,
            scheduler,
            preemptive if isinstance(preemptive, bool) else True,
            cores,
            path,
        )
        self.processors[id(obj)] = processor
        return processor

    def scheduler(self, obj: Any) -> Scheduler:
        """``Scheduling_Protocol`` (first literal) of the processor or of its cores, else
        ``Cheddar_Properties::Scheduler``; unsupported protocols are analysed as fixed priority."""
        from rosaadl.properties import EnumLiteral

        candidates = [obj]
        candidates.extend(c for c in obj.componentInstances if self.category(c) == "processor")
        for prop in ("Scheduling_Protocol", "Cheddar_Properties::Scheduler"):
            for holder in candidates:
                value = self.value(holder, prop)
                items = value if isinstance(value, list) else [value] if value is not None else []
                for item in items:
                    text = (
                        item.name
                        if isinstance(item, EnumLiteral)
                        else item
                        if isinstance(item, str)
                        else None
                    )
                    if text is None:
                        continue
                    found = Scheduler.from_name(text)
                    if found is None:
                        self.diag(
                            "warning",
                            f"scheduling protocol {text} is not supported by the scheduling analyses; "
                            "analysed as preemptive fixed priority with the given priorities",
                            holder,
                        )
                        return Scheduler.FIXED_PRIORITY
                    return found
        self.diag(
            "warning",
            "no Scheduling_Protocol: analysed as preemptive fixed priority with the given priorities",
            obj,
        )
        return Scheduler.FIXED_PRIORITY

    def binding_targets(self, obj: Any) -> list[Any] | None:
        """Resolved targets of the object's own ``Actual_Processor_Binding`` (None: it has none)."""
        from rosaadl.properties import Reference

        value = self.value(obj, "Actual_Processor_Binding")
        if value is None:
            return None
        items = value if isinstance(value, list) else [value]
        targets = []
        for item in items:
            if isinstance(item, Reference):
                self.diag("warning", f"Actual_Processor_Binding {item.path} does not resolve", obj)
            elif item is not None and hasattr(item, "eClass"):
                targets.append(item)
        return targets

    def binding(self, thread: Any) -> list[Any]:
        """The thread's own binding, else the nearest container's (``Actual_Processor_Binding``
        is inherited in AADL; producers that did not push it down are still understood)."""
        current = thread
        while current is not None and hasattr(current, "ownedPropertyAssociations"):
            targets = self.binding_targets(current)
            if targets is not None:
                return targets
            current = current.eContainer()
        return []

    # ------------------------------------------------------------------ threads

    def address_space(self, thread: Any) -> str:
        current = thread.eContainer()
        while current is not None and hasattr(current, "category"):
            if self.category(current) == "process":
                return self.path(current)
            current = current.eContainer()
        return ""

    def thread(self, obj: Any) -> Task | None:
        from rosaadl.properties import EnumLiteral

        path = self.path(obj)
        dispatch_value = self.value(obj, "Dispatch_Protocol")
        dispatch = Dispatch.PERIODIC
        if isinstance(dispatch_value, EnumLiteral):
            found = Dispatch.from_name(dispatch_value.name)
            if found is None:
                self.diag("error", f"unknown Dispatch_Protocol {dispatch_value.name}", obj)
                return None
            dispatch = found
        values = {name: self.value(obj, name) for name in _TIME_PROPERTIES}
        period = None
        if values["Period"] is not None:
            period = self.time(obj, "Period", values["Period"])
            if period is None:
                return None
            if period <= 0:
                self.diag("error", f"Period is {period} {self.time_unit}; it must be positive", obj)
                return None
            resolution = exact_time(self.units.factor("ps", self.time_unit)) if self.units.knows("ps") else 0
            if period < resolution:
                # AADL's finest Time_Units literal is ps: no clock, simulation or analysis
                # step resolves less, and a shorter period multiplies the jobs without bound
                self.diag(
                    "error",
                    f"Period is {_written(values['Period'])}, below the time resolution 1 ps",
                    obj,
                )
                return None
        elif dispatch.recurrent:
            self.diag("error", f"{dispatch.value} thread has no Period", obj)
            return None
        if values["Compute_Execution_Time"] is None:
            # a thread the profile did not measure (a ROS spinner, a main thread) has no
            # execution to schedule: it is left out of the task set, and said so
            self.diag("warning", "thread has no Compute_Execution_Time; left out of the task set", obj)
            return None
        capacity = self.time(obj, "Compute_Execution_Time", values["Compute_Execution_Time"])
        if capacity is None:
            return None
        if capacity <= 0:
            self.diag("error", "Compute_Execution_Time must be positive", obj)
            return None
        deadline = None
        if values["Deadline"] is not None:
            deadline = self.time(obj, "Deadline", values["Deadline"])
            if deadline is None:
                return None
            if deadline <= 0:
                self.diag("error", "Deadline must be positive", obj)
                return None
        offset = jitter = blocking = 0
        for name in ("Dispatch_Offset", "Dispatch_Jitter", "Cheddar_Properties::Bound_On_Data_Blocking_Time"):
            if values[name] is None:
                continue
            value = self.time(obj, name, values[name])
            if value is None:
                return None
            if value < 0:
                self.diag("error", f"{name} must not be negative", obj)
                return None
            if name == "Dispatch_Offset":
                offset = value
            elif name == "Dispatch_Jitter":
                jitter = value
            else:
                blocking = value
        priority_value = self.value(obj, "Priority")
        priority = 0
        if priority_value is not None:
            if isinstance(priority_value, int) and not isinstance(priority_value, bool):
                priority = priority_value
            else:
                self.diag("error", f"Priority must be an integer, got {priority_value!r}", obj)
                return None
        targets = self.binding(obj)
        if not targets:
            self.diag(
                "warning", "thread is not bound to a processor (Actual_Processor_Binding); not analysed", obj
            )
            return None
        if len(targets) > 1:
            self.diag(
                "warning",
                f"Actual_Processor_Binding lists {len(targets)} processors; analysed on the first",
                obj,
            )
        placed = self.processor_of(targets[0], obj)
        if placed is None:
            return None
        processor, core = placed
        sections = self.sections_of(obj, capacity)
        return Task(
            name=path,
            period=period,
            capacity=capacity,
            deadline=deadline,
            priority=priority,
            offset=offset,
            jitter=jitter,
            blocking=blocking,
            dispatch=dispatch,
            processor=processor.name,
            core=core,
            address_space=self.address_space(obj),
            critical_sections=sections,
            path=path,
        )

    # ------------------------------------------------------------------ resources

    def resource(self, obj: Any) -> Resource | None:
        """A data component with a ``Concurrency_Control_Protocol`` (Cheddar's
        ``Resource_Protocol`` refines it); its ``Priority`` is the ceiling unless Cheddar says
        the ceiling is assigned automatically. Its critical sections are collected."""
        from rosaadl.properties import EnumLiteral

        value = self.value(obj, "Concurrency_Control_Protocol")
        if not isinstance(value, EnumLiteral):
            return None
        protocol = Protocol.from_name(value.name)
        refined = self.value(obj, "Cheddar_Properties::Resource_Protocol")
        if isinstance(refined, EnumLiteral) and Protocol.from_name(refined.name) is not None:
            protocol = Protocol.from_name(refined.name)
        if protocol is None:
            self.diag(
                "warning", f"Concurrency_Control_Protocol {value.name} is not supported; no protocol", obj
            )
            protocol = Protocol.NONE
        ceiling = self.value(obj, "Priority")
        assignment = self.value(obj, "Cheddar_Properties::Priority_Assignment")
        if isinstance(assignment, EnumLiteral) and assignment.name.upper() == "AUTOMATIC_ASSIGNMENT":
            ceiling = None
        if ceiling is not None and (isinstance(ceiling, bool) or not isinstance(ceiling, int)):
            self.diag(
                "warning", "Priority of shared data (its ceiling) is not an integer; computed instead", obj
            )
            ceiling = None
        path = self.path(obj)
        self.collect_sections(obj, path)
        return Resource(path, protocol, ceiling, path)

    def collect_sections(self, obj: Any, resource: str) -> None:
        """``Cheddar_Properties::Critical_Sections`` of a resource: the task's execution units
        [Task_Begin, Task_End] (1-based, inclusive) hold it, i.e. [begin - 1, end) here."""
        from rosaadl.properties import Reference
        from rosaadl.units import Quantity

        records = self.value(obj, "Cheddar_Properties::Critical_Sections")
        if not isinstance(records, list):
            return
        for record in records:
            if not isinstance(record, dict):
                self.diag("warning", "a critical section is not a record; ignored", obj)
                continue
            task = record.get("Task")
            begin, end = record.get("Task_Begin"), record.get("Task_End")
            if isinstance(task, Reference) or not hasattr(task, "eClass"):
                self.diag("warning", "a critical section names a task that does not resolve; ignored", obj)
                continue
            if not isinstance(begin, Quantity) or not isinstance(end, Quantity):
                self.diag("warning", "a critical section has no Task_Begin / Task_End time; ignored", obj)
                continue
            start = self.time(obj, "Task_Begin", Quantity(begin.value - 1, begin.unit))
            stop = self.time(obj, "Task_End", end)
            if start is None or stop is None:
                continue
            self.sections.setdefault(id(task), []).append((resource, start, stop, obj))

    def sections_of(self, thread: Any, capacity: Time) -> tuple[CriticalSection, ...]:
        result: list[CriticalSection] = []
        for resource, start, stop, owner in self.sections.get(id(thread), []):
            if not 0 <= start < stop <= capacity:
                self.diag(
                    "error",
                    f"critical section {start}..{stop} {self.time_unit} of {self.path(thread)} is not "
                    f"within its capacity {capacity} {self.time_unit}; ignored",
                    owner,
                )
                continue
            result.append(CriticalSection(resource, start, stop))
        try:
            probe = Task(
                "probe", None, capacity, dispatch=Dispatch.APERIODIC, critical_sections=tuple(result)
            )
        except ModelError as exc:
            self.diag("error", f"{exc.message}; its critical sections are ignored", thread)
            return ()
        return probe.critical_sections

    # ------------------------------------------------------------------ main

    def run(self) -> TaskSet:
        from rosaadl import model

        tasks: list[Task] = []
        resources: list[Resource] = []
        threads = []
        for obj in model.walk(self.root):
            if not model.is_a(obj, "ComponentInstance"):
                continue
            category = self.category(obj)
            if category == "thread":
                threads.append(obj)
            elif category == "processor":
                outer = obj.eContainer()
                if outer is None or self.category(outer) != "processor":
                    self.processor(obj)
            elif category == "data":
                resource = self.resource(obj)
                if resource is not None:
                    resources.append(resource)
        for obj in threads:
            task = self.thread(obj)
            if task is not None:
                tasks.append(task)
        processors = list(self.processors.values())
        log.debug(
            "extracted %d tasks, %d processors, %d resources", len(tasks), len(processors), len(resources)
        )
        return TaskSet(
            tuple(tasks), tuple(processors), tuple(resources), self.time_unit, tuple(self.diagnostics)
        )


def taskset_from_instance(root: Any, *, time_unit: str = "us") -> TaskSet:
    """The task set of an instance model (a ``SystemInstance`` or any component instance).

    Times are converted exactly to ``time_unit``; each problem becomes a diagnostic on
    ``TaskSet.diagnostics`` naming the instance path, and the offending thread is left out.
    """
    if root is None or not hasattr(root, "eClass"):
        raise ModelError(f"expected an instance model, got {type(root).__name__}")
    if root.eClass.name == "AadlModel":
        if not root.instances:
            raise ModelError("the model has no system instance")
        root = root.instances[0]
    return _Extractor(root, time_unit).run()
