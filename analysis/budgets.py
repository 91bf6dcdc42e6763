"""Not-bound resource budgets, as OSATE's *Analyze Resource Budgets (Not Bound)* computes them.

:func:`analyze_budgets`: the budget and demand of every software component (OSATE's
``sumBudgets`` over the whole instance, :mod:`~rosaadl.analysis.demand`; an error when a
component's demand exceeds its own ``MIPSBudget``, e.g. a process whose threads need more than
the process is budgeted), and the system-wide totals per resource kind (MIPS, Memory, RAM, ROM)
and system operation mode: processor capacity vs the budget total, how many processors have a
capacity and how many components a budget.

Registered as the ``budget`` analysis; its CSV report is in the style of OSATE's
(``<instance>__ResourceBudgets.csv``).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rosaadl.analysis.demand import ComponentBudget, ResourceDemand
from rosaadl.analysis.instance_values import category_of, instance_root, system_modes
from rosaadl.analysis.registry import Analysis, register
from rosaadl.analysis.rendering import category_word, fmt, fmt3, json_number, short_path, table
from rosaadl.errors import Diagnostic, ModelError

__all__ = ["BudgetTotals", "BudgetResult", "analyze_budgets", "budgets_text", "budgets_csv"]


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
            f"capacity_{unit}": json_number(self.capacity),
            f"budget_{unit}": json_number(self.budget),
            "resources": self.resources,
            "resources_with_capacity": self.resources_with_capacity,
            "components": self.components,
            "budgeted_components": self.budgeted_components,
            "rows": [r.as_dict() for r in self.rows],
        }
        if self.kind == "MIPS":
            out["virtual_capacity_mips"] = json_number(self.virtual_capacity)
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
    analysis = ResourceDemand(root, diagnostics)
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
                    f"{kind} capacity {fmt3(capacity)} {unit} : {kind} budget {fmt3(budget)} {unit}",
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


def budgets_text(result: BudgetResult) -> list[str]:
    """The ``Budgets (not bound)`` section of the text report."""
    lines = ["Budgets (not bound)", ""]
    for total in result.totals:
        unit = "MIPS" if total.kind == "MIPS" else "KByte"
        title = f"{total.kind} capacity {fmt(total.capacity)} {unit}, budget {fmt(total.budget)} {unit}"
        lines.append(title + (f" {total.mode}" if total.mode else ""))
        rows = [
            ["  " * r.depth + short_path(r.path), r.category, r.budget, r.actual, r.note] for r in total.rows
        ]
        lines += table(["component", "category", f"budget {unit}", f"actual {unit}", "note"], rows)
        lines.append("")
    return lines


def budgets_csv(result: BudgetResult, base: str) -> dict[str, str]:
    """``<base>__ResourceBudgets.csv``, in the style of OSATE's not-bound resource budget report."""
    lines = [f"Resource budget analysis of {result.instance}", ""]
    for total in result.totals:
        unit = "MIPS" if total.kind == "MIPS" else "KByte"
        lines += [
            f"Detailed {total.kind} Budget Report {total.mode}".rstrip(),
            "",
            "Component,Budget,Actual,Notes",
        ]
        for row in total.rows:
            lines.append(
                f"{'  ' * row.depth}{category_word(row.category)} {short_path(row.path)},"
                f"{fmt3(row.budget)} {unit},{fmt3(row.actual)} {unit},{row.note}"
            )
        lines += [
            f"Total,,{fmt3(total.budget)} {unit}",
            "",
            f"{total.kind} capacity {fmt3(total.capacity)} {unit} : "
            f"{total.kind} budget {fmt3(total.budget)} {unit}",
            f"{total.resources_with_capacity} out of {total.resources} with {total.kind} capacity",
            f"{total.budgeted_components} out of {total.components} with {total.kind} budget",
            "",
        ]
    return {f"{base}__ResourceBudgets.csv": "\n".join(lines) + "\n"}


register(
    Analysis(
        name="budget",
        json_key="budget",
        order=20,
        run=lambda context: analyze_budgets(context.root),
        text=budgets_text,
        csv=budgets_csv,
        description="MIPS and memory budgets of the software, not bound (OSATE's resource budgets)",
    )
)
