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

import heapq
import logging
import math
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, NamedTuple

from rosaadl.analysis.schedulability import assign_priorities, feasibility_interval, hyperperiod
from rosaadl.analysis.tasks import (
    Protocol,
    Scheduler,
    Task,
    TaskSet,
    Time,
    exact_time,
    taskset_from_instance,
    time_base,
)
from rosaadl.errors import Diagnostic, Location, ModelError

__all__ = [
    "Interval",
    "JobRecord",
    "TaskStatistics",
    "SimulationResult",
    "simulate",
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

    @property
    def deadline_misses(self) -> int:
        return sum(t.deadline_misses for t in self.tasks)

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
        }


# =============================================================================== engine

_READY, _RUNNING, _BLOCKED, _DONE = 0, 1, 2, 3


class _TaskState:
    __slots__ = (
        "task",
        "index",
        "core",
        "period",
        "capacity",
        "deadline",
        "offset",
        "priority",
        "points",
        "locks_at",
        "unlocks_at",
        "released",
        "completed",
        "responses",
        "first_response",
        "worst",
        "total",
        "misses",
        "preemptions",
        "active",
        "pending",
        "llf",
    )


class _Job:
    __slots__ = (
        "ts",
        "number",
        "release",
        "deadline",
        "executed",
        "point",
        "state",
        "seq",
        "primary",
        "held",
        "blocker",
        "waiting_on",
        "start",
        "completion",
        "run_since",
        "order",
    )


class _Core:
    __slots__ = ("processor", "core", "scheduler", "preemptive", "ready", "running", "last", "edf_like")

    def __init__(self, processor: str, core: str, scheduler: Scheduler, preemptive: bool) -> None:
        self.processor = processor
        self.core = core
        self.scheduler = scheduler
        self.preemptive = preemptive
        self.ready: list[tuple[Any, int, _Job]] = []
        self.running: _Job | None = None
        self.last: list[Any] | None = None  # the open interval [start, end, task, job]
        self.edf_like = not scheduler.fixed_priority


class _Engine:
    """One simulation group: cores that share no resource with cores outside the group."""

    def __init__(
        self,
        taskset: TaskSet,
        domains: list[tuple[str, str]],
        horizon: Time,
        base: int,
        record_schedule: bool,
        diagnostics: list[Diagnostic],
    ) -> None:
        self.base = base
        self.horizon = int(horizon * base)
        self.record_schedule = record_schedule
        self.diagnostics = diagnostics
        self.cores: dict[tuple[str, str], _Core] = {}
        for name, core in domains:
            processor = taskset.processor(name)
            self.cores[(name, core)] = _Core(name, core, processor.scheduler, processor.preemptive)
        self.tasks: list[_TaskState] = []
        self.holder: dict[str, _Job | None] = {}
        self.protocol: dict[str, Protocol] = {}
        self.ceiling: dict[str, int] = {}
        self.blocked: list[_Job] = []
        self.holders: list[_Job] = []
        self.jobs: list[_Job] = []
        self.intervals: list[list[Any]] = []
        self.seq = 0
        self.activations = 0
        self.deferred: list[_Job] = []
        self.deadlock_reported = False
        for domain in domains:
            for task in taskset.tasks_on(*domain):
                self._add_task(taskset, task, domain)

    # ------------------------------------------------------------------ set-up

    def _scale(self, value: Time) -> int:
        if type(value) is int:
            return value * self.base
        return int(value * self.base)

    def _add_task(self, taskset: TaskSet, task: Task, domain: tuple[str, str]) -> None:
        ts = _TaskState()
        ts.task = task
        ts.index = len(self.tasks)
        ts.core = self.cores[domain]
        ts.period = None if task.period is None else self._scale(task.period)
        ts.capacity = self._scale(task.capacity)
        ts.deadline = None if task.deadline is None else self._scale(task.deadline)
        ts.offset = self._scale(task.offset)
        ts.priority = task.priority
        locks: dict[int, list[str]] = {}
        unlocks: dict[int, list[str]] = {}
        for section in sorted(task.critical_sections, key=lambda s: (s.start, -s.end)):
            locks.setdefault(self._scale(section.start), []).append(section.resource)
            unlocks.setdefault(self._scale(section.end), []).insert(0, section.resource)
            name = section.resource
            if name not in self.holder:
                resource = taskset.resource(name)
                self.holder[name] = None
                protocol = resource.protocol
                if protocol in (Protocol.PCP, Protocol.IPCP) and ts.core.edf_like:
                    self.diagnostics.append(
                        Diagnostic(
                            "warning",
                            f"{protocol.value} needs fixed priorities; simulated as priority inheritance "
                            f"under {ts.core.scheduler.value}",
                            Location(path=resource.path),
                        )
                    )
                    protocol = Protocol.PIP
                self.protocol[name] = protocol
                ceiling = taskset.ceiling(name)
                self.ceiling[name] = ceiling if ceiling is not None else task.priority
        ts.locks_at = locks
        ts.unlocks_at = unlocks
        ts.points = sorted(set(locks) | set(unlocks) | {ts.capacity})
        ts.released = ts.completed = ts.misses = ts.preemptions = 0
        ts.first_response = ts.worst = None
        ts.total = 0
        ts.active = None
        ts.pending = deque()
        ts.llf = ts.core.scheduler is Scheduler.LEAST_LAXITY_FIRST
        self.tasks.append(ts)

    # ------------------------------------------------------------------ keys

    def _base_primary(self, job: _Job) -> int:
        core = job.ts.core
        if core.scheduler is Scheduler.LEAST_LAXITY_FIRST:
            return job.deadline - (job.ts.capacity - job.executed)
        if core.edf_like:
            return job.deadline
        return -job.ts.priority

    def _key(self, job: _Job) -> tuple[int, int]:
        """Smaller is more urgent: (priority or deadline or laxity, activation order)."""
        if job.ts.llf and not job.held and job.blocker is None:
            # laxity d - t - remaining, ranked as d - remaining (t is common to all jobs)
            return (job.deadline - job.ts.capacity + job.executed, job.order)
        return (job.primary, job.order)

    def _push(self, job: _Job) -> None:
        self.seq += 1
        job.seq = self.seq
        job.state = _READY
        heapq.heappush(job.ts.core.ready, (self._key(job), self.seq, job))

    def _top(self, core: _Core) -> _Job | None:
        ready = core.ready
        while ready:
            _, seq, job = ready[0]
            if job.state == _READY and job.seq == seq:
                return job
            heapq.heappop(ready)
        return None

    # ------------------------------------------------------------------ resources

    def _refresh(self, now: int) -> None:
        """Recompute inherited priorities (PIP, PCP) and ceilings (IPCP) until stable."""
        if not self.holders and not self.blocked:
            return
        for _ in range(len(self.holders) + len(self.blocked) + 1):
            changed = False
            for job in self.holders:
                primary = self._base_primary(job)
                for name in job.held:
                    if self.protocol[name] is Protocol.IPCP:
                        primary = min(primary, -self.ceiling[name])
                for waiter in self.blocked:
                    if waiter.blocker is job and self.protocol.get(waiter.waiting_on) in (
                        Protocol.PIP,
                        Protocol.PCP,
                    ):
                        primary = min(primary, waiter.primary)
                if primary != job.primary:
                    job.primary = primary
                    changed = True
                    if job.state == _READY:
                        self._push(job)
            if not changed:
                return

    def _system_ceiling(self, job: _Job) -> tuple[int | None, _Job | None]:
        """Highest PCP ceiling among resources locked by other jobs of the job's core."""
        best: int | None = None
        owner: _Job | None = None
        core = job.ts.core
        for other in self.holders:
            if other is job or other.ts.core is not core:
                continue
            for name in other.held:
                if self.protocol[name] is Protocol.PCP:
                    c = self.ceiling[name]
                    if best is None or c > best:
                        best, owner = c, other
        return best, owner

    def _try_lock(self, job: _Job, name: str, now: int) -> bool:
        holder = self.holder[name]
        protocol = self.protocol[name]
        blocker: _Job | None = holder
        if holder is None and protocol is Protocol.PCP and not job.ts.core.edf_like:
            ceiling, owner = self._system_ceiling(job)
            if ceiling is not None and -job.primary <= ceiling:
                blocker = owner
        if blocker is None:
            self.holder[name] = job
            job.held.append(name)
            if len(job.held) == 1:
                self.holders.append(job)
            if protocol is Protocol.IPCP:
                self._refresh(now)
            return True
        job.state = _BLOCKED
        job.blocker = blocker
        job.waiting_on = name
        self.blocked.append(job)
        self._check_deadlock(job)
        self._refresh(now)
        return False

    def _check_deadlock(self, job: _Job) -> None:
        seen = set()
        current = job.blocker
        while current is not None and id(current) not in seen:
            if current is job:
                if not self.deadlock_reported:
                    self.deadlock_reported = True
                    self.diagnostics.append(
                        Diagnostic(
                            "error",
                            f"deadlock: {job.ts.task.name} waits for {job.waiting_on}, "
                            "held in a cycle of locks",
                            Location(path=job.ts.task.path),
                        )
                    )
                return
            seen.add(id(current))
            current = current.blocker if current.state == _BLOCKED else None

    def _unlock(self, job: _Job, name: str, now: int) -> None:
        self.holder[name] = None
        job.held.remove(name)
        if not job.held:
            self.holders.remove(job)
        woken = [w for w in self.blocked if w.waiting_on == name or w.blocker is job]
        if woken:
            self.blocked = [w for w in self.blocked if w not in woken]
            for waiter in woken:
                waiter.blocker = None
                waiter.waiting_on = None
                waiter.primary = self._base_primary(waiter)
                self._push(waiter)
        job.primary = self._base_primary(job)
        self._refresh(now)

    # ------------------------------------------------------------------ jobs

    def _release(self, ts: _TaskState, now: int) -> None:
        job = _Job()
        job.ts = ts
        ts.released += 1
        job.number = ts.released
        job.release = now
        if ts.deadline is not None:
            job.deadline = now + ts.deadline
        else:
            job.deadline = self.horizon * 4 + now + ts.capacity  # never urgent under EDF/LLF
        job.executed = 0
        job.point = 0
        job.held = []
        job.blocker = None
        job.waiting_on = None
        job.start = None
        job.completion = None
        job.run_since = None
        job.state = _BLOCKED
        job.seq = 0
        job.order = 0
        job.primary = self._base_primary(job)
        self.jobs.append(job)
        if ts.active is None:
            self._activate(job)
        else:
            ts.pending.append(job)  # a task runs one job at a time; later releases queue

    def _activate(self, job: _Job) -> None:
        self.activations += 1
        job.order = self.activations
        job.ts.active = job
        self._push(job)

    def _pending_locks(self, job: _Job, now: int) -> bool:
        """Take the locks due at the job's current progress; False if it blocked."""
        names = job.ts.locks_at.get(job.executed)
        if not names:
            return True
        for name in names:
            if name in job.held:
                continue
            if not self._try_lock(job, name, now):
                return False
        return True

    def _stop(self, core: _Core, now: int) -> None:
        """Close the running job's open interval."""
        job = core.running
        if job is None:
            return
        if self.record_schedule and job.run_since is not None and now > job.run_since:
            last = core.last
            if last is not None and last[2] is job and last[1] == job.run_since:
                last[1] = now
            else:
                core.last = [job.run_since, now, job, core]
                self.intervals.append(core.last)
        job.run_since = None

    def _dispatch(self, core: _Core, now: int) -> None:
        while True:
            top = self._top(core)
            running = core.running
            if running is not None:
                if top is None or not core.preemptive:
                    return
                if self._key(top) >= self._key(running):
                    return
                # preemption
                self._stop(core, now)
                running.ts.preemptions += 1
                core.running = None
                self._push(running)
                continue
            if top is None:
                return
            heapq.heappop(core.ready)
            if not self._pending_locks(top, now):
                continue
            top.state = _RUNNING
            core.running = top
            top.run_since = now
            if top.start is None:
                top.start = now

    def _next_boundary(self, core: _Core, now: int) -> int | None:
        job = core.running
        if job is None:
            return None
        points = job.ts.points
        while points[job.point] <= job.executed:
            job.point += 1
        at = now + points[job.point] - job.executed
        if core.scheduler is Scheduler.LEAST_LAXITY_FIRST and core.preemptive:
            top = self._top(core)
            if top is not None:
                running_key = self._key(job)[0]
                waiting_key = self._key(top)[0]
                crossing = now + max(0, waiting_key - running_key) + 1
                at = min(at, crossing)
        return at

    def _reach(self, core: _Core, now: int) -> None:
        """The running job reached a progress point: unlock, complete, or take locks."""
        job = core.running
        if job is None:
            return
        ts = job.ts
        if job.executed != ts.points[job.point]:
            return
        for name in ts.unlocks_at.get(job.executed, ()):
            if name in job.held:
                self._unlock(job, name, now)
        if job.executed >= ts.capacity:
            self._stop(core, now)
            core.running = None
            job.state = _DONE
            job.completion = now
            response = now - job.release
            ts.completed += 1
            if ts.first_response is None:
                ts.first_response = response
            if ts.worst is None or response > ts.worst:
                ts.worst = response
            ts.total += response
            if ts.deadline is not None and now > job.deadline:
                ts.misses += 1
            ts.active = None
            if ts.pending:
                # the next queued job becomes active after this instant's releases
                ts.active = ts.pending.popleft()
                self.deferred.append(ts.active)
            return
        if ts.locks_at.get(job.executed) and not self._pending_locks(job, now):
            self._stop(core, now)
            core.running = None

    # ------------------------------------------------------------------ main loop

    def run(self) -> None:
        """Simulate; one core without resources and without LLF takes the fast path."""
        cores = list(self.cores.values())
        simple = (
            len(cores) == 1 and not self.holder and cores[0].scheduler is not Scheduler.LEAST_LAXITY_FIRST
        )
        if simple:
            self.run_simple(cores[0])
        else:
            self.run_general()

    def _initial_releases(self) -> tuple[list[tuple[int, int, int]], int]:
        # Releases at the same instant are processed in the order they were scheduled.
        releases: list[tuple[int, int, int]] = []
        order = 0
        for ts in self.tasks:
            if ts.offset < self.horizon:
                order += 1
                releases.append((ts.offset, order, ts.index))
        heapq.heapify(releases)
        return releases, order

    def _count_unfinished(self) -> None:
        horizon = self.horizon
        for job in self.jobs:
            if job.completion is None and job.ts.deadline is not None and job.deadline <= horizon:
                job.ts.misses += 1

    def run_simple(self, core: _Core) -> None:
        """The general loop specialised to one core, fixed keys, no resources (same semantics)."""
        heappush, heappop = heapq.heappush, heapq.heappop
        tasks = self.tasks
        horizon = self.horizon
        edf = core.edf_like
        preemptive = core.preemptive
        record = self.record_schedule
        intervals = self.intervals
        jobs = self.jobs
        ready: list[tuple[int, int, _Job]] = []
        releases, order = self._initial_releases()
        deferred: list[_Job] = []
        activations = 0
        running: _Job | None = None
        run_key: tuple[int, int] = (0, 0)
        run_since = run_end = 0
        last: list[Any] | None = None
        now = 0
        while True:
            if running is not None and run_end == now:
                job = running
                running = None
                if record and now > run_since:
                    if last is not None and last[2] is job and last[1] == run_since:
                        last[1] = now
                    else:
                        last = [run_since, now, job, core]
                        intervals.append(last)
                job.executed = job.ts.capacity
                job.completion = now
                ts = job.ts
                response = now - job.release
                ts.completed += 1
                if ts.first_response is None:
                    ts.first_response = response
                if ts.worst is None or response > ts.worst:
                    ts.worst = response
                ts.total += response
                if ts.deadline is not None and now > job.deadline:
                    ts.misses += 1
                ts.active = None
                if ts.pending:
                    ts.active = ts.pending.popleft()
                    deferred.append(ts.active)
            if now >= horizon:
                break
            while releases and releases[0][0] == now:
                _, _, index = heappop(releases)
                ts = tasks[index]
                job = _Job()
                job.ts = ts
                ts.released += 1
                job.number = ts.released
                job.release = now
                job.deadline = (
                    now + ts.deadline if ts.deadline is not None else horizon * 4 + now + ts.capacity
                )
                job.executed = 0
                job.start = job.completion = None
                jobs.append(job)
                if ts.active is None:
                    ts.active = job
                    activations += 1
                    job.order = activations
                    heappush(ready, (job.deadline if edf else -ts.priority, activations, job))
                else:
                    ts.pending.append(job)
                if ts.period is not None and now + ts.period < horizon:
                    order += 1
                    heappush(releases, (now + ts.period, order, index))
            if deferred:
                for job in deferred:
                    activations += 1
                    job.order = activations
                    heappush(ready, (job.deadline if edf else -job.ts.priority, activations, job))
                deferred.clear()
            if ready:
                if running is None:
                    primary, rank, job = heappop(ready)
                    running, run_key = job, (primary, rank)
                    run_since = now
                    run_end = now + job.ts.capacity - job.executed
                    if job.start is None:
                        job.start = now
                elif preemptive and ready[0][:2] < run_key:
                    job = running
                    job.executed = job.ts.capacity - (run_end - now)
                    if record and now > run_since:
                        if last is not None and last[2] is job and last[1] == run_since:
                            last[1] = now
                        else:
                            last = [run_since, now, job, core]
                            intervals.append(last)
                    job.ts.preemptions += 1
                    heappush(ready, (run_key[0], run_key[1], job))
                    primary, rank, job = heappop(ready)
                    running, run_key = job, (primary, rank)
                    run_since = now
                    run_end = now + job.ts.capacity - job.executed
                    if job.start is None:
                        job.start = now
            following = releases[0][0] if releases else horizon
            if following > horizon:
                following = horizon
            if running is not None and run_end < following:
                following = run_end
            now = following
        if running is not None:
            running.executed = running.ts.capacity - (run_end - horizon)
            if record and horizon > run_since:
                if last is not None and last[2] is running and last[1] == run_since:
                    last[1] = horizon
                else:
                    intervals.append([run_since, horizon, running, core])
        self._count_unfinished()

    def run_general(self) -> None:
        """The general event loop: any number of cores, resources, LLF."""
        releases, order = self._initial_releases()
        cores = list(self.cores.values())
        horizon = self.horizon
        now = 0
        while True:
            for core in cores:
                self._reach(core, now)
            if now >= horizon:
                break
            while releases and releases[0][0] == now:
                _, _, index = heapq.heappop(releases)
                ts = self.tasks[index]
                self._release(ts, now)
                if ts.period is not None and now + ts.period < horizon:
                    order += 1
                    heapq.heappush(releases, (now + ts.period, order, index))
            if self.deferred:
                # queued releases of tasks whose previous job just completed
                for job in self.deferred:
                    self._activate(job)
                self.deferred.clear()
            for core in cores:
                self._dispatch(core, now)
            following = releases[0][0] if releases else horizon
            following = min(following, horizon)
            for core in cores:
                at = self._next_boundary(core, now)
                if at is not None and at < following:
                    following = at
            step = following - now
            for core in cores:
                job = core.running
                if job is not None:
                    job.executed += step
            now = following
        for core in cores:
            self._stop(core, horizon)
        self._count_unfinished()


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


def _job_count(tasks: Sequence[Task], horizon: Time) -> int:
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


def simulate(
    source: TaskSet | Any,
    *,
    horizon: Time | None = None,
    max_jobs: int = 1_000_000,
    record_schedule: bool = True,
    record_jobs: bool = True,
    time_unit: str = "us",
) -> SimulationResult:
    """Simulate ``source`` (a TaskSet or an instance model) on every processor and core.

    ``horizon`` overrides the feasibility interval of every domain. When the interval would
    release more than ``max_jobs`` jobs, the horizon is shortened to fit and a warning says so.
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
    for group in _groups(taskset):
        group_tasks = [t for n, c in group for t in taskset.tasks_on(n, c)]
        length = horizon if horizon is not None else _default_horizon(taskset, group)
        count = _job_count(group_tasks, length)
        if count > max_jobs:
            rate = sum((Fraction(1) / t.period for t in group_tasks if t.period is not None), Fraction(0))
            shorter = exact_time(Fraction(math.floor(max_jobs / rate))) if rate else length
            shorter = max(shorter, 1)
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
        base = time_base([*taskset.times(), length])
        engine = _Engine(taskset, group, length, base, record_schedule, diagnostics)
        engine.run()
        log.debug("simulated %s up to %s %s: %d jobs", group, length, taskset.time_unit, len(engine.jobs))
        for domain in group:
            horizons[domain] = length
        _collect(engine, base, stats, jobs, schedule, record_jobs, record_schedule)
    ordered = tuple(stats[t.name] for t in taskset.tasks if t.name in stats)
    schedule.sort(key=lambda i: (i.start, i.processor, i.core))
    return SimulationResult(
        ordered, tuple(jobs), tuple(schedule), horizons, tuple(diagnostics), taskset.time_unit
    )


def _collect(
    engine: _Engine,
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
