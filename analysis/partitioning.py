"""Partitioning a task set onto the cores of its processors, as Cheddar's partitioning tools do.

:func:`partition` places tasks into bins (cores) by first, best, next or worst fit, a task fitting
a core when the core stays within Liu and Layland's bound and Oh and Son's IP condition;
:func:`partition_taskset` moves the tasks of multi-core processors onto their cores that way.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from fractions import Fraction

from rosaadl.analysis.schedulability import within_liu_layland
from rosaadl.analysis.tasks import Task, TaskSet
from rosaadl.errors import ModelError

__all__ = ["Partition", "partition", "partition_taskset"]


@dataclass(frozen=True)
class Partition:
    """Where each task goes (task name → bin), the tasks that fit nowhere, and the bins' loads."""

    method: str
    assignment: dict[str, str]
    unplaced: tuple[str, ...]
    loads: dict[str, Fraction]

    @property
    def ok(self) -> bool:
        return not self.unplaced


def _ip_margin(load: Fraction, count: int) -> Fraction:
    """(1 + U/k)^k of a bin with k tasks of total utilisation U (1 for an empty bin)."""
    return (1 + load / count) ** count if count else Fraction(1)


def _fits(load: Fraction, count: int, u: Fraction) -> bool:
    # Liu and Layland on the k+1 tasks, and Oh and Son's IP condition
    # u <= 2 (1 + U/k)^(-k) - 1, i.e. (1 + u)(1 + U/k)^k <= 2.
    if not within_liu_layland(load + u, count + 1):
        return False
    return (1 + u) * _ip_margin(load, count) <= 2


def partition(tasks: Sequence[Task], bins: Sequence[str], method: str = "best_fit") -> Partition:
    """Rate-monotonic bin packing of ``tasks`` onto ``bins`` (processors or cores), as Cheddar's
    partitioning tools do it: tasks by increasing period; a task fits a bin when the bin stays
    under the Liu and Layland bound and meets Oh and Son's IP condition.

    ``best_fit``: the fitting bin with the least room left (smallest 2(1+U/k)^{-k} − 1; ties to
    the first); ``first_fit``: the first fitting bin; ``next_fit``: the current bin, else the
    next one (never going back).
    """
    if method not in ("best_fit", "first_fit", "next_fit"):
        raise ModelError(f"unknown partitioning method {method!r} (best_fit, first_fit, next_fit)")
    if not bins:
        raise ModelError("partitioning needs at least one processor or core")
    loads = {b: Fraction(0) for b in bins}
    counts = {b: 0 for b in bins}
    assignment: dict[str, str] = {}
    unplaced: list[str] = []
    ordered = sorted((t for t in tasks if t.period is not None), key=lambda t: t.period)
    current = 0
    for task in ordered:
        u = task.utilization
        chosen: str | None = None
        if method == "next_fit":
            while current < len(bins) and not _fits(loads[bins[current]], counts[bins[current]], u):
                current += 1
            chosen = bins[current] if current < len(bins) else None
        else:
            fitting = [b for b in bins if _fits(loads[b], counts[b], u)]
            if fitting:
                if method == "first_fit":
                    chosen = fitting[0]
                else:
                    # least room left = largest (1 + U/k)^k
                    chosen = max(fitting, key=lambda b: (_ip_margin(loads[b], counts[b]), -bins.index(b)))
        if chosen is None:
            unplaced.append(task.name)
            continue
        assignment[task.name] = chosen
        loads[chosen] += u
        counts[chosen] += 1
    return Partition(method, assignment, tuple(unplaced), loads)


def partition_taskset(taskset: TaskSet, method: str = "best_fit") -> tuple[TaskSet, Partition]:
    """Partition all tasks of ``taskset`` over every processor / core it declares; returns the
    re-bound task set (tasks that fit nowhere keep their binding) and the partition."""
    bins: list[str] = []
    where: dict[str, tuple[str, str]] = {}
    for processor in taskset.processors:
        for core in processor.domains:
            key = f"{processor.name}.{core}" if core else processor.name
            bins.append(key)
            where[key] = (processor.name, core)
    result = partition(taskset.tasks, bins, method)
    moved = []
    for task in taskset.tasks:
        target = result.assignment.get(task.name)
        if target is None:
            moved.append(task)
        else:
            processor, core = where[target]
            moved.append(replace(task, processor=processor, core=core))
    return taskset.replace_tasks(moved), result
