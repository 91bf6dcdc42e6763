"""Worst-case response times under EDF: deadline busy periods and candidate release offsets.

The bound of every periodic (or sporadic) task of one processor scheduled by earliest deadline
first, with arbitrary deadlines (D may exceed T), release jitter J and a blocking time B:

* preemptive: M. Spuri, "Analysis of Deadline Scheduled Real-Time Systems", INRIA RR-2772
  (1996), the analysis Cheddar's feasibility tests run for EDF;
* non-preemptive: L. George, N. Rivierre and M. Spuri, "Preemptive and Non-Preemptive
  Real-Time Uniprocessor Scheduling", INRIA RR-2966 (1996), Cheddar's non-preemptive case.

The job of task i under analysis arrives at time ``a`` of a busy period that starts at 0, so
its absolute deadline is a + D_i. Only jobs with an absolute deadline at most a + D_i delay it
(the job loses every tie), so the *deadline busy period* L_i(a) counts, for each other task j,
the jobs released in the period, at most those whose deadline is at most a + D_i::

    W_i(a, t) = Σ_{j ≠ i, D_j − J_j ≤ a + D_i} min(⌈(t + J_j) / T_j⌉, 1 + ⌊(a + D_i − D_j + J_j) / T_j⌋) C_j

:func:`deadline_busy_period` solves L_i(a) (see there), :func:`release_offsets` gives the
candidates for ``a``, and :func:`edf_response_times` takes the largest response over them::

    R_i = max(C_i + J_i, max_{a ∈ A_i} r_i(a))

Where Cheddar differs (``feasibility_test-periodic_task_worst_case_response_time_dynamic_priority``
in Cheddar's sources, read for facts):

* it tries every ``a = k T_j + D_j − D_i`` from k = 0, negative ones included; there task i
  has no job, its iteration stays at L_i(a) = 0 and the response is ``|a|``: two tasks
  (C, T) = (1, 2), (1, 10) with D = T get 8 for the second, where Spuri and the simulation
  give 2;
* it stops a task's ``k`` at the first ``a >= L_i(a)`` rather than at the end of the busy
  period, which can miss the worst ``a`` (four tasks (C, T, D) = (1, 4, 3), (1, 5, 5),
  (1, 3, 6), (2, 15, 11): 2 for the second, where a = 7 gives 3, which the simulation reaches
  when that task starts at 2), and stops a task once its response passes its deadline;
* it ignores jitter and blocking, refuses offsets (this bound covers them: a release pattern
  with offsets is one of the sporadic patterns it bounds), and runs the same analysis for LLF,
  for which Spuri's proof does not hold (ours gives LLF no bound);
* in the non-preemptive case it adds ⌊a/T_j⌋ C_i once per other task, divides
  ``⌊a + D_i − D_j⌋`` by T_j without rounding, blocks by C_j instead of C_j − 1 and leaves
  out the job's own C_i.

Ours follows the papers.

Each task's busy periods and candidate arrivals take at most
:data:`~rosaadl.analysis.work_bounds.RTA_STEP_LIMIT` steps (:func:`bounded_edf_response_times`
says which tasks were cut, and the largest response time found before the cut).

Every time is scaled once to integers (the least common multiple of the denominators), so the
results are exact ``int`` or ``Fraction``; the non-preemptive blocking C_j − 1 is one unit of
that base, as in Cheddar's discrete time.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Iterator, Mapping, Sequence
from fractions import Fraction
from itertools import groupby, repeat
from operator import itemgetter
from typing import NamedTuple

from rosaadl.analysis.tasks import Protocol, Task, TaskSet, Time, exact_time, time_base
from rosaadl.analysis.work_bounds import RTA_STEP_LIMIT, StepBudget, WorkCut
from rosaadl.errors import Location, ModelError

__all__ = [
    "synchronous_busy_period",
    "release_offsets",
    "deadline_busy_period",
    "edf_response_times",
    "bounded_edf_response_times",
    "edf_blocking_times",
]


class _Scaled(NamedTuple):
    """The tasks with a period, every time multiplied by ``base`` (integers)."""

    tasks: list[Task]
    base: int
    period: list[int]
    cost: list[int]
    deadline: list[int]
    jitter: list[int]
    blocking: list[int]


def _scaled(
    tasks: Sequence[Task], blocking: Mapping[str, Time] | None = None, extra: Sequence[Time] = ()
) -> _Scaled:
    """The tasks with a period, scaled by a base in which ``extra`` times are whole too."""
    periodic = [t for t in tasks if t.period is not None]
    given = [blocking.get(t.name, t.blocking) if blocking else t.blocking for t in periodic]
    base = time_base(
        [v for t in periodic for v in (t.period, t.capacity, t.deadline, t.jitter, t.offset)]
        + given
        + [exact_time(v) for v in extra]
    )
    return _Scaled(
        periodic,
        base,
        [int(t.period * base) for t in periodic],
        [int(t.capacity * base) for t in periodic],
        [int(t.deadline * base) for t in periodic],
        [int(t.jitter * base) for t in periodic],
        [int(b * base) for b in given],
    )


def _unscaled(value: int, base: int) -> Time:
    return exact_time(Fraction(value, base))


def _ceil_div(a: int, b: int) -> int:
    return -(-a // b)


def _index(s: _Scaled, task: Task) -> int:
    for i, t in enumerate(s.tasks):
        if t.name == task.name:
            return i
    raise ModelError(f"task {task.name}: no period, no EDF response time", Location(path=task.path))


# =============================================================================== busy periods


def _utilization(s: _Scaled) -> Fraction:
    return sum((Fraction(c, t) for c, t in zip(s.cost, s.period, strict=True)), Fraction(0))


def _busy_period(s: _Scaled, blocking: int, budget: StepBudget | None = None) -> int | None:
    """Least L > 0 with L = B + Σ_j ⌈(L + J_j) / T_j⌉ C_j (None: no such L)."""
    u = _utilization(s)
    if u > 1 or (u == 1 and (blocking > 0 or any(s.jitter))):
        return None
    terms = list(zip(s.period, s.cost, s.jitter, strict=True))
    length = blocking + sum(s.cost)
    while True:
        if budget is not None:
            budget.spend()
        new = blocking + sum(_ceil_div(length + j, t) * c for t, c, j in terms)
        if new == length:
            return length
        length = new


def synchronous_busy_period(tasks: Sequence[Task], blocking: Time = 0) -> Time | None:
    """The longest busy period of the tasks with a period (Spuri's L), after a blocking time::

        L = B + Σ_j ⌈(L + J_j) / T_j⌉ C_j

    least solution, from L = B + Σ_j C_j. None when there is none (Σ C/T > 1, or = 1 with
    blocking or jitter): the busy period, hence every EDF response time, is unbounded.
    """
    s = _scaled(tasks, extra=[blocking])
    length = _busy_period(s, int(blocking * s.base))
    return None if length is None else _unscaled(length, s.base)


def _job_counts(s: _Scaled, i: int, a: int) -> list[int]:
    """Jobs of each task counted in L_i(a): for j ≠ i, 1 + ⌊(a + D_i − D_j + J_j) / T_j⌋ (at
    least 0), those with deadline <= a + D_i; for i, 1 + ⌊(a + J_i) / T_i⌋, those arriving
    in [−J_i, a]."""
    return [
        1 + (a + s.jitter[i]) // s.period[i]
        if j == i
        else max(0, 1 + (a + s.deadline[i] - s.deadline[j] + s.jitter[j]) // s.period[j])
        for j in range(len(s.tasks))
    ]


def _np_blocking(s: _Scaled, i: int, a: int) -> int:
    """max(B_i, max_{j ≠ i, D_j > a + D_i} C_j − 1): a job with a later deadline started just before."""
    later = [s.cost[j] - 1 for j in range(len(s.tasks)) if j != i and s.deadline[j] > a + s.deadline[i]]
    return max([s.blocking[i], 0, *later])


def _deadline_busy_period(
    s: _Scaled,
    i: int,
    a: int,
    counts: list[int],
    preemptive: bool,
    start: int = 0,
    budget: StepBudget | None = None,
) -> int:
    """L_i(a), iterated from ``start`` (any value below it); ``counts`` from :func:`_job_counts`."""
    terms = [
        (s.period[j], s.cost[j], s.jitter[j], cap)
        for j, cap in enumerate(counts)
        if cap > 0 and j != i  # task i's own jobs are the fixed term
    ]
    if preemptive:
        fixed = s.blocking[i] + counts[i] * s.cost[i]
        length = max(start, fixed)
        while True:
            if budget is not None:
                budget.spend()
            new = fixed
            for t, c, j, cap in terms:
                jobs = -(-(length + j) // t)  # ⌈(L + J_j) / T_j⌉
                new += (jobs if jobs < cap else cap) * c
            if new == length:
                return length
            length = new
    fixed = _np_blocking(s, i, a) + (counts[i] - 1) * s.cost[i]
    length = max(start, 0)
    while True:
        if budget is not None:
            budget.spend()
        new = fixed
        for t, c, j, cap in terms:
            jobs = 1 + (length + j) // t  # 1 + ⌊(L + J_j) / T_j⌋
            new += (jobs if jobs < cap else cap) * c
        if new == length:
            return length
        length = new


def deadline_busy_period(
    task: Task, tasks: Sequence[Task], a: Time, *, preemptive: bool = True, blocking: Time | None = None
) -> Time:
    """L_i(a) of ``task`` (i) among ``tasks``, its job arriving at ``a`` (a >= −J_i).

    Preemptive (Spuri): the end of the busy period of the jobs with deadline <= a + D_i::

        L_i(a) = B_i + W_i(a, L_i(a)) + (1 + ⌊(a + J_i) / T_i⌋) C_i

    Non-preemptive (George, Rivierre and Spuri): the latest start of the job, after a job with
    a later deadline started one unit before the period, the jobs with deadline <= a + D_i
    released up to its start (ties lost) and the earlier jobs of i::

        L_i(a) = max(B_i, max_{j ≠ i, D_j > a + D_i} C_j − 1)
                 + Σ_{j ≠ i, D_j − J_j ≤ a + D_i} min(1 + ⌊(L_i(a) + J_j) / T_j⌋,
                                                     1 + ⌊(a + D_i − D_j + J_j) / T_j⌋) C_j
                 + ⌊(a + J_i) / T_i⌋ C_i

    Least solutions: each right-hand side is non-decreasing in L and bounded, so the iteration
    from below always ends. ``blocking`` replaces the task's own B_i.
    """
    if a < -task.jitter:
        raise ModelError(f"deadline_busy_period(): a = {a} is before -J_i = {-task.jitter}")
    given = {task.name: blocking} if blocking is not None else None
    s = _scaled(_with(tasks, task), given, extra=[a])
    i = _index(s, task)
    scaled = int(a * s.base)
    return _unscaled(_deadline_busy_period(s, i, scaled, _job_counts(s, i, scaled), preemptive), s.base)


def _with(tasks: Sequence[Task], task: Task) -> list[Task]:
    """``tasks`` with ``task`` among them."""
    return [*tasks, *([task] if all(t.name != task.name for t in tasks) else [])]


# =============================================================================== candidates for a


def _demand_steps(s: _Scaled, i: int, limit: int) -> tuple[list[int], Iterator[tuple[int, list[int]]]]:
    """The jobs counted in L_i(a) as ``a`` grows from −J_i to ``limit``: the counts at −J_i
    (:func:`_job_counts`) without the jobs counted from exactly −J_i on, and, lazily and
    ascending, each point ``a`` of A_i with the tasks one more job of which counts from ``a``.

    The work of the counted jobs, plus the blocking, bounds L_i(a) from above, so the response
    at ``a`` cannot exceed that demand minus ``a``.
    """
    low = -s.jitter[i]
    counts = [0] * len(s.tasks)
    ranges = []
    for j in range(len(s.tasks)):
        first = (s.deadline[j] - s.jitter[j] - s.deadline[i]) if j != i else low
        k = max(0, _ceil_div(low - first, s.period[j]))
        counts[j] = k
        ranges.append(zip(range(first + k * s.period[j], limit + 1, s.period[j]), repeat(j)))
    merged = heapq.merge(*ranges)
    return counts, ((a, [j for _, j in group]) for a, group in groupby(merged, key=itemgetter(0)))


def _release_offsets(s: _Scaled, i: int, limit: int) -> list[int]:
    """A_i ∩ [−J_i, limit], ascending."""
    return [a for a, _ in _demand_steps(s, i, limit)[1]]


def release_offsets(task: Task, tasks: Sequence[Task], limit: Time) -> list[Time]:
    """The arrival times ``a`` of ``task`` (i) to try, up to ``limit`` (the busy period): those
    where the job's deadline a + D_i meets the deadline of a job of another task j, or where a
    job of i arrives (the points where L_i(a) can grow; between two of them L_i(a) − a only
    falls)::

        A_i = ({k T_j + D_j − J_j − D_i : j ≠ i, k ∈ N} ∪ {k T_i − J_i : k ∈ N}) ∩ [−J_i, L]

    (Spuri's set S ∩ [0, L) without jitter; the limit is taken inclusive, which adds nothing).
    """
    s = _scaled(_with(tasks, task), extra=[limit])
    i = _index(s, task)
    found = _release_offsets(s, i, math.floor(limit * s.base))
    return [_unscaled(a, s.base) for a in found]


# =============================================================================== response times


def _response_time(s: _Scaled, i: int, preemptive: bool, budget: StepBudget) -> int:
    if preemptive:
        blocking = s.blocking[i]
    else:
        blocking = max([s.blocking[i], 0, *(s.cost[j] - 1 for j in range(len(s.tasks)) if j != i)])
    budget.found(s.cost[i] + s.jitter[i])
    busy = _busy_period(s, blocking, budget)
    # One hyperperiod of a is enough: L_i(a + H) <= L_i(a) + H when U <= 1.
    limit = math.lcm(*s.period) - s.jitter[i] - 1
    if busy is not None:
        limit = min(limit, busy)
    c_i = s.cost[i]
    worst = c_i + s.jitter[i]
    budget.found(worst)
    counts, steps = _demand_steps(s, i, limit)
    demand = blocking + sum(k * c for k, c in zip(counts, s.cost, strict=True))
    previous = 0
    for a, counted in steps:
        budget.spend()
        for j in counted:
            counts[j] += 1
            demand += s.cost[j]
        if preemptive and busy is not None and busy - a <= worst:
            break  # L_i(a) <= L: no later a can do better
        if demand - a <= worst:
            continue  # r_i(a) <= demand - a
        if preemptive:
            previous = _deadline_busy_period(s, i, a, counts, True, previous, budget)  # not falling
            worst = max(worst, previous - a)
        else:
            worst = max(worst, _deadline_busy_period(s, i, a, counts, False, 0, budget) + c_i - a)
        budget.found(worst)
    return worst


def edf_response_times(
    tasks: Sequence[Task], *, preemptive: bool = True, blocking: Mapping[str, Time] | None = None
) -> dict[str, Time | None]:
    """Worst-case response time of every task with a period under EDF, with arbitrary deadlines;
    None for every task when Σ C/T > 1 (unbounded). ``blocking`` gives tasks a blocking time
    other than their own (:func:`edf_blocking_times`).

    Preemptive (Spuri 1996, release jitter included)::

        r_i(a) = L_i(a) − a
        R_i    = max(C_i + J_i, max_{a ∈ A_i} r_i(a)),   L = B_i + Σ_j ⌈(L + J_j) / T_j⌉ C_j

    Non-preemptive (George, Rivierre and Spuri 1996): the job starts at L_i(a) at the latest::

        r_i(a) = L_i(a) + C_i − a
        R_i    = max(C_i + J_i, max_{a ∈ A_i} r_i(a)),
        L      = max(B_i, max_{j ≠ i} C_j − 1) + Σ_j ⌈(L + J_j) / T_j⌉ C_j

    with L_i(a) of :func:`deadline_busy_period` and A_i of :func:`release_offsets` up to
    min(L, H − J_i) exclusive of H − J_i, H the hyperperiod: when Σ C/T <= 1,
    L_i(a + H) <= L_i(a) + H (each count grows by H/T_j, the blocking does not grow), so one
    hyperperiod of ``a`` covers every later one, and the bound stays finite when L is not
    (Σ C/T = 1 with blocking or jitter). Offsets are ignored: the bound holds for every release
    pattern with at least T_j between two releases of task j.
    """
    values, cut = bounded_edf_response_times(tasks, preemptive=preemptive, blocking=blocking)
    return {name: None if name in cut else value for name, value in values.items()}


def bounded_edf_response_times(
    tasks: Sequence[Task],
    *,
    preemptive: bool = True,
    blocking: Mapping[str, Time] | None = None,
    step_limit: int = RTA_STEP_LIMIT,
) -> tuple[dict[str, Time | None], dict[str, Time]]:
    """(response times, cut): :func:`edf_response_times`, where a task whose busy periods and
    candidate arrivals need more than ``step_limit`` steps (fixed-point steps plus candidates
    tried, :mod:`~rosaadl.analysis.work_bounds`) is cut: ``cut`` maps it to the largest response
    time found before the cut (a lower bound of its worst case), and its value is that bound."""
    s = _scaled(tasks, blocking)
    cut: dict[str, Time] = {}
    if _utilization(s) > 1:
        return {task.name: None for task in s.tasks}, cut
    values: dict[str, Time | None] = {}
    for i, task in enumerate(s.tasks):
        try:
            r = _response_time(s, i, preemptive, StepBudget(step_limit))
        except WorkCut as stop:
            r = stop.at_least
            cut[task.name] = _unscaled(r, s.base)
        values[task.name] = _unscaled(r, s.base)
    return values, cut


# =============================================================================== blocking


def edf_blocking_times(tasks: Sequence[Task], taskset: TaskSet) -> dict[str, Time | None]:
    """Worst-case blocking of each task through shared resources under preemptive EDF, at least
    the task's own ``blocking``; None when it is unbounded.

    A job of task i can only be blocked by jobs with a later deadline that started before its
    deadline busy period, one per task j with D_j > D_i − J_i, each for one outermost critical
    section on a resource another task of the processor also uses. Under EDF, PCP and IPCP
    behave as priority inheritance of deadlines (as the simulator runs them), so for every
    protocol the bound is priority inheritance's::

        B_i = max(blocking_i, min(Σ_{resources} longest such section,
                                  Σ_{tasks j} longest such section))

    Without access protocol, a job holding the resource runs only when no job with an earlier
    deadline is ready: with a third task on the processor, the wait is unbounded (None).
    """
    users: dict[str, set[str]] = {}
    for task in tasks:
        for name in task.resources:
            users.setdefault(name, set()).add(task.name)
    shared = {name for name, names in users.items() if len(names) > 1}
    result: dict[str, Time | None] = {}
    for task in tasks:
        if task.deadline is None:
            continue
        held = [
            (section.resource, other.name, other.outermost_section(section))
            for other in tasks
            if other.name != task.name and other.deadline is not None
            if other.deadline > task.deadline - task.jitter
            for section in other.critical_sections
            if section.resource in shared
        ]
        if len(tasks) > 2 and any(taskset.resource(name).protocol is Protocol.NONE for name, _, _ in held):
            result[task.name] = None
            continue
        result[task.name] = max(task.blocking, min(_longest_per(held, 0), _longest_per(held, 1)))
    return result


def _longest_per(held: list[tuple[str, str, Time]], key: int) -> Time:
    """Σ over resources (key 0) or tasks (key 1) of the longest section held."""
    longest: dict[str, Time] = {}
    for item in held:
        longest[item[key]] = max(longest.get(item[key], 0), item[2])
    return sum(longest.values())
