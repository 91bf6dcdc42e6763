"""The event-driven engine of the scheduling simulation (:mod:`rosaadl.analysis.simulation`).

One :class:`Engine` simulates one group of cores that share no resource with cores outside
the group, in integer time (the front end scales every time once), from event to event:
releases, completions, lock and unlock points of critical sections, laxity crossings for LLF.
It keeps, per task, the released and completed jobs, response times, deadline misses and
preemptions, and, when asked, every job and the schedule's intervals.
"""

from __future__ import annotations

import heapq
import logging
from collections import deque
from typing import Any

from rosaadl.analysis.tasks import Protocol, Scheduler, Task, TaskSet, Time
from rosaadl.arguments import expect_number
from rosaadl.errors import Diagnostic, Location, UsageError

__all__ = ["Engine"]

log = logging.getLogger(__name__)


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


class Engine:
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
        self.base = expect_number(base, "base", integer=True, positive=True)
        if horizon < 0:
            raise UsageError(f"the simulation horizon must not be negative, got {horizon}")
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
