"""Cheddar's feasibility tests on a :class:`~rosaadl.analysis.tasks.TaskSet`.

Per scheduling domain (a processor, or one core of a partitioned multi-core processor):

* processor utilisation by period (Σ C/T) and by deadline (Σ C/D);
* the utilisation bound: n(2^{1/n} − 1) for fixed priorities (1.0 when the periods are
  harmonic), 1.0 for EDF and LLF; the verdict uses Cheddar's test for the scheduler (RM:
  utilisation by period; DM, EDF, LLF: by deadline; non-preemptive RM: Cheddar's per-task
  condition; non-preemptive EDF with D = T: Jeffay's condition), decided exactly in rationals;
* the feasibility interval as Cheddar computes it (lcm of the periods, 2·lcm + max offset when
  a task has an offset; Goossens–Devillers for EDF) and the units left unused in it;
* RM / DM priority assignment as Cheddar does it (1 for the longest period or deadline, n for
  the shortest; equal periods keep task order: the task listed first gets the higher priority);
* worst-case response times: preemptive fixed priority with release jitter and blocking
  (Tindell's busy window, Cheddar's equation), and non-preemptive fixed priority (George et
  al., Cheddar's discrete-time blocking max(C_lp) − 1); under EDF, preemptive or not, Spuri's
  deadline busy periods with arbitrary deadlines, jitter and blocking
  (:mod:`~rosaadl.analysis.edf_response`; LLF gets none);
* best-fit / first-fit / next-fit partitioning of tasks onto processors or cores (Cheddar's
  Rate-Monotonic Best Fit and companions: utilisation bound and the IP condition).

Every function is pure; :func:`analyze_schedulability` gathers them into a
:class:`SchedulabilityResult` with rows and located diagnostics.

Work bound: a task's response-time iteration takes at most
:data:`~rosaadl.analysis.work_bounds.RTA_STEP_LIMIT` fixed-point steps (a busy period at
utilisation exactly 1 can last the whole hyperperiod). Past it, a response time already above
the deadline is reported as a lower bound (``>=X``, a miss); otherwise the task is undecided,
a warning names it, and the utilisation test gives the verdict.
"""

from __future__ import annotations

import heapq
import itertools
import logging
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

from rosaadl.analysis.edf_response import bounded_edf_response_times, edf_blocking_times
from rosaadl.analysis.registry import Analysis, AnalysisContext, register
from rosaadl.analysis.rendering import csv_text, fmt, short_path, table
from rosaadl.analysis.tasks import (
    Processor,
    Protocol,
    Scheduler,
    Task,
    TaskSet,
    Time,
    exact_time,
    taskset_from_instance,
    time_base,
)
from rosaadl.analysis.work_bounds import RTA_STEP_LIMIT, StepBudget, WorkCut
from rosaadl.arguments import checked
from rosaadl.errors import Diagnostic, Location, ModelError

__all__ = [
    "utilization",
    "utilization_by_deadline",
    "is_harmonic",
    "liu_layland_bound",
    "within_liu_layland",
    "utilization_bound",
    "utilization_test",
    "non_preemptive_rm_failures",
    "hyperperiod",
    "FeasibilityInterval",
    "feasibility_interval",
    "unused_units",
    "rate_monotonic_priorities",
    "deadline_monotonic_priorities",
    "assign_priorities",
    "response_times",
    "bounded_response_times",
    "blocking_times",
    "TaskRow",
    "DomainResult",
    "SchedulabilityResult",
    "analyze_schedulability",
]

log = logging.getLogger(__name__)


# =============================================================================== utilisation


def _recurrent(tasks: Iterable[Task]) -> list[Task]:
    return [t for t in tasks if t.period is not None]


def utilization(tasks: Iterable[Task]) -> Fraction:
    """Σ C/T over the tasks with a period (Cheddar's "processor utilization factor with period")."""
    return sum((t.utilization for t in tasks), Fraction(0))


def utilization_by_deadline(tasks: Iterable[Task]) -> Fraction:
    """Σ C/D (Cheddar's "processor utilization factor with deadline")."""
    return sum(
        (Fraction(t.capacity) / t.deadline for t in tasks if t.deadline is not None),
        Fraction(0),
    )


def is_harmonic(periods: Iterable[Time]) -> bool:
    """Every period divides every longer one (Cheddar's harmonic test)."""
    ordered = sorted(set(periods))
    return all((b / Fraction(a)).denominator == 1 for a, b in zip(ordered, ordered[1:], strict=False))


def liu_layland_bound(n: int) -> float:
    """n(2^{1/n} − 1), for display (verdicts use :func:`within_liu_layland`)."""
    if n <= 0:
        return 1.0
    return n * (2.0 ** (1.0 / n) - 1.0)


def within_liu_layland(u: Fraction, n: int) -> bool:
    """u ≤ n(2^{1/n} − 1), decided exactly: (u/n + 1)^n ≤ 2."""
    if n <= 0:
        return u <= 0
    if u < 0:
        return True
    return (Fraction(u) / n + 1) ** n <= 2


def utilization_bound(scheduler: Scheduler, tasks: Sequence[Task]) -> tuple[float, bool]:
    """(bound, harmonic): Cheddar's bound for ``scheduler`` on ``tasks``."""
    periodic = _recurrent(tasks)
    harmonic = is_harmonic(t.period for t in periodic) if periodic else True
    if not scheduler.fixed_priority:
        return 1.0, harmonic
    if harmonic:
        return 1.0, True
    return liu_layland_bound(len(periodic)), False


def utilization_test(scheduler: Scheduler, preemptive: bool, tasks: Sequence[Task]) -> bool | None:
    """Cheddar's utilisation-factor feasibility test (None where Cheddar has none, or where
    Jeffay's non-preemptive EDF condition passes its work bound of RTA_STEP_LIMIT × n points)."""
    periodic = _recurrent(tasks)
    if not periodic:
        return True
    n = len(periodic)
    harmonic = is_harmonic(t.period for t in periodic)
    if preemptive:
        if scheduler is Scheduler.RATE_MONOTONIC:
            u = utilization(periodic)
            return u <= 1 if harmonic else within_liu_layland(u, n)
        if scheduler is Scheduler.DEADLINE_MONOTONIC:
            u = utilization_by_deadline(periodic)
            return u <= 1 if harmonic else within_liu_layland(u, n)
        if scheduler in (Scheduler.EARLIEST_DEADLINE_FIRST, Scheduler.LEAST_LAXITY_FIRST):
            return utilization_by_deadline(periodic) <= 1
        return None
    if scheduler is Scheduler.RATE_MONOTONIC:
        return _non_preemptive_rm_test(periodic)
    if scheduler is Scheduler.EARLIEST_DEADLINE_FIRST:
        return _non_preemptive_edf_test(periodic)
    return None


def _non_preemptive_rm_test(tasks: list[Task]) -> bool:
    return not non_preemptive_rm_failures(tasks)


def non_preemptive_rm_failures(tasks: Sequence[Task]) -> list[str]:
    """Tasks failing Cheddar's non-preemptive RM utilisation condition: for each task i by
    increasing period, Σ_{j<=i} C_j/T_j + max_{k>i} C_k / T_i <= i(2^{1/i} - 1)."""
    ordered = sorted(_recurrent(tasks), key=lambda t: t.period)
    failing = []
    for i, task in enumerate(ordered):
        u = utilization(ordered[: i + 1])
        later = [t.capacity for t in ordered[i + 1 :]]
        if later:
            u += Fraction(max(later)) / task.period
        if not within_liu_layland(u, i + 1):
            failing.append(task.name)
    return failing


def _non_preemptive_edf_test(tasks: list[Task]) -> bool | None:
    # Jeffay, Stanat and Martel (1991) for D = T: U <= 1 and, for every task i and every
    # L in (T_1, T_i): C_i + Σ_{j<i} floor((L-1)/T_j) C_j <= L (tasks by increasing period).
    if any(t.deadline != t.period for t in tasks):
        return None
    if utilization(tasks) > 1:
        return False
    base = time_base(t.period for t in tasks) * time_base(t.capacity for t in tasks)
    ordered = sorted(tasks, key=lambda t: t.period)
    periods = [int(t.period * base) for t in ordered]
    capacities = [int(t.capacity * base) for t in ordered]
    first = periods[0]
    budget = RTA_STEP_LIMIT * len(ordered)  # the work bound: past it the test has no verdict
    for i in range(1, len(ordered)):
        # The demand only grows at L = k T_j + 1: checking those L (and the first) is exact.
        steps = heapq.merge(
            *(range((first // periods[j] + 1) * periods[j] + 1, periods[i], periods[j]) for j in range(i))
        )
        for length in itertools.chain((first + 1,), steps):
            budget -= 1
            if budget < 0:
                return None
            demand = capacities[i] + sum((length - 1) // periods[j] * capacities[j] for j in range(i))
            if demand > length:
                return False
    return True


# =============================================================================== feasibility interval


@dataclass(frozen=True)
class FeasibilityInterval:
    """The interval to simulate: ``length`` time units from 0; ``validated`` is False when no
    published result proves it sufficient for this scheduler and task model (Cheddar's flag)."""

    length: Time
    validated: bool
    reference: str


def hyperperiod(periods: Iterable[Time]) -> Time:
    """The least common multiple of exact periods (integers or fractions)."""
    return _lcm(periods)


def _lcm(values: Iterable[Time]) -> Time:
    result: Fraction = Fraction(1)
    first = True
    for value in values:
        value = Fraction(value)
        if first:
            result, first = value, False
            continue
        result = Fraction(
            math.lcm(result.numerator, value.numerator), math.gcd(result.denominator, value.denominator)
        )
    return exact_time(result)


def feasibility_interval(
    tasks: Sequence[Task], scheduler: Scheduler = Scheduler.FIXED_PRIORITY, *, independent: bool = True
) -> FeasibilityInterval | None:
    """Cheddar's feasibility interval for the tasks of one processor (None without periodic tasks).

    lcm of the periods; when some task has a non-zero first release (offset), 2·lcm + max offset
    (Leung and Merrill 1980); for EDF with constrained deadlines and independent tasks, Goossens
    and Devillers' S_n + lcm.
    """
    periodic = _recurrent(tasks)
    if not periodic:
        return None
    hyper = _lcm(t.period for t in periodic)
    max_offset = max(t.offset for t in periodic)
    with_offset = hyper if max_offset == 0 else exact_time(2 * hyper + max_offset)
    constrained = all(t.deadline <= t.period for t in periodic)
    if scheduler is Scheduler.EARLIEST_DEADLINE_FIRST:
        if constrained and independent:
            return FeasibilityInterval(
                exact_time(_goossens_devillers(periodic) + hyper), True, "Goossens and Devillers (1997)"
            )
        if not constrained:
            return FeasibilityInterval(with_offset, True, "Goossens and Devillers (1999)")
    if scheduler.fixed_priority and constrained and independent:
        return FeasibilityInterval(with_offset, True, "Leung and Merrill (1980)")
    if constrained and not independent and scheduler is not Scheduler.LEAST_LAXITY_FIRST:
        return FeasibilityInterval(
            with_offset, True, "Choquet-Geniet and Grolleau (2004), Bado et al. (2012)"
        )
    return FeasibilityInterval(with_offset, False, "Leung and Merrill (1980)")


def _goossens_devillers(tasks: list[Task]) -> Time:
    # S_1 = O_1; S_i = max(O_i, O_i + ceil((S_{i-1} - O_i) / T_i) T_i), tasks by decreasing priority.
    ordered = sorted(tasks, key=lambda t: -t.priority)
    s = Fraction(ordered[0].offset)
    for task in ordered[1:]:
        candidate = math.ceil((s - task.offset) / Fraction(task.period)) * task.period + task.offset
        s = Fraction(max(task.offset, candidate))
    return exact_time(s)


def unused_units(tasks: Sequence[Task], length: Time) -> Time:
    """Time units of [0, length) not demanded by the jobs released in it (negative when overloaded)."""
    demand = Fraction(0)
    for task in tasks:
        if task.offset >= length:
            continue
        if task.period is None:
            demand += task.capacity
        else:
            demand += math.ceil((length - task.offset) / Fraction(task.period)) * task.capacity
    return exact_time(length - demand)


# =============================================================================== priorities


def _monotonic(tasks: Sequence[Task], attribute: str) -> dict[str, int]:
    # Cheddar: sort by decreasing period (deadline), number from 1; the shortest gets n.
    # Equal keys: the task listed first gets the higher priority.
    indexed = [(i, t) for i, t in enumerate(tasks) if getattr(t, attribute) is not None]
    ordered = sorted(indexed, key=lambda it: (-Fraction(getattr(it[1], attribute)), -it[0]))
    return {task.name: number for number, (_, task) in enumerate(ordered, start=1)}


def rate_monotonic_priorities(tasks: Sequence[Task]) -> dict[str, int]:
    """Cheddar's rate-monotonic priorities: 1 for the longest period, n for the shortest."""
    return _monotonic(tasks, "period")


def deadline_monotonic_priorities(tasks: Sequence[Task]) -> dict[str, int]:
    """Cheddar's deadline-monotonic priorities: 1 for the longest deadline, n for the shortest."""
    return _monotonic(tasks, "deadline")


def assign_priorities(taskset: TaskSet) -> TaskSet:
    """The task set with RM / DM priorities set on every RM / DM domain (others unchanged)."""
    new: dict[str, int] = {}
    for processor, _core, tasks in taskset.domains():
        if processor.scheduler is Scheduler.RATE_MONOTONIC:
            new.update(rate_monotonic_priorities(tasks))
        elif processor.scheduler is Scheduler.DEADLINE_MONOTONIC:
            new.update(deadline_monotonic_priorities(tasks))
    return taskset.with_priorities(new) if new else taskset


# =============================================================================== response times


def _ceil_div(a: int, b: int) -> int:
    return -(-a // b)


def response_times(
    tasks: Sequence[Task], *, preemptive: bool = True, step_limit: int = RTA_STEP_LIMIT
) -> dict[str, Time | None]:
    """Worst-case response time of every task with a period, under fixed priorities (larger
    number = higher priority); None when it is unbounded (the higher-or-equal priority load
    saturates the processor) or when its analysis passed the work bound (``step_limit``
    fixed-point steps per task, :mod:`~rosaadl.analysis.work_bounds`; see
    :func:`bounded_response_times` for what was found before the cut).

    Preemptive (Cheddar's equation, Tindell's busy window with arbitrary deadlines)::

        w(q) = (q+1) C_i + B_i + Σ_{j ∈ hp(i)} ⌈(w(q) + J_j) / T_j⌉ C_j
        R_i  = max_q  w(q) + J_i − q T_i,   q = 0, 1, … while w(q) > (q+1) T_i − J_i

    Non-preemptive (George, Rivierre and Spuri; Cheddar's discrete-time blocking)::

        B_i  = max(max_{j ∈ lp(i)} C_j − 1, blocking_i)
        w(q) = B_i + q C_i + Σ_{j ∈ hp(i)} (⌊(w(q) + J_j) / T_j⌋ + 1) C_j
        R_i  = max_{q ≤ ⌊L_i / T_i⌋}  w(q) + C_i + J_i − q T_i

    where L_i is the level-i busy period. Tasks of *equal* priority count as interference
    (Cheddar counts only strictly higher ones; with distinct priorities both agree).
    """
    values, cut = bounded_response_times(tasks, preemptive=preemptive, step_limit=step_limit)
    return {name: None if name in cut else value for name, value in values.items()}


def bounded_response_times(
    tasks: Sequence[Task], *, preemptive: bool = True, step_limit: int = RTA_STEP_LIMIT
) -> tuple[dict[str, Time | None], dict[str, Time]]:
    """(response times, cut): :func:`response_times`, where a task whose busy window needs more
    than ``step_limit`` fixed-point steps is cut: ``cut`` maps it to the largest response time
    found before the cut (a lower bound of its worst case), and its value is that bound."""
    periodic = _recurrent(tasks)
    cut: dict[str, Time] = {}
    if not periodic:
        return {}, cut
    base = time_base(v for t in periodic for v in (t.period, t.capacity, t.jitter, t.blocking))
    order = sorted(range(len(periodic)), key=lambda i: -periodic[i].priority)
    prio = [periodic[i].priority for i in order]
    period = [int(periodic[i].period * base) for i in order]
    cost = [int(periodic[i].capacity * base) for i in order]
    jitter = [int(periodic[i].jitter * base) for i in order]
    block = [int(periodic[i].blocking * base) for i in order]
    n = len(order)
    results: dict[str, Time | None] = {}
    # Utilisation of the first k tasks (by decreasing priority): floats, made exact near 1.
    prefix_u = [0.0]
    for k in range(n):
        prefix_u.append(prefix_u[-1] + cost[k] / period[k])
    # Start of the fixed-point iteration: any value below the least fixed point is valid. When
    # the previous task has a strictly higher priority, no tie and no blocking, its own window
    # w' = C' + Σ_{hp'} ... is below the level's busy window, so w' + C_i + B_i is a valid start.
    hint: int | None = None
    jitter_seen = [False]
    for k in range(n):
        jitter_seen.append(jitter_seen[-1] or jitter[k] != 0)
    lower_max = [0] * (n + 1)  # largest capacity among positions >= k
    for k in range(n - 1, -1, -1):
        lower_max[k] = max(lower_max[k + 1], cost[k])
    for pos in range(n):
        p = prio[pos]
        # hep(i) \ {i}: every other task whose priority is >= p (ties included).
        end = pos + 1
        while end < n and prio[end] == p:
            end += 1
        tied = end - pos > 1 or (pos > 0 and prio[pos - 1] == p)
        t_i, c_i, j_i = period[pos], cost[pos], jitter[pos]
        u_level = _level_utilization(prefix_u[end], cost, period, end)
        # Non-preemptive: a lower-priority job started one tick before (Cheddar's max C - 1).
        b_i = block[pos] if preemptive else max(lower_max[end] - 1, block[pos], 0)
        name = periodic[order[pos]].name
        if u_level > 1 or (u_level == 1 and (b_i > 0 or jitter_seen[end])):
            results[name] = None
            hint = None
            continue
        if tied:
            hp_t = period[:pos] + period[pos + 1 : end]
            hp_c = cost[:pos] + cost[pos + 1 : end]
            hp_j = jitter[:pos] + jitter[pos + 1 : end]
        else:
            hp_t, hp_c, hp_j = period[:pos], cost[:pos], jitter[:pos]
        budget = StepBudget(step_limit)
        budget.found(c_i + j_i)
        try:
            if preemptive:
                start = c_i + b_i + sum(hp_c)
                if hint is not None and not tied:
                    start = max(start, hint + c_i + b_i)
                r, w0 = _preemptive_rta(t_i, c_i, j_i, b_i, hp_t, hp_c, hp_j, start, budget)
                hint = w0 if (b_i == 0 and not tied) else None
            else:
                r = _non_preemptive_rta(t_i, c_i, j_i, b_i, hp_t, hp_c, hp_j, budget)
        except WorkCut as stop:
            r, hint = stop.at_least, None
            cut[name] = exact_time(Fraction(r, base))
        results[name] = exact_time(Fraction(r, base))
    return {t.name: results[t.name] for t in periodic}, cut


def _level_utilization(approx: float, cs: list[int], ts: list[int], count: int) -> Fraction | float:
    """Σ C/T of the first ``count`` tasks, exact when it is within rounding distance of 1 (the
    only value it is compared with)."""
    if abs(approx - 1.0) > 1e-9 * (count + 1):
        return approx
    return sum((Fraction(c, t) for c, t in zip(cs[:count], ts[:count], strict=True)), Fraction(0))


def _preemptive_rta(
    t_i: int,
    c_i: int,
    j_i: int,
    b_i: int,
    ts: list[int],
    cs: list[int],
    js: list[int],
    start: int,
    budget: StepBudget,
) -> tuple[int, int]:
    """(worst response time, window of the first job) by Cheddar's busy-window iteration."""
    jittery = any(js)
    pairs = list(zip(ts, cs, strict=True))
    triples = list(zip(ts, cs, js, strict=True)) if jittery else []
    w = start
    worst = 0
    first = 0
    q = 0
    while True:
        base_term = (q + 1) * c_i + b_i
        while True:
            budget.spend()
            if jittery:
                new = base_term + sum([-((-(w + j)) // t) * c for t, c, j in triples])
            else:
                new = base_term + sum([-(-w // t) * c for t, c in pairs])
            if new == w:
                break
            w = new
        if q == 0:
            first = w
        worst = max(worst, w + j_i - q * t_i)
        budget.found(worst)
        if w <= (q + 1) * t_i - j_i:
            return worst, first
        q += 1
        w += c_i  # w(q+1) >= w(q) + C_i


def _non_preemptive_rta(
    t_i: int, c_i: int, j_i: int, b_i: int, ts: list[int], cs: list[int], js: list[int], budget: StepBudget
) -> int:
    # Level-i busy period (blocking included, conservative against Cheddar's).
    all_t, all_c, all_j = ts + [t_i], cs + [c_i], js + [j_i]
    length = max(c_i + b_i, 1)
    while True:
        budget.spend()
        new = b_i + sum(-((-(length + j)) // t) * c for t, c, j in zip(all_t, all_c, all_j, strict=True))
        if new == length:
            break
        length = new
    last_q = length // t_i
    worst = 0
    w = b_i
    for q in range(last_q + 1):
        w = max(w, b_i + q * c_i)
        while True:
            budget.spend()
            new = b_i + q * c_i + sum(((w + j) // t + 1) * c for t, c, j in zip(ts, cs, js, strict=True))
            if new == w:
                break
            w = new
        worst = max(worst, w + c_i + j_i - q * t_i)
        budget.found(worst)
    return worst


# =============================================================================== blocking


def blocking_times(tasks: Sequence[Task], taskset: TaskSet) -> dict[str, Time | None]:
    """Worst-case blocking of each task by lower-priority tasks of the same domain through
    shared resources, at least the task's own ``blocking``; None when it is unbounded (a
    resource without access protocol shared with a lower-priority task while a task of
    intermediate priority exists: priority inversion).

    PCP and IPCP: the longest critical section (outermost, where nested) of a lower-priority
    task on a resource whose ceiling is at least the task's priority. PIP: the lesser of the
    sum over such resources of their longest lower-priority section and the sum over
    lower-priority tasks of their longest such section.
    """
    used = {s.resource for t in tasks for s in t.critical_sections}
    ceiling: dict[str, int] = {}
    for name in used:
        declared = taskset.resource(name).ceiling
        users = [t.priority for t in tasks if name in t.resources]
        ceiling[name] = declared if declared is not None else max(users)
    result: dict[str, Time | None] = {}
    for task in tasks:
        by_resource: dict[str, Time] = {}
        by_task: dict[str, Time] = {}
        unbounded = False
        pcp_only = True
        for other in tasks:
            if other.priority >= task.priority or not other.critical_sections:
                continue
            for section in other.critical_sections:
                if ceiling[section.resource] < task.priority:
                    continue
                protocol = taskset.resource(section.resource).protocol
                if protocol is Protocol.NONE and any(
                    other.priority < k.priority < task.priority for k in tasks
                ):
                    unbounded = True
                if protocol in (Protocol.PIP, Protocol.NONE):
                    pcp_only = False
                length = other.outermost_section(section)
                by_resource[section.resource] = max(by_resource.get(section.resource, 0), length)
                by_task[other.name] = max(by_task.get(other.name, 0), length)
        if unbounded:
            result[task.name] = None
            continue
        if not by_task:
            computed: Time = 0
        elif pcp_only:
            computed = max(by_task.values())
        else:
            computed = min(sum(by_resource.values()), sum(by_task.values()))
        result[task.name] = max(task.blocking, computed)
    return result


# =============================================================================== the analysis


@dataclass(frozen=True)
class TaskRow:
    """One task of a domain: parameters (priorities after RM/DM assignment), utilisation and
    worst-case response time (None: unbounded, not analysed or not decided within the work
    bound; a lower bound when ``wcrt_exact`` is False)."""

    name: str
    path: str
    priority: int
    period: Time | None
    capacity: Time
    deadline: Time | None
    offset: Time
    jitter: Time
    blocking: Time
    utilization: Fraction
    wcrt: Time | None
    met: bool | None
    wcrt_exact: bool = True  #: False: ``wcrt`` is a lower bound (the analysis passed its work bound)

    def as_dict(self) -> dict[str, Any]:
        extra = {} if self.wcrt_exact else {"wcrt_at_least": True}
        return {
            "path": self.path,
            "priority": self.priority,
            "period": _number(self.period),
            "capacity": _number(self.capacity),
            "deadline": _number(self.deadline),
            "wcrt": _number(self.wcrt),
            "met": self.met,
            **extra,
        }


def _number(value: Time | None) -> int | float | None:
    if value is None or isinstance(value, int):
        return value
    return float(value)


@dataclass(frozen=True)
class DomainResult:
    """The feasibility tests of one processor (or one core of a partitioned multi-core one)."""

    processor: str
    core: str
    path: str
    scheduler: Scheduler
    preemptive: bool
    tasks: tuple[TaskRow, ...]
    utilization: Fraction
    utilization_by_deadline: Fraction
    harmonic: bool
    bound: float
    utilization_test: bool | None
    feasibility_interval: FeasibilityInterval | None
    unused_units: Time | None
    rta_schedulable: bool | None

    @property
    def schedulable(self) -> bool | None:
        """The response-time verdict where there is one, else the utilisation test's."""
        return self.rta_schedulable if self.rta_schedulable is not None else self.utilization_test

    @property
    def priorities(self) -> dict[str, int]:
        return {row.name: row.priority for row in self.tasks}

    def as_dict(self) -> dict[str, Any]:
        interval = self.feasibility_interval
        return {
            "path": f"{self.path}.{self.core}" if self.core else self.path,
            "scheduler": self.scheduler.value,
            "utilization": float(self.utilization),
            "bound": self.bound,
            "feasibility_interval": _number(interval.length) if interval else None,
            "tasks": [row.as_dict() for row in self.tasks],
        }


@dataclass(frozen=True)
class SchedulabilityResult:
    """Per-domain results, in declaration order, and the diagnostics of the whole analysis."""

    domains: tuple[DomainResult, ...]
    diagnostics: tuple[Diagnostic, ...]
    time_unit: str

    @property
    def ok(self) -> bool:
        return all(d.severity != "error" for d in self.diagnostics) and all(
            dom.schedulable is not False for dom in self.domains
        )

    @property
    def decided(self) -> bool:
        """Every domain got a verdict (schedulable or not): a simulation cut short adds nothing."""
        return bool(self.domains) and all(dom.schedulable is not None for dom in self.domains)

    def domain(self, processor: str, core: str = "") -> DomainResult:
        for dom in self.domains:
            if dom.processor == processor and dom.core == core:
                return dom
        raise ModelError(f"no scheduling domain {processor!r} {core!r}")

    def as_dict(self) -> dict[str, Any]:
        return {"processors": [d.as_dict() for d in self.domains]}


_UNBOUNDED_BLOCKING = {
    "fp": "a lower-priority task shares a resource without access protocol with it while a task "
    "of intermediate priority exists",
    "edf": "a task with a later deadline shares a resource without access protocol with it while "
    "a third task runs on the processor",
}


def _uses_resources(tasks: Sequence[Task]) -> bool:
    return any(t.critical_sections for t in tasks)


def _analyze_domain(
    taskset: TaskSet, processor: Processor, core: str, tasks: tuple[Task, ...], diagnostics: list[Diagnostic]
) -> DomainResult:
    scheduler = processor.scheduler
    where = Location(path=f"{processor.path}.{core}" if core else processor.path)
    if scheduler is Scheduler.RATE_MONOTONIC:
        tasks = tuple(replace(t, priority=p) for t, p in zip(tasks, _prio_list(tasks, "period"), strict=True))
    elif scheduler is Scheduler.DEADLINE_MONOTONIC:
        tasks = tuple(
            replace(t, priority=p) for t, p in zip(tasks, _prio_list(tasks, "deadline"), strict=True)
        )
    periodic = _recurrent(tasks)
    for task in tasks:
        if task.period is None:
            diagnostics.append(
                Diagnostic(
                    "warning",
                    f"{task.dispatch.value} task without period: left out of the feasibility tests",
                    Location(path=task.path),
                )
            )
    bound, harmonic = utilization_bound(scheduler, periodic)
    verdict = utilization_test(scheduler, processor.preemptive, periodic)
    interval = feasibility_interval(periodic, scheduler, independent=not _uses_resources(periodic))
    unused = unused_units(periodic, interval.length) if interval else None
    wcrt: dict[str, Time | None] = {}
    cut: dict[str, Time] = {}
    rta: bool | None = None
    unbounded_blocking: set[str] = set()
    edf = scheduler is Scheduler.EARLIEST_DEADLINE_FIRST
    if (scheduler.fixed_priority or edf) and periodic and processor.preemptive and _uses_resources(periodic):
        blocking = edf_blocking_times(periodic, taskset) if edf else blocking_times(periodic, taskset)
        unbounded_blocking = {name for name, b in blocking.items() if b is None}
        tasks = tuple(
            replace(t, blocking=blocking[t.name]) if blocking.get(t.name) is not None else t for t in tasks
        )
        periodic = _recurrent(tasks)
        for task in periodic:
            if task.name in unbounded_blocking:
                diagnostics.append(
                    Diagnostic(
                        "warning",
                        f"{_UNBOUNDED_BLOCKING['edf' if edf else 'fp']}: its blocking is unbounded, no "
                        "response time is computed",
                        Location(path=task.path),
                    )
                )
    if (scheduler.fixed_priority or edf) and periodic:
        if edf:
            wcrt, cut = bounded_edf_response_times(periodic, preemptive=processor.preemptive)
        else:
            wcrt, cut = bounded_response_times(periodic, preemptive=processor.preemptive)
        for name in unbounded_blocking:
            wcrt.pop(name, None)
            cut.pop(name, None)
        undecided = set(unbounded_blocking)
        for task in periodic:
            if task.name in cut and cut[task.name] <= task.deadline:
                # cut before the busy period ended, no miss found yet: not decided
                undecided.add(task.name)
                wcrt.pop(task.name, None)
                diagnostics.append(
                    Diagnostic(
                        "warning",
                        f"response-time analysis cut after {RTA_STEP_LIMIT} steps (work bound) "
                        f"before the busy period ended: response time at least "
                        f"{cut[task.name]} {taskset.time_unit}, not decided",
                        Location(path=task.path),
                    )
                )
        rta = all(
            wcrt.get(t.name) is not None and wcrt[t.name] <= t.deadline
            for t in periodic
            if t.name not in undecided
        )
        if undecided and rta:
            rta = None  # the others meet their deadlines; these cannot be bounded or decided
        if scheduler is Scheduler.FIXED_PRIORITY and len({t.priority for t in periodic}) < len(periodic):
            diagnostics.append(
                Diagnostic(
                    "info",
                    "tasks share a priority: each counts the others as interference "
                    "(Cheddar counts only strictly higher priorities)",
                    where,
                )
            )
    rows = []
    for task in tasks:
        r = wcrt.get(task.name)
        met = None
        if task.name in wcrt:
            met = r is not None and r <= task.deadline
            if not met:
                text = "unbounded" if r is None else f"{r} {taskset.time_unit}"
                if task.name in cut:
                    text = (
                        f"at least {r} {taskset.time_unit} (analysis cut after "
                        f"{RTA_STEP_LIMIT} steps, the work bound)"
                    )
                diagnostics.append(
                    Diagnostic(
                        "error",
                        f"worst-case response time {text} exceeds the deadline "
                        f"{task.deadline} {taskset.time_unit}",
                        Location(path=task.path),
                    )
                )
        rows.append(
            TaskRow(
                task.name,
                task.path,
                task.priority,
                task.period,
                task.capacity,
                task.deadline,
                task.offset,
                task.jitter,
                task.blocking,
                task.utilization,
                r,
                met,
                task.name not in cut or r is None,
            )
        )
    u = utilization(periodic)
    if verdict is False and rta is None:
        diagnostics.append(
            Diagnostic(
                "error", f"utilisation {float(u):.5f} fails the {scheduler.value} feasibility test", where
            )
        )
    elif verdict is False:
        diagnostics.append(
            Diagnostic("info", _utilisation_note(scheduler, processor.preemptive, periodic, bound), where)
        )
    if interval is not None and not interval.validated:
        diagnostics.append(
            Diagnostic(
                "info",
                "no published feasibility interval for this task model; lcm-based interval used",
                where,
            )
        )
    return DomainResult(
        processor.name,
        core,
        processor.path,
        scheduler,
        processor.preemptive,
        tuple(rows),
        u,
        utilization_by_deadline(periodic),
        harmonic,
        bound,
        verdict,
        interval,
        unused,
        rta,
    )


def _utilisation_note(scheduler: Scheduler, preemptive: bool, tasks: Sequence[Task], bound: float) -> str:
    """Why the utilisation test failed while the response times decide, in the test's terms."""
    u = utilization(tasks)
    if scheduler is Scheduler.EARLIEST_DEADLINE_FIRST:
        if u > 1:
            return f"utilisation {float(u):.5f} is above 1: the processor is overloaded"
        if not preemptive:
            return (
                f"Jeffay's non-preemptive condition fails (utilisation {float(u):.5f}): "
                "the response times decide"
            )
        return (
            f"utilisation by deadline {float(utilization_by_deadline(tasks)):.5f} is above 1: the "
            "utilisation test is inconclusive, the response times decide"
        )
    return (
        f"utilisation {float(u):.5f} is above the bound {bound:.5f}: the utilisation test is "
        "inconclusive, the response times decide"
    )


def _prio_list(tasks: Sequence[Task], attribute: str) -> list[int]:
    mapping = _monotonic(tasks, attribute)
    return [mapping.get(t.name, t.priority) for t in tasks]


@checked
def analyze_schedulability(source: TaskSet | Any, *, time_unit: str = "us") -> SchedulabilityResult:
    """Cheddar's feasibility tests on every processor and core of ``source`` (a TaskSet, or an
    instance model read with :func:`~rosaadl.analysis.tasks.taskset_from_instance`)."""
    taskset = source if isinstance(source, TaskSet) else taskset_from_instance(source, time_unit=time_unit)
    diagnostics = list(taskset.diagnostics)
    domains = []
    for processor, core, tasks in taskset.domains():
        if not tasks:
            continue
        domains.append(_analyze_domain(taskset, processor, core, tasks, diagnostics))
        log.debug("analysed %s %s: %d tasks", processor.path, core, len(tasks))
    return SchedulabilityResult(tuple(domains), tuple(diagnostics), taskset.time_unit)


# =============================================================================== report


def schedulability_text(result: SchedulabilityResult) -> list[str]:
    """The ``Schedulability`` section of the text report."""
    lines = ["Schedulability", ""]
    for dom in result.domains:
        where = short_path(dom.path) + (f".{dom.core}" if dom.core else "")
        interval = dom.feasibility_interval.length if dom.feasibility_interval else None
        lines.append(
            f"{where}: {dom.scheduler.value}, utilization {fmt(dom.utilization, 4)}, "
            f"bound {fmt(dom.bound, 4)}, feasibility interval {fmt(interval)} "
            f"{result.time_unit}, schedulable {fmt(dom.schedulable)}"
        )
        rows = [
            [short_path(t.path), t.priority, t.period, t.capacity, t.deadline, _wcrt_cell(t), t.met]
            for t in dom.tasks
        ]
        lines += table(["task", "priority", "period", "capacity", "deadline", "WCRT", "met"], rows)
        lines.append("")
    return lines


def _wcrt_cell(row: TaskRow) -> Any:
    """The WCRT as shown: ``>=X`` when it is a lower bound (the analysis passed its work bound)."""
    return row.wcrt if row.wcrt_exact else f">={fmt(row.wcrt)}"


def schedulability_csv(result: SchedulabilityResult, base: str) -> dict[str, str]:
    """``<base>__Schedulability.csv``: one row per task with its domain, scheduler and WCRT."""
    rows: list[list[Any]] = [
        ["Processor", "Scheduler", "Task", "Priority", "Period", "Capacity", "Deadline", "WCRT", "Met"]
    ]
    for dom in result.domains:
        where = dom.path + (f".{dom.core}" if dom.core else "")
        for t in dom.tasks:
            rows.append(
                [
                    where,
                    dom.scheduler.value,
                    t.path,
                    t.priority,
                    t.period,
                    t.capacity,
                    t.deadline,
                    _wcrt_cell(t),
                    t.met,
                ]
            )
    return {f"{base}__Schedulability.csv": csv_text(rows)}


def unschedulable_domains(result: SchedulabilityResult) -> list[Diagnostic]:
    """An error for each domain the feasibility tests find not schedulable."""
    verdicts = []
    for dom in result.domains:
        if dom.schedulable is False:
            where = dom.path + (f".{dom.core}" if dom.core else "")
            verdicts.append(
                Diagnostic(
                    "error",
                    f"not schedulable under {dom.scheduler.value} "
                    f"(utilization {float(dom.utilization):.4f}, bound {dom.bound:.4f})",
                    Location(path=where),
                )
            )
    return verdicts


def _run(context: AnalysisContext) -> SchedulabilityResult | None:
    taskset = context.taskset
    return analyze_schedulability(taskset) if taskset is not None else None


register(
    Analysis(
        name="sched",
        json_key="schedulability",
        order=40,
        run=_run,
        text=schedulability_text,
        csv=schedulability_csv,
        verdicts=unschedulable_domains,
        aliases=("schedulability",),
        description="Cheddar's feasibility tests: utilisation bounds, feasibility interval, response times",
    )
)
