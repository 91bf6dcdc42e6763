"""Event-driven scheduling simulation of a :class:`~rosaadl.analysis.tasks.TaskSet`.

The simulator jumps from event to event (releases, completions, lock and unlock points,
laxity crossings for LLF), never tick by tick, over Cheddar's feasibility interval of each
processor (or a given horizon). It supports:

* fixed priorities (as given, RM, DM; larger number = higher priority; equal priorities are
  served in release order), EDF and LLF; preemptive and non-preemptive processors;
* shared resources with critical sections (lock at ``start``, unlock at ``end`` units of the
  task's execution) under no protocol, PIP, PCP and IPCP (PCP and IPCP need fixed priorities;
  under EDF and LLF they behave as PIP, with deadline inheritance);
* partitioned multi-core processors: each core schedules its own tasks; cores that share a
  resource are simulated together.

Exactness: every time is scaled once to integers (the least common multiple of the time
denominators), simulated in integers and scaled back, so results are exact ``int`` or
``Fraction``. Sporadic tasks are released at their minimum inter-arrival time (their worst
case); release jitter is not simulated (it enters the response-time analysis only).

Results: per task the observed worst, average and first-job response times, deadline misses and
preemptions; per job its release, start and completion; the schedule as merged intervals
(processor, core, task, job) for Gantt charts; and located diagnostics.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, NamedTuple

from rosaadl.analysis.registry import Analysis, AnalysisContext, register
from rosaadl.analysis.rendering import csv_text, short_path, table
from rosaadl.analysis.schedulability import assign_priorities, feasibility_interval, hyperperiod
from rosaadl.analysis.simulation_engine import Engine
from rosaadl.analysis.tasks import (
    Task,
    TaskSet,
    Time,
    exact_time,
    taskset_from_instance,
    time_base,
)
from rosaadl.analysis.work_bounds import SIMULATION_JOB_LIMIT
from rosaadl.arguments import checked
from rosaadl.errors import Diagnostic, Location, ModelError

__all__ = [
    "Interval",
    "JobRecord",
    "TaskStatistics",
    "SimulationResult",
    "simulate",
    "job_count",
    "simulation_text",
    "simulation_csv",
    "missed_deadlines",
]

log = logging.getLogger(__name__)


# =============================================================================== results


class Interval(NamedTuple):
    """``task``'s job number ``job`` (1 = first) ran on ``processor``/``core`` from ``start`` to ``end``."""

    start: Time
    end: Time
    task: str
    job: int
    processor: str
    core: str


class JobRecord(NamedTuple):
    """One job: release, absolute deadline, first start and completion (None if unfinished)."""

    task: str
    job: int
    release: Time
    deadline: Time | None
    start: Time | None
    completion: Time | None

    @property
    def response_time(self) -> Time | None:
        return None if self.completion is None else exact_time(Fraction(self.completion) - self.release)

    @property
    def missed(self) -> bool | None:
        """True when it completed after its deadline; None while unfinished."""
        if self.completion is None:
            return None
        return self.deadline is not None and self.completion > self.deadline


@dataclass(frozen=True)
class TaskStatistics:
    """Observed behaviour of one task over the simulated interval."""

    name: str
    path: str
    processor: str
    core: str
    priority: int
    released: int
    completed: int
    first_response: Time | None
    worst_response: Time | None
    average_response: Time | None
    deadline_misses: int
    preemptions: int

    def as_dict(self) -> dict[str, Any]:
        def number(value: Time | None) -> int | float | None:
            return value if value is None or isinstance(value, int) else float(value)

        return {
            "path": self.path,
            "priority": self.priority,
            "released": self.released,
            "completed": self.completed,
            "first_response": number(self.first_response),
            "worst_response": number(self.worst_response),
            "average_response": number(self.average_response),
            "deadline_misses": self.deadline_misses,
            "preemptions": self.preemptions,
        }


@dataclass(frozen=True)
class SimulationResult:
    """Statistics per task, the jobs, the schedule and the simulated horizon of every domain."""

    tasks: tuple[TaskStatistics, ...]
    jobs: tuple[JobRecord, ...]
    schedule: tuple[Interval, ...]
    horizons: dict[tuple[str, str], Time]
    diagnostics: tuple[Diagnostic, ...]
    time_unit: str
    cut: tuple[tuple[str, str], ...] = ()  #: domains whose horizon the job cap shortened

    @property
    def deadline_misses(self) -> int:
        return sum(t.deadline_misses for t in self.tasks)

    @property
    def inconclusive(self) -> bool:
        """A domain's horizon was cut before its feasibility interval ended and no task of it
        missed a deadline in what was simulated: a cut horizon is never a pass."""
        missed = {(t.processor, t.core) for t in self.tasks if t.deadline_misses}
        return any(domain not in missed for domain in self.cut)

    @property
    def ok(self) -> bool:
        return self.deadline_misses == 0 and all(d.severity != "error" for d in self.diagnostics)

    def task(self, name: str) -> TaskStatistics:
        for stats in self.tasks:
            if stats.name == name:
                return stats
        raise ModelError(f"no task {name!r} in the simulation")

    def jobs_of(self, name: str) -> list[JobRecord]:
        return [j for j in self.jobs if j.task == name]

    def as_dict(self) -> dict[str, Any]:
        return {
            "horizons": [
                {"path": f"{p}.{c}" if c else p, "horizon": h if isinstance(h, int) else float(h)}
                for (p, c), h in self.horizons.items()
            ],
            "deadline_misses": self.deadline_misses,
            "tasks": [t.as_dict() for t in self.tasks],
            **({"inconclusive": True} if self.inconclusive else {}),
        }


# =============================================================================== front end


def _groups(taskset: TaskSet) -> list[list[tuple[str, str]]]:
    """Domains (processor, core) with tasks, joined into groups when they share a resource."""
    domains = [(p.name, c) for p, c, tasks in taskset.domains() if tasks]
    parent = {d: d for d in domains}

    def find(d: tuple[str, str]) -> tuple[str, str]:
        while parent[d] != d:
            parent[d] = parent[parent[d]]
            d = parent[d]
        return d

    users: dict[str, tuple[str, str]] = {}
    for task in taskset.tasks:
        domain = (task.processor, task.core)
        for name in task.resources:
            if name in users:
                parent[find(domain)] = find(users[name])
            else:
                users[name] = domain
    grouped: dict[tuple[str, str], list[tuple[str, str]]] = {}
    for d in domains:
        grouped.setdefault(find(d), []).append(d)
    return list(grouped.values())


def _default_horizon(taskset: TaskSet, group: list[tuple[str, str]]) -> Time:
    length: Time = 0
    for name, core in group:
        tasks = taskset.tasks_on(name, core)
        processor = taskset.processor(name)
        interval = feasibility_interval(
            tasks, processor.scheduler, independent=not any(t.critical_sections for t in tasks)
        )
        if interval is not None:
            candidate = interval.length
        else:
            candidate = max(t.offset for t in tasks) + sum(Fraction(t.capacity) for t in tasks)
        # long enough to see every aperiodic job reach its deadline (or, without one, its capacity)
        aperiodic_end = max(
            (
                t.offset + Fraction(t.deadline if t.deadline is not None else t.capacity)
                for t in tasks
                if t.period is None
            ),
            default=Fraction(0),
        )
        length = max(length, exact_time(Fraction(max(candidate, aperiodic_end))))
    if len(group) > 1:
        periods = [t.period for n, c in group for t in taskset.tasks_on(n, c) if t.period is not None]
        if periods:
            offsets = [t.offset for n, c in group for t in taskset.tasks_on(n, c)]
            hyper = hyperperiod(periods)
            joint = hyper if max(offsets) == 0 else exact_time(2 * hyper + max(offsets))
            length = max(length, joint)
    return length


def job_count(tasks: Sequence[Task], horizon: Time) -> int:
    """How many jobs ``tasks`` release before ``horizon`` (a task without a period: one)."""
    count = 0
    for task in tasks:
        if task.offset >= horizon:
            continue
        if task.period is None:
            count += 1
        elif type(horizon) is int and type(task.offset) is int and type(task.period) is int:
            count += -(-(horizon - task.offset) // task.period)
        else:
            count += math.ceil((horizon - task.offset) / Fraction(task.period))
    return count


@checked
def simulate(
    source: TaskSet | Any,
    *,
    horizon: Time | None = None,
    max_jobs: int = SIMULATION_JOB_LIMIT,
    record_schedule: bool = True,
    record_jobs: bool = True,
    time_unit: str = "us",
) -> SimulationResult:
    """Simulate ``source`` (a TaskSet or an instance model) on every processor and core.

    ``horizon`` overrides the feasibility interval of every domain. When the interval would
    release more than ``max_jobs`` jobs (the work bound, :data:`~rosaadl.analysis.work_bounds.
    SIMULATION_JOB_LIMIT` by default), the horizon is shortened to fit, however short the
    periods, and a warning says so; the result is then ``inconclusive`` unless a task of the
    domain missed a deadline in what was simulated (a cut horizon is never a pass).
    RM and DM processors get Cheddar's priorities first.
    """
    taskset = source if isinstance(source, TaskSet) else taskset_from_instance(source, time_unit=time_unit)
    taskset = assign_priorities(taskset)
    diagnostics = list(taskset.diagnostics)
    if horizon is not None:
        horizon = exact_time(horizon, "horizon")
        if horizon <= 0:
            raise ModelError(f"the simulation horizon must be positive, got {horizon}")
    stats: dict[str, TaskStatistics] = {}
    jobs: list[JobRecord] = []
    schedule: list[Interval] = []
    horizons: dict[tuple[str, str], Time] = {}
    cut: list[tuple[str, str]] = []
    for group in _groups(taskset):
        group_tasks = [t for n, c in group for t in taskset.tasks_on(n, c)]
        length = horizon if horizon is not None else _default_horizon(taskset, group)
        count = job_count(group_tasks, length)
        if count > max_jobs:
            shorter = _capped_horizon(group_tasks, length, max_jobs)
            where = ", ".join(f"{n}.{c}" if c else n for n, c in group)
            diagnostics.append(
                Diagnostic(
                    "warning",
                    f"the feasibility interval {length} {taskset.time_unit} would release {count} jobs; "
                    f"simulated up to {shorter} {taskset.time_unit} only",
                    Location(path=where),
                )
            )
            length = shorter
            if horizon is None:
                cut.extend(group)
        base = time_base([*taskset.times(), length])
        engine = Engine(taskset, group, length, base, record_schedule, diagnostics)
        engine.run()
        log.debug("simulated %s up to %s %s: %d jobs", group, length, taskset.time_unit, len(engine.jobs))
        for domain in group:
            horizons[domain] = length
        _collect(engine, base, stats, jobs, schedule, record_jobs, record_schedule)
    ordered = tuple(stats[t.name] for t in taskset.tasks if t.name in stats)
    schedule.sort(key=lambda i: (i.start, i.processor, i.core))
    return SimulationResult(
        ordered, tuple(jobs), tuple(schedule), horizons, tuple(diagnostics), taskset.time_unit, tuple(cut)
    )


def _capped_horizon(tasks: Sequence[Task], length: Time, max_jobs: int) -> Time:
    """A horizon shorter than ``length`` in which ``tasks`` release at most ``max_jobs`` jobs: a
    whole number of time units when one fits, else the exact fraction (never more jobs than
    the cap, however short the periods)."""
    rate = sum((Fraction(1) / t.period for t in tasks if t.period is not None), Fraction(0))
    if not rate:
        return length
    exact = Fraction(max_jobs) / rate
    return exact_time(Fraction(math.floor(exact))) if exact >= 1 else exact_time(exact)


def _collect(
    engine: Engine,
    base: int,
    stats: dict[str, TaskStatistics],
    jobs: list[JobRecord],
    schedule: list[Interval],
    record_jobs: bool,
    record_schedule: bool,
) -> None:
    def back(value: int | None) -> Time | None:
        if value is None or base == 1:
            return value
        whole, rest = divmod(value, base)
        return whole if rest == 0 else Fraction(value, base)

    for ts in engine.tasks:
        task = ts.task
        average = None if ts.completed == 0 else exact_time(Fraction(ts.total, base * ts.completed))
        stats[task.name] = TaskStatistics(
            task.name,
            task.path,
            task.processor,
            task.core,
            ts.priority,
            ts.released,
            ts.completed,
            back(ts.first_response),
            back(ts.worst),
            average,
            ts.misses,
            ts.preemptions,
        )
    make_job = JobRecord._make
    if record_jobs and base == 1:  # integer times: nothing to convert
        jobs.extend(
            make_job(
                (
                    job.ts.task.name,
                    job.number,
                    job.release,
                    job.deadline if job.ts.deadline is not None else None,
                    job.start,
                    job.completion,
                )
            )
            for job in engine.jobs
        )
    elif record_jobs:
        for job in engine.jobs:
            jobs.append(
                make_job(
                    (
                        job.ts.task.name,
                        job.number,
                        back(job.release),
                        back(job.deadline) if job.ts.deadline is not None else None,
                        back(job.start),
                        back(job.completion),
                    )
                )
            )
    if record_schedule:
        for start, end, job, core in engine.intervals:
            schedule.append(
                Interval(back(start), back(end), job.ts.task.name, job.number, core.processor, core.core)
            )


# =============================================================================== report


def simulation_text(result: SimulationResult) -> list[str]:
    """The ``Simulation`` section of the text report."""
    verdict = ", horizon cut by the job cap: inconclusive" if result.inconclusive else ""
    lines = [f"Simulation ({result.deadline_misses} deadline misses{verdict})", ""]
    rows = [
        [
            short_path(t.path),
            t.released,
            t.completed,
            t.worst_response,
            t.average_response,
            t.deadline_misses,
            t.preemptions,
        ]
        for t in result.tasks
    ]
    lines += table(["task", "released", "completed", "worst RT", "average RT", "misses", "preemptions"], rows)
    lines.append("")
    return lines


def simulation_csv(result: SimulationResult, base: str) -> dict[str, str]:
    """``<base>__Simulation.csv``: one row per task with its jobs and response times."""
    rows: list[list[Any]] = [
        [
            "Task",
            "Released",
            "Completed",
            "First response",
            "Worst response",
            "Average response",
            "Deadline misses",
            "Preemptions",
        ]
    ]
    for t in result.tasks:
        rows.append(
            [
                t.path,
                t.released,
                t.completed,
                t.first_response,
                t.worst_response,
                t.average_response,
                t.deadline_misses,
                t.preemptions,
            ]
        )
    return {f"{base}__Simulation.csv": csv_text(rows)}


def missed_deadlines(result: SimulationResult) -> list[Diagnostic]:
    """An error for each task that missed deadlines in the simulation."""
    return [
        Diagnostic(
            "error", f"missed {stats.deadline_misses} deadlines in simulation", Location(path=stats.path)
        )
        for stats in result.tasks
        if stats.deadline_misses
    ]


def _run(context: AnalysisContext) -> SimulationResult | None:
    taskset = context.taskset
    if taskset is None:
        return None
    return simulate(taskset, horizon=context.options.get("simulation_horizon"), record_schedule=False)


register(
    Analysis(
        name="sim",
        json_key="simulation",
        order=50,
        run=_run,
        text=simulation_text,
        csv=simulation_csv,
        verdicts=missed_deadlines,
        aliases=("simulation",),
        description="event-driven scheduling simulation (Cheddar's), response times and deadline misses",
    )
)
