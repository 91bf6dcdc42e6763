"""Bound resource allocation, as OSATE's *Analyze Bound Resource Budgets* computes it.

:func:`analyze_resources`: for every processor and virtual processor, in every system operation
mode,

* the capacity: ``SEI::MIPSCapacity``, else ``Processor_Capacity`` (a virtual processor without
  either: its ``SEI::MIPSBudget``);
  a multi-core processor (a processor whose subcomponents are processors) without a capacity of
  its own has the sum of its cores' capacities, and its demand includes its cores' demands;
* the software bound to it (``Actual_Processor_Binding``, directly or through virtual processors),
  the outermost bound components only, as OSATE's ``getBoundSWComponents``;
* the demand of each bound component as OSATE's ``sumBudgets`` (:mod:`~rosaadl.analysis.demand`);
* the load in % (demand / capacity) and the CPU utilisation (Σ CET / Period of its threads);
  an error when the demand exceeds the capacity.

Memory (OSATE's memory loads): a memory, system, processor, virtual processor or abstract
component with ``Memory_Size``, ``SEI::RAMCapacity`` or ``SEI::ROMCapacity`` is loaded by the
components bound to it with ``Actual_Memory_Binding``: ``Data_Size + Heap_Size + Stack_Size``
(RAM), ``Code_Size`` (ROM), all four (Memory_Size), summed over the bound component's subtree,
else its ``SEI::RAMActual`` / ``ROMActual``, else its ``RAMBudget`` / ``ROMBudget``.

Every number is an exact :class:`~fractions.Fraction` (decimal values are read as written).
Problems — a thread without ``Period`` or ``Compute_Execution_Time``, a zero period, a binding to
something that is not a processor — are located :class:`~rosaadl.errors.Diagnostic` s naming the
instance path, never exceptions. Registered as the ``cpu`` analysis; its CSV report is in the
style of OSATE's (``<instance>__BoundResourceAnalysis.csv``).

The instance readers the analyses share (:class:`SystemMode`, :class:`PropertyReader`,
:func:`bound_processor`, ...) live in :mod:`~rosaadl.analysis.instance_values` and are
re-exported here, where earlier releases had them.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rosaadl.analysis.demand import ComponentBudget, ResourceDemand, ThreadLoad, contains, subtree
from rosaadl.analysis.instance_values import (
    PropertyReader,
    SystemMode,
    bound_processor,
    category_of,
    instance_root,
    system_modes,
)
from rosaadl.analysis.registry import Analysis, register
from rosaadl.analysis.rendering import category_word, fmt3, json_number, short_path, squeeze, table
from rosaadl.errors import Diagnostic, ModelError
from rosaadl.model import instance_path

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
    "analyze_resources",
    "resources_text",
    "resources_csv",
]

log = logging.getLogger(__name__)

_MEMORY_HOLDERS = frozenset({"memory", "system", "processor", "virtualProcessor", "abstract"})


# =============================================================================== rows


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
            "capacity_mips": json_number(self.capacity_mips),
            "demand_mips": json_number(self.demand_mips),
            "load_percent": json_number(self.load_percent),
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
            "capacity_kbyte": json_number(self.capacity_kbyte),
            "demand_kbyte": json_number(self.demand_kbyte),
            "load_percent": json_number(self.load_percent),
            "components": [c.as_dict() for c in self.components],
        }
        if self.mode:
            out["mode"] = self.mode
        return out


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


def processor_load(
    demand: ResourceDemand, processor: Any, mode: SystemMode, cores: list[ProcessorLoad]
) -> ProcessorLoad:
    """The load of one processor, core or virtual processor in ``mode``; ``cores``: the loads of
    its cores (a multi-core processor without a capacity of its own has theirs)."""
    reader = demand.reader
    category = category_of(processor)
    capacity = reader.mips_capacity(processor, mode)
    if capacity == 0 and category == "virtualProcessor":
        capacity = reader.mips_budget(processor, mode)
    own_capacity = capacity
    if capacity == 0 and cores:
        capacity = sum((c.capacity_mips for c in cores), Fraction(0))
    bound = demand.bound_components(processor, mode)
    rows: list[ComponentBudget] = []
    threads: list[ThreadLoad] = []
    mips = Fraction(0)
    for ci in bound:
        actual = demand.sum_budgets(ci, "MIPS", mode, rows, threads, [0, 0])
        if actual is not None and actual > 0:
            mips += actual
    for core in cores:
        mips += core.demand_mips
        threads.extend(core.threads)
    path = instance_path(processor)
    what = "Virtual processor" if category == "virtualProcessor" else "Processor"
    if bound or cores:
        if capacity == 0 and (bound or any(c.threads for c in cores)):
            if category == "virtualProcessor":
                reader.report("warning", f"{what} {path} has no MIPS capacity or budget", processor)
            else:
                reader.report(
                    "error", f"{what} {path} has no MIPS capacity but has bound components", processor
                )
        elif capacity > 0 and mips > capacity:
            reader.report(
                "error",
                f"{what} {path}: total MIPS {fmt3(mips)} MIPS of bound tasks exceeds MIPS capacity "
                f"{fmt3(capacity)} MIPS ({float(mips / capacity * 100):.2f} %)",
                processor,
            )
        elif mips == 0 and bound:
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
        mips,
        tuple(threads),
        tuple(rows),
        tuple(c.path for c in cores),
    )


def memory_loads(demand: ResourceDemand, holder: Any, mode: SystemMode) -> list[MemoryLoad]:
    """The loads of one memory holder (Memory_Size, RAM and ROM capacities) in ``mode``."""
    reader = demand.reader
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
            for ci in reversed(demand.components()):  # OSATE collects them post-order
                targets = reader.targets(ci, "Actual_Memory_Binding", mode) or []
                if any(t is holder for t in targets):
                    if any(contains(outer, ci) for outer in bound):
                        continue
                    bound = [outer for outer in bound if not contains(ci, outer)]
                    bound.append(ci)
            bound.sort(key=lambda c: demand.position[id(c)])
        rows = []
        total = Fraction(0)
        for ci in bound:
            if not mode.active(ci):
                continue
            actual = sum((demand.memory_actual(c, kind, mode) for c in subtree(ci)), Fraction(0))
            declared = Fraction(0)
            for c in subtree(ci):
                for name in ("SEI::RAMActual",) if kind != "ROM" else ("SEI::ROMActual",):
                    declared += reader.size_kbyte(c, name, mode) or Fraction(0)
            budget = demand.memory_budget(ci, "RAM" if kind != "ROM" else "ROM", mode)
            used = actual if actual > 0 else declared if declared > 0 else budget
            note = ""
            if budget > 0 and used > budget:
                note = f"exceeds budget by {fmt3(used - budget)} KByte"
                reader.report(
                    "error",
                    f"{kind} use {fmt3(used)} KByte exceeds its budget {fmt3(budget)} KByte",
                    ci,
                )
            elif actual == 0 and declared == 0:
                note = "no actual; budget counted"
            rows.append(ComponentBudget(instance_path(ci), category_of(ci), 0, budget, used, note))
            total += used
        path = instance_path(holder)
        if total > capacity:
            reader.report(
                "error",
                f"total {kind} {fmt3(total)} KByte of bound components exceeds the {kind} capacity "
                f"{fmt3(capacity)} KByte of {path}",
                holder,
            )
        result.append(MemoryLoad(path, kind, mode.label, capacity, total, tuple(rows)))
    return result


def report_unbound_threads(demand: ResourceDemand, mode: SystemMode, analysed: set[str]) -> None:
    """Report the threads no processor row covers: unbound, or bound to something that does
    not lead to a processor (their timing problems too)."""
    for ci in demand.components():
        if category_of(ci) != "thread" or not mode.active(ci) or instance_path(ci) in analysed:
            continue
        if not demand.bindings.processor_binding(ci, mode):
            demand.reader.report(
                "warning", "thread is not bound to a processor (Actual_Processor_Binding)", ci
            )
        demand.thread_load(ci, mode)


def analyze_resources(source: Any) -> ResourceResult:
    """Bound resource allocation of an instance (``SystemInstance`` or ``AadlModel``): processor,
    core and virtual processor loads in MIPS and %, memory loads, per system operation mode."""
    root = instance_root(source)
    diagnostics: list[Diagnostic] = []
    analysis = ResourceDemand(root, diagnostics)
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
            loads[id(processor)] = processor_load(analysis, processor, mode, cores)
        processors.extend(loads[id(p)] for p in ordered if id(p) in loads)
        for vp in analysis.components():
            if category_of(vp) == "virtualProcessor" and mode.active(vp):
                processors.append(processor_load(analysis, vp, mode, []))
        for holder in analysis.components():
            if category_of(holder) in _MEMORY_HOLDERS and mode.active(holder):
                memories.extend(memory_loads(analysis, holder, mode))
        analysed = {t.path for row in processors if row.mode == mode.label for t in row.threads}
        report_unbound_threads(analysis, mode, analysed)
    log.debug("resource analysis of %s: %d processor rows", root.name, len(processors))
    return ResourceResult(root.name or "", tuple(processors), tuple(memories), tuple(diagnostics))


# =============================================================================== renderings


def resources_text(result: ResourceResult) -> list[str]:
    """The ``CPU (bound resources)`` section of the text report."""
    lines = ["CPU (bound resources)", ""]
    rows = []
    for p in result.processors:
        name = short_path(p.path) + (f" {p.mode}" if p.mode else "")
        rows.append([name, p.capacity_mips, p.demand_mips, p.load_percent, p.utilization * 100])
        for t in p.threads:
            rows.append(["  " + short_path(t.path), "", t.mips, t.load_percent, ""])
    lines += table(["processor / thread", "capacity MIPS", "demand MIPS", "load %", "CET/T %"], rows)
    if result.memories:
        lines.append("")
        rows = [
            [short_path(m.path) + f" ({m.kind})", m.capacity_kbyte, m.demand_kbyte, m.load_percent]
            for m in result.memories
        ]
        lines += table(["memory", "capacity KByte", "demand KByte", "load %"], rows)
    lines.append("")
    return lines


def resources_csv(result: ResourceResult, base: str) -> dict[str, str]:
    """``<base>__BoundResourceAnalysis.csv``, in the style of OSATE's bound resource report."""
    lines = [f"Bound resource analysis of {result.instance}", ""]
    modes = sorted({p.mode for p in result.processors}) or [""]
    for mode in modes:
        lines += [f"Processor Summary Report: {mode}".rstrip(), ""]
        for p in (p for p in result.processors if p.mode == mode):
            kind = "Virtual Processor" if p.category == "virtualProcessor" else "Processor"
            lines += [
                squeeze(
                    f"Detailed Workload Report: {mode} for {kind} {short_path(p.path)} "
                    f"with Capacity {fmt3(p.capacity_mips)} MIPS"
                ),
                "",
                "Component,Budget,Actual,Notes",
            ]
            for row in p.components:
                lines.append(
                    f"{'  ' * row.depth}{category_word(row.category)} {short_path(row.path)},"
                    f"{fmt3(row.budget)} MIPS,{fmt3(row.actual)} MIPS,{row.note}"
                )
            load = f",{float(p.load_percent):.2f} %" if p.load_percent is not None else ","
            lines += [f"Total,,{fmt3(p.demand_mips)} MIPS{load}", ""]
    for m in result.memories:
        lines += [
            squeeze(
                f"Detailed Workload Report: {m.mode} for memory {short_path(m.path)} ({m.kind}) "
                f"with Capacity {fmt3(m.capacity_kbyte)} KByte"
            ),
            "",
            "Component,Budget,Actual,Notes",
        ]
        for row in m.components:
            lines.append(
                f"{category_word(row.category)} {short_path(row.path)},{fmt3(row.budget)} KByte,"
                f"{fmt3(row.actual)} KByte,{row.note}"
            )
        lines += [f"Total,,{fmt3(m.demand_kbyte)} KByte", ""]
    return {f"{base}__BoundResourceAnalysis.csv": "\n".join(lines) + "\n"}


register(
    Analysis(
        name="cpu",
        json_key="cpu",
        order=10,
        run=lambda context: analyze_resources(context.root),
        text=resources_text,
        csv=resources_csv,
        description="CPU and MIPS load of every processor, core and virtual processor; memory loads",
    )
)
