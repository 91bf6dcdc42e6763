"""Bound resource allocation and not-bound budgets, as OSATE's resource budget analyses compute them.

**Bound resources** (:func:`analyze_resources`, OSATE's *Analyze Bound Resource Budgets*): for every
processor and virtual processor, in every system operation mode,

* the capacity: ``SEI::MIPSCapacity``, else ``Processor_Capacity`` (a virtual processor without
  either: its ``SEI::MIPSBudget``);
  a multi-core processor (a processor whose subcomponents are processors) without a capacity of
  its own has the sum of its cores' capacities, and its demand includes its cores' demands;
* the software bound to it (``Actual_Processor_Binding``, directly or through virtual processors),
  the outermost bound components only, as OSATE's ``getBoundSWComponents``;
* the demand of each bound component as OSATE's ``sumBudgets``: a thread demands
  ``SEI::InstructionsPerDispatch / Period`` MIPS, else ``max Compute_Execution_Time / Period``
  times the MIPS of its ``Reference_Processor`` (when the declarative model is at hand), else of
  the physical processor it is bound to; any other component demands the sum of its children, or
  its ``SEI::MIPSBudget`` when they demand nothing;
* the load in % (demand / capacity) and the CPU utilisation (Σ CET / Period of its threads);
  an error when the demand exceeds the capacity.

Memory (OSATE's memory loads): a memory, system, processor, virtual processor or abstract
component with ``Memory_Size``, ``SEI::RAMCapacity`` or ``SEI::ROMCapacity`` is loaded by the
components bound to it with ``Actual_Memory_Binding``: ``Data_Size + Heap_Size + Stack_Size``
(RAM), ``Code_Size`` (ROM), all four (Memory_Size), summed over the bound component's subtree,
else its ``SEI::RAMActual`` / ``ROMActual``, else its ``RAMBudget`` / ``ROMBudget``.

**Not-bound budgets** (:func:`analyze_budgets`, OSATE's *Analyze Resource Budgets (Not Bound)*):
the budget and demand of every software component (``sumBudgets`` over the whole instance, an
error when a component's demand exceeds its own ``MIPSBudget``, e.g. a process whose threads need
more than the process is budgeted), and the system-wide totals: processor capacity vs the
budget total, how many processors have a capacity and how many components a budget.

Every number is an exact :class:`~fractions.Fraction` (decimal values are read as written).
Problems — a thread without ``Period`` or ``Compute_Execution_Time``, a zero period, a binding to
something that is not a processor — are located :class:`~rosaadl.errors.Diagnostic` s naming the
instance path, never exceptions.

The helpers shared by the other analyses live here too: :class:`SystemMode` (a system operation
mode and what is active in it) and :class:`PropertyReader` (exact, unit-converted, mode-aware
property values with diagnostics).
"""

from __future__ import annotations

import logging
import math
from collections.abc import Iterator
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from rosaadl.errors import Diagnostic, Location, ModelError, RosaadlError
from rosaadl.properties import EnumLiteral, Range, Reference, own_association, python_value
from rosaadl.units import Quantity, standard_units

__all__ = [
    "SystemMode",
    "system_modes",
    "instance_root",
    "category_of",
    "PropertyReader",
    "bound_processor",
    "ThreadLoad",
    "ComponentBudget",
    "ProcessorLoad",
    "MemoryLoad",
    "ResourceResult",
    "BudgetTotals",
    "BudgetResult",
    "analyze_resources",
    "analyze_budgets",
]

log = logging.getLogger(__name__)

_SOFTWARE = frozenset({"thread", "threadGroup", "process", "system"})
_HARDWARE = frozenset({"bus", "processor", "virtualProcessor", "memory"})
_MEMORY_HOLDERS = frozenset({"memory", "system", "processor", "virtualProcessor", "abstract"})

# Units that the standard unit system does not know: SEI's instruction volumes (to MIPD) and
# the per-second rate unit of SEI::Data_Rate / SEI::Message_Rate.
_MIPD = {"ipd": Fraction(1, 1_000_000), "kipd": Fraction(1, 1000), "mipd": Fraction(1)}


# =============================================================================== shared helpers


def instance_root(source: Any) -> Any:
    """The ``SystemInstance`` of ``source`` (an ``AadlModel`` holding instances, or an instance)."""
    if source is None or not hasattr(source, "eClass"):
        raise ModelError(f"expected an instance model, got {type(source).__name__}")
    kind = source.eClass.name
    if kind == "AadlModel":
        if not source.instances:
            raise ModelError("the model has no system instance")
        return source.instances[0]
    if kind not in ("SystemInstance", "ComponentInstance"):
        raise ModelError(f"expected an instance model, got a {kind}")
    return source


def category_of(obj: Any) -> str:
    """The category literal name of a component or feature instance (``virtualProcessor``)."""
    value = getattr(obj, "category", None)
    return getattr(value, "name", str(value or ""))


def _path(obj: Any) -> str:
    from rosaadl.model import instance_path

    return instance_path(obj)


def _relative_path(obj: Any) -> str:
    """The instance path without the root's segment (OSATE's ``getComponentInstancePath``)."""
    path = _path(obj)
    head, dot, rest = path.partition(".")
    return rest if dot else path


def _component_of(obj: Any) -> Any:
    current = obj
    while current is not None and not hasattr(current, "componentInstances"):
        current = current.eContainer()
    return current


def _exact(number: Any) -> Fraction | None:
    if isinstance(number, bool):
        return None
    if isinstance(number, Fraction):
        return number
    if isinstance(number, int):
        return Fraction(number)
    if isinstance(number, float):
        if not math.isfinite(number):
            return None
        return Fraction(repr(number))  # the decimal as written, not its binary rounding
    return None


@dataclass(frozen=True)
class SystemMode:
    """A system operation mode: the mode instances that are current in it.

    ``label`` is OSATE's printable form, ``(theBus.m1, VB3.z1)``, empty for a model without
    modes.
    """

    name: str
    modes: tuple[Any, ...] = ()
    _owners: dict[int, Any] = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        for mode in self.modes:
            owner = mode.eContainer()
            if owner is not None:
                self._owners[id(owner)] = mode

    @property
    def label(self) -> str:
        if not self.modes:
            return ""
        return "(" + ", ".join(_relative_path(m) for m in self.modes) + ")"

    def current_mode(self, component: Any) -> Any | None:
        """The mode instance of ``component`` that is current in this system mode (None: no modes)."""
        return self._owners.get(id(component))

    def active(self, obj: Any) -> bool:
        """Whether a component, feature or connection instance exists in this system mode."""
        if obj is None:
            return True
        if hasattr(obj, "inSystemOperationModes") and not hasattr(obj, "componentInstances"):
            soms = list(obj.inSystemOperationModes)
            return not soms or not self.modes or any(s.lower() == self.name.lower() for s in soms)
        current = _component_of(obj)
        while current is not None and hasattr(current, "componentInstances"):
            in_modes = list(getattr(current, "inModes", None) or [])
            parent = current.eContainer()
            if in_modes and parent is not None:
                mode = self.current_mode(parent)
                if mode is not None:
                    name = (mode.name or mode.mode or "").lower()
                    if all(m.lower() != name for m in in_modes):
                        return False
            current = parent
        return True

    def mode_names_for(self, obj: Any) -> set[str]:
        """Names of the current modes of ``obj``'s component and of its ancestors."""
        names: set[str] = set()
        current = _component_of(obj)
        while current is not None:
            mode = self.current_mode(current)
            if mode is not None:
                names.add((mode.name or mode.mode or "").lower())
            current = current.eContainer()
        return names


def system_modes(root: Any) -> list[SystemMode]:
    """The system operation modes of an instance, in order (one empty mode when it has none)."""
    soms = list(getattr(root, "systemOperationModes", None) or [])
    result = [SystemMode(som.name or f"som_{i}", tuple(som.currentModes)) for i, som in enumerate(soms)]
    return result or [SystemMode("No Modes")]


class PropertyReader:
    """Reads property values of instance objects exactly, in a unit and a system mode, and
    collects located diagnostics instead of raising."""

    def __init__(self, diagnostics: list[Diagnostic] | None = None) -> None:
        self.units = standard_units()
        self.diagnostics: list[Diagnostic] = diagnostics if diagnostics is not None else []
        self._seen: set[tuple[str, str, str]] = set()
        self._cache: dict[tuple[int, str, str], tuple[Any, Any]] = {}

    # ------------------------------------------------------------------ diagnostics

    def report(self, severity: str, message: str, obj: Any) -> None:
        """Add a diagnostic on ``obj`` (once per severity, object and message)."""
        path = _path(obj) if obj is not None and hasattr(obj, "eClass") else ""
        key = (severity, path, message)
        if key in self._seen:
            return
        self._seen.add(key)
        self.diagnostics.append(Diagnostic(severity, message, Location(path=path or None)))

    # ------------------------------------------------------------------ raw values

    def value(self, obj: Any, name: str, mode: SystemMode | None = None) -> Any:
        """The Python value of property ``name`` on ``obj`` (its value in ``mode`` when modal).
        Values are cached for the reader's life: analyses do not change the model they read."""
        key = (id(obj), name.lower(), mode.name if mode is not None and mode.modes else "")
        if key in self._cache:
            return self._cache[key][1]
        value = self._value(obj, name, mode)
        self._cache[key] = (obj, value)  # holding obj keeps its id from being reused
        return value

    def _value(self, obj: Any, name: str, mode: SystemMode | None) -> Any:
        try:
            assoc = own_association(obj, name)
            if assoc is None:
                return None
            expr = None
            default = None
            wanted = mode.mode_names_for(obj) if mode is not None and mode.modes else set()
            for modal in assoc.ownedValues:
                in_modes = [m.lower() for m in (modal.inModes or [])]
                if not in_modes:
                    if default is None:
                        default = modal.value
                elif wanted and any(m in wanted for m in in_modes):
                    expr = modal.value
                    break
            if expr is None:
                expr = default
            if expr is None and assoc.ownedValues and not wanted:
                expr = assoc.ownedValues[0].value
            return python_value(expr)
        except ModelError as exc:
            self.report("error", f"property {name}: {exc.message}", obj)
            return None

    def number(
        self,
        obj: Any,
        name: str,
        unit: str | None = None,
        mode: SystemMode | None = None,
        *,
        part: str = "max",
        value: Any = None,
    ) -> Fraction | None:
        """The value of ``name`` as an exact number, converted to ``unit`` (None when absent or
        unusable, with a diagnostic for the latter). Ranges give their ``part`` (max or min)."""
        raw = value if value is not None else self.value(obj, name, mode)
        if raw is None:
            return None
        return self.convert(obj, name, raw, unit, part=part)

    def convert(
        self, obj: Any, name: str, raw: Any, unit: str | None, *, part: str = "max"
    ) -> Fraction | None:
        if isinstance(raw, Range):
            raw = raw.maximum if part == "max" else raw.minimum
        if isinstance(raw, Quantity):
            number = _exact(raw.value)
            if number is None:
                self.report("error", f"{name} is not a finite number", obj)
                return None
            if unit is None or raw.unit is None:
                return number
            literal = raw.unit.lower()
            if unit.lower() in _MIPD and literal in _MIPD:
                return number * _MIPD[literal] / _MIPD[unit.lower()]
            if unit.lower() == "persecond" and literal == "persecond":
                return number
            try:
                return number * self.units.factor(raw.unit, unit)
            except ModelError as exc:
                self.report("error", f"{name}: {exc.message}", obj)
                return None
        number = _exact(raw)
        if number is None:
            self.report("error", f"{name} is not a number (got {raw!r})", obj)
            return None
        if unit is not None and unit.lower() not in ("persecond",):
            self.report("warning", f"{name} = {raw} has no unit; read as {unit}", obj)
        return number

    def targets(self, obj: Any, name: str, mode: SystemMode | None = None) -> list[Any] | None:
        """Resolved instance objects of a reference (list) property; None when it is not set.
        References that do not resolve are reported as warnings and left out."""
        value = self.value(obj, name, mode)
        if value is None:
            return None
        items = value if isinstance(value, list) else [value]
        result = []
        for item in items:
            if isinstance(item, Reference):
                self.report("warning", f"{name} refers to {item.path}, which does not resolve", obj)
            elif item is not None and hasattr(item, "eClass"):
                result.append(item)
        return result

    def flag(self, obj: Any, name: str, mode: SystemMode | None = None) -> bool:
        value = self.value(obj, name, mode)
        return value is True

    def enum(self, obj: Any, name: str, mode: SystemMode | None = None) -> str | None:
        value = self.value(obj, name, mode)
        if isinstance(value, EnumLiteral):
            return value.name
        if isinstance(value, str):
            return value
        return None

    # ------------------------------------------------------------------ common properties

    def seconds(
        self, obj: Any, name: str, mode: SystemMode | None = None, *, part: str = "max"
    ) -> Fraction | None:
        return self.number(obj, name, "sec", mode, part=part)

    def mips_capacity(self, obj: Any, mode: SystemMode | None = None) -> Fraction:
        """``SEI::MIPSCapacity``, else ``Timing_Properties::Processor_Capacity``, in MIPS (0: none)."""
        capacity = self.number(obj, "SEI::MIPSCapacity", "MIPS", mode)
        if capacity is None:
            capacity = self.number(obj, "Timing_Properties::Processor_Capacity", "MIPS", mode)
        return capacity or Fraction(0)

    def mips_budget(self, obj: Any, mode: SystemMode | None = None) -> Fraction:
        return self.number(obj, "SEI::MIPSBudget", "MIPS", mode) or Fraction(0)

    def size_kbyte(self, obj: Any, name: str, mode: SystemMode | None = None) -> Fraction | None:
        return self.number(obj, name, "KByte", mode)


# =============================================================================== bindings


class _Bindings:
    """Processor bindings as OSATE's InstanceModelUtil follows them."""

    def __init__(self, reader: PropertyReader) -> None:
        self.reader = reader

    def processor_binding(self, ci: Any, mode: SystemMode | None) -> list[Any]:
        """What ``ci`` is directly bound to; a virtual processor without a binding is bound to the
        processor or virtual processor that contains it."""
        bound = self.reader.targets(ci, "Actual_Processor_Binding", mode) or []
        if not bound and category_of(ci) == "virtualProcessor":
            parent = ci.eContainer()
            if parent is not None and category_of(parent) in ("processor", "virtualProcessor"):
                bound = [parent]
        return bound

    def physical_processor(
        self, ci: Any, mode: SystemMode | None, seen: frozenset[int] = frozenset()
    ) -> Any | None:
        """The physical processor ``ci`` runs on (through virtual processors), None when unbound.
        A binding target that is neither a processor nor a virtual processor is reported."""
        if id(ci) in seen:
            self.reader.report("error", "virtual processors are bound in a cycle", ci)
            return None
        for target in self.processor_binding(ci, mode):
            kind = category_of(target)
            if kind == "virtualProcessor":
                found = self.physical_processor(target, mode, seen | {id(ci)})
                if found is not None:
                    return found
            elif kind == "processor":
                return target
            else:
                self.reader.report(
                    "error",
                    f"Actual_Processor_Binding refers to {_path(target)} ({kind or 'not a component'}), "
                    "not a processor or virtual processor",
                    ci,
                )
        return None


def bound_processor(
    obj: Any, mode: SystemMode | None = None, reader: PropertyReader | None = None
) -> Any | None:
    """The physical processor a component instance is bound to (``Actual_Processor_Binding``,
    through virtual processors), None when it is not bound to one."""
    return _Bindings(reader or PropertyReader()).physical_processor(obj, mode)


# =============================================================================== rows


@dataclass(frozen=True)
class ThreadLoad:
    """One thread's CPU demand: period and CET in microseconds, utilisation CET / Period, and the
    MIPS it demands (OSATE's thread execution in MIPS)."""

    path: str
    period_us: Fraction | None
    cet_us: Fraction | None
    utilization: Fraction | None
    mips: Fraction
    capacity_mips: Fraction = Fraction(0)

    @property
    def load_percent(self) -> Fraction | None:
        """CET / Period in % (else MIPS demand / processor capacity in %)."""
        if self.utilization is not None:
            return self.utilization * 100
        if self.capacity_mips > 0:
            return self.mips / self.capacity_mips * 100
        return None

    def as_dict(self) -> dict[str, Any]:
        return {
            "path": self.path,
            "period_us": _num(self.period_us),
            "cet_us": _num(self.cet_us),
            "load_percent": _num(self.load_percent),
            "mips_demand": _num(self.mips),
        }


@dataclass(frozen=True)
class ComponentBudget:
    """A component's budget and actual demand (MIPS or KByte) as OSATE's ``sumBudgets`` lists it."""

    path: str
    category: str
    depth: int
    budget: Fraction
    actual: Fraction
    note: str = ""

    def as_dict(self) -> dict[str, Any]:
        return {
            "path": self.path,
            "category": self.category,
            "budget": _num(self.budget),
            "actual": _num(self.actual),
            "note": self.note,
        }


@dataclass(frozen=True)
class ProcessorLoad:
    """The load of one processor (or core, or virtual processor) in one system mode."""

    path: str
    category: str
    mode: str
    capacity_mips: Fraction
    demand_mips: Fraction
    threads: tuple[ThreadLoad, ...]
    components: tuple[ComponentBudget, ...]
    cores: tuple[str, ...] = ()

    @property
    def load_percent(self) -> Fraction | None:
        """Demand / capacity in % (None without a capacity)."""
        return self.demand_mips / self.capacity_mips * 100 if self.capacity_mips > 0 else None

    @property
    def utilization(self) -> Fraction:
        """Σ CET / Period of the threads bound to it (including its cores')."""
        return sum((t.utilization for t in self.threads if t.utilization is not None), Fraction(0))

    @property
    def overloaded(self) -> bool:
        return self.capacity_mips > 0 and self.demand_mips > self.capacity_mips

    def as_dict(self) -> dict[str, Any]:
        out = {
            "path": self.path,
            "capacity_mips": _num(self.capacity_mips),
            "demand_mips": _num(self.demand_mips),
            "load_percent": _num(self.load_percent),
            "threads": [t.as_dict() for t in self.threads],
        }
        if self.mode:
            out["mode"] = self.mode
        return out


@dataclass(frozen=True)
class MemoryLoad:
    """The load of one memory resource (``Memory``, ``RAM`` or ``ROM``) in KByte."""

    path: str
    kind: str
    mode: str
    capacity_kbyte: Fraction
    demand_kbyte: Fraction
    components: tuple[ComponentBudget, ...]

    @property
    def load_percent(self) -> Fraction | None:
        return self.demand_kbyte / self.capacity_kbyte * 100 if self.capacity_kbyte > 0 else None

    def as_dict(self) -> dict[str, Any]:
        out = {
            "path": self.path,
            "kind": self.kind,
            "capacity_kbyte": _num(self.capacity_kbyte),
            "demand_kbyte": _num(self.demand_kbyte),
            "load_percent": _num(self.load_percent),
            "components": [c.as_dict() for c in self.components],
        }
        if self.mode:
            out["mode"] = self.mode
        return out


def _num(value: Fraction | int | None) -> float | int | None:
    if value is None:
        return None
    if isinstance(value, int):
        return value
    return int(value) if value.denominator == 1 else float(value)


@dataclass(frozen=True)
class ResourceResult:
    """Bound resource allocation: processors (cores, virtual processors) and memories, per mode."""

    instance: str
    processors: tuple[ProcessorLoad, ...]
    memories: tuple[MemoryLoad, ...]
    diagnostics: tuple[Diagnostic, ...]

    @property
    def ok(self) -> bool:
        return all(d.severity != "error" for d in self.diagnostics)

    def processor(self, path: str, mode: str = "") -> ProcessorLoad:
        for row in self.processors:
            if row.path == path and (not mode or row.mode == mode):
                return row
        raise ModelError(f"no processor {path!r} in the resource analysis")

    def as_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"processors": [p.as_dict() for p in self.processors]}
        if self.memories:
            out["memories"] = [m.as_dict() for m in self.memories]
        return out


# =============================================================================== the analysis


class _Analysis:
    """State of one resource analysis run: reader, bindings and caches (no global state)."""

    def __init__(self, root: Any, diagnostics: list[Diagnostic]) -> None:
        self.root = root
        self.reader = PropertyReader(diagnostics)
        self.bindings = _Bindings(self.reader)
        self._lookup: Any = None
        self._reference_mips: dict[str, Fraction | None] = {}
        self._preorder: list[Any] | None = None
        self._position: dict[int, int] = {}
        self._bound: dict[str, dict[int, tuple[list[Any], set[int]]]] = {}

    # ------------------------------------------------------------------ traversal

    def components(self) -> list[Any]:
        """Every component instance, pre-order, root first."""
        if self._preorder is None:
            order = []
            stack = [self.root]
            while stack:
                ci = stack.pop()
                order.append(ci)
                stack.extend(reversed(list(ci.componentInstances)))
            self._preorder = order
            self._position = {id(ci): i for i, ci in enumerate(order)}
        return self._preorder

    # ------------------------------------------------------------------ thread demand

    def reference_mips(self, thread: Any, mode: SystemMode | None) -> Fraction | None:
        """MIPSCapacity of the thread's ``Reference_Processor`` classifier, when the declarative
        model is available (None otherwise)."""
        value = self.reader.value(thread, "Reference_Processor", mode)
        if not isinstance(value, str) or not value:
            return None
        key = value.lower()
        if key in self._reference_mips:
            return self._reference_mips[key]
        result = None
        try:
            from rosaadl import model as _model

            holder = _model.root_of(self.root)
            if hasattr(holder, "units") and holder.units:
                classifier = _model.find_classifier(holder, value)
                if classifier is not None:
                    if self._lookup is None:
                        from rosaadl.lookup import PropertyLookup
                        from rosaadl.resolution import Resolver

                        self._lookup = PropertyLookup(holder, Resolver(holder))
                    capacity = self._lookup.python_value(classifier, "SEI::MIPSCapacity")
                    if capacity is None:
                        capacity = self._lookup.python_value(
                            classifier, "Timing_Properties::Processor_Capacity"
                        )
                    converted = (
                        self.reader.convert(thread, "MIPSCapacity", capacity, "MIPS") if capacity else None
                    )
                    result = converted if converted else None
        except (RosaadlError, LookupError, AttributeError, TypeError, ValueError) as exc:
            # a declarative model that cannot answer: the bound processor's MIPS are used
            log.debug("Reference_Processor %s of %s not resolved: %s", value, _path(thread), exc)
            result = None
        self._reference_mips[key] = result
        return result

    def thread_load(self, thread: Any, mode: SystemMode | None, *, report: bool = True) -> ThreadLoad:
        """OSATE's ``getThreadExecutioninMIPS`` with our diagnostics."""
        reader = self.reader
        path = _path(thread)
        period = reader.seconds(thread, "Timing_Properties::Period", mode)
        cet = reader.seconds(thread, "Timing_Properties::Compute_Execution_Time", mode)
        dispatch = (reader.enum(thread, "Thread_Properties::Dispatch_Protocol", mode) or "").lower()
        mipd = reader.number(thread, "SEI::InstructionsPerDispatch", "MIPD", mode)
        processor = self.bindings.physical_processor(thread, mode)
        capacity = reader.mips_capacity(processor, mode) if processor is not None else Fraction(0)
        if report:
            if period is not None and period <= 0:
                reader.report("error", f"Period is {_fmt_us(period)} us; it must be positive", thread)
            if (cet is not None or mipd is not None) and period is None:
                if dispatch in ("aperiodic", "background"):
                    reader.report("warning", f"{dispatch} thread has no Period; its MIPS demand is 0", thread)
                else:
                    reader.report("error", "thread has no Period; its MIPS demand cannot be computed", thread)
            if cet is None and mipd is None:
                reader.report(
                    "warning",
                    "thread has no Compute_Execution_Time (or SEI::InstructionsPerDispatch); "
                    "its demand is its MIPSBudget, if any",
                    thread,
                )
            if cet is not None and cet <= 0:
                reader.report("error", "Compute_Execution_Time must be positive", thread)
        usable_period = period if period is not None and period > 0 else None
        utilization = cet / usable_period if cet is not None and cet > 0 and usable_period else None
        mips = Fraction(0)
        if mipd is not None and mipd > 0 and usable_period:
            mips = mipd / usable_period
        elif utilization is not None:
            reference = self.reference_mips(thread, mode)
            mips = utilization * (reference if reference else capacity)
            if report and not reference and processor is not None and capacity == 0:
                reader.report(
                    "warning",
                    f"the processor it is bound to ({_path(processor)}) has no SEI::MIPSCapacity; "
                    "its MIPS demand is 0",
                    thread,
                )
        return ThreadLoad(
            path,
            usable_period * 1_000_000 if usable_period else None,
            cet * 1_000_000 if cet is not None else None,
            utilization,
            mips,
            capacity,
        )

    # ------------------------------------------------------------------ sumBudgets

    def is_hardware(self, ci: Any) -> bool:
        kind = category_of(ci)
        if kind in _HARDWARE:
            return True
        if kind in ("system", "device"):
            return all(category_of(fi) == "busAccess" for fi in ci.featureInstances)
        return False

    def sum_budgets(
        self,
        ci: Any,
        kind: str,
        mode: SystemMode | None,
        rows: list[ComponentBudget],
        threads: list[ThreadLoad],
        counts: list[int],
        depth: int = 0,
    ) -> Fraction | None:
        """OSATE's ``sumBudgets``: None for hardware-only subtrees (its -1), else the subtotal,
        or the component's budget when its subtotal is 0."""
        if mode is not None and not mode.active(ci):
            return Fraction(0)
        children = list(ci.componentInstances)
        is_root = ci is self.root
        hw_only = bool(children)
        if not children and self.is_hardware(ci):
            return None
        subtotal = Fraction(0)
        index = len(rows)
        for child in children:
            result = self.sum_budgets(
                child, kind, mode, rows, threads, counts, depth if is_root else depth + 1
            )
            if result is None:
                continue
            hw_only = False
            subtotal += result
            if category_of(child) == "device":
                if result > 0:
                    counts[0] += 1
                    counts[1] += 1
            else:
                counts[0] += 1
                if result > 0:
                    counts[1] += 1
        if hw_only:
            del rows[index:]
            return None
        category = category_of(ci)
        if kind == "MIPS":
            budget = self.reader.mips_budget(ci, mode)
            if category == "thread":
                load = self.thread_load(ci, mode)
                threads.append(load)
                subtotal = load.mips
        else:
            budget = self.memory_budget(ci, kind, mode)
            subtotal += self.memory_actual(ci, kind, mode)
        unit = "MIPS" if kind == "MIPS" else "KByte"
        note = ""
        if budget > 0 and subtotal > budget:
            note = f"subtotal/actual exceeds budget {_fmt3(budget)} by {_fmt3(subtotal - budget)} {unit}"
            if not is_root:
                self.reader.report(
                    "error",
                    f"{_category_word(category)} needs {_fmt3(subtotal)} {unit}, more than its "
                    f"{'SEI::MIPSBudget' if kind == 'MIPS' else kind + ' budget'} {_fmt3(budget)} {unit}",
                    ci,
                )
        elif budget > 0 and subtotal < budget:
            slack = (budget - subtotal) / budget * 100
            note = (
                f"total {_fmt3(subtotal)} {unit} below budget {_fmt3(budget)} {unit} "
                f"({float(slack):.1f} % slack)"
            )
        if not is_root:
            rows.insert(index, ComponentBudget(_path(ci), category, depth, budget, subtotal, note))
        return budget if subtotal == 0 else subtotal

    # ------------------------------------------------------------------ memory

    def memory_budget(self, ci: Any, kind: str, mode: SystemMode | None) -> Fraction:
        ram = self.reader.size_kbyte(ci, "SEI::RAMBudget", mode) or Fraction(0)
        rom = self.reader.size_kbyte(ci, "SEI::ROMBudget", mode) or Fraction(0)
        return {"RAM": ram, "ROM": rom}.get(kind, ram + rom)

    def memory_actual(self, ci: Any, kind: str, mode: SystemMode | None) -> Fraction:
        """Data_Size + Heap_Size + Stack_Size (RAM), Code_Size (ROM), all four (Memory) of ``ci``
        itself (each falling back to its ``Source_`` property, as OSATE)."""
        names = {
            "RAM": ("Data_Size", "Heap_Size", "Stack_Size"),
            "ROM": ("Code_Size",),
            "Memory": ("Data_Size", "Heap_Size", "Stack_Size", "Code_Size"),
        }[kind]
        total = Fraction(0)
        for name in names:
            size = self.reader.size_kbyte(ci, f"Memory_Properties::{name}", mode)
            if size is None:
                size = self.reader.size_kbyte(ci, f"Memory_Properties::Source_{name}", mode)
            total += size or Fraction(0)
        return total

    # ------------------------------------------------------------------ bound software

    def bound_components(self, processor: Any, mode: SystemMode | None) -> list[Any]:
        """Outermost threads, thread groups, processes and systems bound to ``processor``
        (directly or through virtual processors), in model order."""
        key = mode.name if mode is not None else ""
        index = self._bound.get(key)
        if index is None:
            index = {}
            for ci in self.components():
                if ci is self.root or category_of(ci) not in _SOFTWARE:
                    continue
                for target in self.reachable_processors(ci, mode):
                    found = index.setdefault(id(target), ([], set()))
                    if not any(id(outer) in found[1] for outer in _ancestors(ci)):
                        found[0].append(ci)
                        found[1].add(id(ci))
            self._bound[key] = index
        return list(index.get(id(processor), ([], set()))[0])

    def reachable_processors(self, ci: Any, mode: SystemMode | None) -> list[Any]:
        """Every processor and virtual processor ``ci`` is bound to, directly or through
        virtual processors."""
        out: list[Any] = []
        stack = list(self.bindings.processor_binding(ci, mode))
        seen: set[int] = {id(ci)}
        while stack:
            target = stack.pop(0)
            if id(target) in seen:
                continue
            seen.add(id(target))
            out.append(target)
            if category_of(target) == "virtualProcessor":
                stack.extend(self.bindings.processor_binding(target, mode))
        return out

    def processor_load(self, processor: Any, mode: SystemMode, cores: list[ProcessorLoad]) -> ProcessorLoad:
        reader = self.reader
        category = category_of(processor)
        capacity = reader.mips_capacity(processor, mode)
        if capacity == 0 and category == "virtualProcessor":
            capacity = reader.mips_budget(processor, mode)
        own_capacity = capacity
        if capacity == 0 and cores:
            capacity = sum((c.capacity_mips for c in cores), Fraction(0))
        bound = self.bound_components(processor, mode)
        rows: list[ComponentBudget] = []
        threads: list[ThreadLoad] = []
        demand = Fraction(0)
        for ci in bound:
            actual = self.sum_budgets(ci, "MIPS", mode, rows, threads, [0, 0])
            if actual is not None and actual > 0:
                demand += actual
        for core in cores:
            demand += core.demand_mips
            threads.extend(core.threads)
        path = _path(processor)
        what = "Virtual processor" if category == "virtualProcessor" else "Processor"
        if bound or cores:
            if capacity == 0 and (bound or any(c.threads for c in cores)):
                if category == "virtualProcessor":
                    reader.report("warning", f"{what} {path} has no MIPS capacity or budget", processor)
                else:
                    reader.report(
                        "error", f"{what} {path} has no MIPS capacity but has bound components", processor
                    )
            elif capacity > 0 and demand > capacity:
                reader.report(
                    "error",
                    f"{what} {path}: total MIPS {_fmt3(demand)} MIPS of bound tasks exceeds MIPS capacity "
                    f"{_fmt3(capacity)} MIPS ({float(demand / capacity * 100):.2f} %)",
                    processor,
                )
            elif demand == 0 and bound:
                reader.report(
                    "warning", f"{what} {path}: bound components have no MIPS demand or budget", processor
                )
        if own_capacity == 0 and not cores and not bound:
            log.debug("processor %s: no capacity and nothing bound", path)
        return ProcessorLoad(
            path,
            category,
            mode.label,
            capacity,
            demand,
            tuple(threads),
            tuple(rows),
            tuple(c.path for c in cores),
        )

    def memory_loads(self, holder: Any, mode: SystemMode) -> list[MemoryLoad]:
        reader = self.reader
        capacities = (
            ("Memory", reader.size_kbyte(holder, "Memory_Properties::Memory_Size", mode)),
            ("RAM", reader.size_kbyte(holder, "SEI::RAMCapacity", mode)),
            ("ROM", reader.size_kbyte(holder, "SEI::ROMCapacity", mode)),
        )
        result = []
        bound: list[Any] | None = None
        for kind, capacity in capacities:
            if capacity is None or capacity <= 0:
                continue
            if bound is None:
                bound = []
                for ci in reversed(self.components()):  # OSATE collects them post-order
                    targets = reader.targets(ci, "Actual_Memory_Binding", mode) or []
                    if any(t is holder for t in targets):
                        if any(_contains(outer, ci) for outer in bound):
                            continue
                        bound = [outer for outer in bound if not _contains(ci, outer)]
                        bound.append(ci)
                bound.sort(key=lambda c: self._position[id(c)])
            rows = []
            total = Fraction(0)
            for ci in bound:
                if not mode.active(ci):
                    continue
                actual = sum((self.memory_actual(c, kind, mode) for c in _subtree(ci)), Fraction(0))
                declared = Fraction(0)
                for c in _subtree(ci):
                    for name in ("SEI::RAMActual",) if kind != "ROM" else ("SEI::ROMActual",):
                        declared += reader.size_kbyte(c, name, mode) or Fraction(0)
                budget = self.memory_budget(ci, "RAM" if kind != "ROM" else "ROM", mode)
                used = actual if actual > 0 else declared if declared > 0 else budget
                note = ""
                if budget > 0 and used > budget:
                    note = f"exceeds budget by {_fmt3(used - budget)} KByte"
                    reader.report(
                        "error",
                        f"{kind} use {_fmt3(used)} KByte exceeds its budget {_fmt3(budget)} KByte",
                        ci,
                    )
                elif actual == 0 and declared == 0:
                    note = "no actual; budget counted"
                rows.append(ComponentBudget(_path(ci), category_of(ci), 0, budget, used, note))
                total += used
            path = _path(holder)
            if total > capacity:
                reader.report(
                    "error",
                    f"total {kind} {_fmt3(total)} KByte of bound components exceeds the {kind} capacity "
                    f"{_fmt3(capacity)} KByte of {path}",
                    holder,
                )
            result.append(MemoryLoad(path, kind, mode.label, capacity, total, tuple(rows)))
        return result

    def unbound_threads(self, mode: SystemMode, analysed: set[str]) -> None:
        """Report the threads no processor row covers: unbound, or bound to something that does
        not lead to a processor (their timing problems too)."""
        for ci in self.components():
            if category_of(ci) != "thread" or not mode.active(ci) or _path(ci) in analysed:
                continue
            if not self.bindings.processor_binding(ci, mode):
                self.reader.report(
                    "warning", "thread is not bound to a processor (Actual_Processor_Binding)", ci
                )
            self.thread_load(ci, mode)


def _contains(outer: Any, inner: Any) -> bool:
    current = inner.eContainer()
    while current is not None:
        if current is outer:
            return True
        current = current.eContainer()
    return False


def _ancestors(ci: Any) -> Iterator[Any]:
    current = ci.eContainer()
    while current is not None:
        yield current
        current = current.eContainer()


def _subtree(ci: Any) -> Iterator[Any]:
    stack = [ci]
    while stack:
        current = stack.pop()
        yield current
        stack.extend(reversed(list(current.componentInstances)))


def _category_word(category: str) -> str:
    return {"threadGroup": "thread group", "virtualProcessor": "virtual processor"}.get(category, category)


def _fmt3(value: Fraction) -> str:
    return f"{float(value):.3f}"


def _fmt_us(value: Fraction) -> str:
    us = value * 1_000_000
    return str(us.numerator) if us.denominator == 1 else f"{float(us):g}"


def analyze_resources(source: Any) -> ResourceResult:
    """Bound resource allocation of an instance (``SystemInstance`` or ``AadlModel``): processor,
    core and virtual processor loads in MIPS and %, memory loads, per system operation mode."""
    root = instance_root(source)
    diagnostics: list[Diagnostic] = []
    analysis = _Analysis(root, diagnostics)
    processors: list[ProcessorLoad] = []
    memories: list[MemoryLoad] = []
    for mode in system_modes(root):
        loads: dict[int, ProcessorLoad] = {}
        # cores before the processors that contain them: post-order over processors
        ordered = [ci for ci in analysis.components() if category_of(ci) == "processor"]
        for processor in reversed(ordered):
            if not mode.active(processor):
                continue
            cores = [
                loads[id(c)]
                for c in processor.componentInstances
                if category_of(c) == "processor" and id(c) in loads
            ]
            loads[id(processor)] = analysis.processor_load(processor, mode, cores)
        processors.extend(loads[id(p)] for p in ordered if id(p) in loads)
        for vp in analysis.components():
            if category_of(vp) == "virtualProcessor" and mode.active(vp):
                processors.append(analysis.processor_load(vp, mode, []))
        for holder in analysis.components():
            if category_of(holder) in _MEMORY_HOLDERS and mode.active(holder):
                memories.extend(analysis.memory_loads(holder, mode))
        analysed = {t.path for row in processors if row.mode == mode.label for t in row.threads}
        analysis.unbound_threads(mode, analysed)
    log.debug("resource analysis of %s: %d processor rows", root.name, len(processors))
    return ResourceResult(root.name or "", tuple(processors), tuple(memories), tuple(diagnostics))


# =============================================================================== not bound


@dataclass(frozen=True)
class BudgetTotals:
    """System-wide totals of one resource kind in one mode (MIPS, or KByte for memory)."""

    kind: str
    mode: str
    capacity: Fraction
    budget: Fraction
    resources: int
    resources_with_capacity: int
    components: int
    budgeted_components: int
    rows: tuple[ComponentBudget, ...]
    virtual_capacity: Fraction = Fraction(0)

    @property
    def over_capacity(self) -> bool:
        return self.budget > self.capacity

    def as_dict(self) -> dict[str, Any]:
        unit = "mips" if self.kind == "MIPS" else "kbyte"
        out = {
            "kind": self.kind,
            f"capacity_{unit}": _num(self.capacity),
            f"budget_{unit}": _num(self.budget),
            "resources": self.resources,
            "resources_with_capacity": self.resources_with_capacity,
            "components": self.components,
            "budgeted_components": self.budgeted_components,
            "rows": [r.as_dict() for r in self.rows],
        }
        if self.kind == "MIPS":
            out["virtual_capacity_mips"] = _num(self.virtual_capacity)
        if self.mode:
            out["mode"] = self.mode
        return out


@dataclass(frozen=True)
class BudgetResult:
    """Not-bound resource budgets: per component rows and totals per resource kind and mode."""

    instance: str
    totals: tuple[BudgetTotals, ...]
    diagnostics: tuple[Diagnostic, ...]

    @property
    def ok(self) -> bool:
        return all(d.severity != "error" for d in self.diagnostics)

    def total(self, kind: str = "MIPS", mode: str = "") -> BudgetTotals:
        for row in self.totals:
            if row.kind == kind and (not mode or row.mode == mode):
                return row
        raise ModelError(f"no {kind} budget totals")

    def as_dict(self) -> dict[str, Any]:
        return {"totals": [t.as_dict() for t in self.totals]}


def analyze_budgets(source: Any) -> BudgetResult:
    """Not-bound resource budgets of an instance, per system operation mode: every software
    component's budget and demand, and capacity vs budget totals for MIPS, Memory, RAM and ROM."""
    root = instance_root(source)
    diagnostics: list[Diagnostic] = []
    analysis = _Analysis(root, diagnostics)
    reader = analysis.reader
    totals: list[BudgetTotals] = []
    for mode in system_modes(root):
        processors = [ci for ci in analysis.components() if category_of(ci) == "processor"]
        vps = [ci for ci in analysis.components() if category_of(ci) == "virtualProcessor"]
        memories = [ci for ci in analysis.components() if category_of(ci) == "memory"]
        capacities = [reader.mips_capacity(p, mode) for p in processors]
        kinds: list[tuple[str, Fraction, int, int]] = [
            ("MIPS", sum(capacities, Fraction(0)), len(capacities), sum(1 for c in capacities if c > 0))
        ]
        for kind, prop in (
            ("Memory", "Memory_Properties::Memory_Size"),
            ("RAM", "SEI::RAMCapacity"),
            ("ROM", "SEI::ROMCapacity"),
        ):
            values = [reader.size_kbyte(m, prop, mode) or Fraction(0) for m in memories]
            if sum(values, Fraction(0)) > 0:
                kinds.append((kind, sum(values, Fraction(0)), len(values), sum(1 for v in values if v > 0)))
        for kind, capacity, resources, with_capacity in kinds:
            rows: list[ComponentBudget] = []
            counts = [0, 0]
            total = analysis.sum_budgets(root, kind, mode, rows, [], counts)
            budget = total if total is not None and total > 0 else Fraction(0)
            virtual = (
                sum((reader.mips_budget(v, mode) for v in vps), Fraction(0))
                if kind == "MIPS"
                else Fraction(0)
            )
            unit = "MIPS" if kind == "MIPS" else "KByte"
            where = f" in modes {mode.label}" if mode.label else ""
            if budget > capacity:
                reader.report(
                    "error",
                    f"System {root.name} budgets over capacity{where}: "
                    f"{kind} capacity {_fmt3(capacity)} {unit} : {kind} budget {_fmt3(budget)} {unit}",
                    root,
                )
            if with_capacity < resources:
                reader.report(
                    "warning", f"{with_capacity} out of {resources} with {kind} capacity{where}", root
                )
            if counts[1] < counts[0]:
                reader.report("warning", f"{counts[1]} out of {counts[0]} with {kind} budget{where}", root)
            totals.append(
                BudgetTotals(
                    kind,
                    mode.label,
                    capacity,
                    budget,
                    resources,
                    with_capacity,
                    counts[0],
                    counts[1],
                    tuple(rows),
                    virtual,
                )
            )
    return BudgetResult(root.name or "", tuple(totals), tuple(diagnostics))
