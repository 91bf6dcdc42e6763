"""What the software of an instance demands of its processors and memories, as OSATE sums it.

:class:`ResourceDemand` holds one run's state and answers, per system operation mode:

* a thread's load (:class:`ThreadLoad`, OSATE's ``getThreadExecutioninMIPS``):
  ``SEI::InstructionsPerDispatch / Period`` MIPS, else ``max Compute_Execution_Time / Period``
  times the MIPS of its ``Reference_Processor`` (when the declarative model is at hand), else of
  the physical processor it is bound to;
* OSATE's ``sumBudgets``: the demand of a component as the sum of its children's (hardware-only
  subtrees left out), or its own ``SEI::MIPSBudget`` / RAM and ROM budgets when they demand
  nothing, one :class:`ComponentBudget` row per component, and an error where a component needs
  more than its budget;
* the memory a component uses (``Data_Size + Heap_Size + Stack_Size`` for RAM, ``Code_Size``
  for ROM, each falling back to its ``Source_`` property);
* the outermost software components bound to a processor, directly or through virtual
  processors (OSATE's ``getBoundSWComponents``).

The bound resource analysis (:mod:`~rosaadl.analysis.resources`) and the not-bound budgets
(:mod:`~rosaadl.analysis.budgets`) are both built on it.
"""

from __future__ import annotations

import logging
from collections.abc import Iterator
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rosaadl.analysis.instance_values import ProcessorBindings, PropertyReader, SystemMode, category_of
from rosaadl.analysis.rendering import category_word, fmt3, json_number
from rosaadl.arguments import describe
from rosaadl.errors import Diagnostic, RosaadlError, UsageError
from rosaadl.model import component_instances, instance_path

__all__ = [
    "ThreadLoad",
    "ComponentBudget",
    "ResourceDemand",
    "SOFTWARE",
    "contains",
    "ancestors",
    "subtree",
    "fmt_us",
]

log = logging.getLogger(__name__)

#: The categories whose components are bound to processors (OSATE's bound software).
SOFTWARE = frozenset({"thread", "threadGroup", "process", "system"})
_HARDWARE = frozenset({"bus", "processor", "virtualProcessor", "memory"})


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
            "period_us": json_number(self.period_us),
            "cet_us": json_number(self.cet_us),
            "load_percent": json_number(self.load_percent),
            "mips_demand": json_number(self.mips),
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
            "budget": json_number(self.budget),
            "actual": json_number(self.actual),
            "note": self.note,
        }


class ResourceDemand:
    """What the software of one instance demands of its processors and memories, as OSATE's
    resource analyses sum it; one per analysis run (reader, bindings and caches: no global state)."""

    def __init__(self, root: Any, diagnostics: list[Diagnostic]) -> None:
        self.root = root
        self.reader = PropertyReader(diagnostics)
        self.bindings = ProcessorBindings(self.reader)
        self._lookup: Any = None
        self._reference_mips: dict[str, Fraction | None] = {}
        self._preorder: list[Any] | None = None
        self.position: dict[int, int] = {}  #: pre-order index of each component
        self._bound: dict[str, dict[int, tuple[list[Any], set[int]]]] = {}

    # ------------------------------------------------------------------ traversal

    def components(self) -> list[Any]:
        """Every component instance, pre-order, root first."""
        if self._preorder is None:
            self._preorder = component_instances(self.root)
            self.position = {id(ci): i for i, ci in enumerate(self._preorder)}
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
            log.debug("Reference_Processor %s of %s not resolved: %s", value, instance_path(thread), exc)
            result = None
        self._reference_mips[key] = result
        return result

    def thread_load(self, thread: Any, mode: SystemMode | None, *, report: bool = True) -> ThreadLoad:
        """OSATE's ``getThreadExecutioninMIPS`` with our diagnostics."""
        reader = self.reader
        path = instance_path(thread)
        period = reader.seconds(thread, "Timing_Properties::Period", mode)
        cet = reader.seconds(thread, "Timing_Properties::Compute_Execution_Time", mode)
        dispatch = (reader.enum(thread, "Thread_Properties::Dispatch_Protocol", mode) or "").lower()
        mipd = reader.number(thread, "SEI::InstructionsPerDispatch", "MIPD", mode)
        processor = self.bindings.physical_processor(thread, mode)
        capacity = reader.mips_capacity(processor, mode) if processor is not None else Fraction(0)
        if report:
            if period is not None and period <= 0:
                reader.report("error", f"Period is {fmt_us(period)} us; it must be positive", thread)
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
                    f"the processor it is bound to ({instance_path(processor)}) has no SEI::MIPSCapacity; "
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
            note = f"subtotal/actual exceeds budget {fmt3(budget)} by {fmt3(subtotal - budget)} {unit}"
            if not is_root:
                self.reader.report(
                    "error",
                    f"{category_word(category)} needs {fmt3(subtotal)} {unit}, more than its "
                    f"{'SEI::MIPSBudget' if kind == 'MIPS' else kind + ' budget'} {fmt3(budget)} {unit}",
                    ci,
                )
        elif budget > 0 and subtotal < budget:
            slack = (budget - subtotal) / budget * 100
            note = (
                f"total {fmt3(subtotal)} {unit} below budget {fmt3(budget)} {unit} "
                f"({float(slack):.1f} % slack)"
            )
        if not is_root:
            rows.insert(index, ComponentBudget(instance_path(ci), category, depth, budget, subtotal, note))
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
                if ci is self.root or category_of(ci) not in SOFTWARE:
                    continue
                for target in self.reachable_processors(ci, mode):
                    found = index.setdefault(id(target), ([], set()))
                    if not any(id(outer) in found[1] for outer in ancestors(ci)):
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


def contains(outer: Any, inner: Any) -> bool:
    current = inner.eContainer()
    while current is not None:
        if current is outer:
            return True
        current = current.eContainer()
    return False


def ancestors(ci: Any) -> Iterator[Any]:
    """The components that contain ``ci``, innermost first."""
    if not hasattr(ci, "eContainer"):
        raise UsageError(f"ancestors(): ci must be an instance object, not {describe(ci)}")
    current = ci.eContainer()
    while current is not None:
        yield current
        current = current.eContainer()


def subtree(ci: Any) -> list[Any]:
    """``ci`` and every component instance below it, pre-order."""
    return component_instances(ci)


def fmt_us(value: Fraction) -> str:
    us = value * 1_000_000
    return str(us.numerator) if us.denominator == 1 else f"{float(us):g}"
