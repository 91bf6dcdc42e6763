"""An executor-faithful simulation: how one executor dispatches its callbacks, job by job.

The scheduling simulation of :mod:`rosaadl.analysis.simulation_engine` runs *threads* under the
processor's scheduler; a ROS executor is one (or a few) of those threads, inside which callbacks
are dispatched by the executor's own rule. :func:`simulate_executor` plays that rule on the
executor's processor in integer time, from event to event (releases, completions, time slices):

``fifo``, ``pfifo``, ``edf``
    ROSMOD's component executor (the ROSMOD paper, section II.A): one thread takes the oldest job
    of its message queue (``fifo``), the most urgent one (``pfifo``: highest priority, then the
    oldest), or the one of earliest absolute deadline (``edf``), and runs it to completion.
``polling``
    The ROS 2 single-threaded executor: when its previous snapshot is used up (or when it is idle
    and a job arrives) it takes a snapshot of the callbacks that have a job ready (a *polling
    point*), then runs the oldest job of each in dispatch order (kind, then registration:
    ``rank``), each at most once, without preemption; jobs that arrive meanwhile wait for the next
    polling point.
``multi``
    A multi-threaded executor of ``threads`` threads whose callbacks share one processor, as the
    callbacks of a rclpy process share the GIL: a free thread takes the ready job first in
    dispatch order whose mutually exclusive callback group is not running; the running callbacks
    compute in turn, ``quantum`` each (CPython's 5 ms switch interval), and a callback that
    becomes ready waits for the current slice to end.

The executor owns its processor here (no other thread preempts it): what the simulation checks is
the executor's dispatch rule, which the bounds of :mod:`rosaadl.analysis.executor_response` must
cover. The trace of a run is the executor's Gantt chart in the HTML report.

It is an engine of its own, not a dispatcher of :mod:`rosaadl.analysis.simulation_engine`: that
engine's dispatch is a fixed per-job key in one ready heap per core, one running job per core,
strictly periodic releases and jobs of exactly their capacity, none of which a polling snapshot,
GIL time slices or sporadic releases fit (``docs/executors.md`` gives the details).
"""

from __future__ import annotations

import heapq
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass

from rosaadl.analysis.executor_response import CallbackTiming
from rosaadl.errors import UsageError

__all__ = ["ExecutorRun", "POLICIES", "simulate_executor", "periodic_releases"]

POLICIES = ("fifo", "pfifo", "edf", "polling", "multi")


@dataclass(frozen=True)
class ExecutorRun:
    """What a simulated executor did: the worst response time of each callback (None: no job
    completed), the number of completed jobs, and the intervals ``(callback, thread, start, end)``
    of the executed work."""

    worst: tuple[int | None, ...]
    completed: tuple[int, ...]
    intervals: tuple[tuple[int, int, int, int], ...]


def periodic_releases(
    callbacks: Sequence[CallbackTiming],
    horizon: int,
    offsets: Sequence[int] | None = None,
    gaps: Sequence[Sequence[int]] | None = None,
) -> list[list[int]]:
    """Release times below ``horizon``: from each callback's offset, every period plus the extra
    delay ``gaps[i][k]`` (cycled) before its ``k``-th next release (sporadic arrivals), and every
    period of each of its further release ``streams`` from the same offset."""
    out = []
    for i, cb in enumerate(callbacks):
        start = offsets[i] if offsets else 0
        extra = gaps[i] if gaps and gaps[i] else [0]
        times = []
        time, k = start, 0
        while time < horizon:
            times.append(time)
            time += cb.period + extra[k % len(extra)]
            k += 1
        for period in cb.streams:
            times.extend(range(start, horizon, period))
        out.append(sorted(times))
    return out


class _Job:
    __slots__ = ("cb", "release", "seq", "work", "left")

    def __init__(self, cb: int, release: int, seq: int, work: int) -> None:
        self.cb, self.release, self.seq, self.work, self.left = cb, release, seq, work, work


def _key(policy: str, callbacks: Sequence[CallbackTiming], job: _Job) -> tuple[int, ...]:
    cb = callbacks[job.cb]
    if policy == "pfifo":
        return (-cb.priority, job.release, job.seq)
    if policy == "edf":
        return (job.release + cb.deadline, job.release, job.seq)
    if policy == "multi":
        return (cb.rank, job.release, job.seq)
    return (job.release, job.seq)


def simulate_executor(
    callbacks: Sequence[CallbackTiming],
    policy: str,
    releases: Sequence[Sequence[int]],
    *,
    executions: Sequence[Sequence[int]] | None = None,
    threads: int = 1,
    groups: Sequence[str | None] | None = None,
    quantum: int = 5000,
) -> ExecutorRun:
    """Run ``callbacks`` released at ``releases[i]`` under ``policy`` until every job completed.

    ``executions[i][k]`` is the execution time of the ``k``-th job (cycled; default the WCET);
    ``threads``, ``groups`` (a mutually exclusive group name per callback, None for a reentrant
    callback) and ``quantum`` are those of the ``multi`` policy.
    """
    if policy not in POLICIES:
        raise UsageError(f"unknown executor policy {policy} (expected one of {', '.join(POLICIES)})")
    if threads < 1 or quantum < 1:
        raise UsageError("an executor needs at least one thread and a positive time slice")
    arrivals: list[tuple[int, int, int]] = []
    for i, times in enumerate(releases):
        for k, time in enumerate(times):
            arrivals.append((time, i, k))
    arrivals.sort()
    jobs = []
    for seq, (time, i, k) in enumerate(arrivals):
        cost = callbacks[i].wcet
        if executions and executions[i]:
            cost = min(cost, executions[i][k % len(executions[i])])
        jobs.append(_Job(i, time, seq, max(cost, 1)))
    worst: list[int | None] = [None] * len(callbacks)
    done = [0] * len(callbacks)
    intervals: list[tuple[int, int, int, int]] = []

    def finish(job: _Job, now: int) -> None:
        response = now - job.release
        current = worst[job.cb]
        worst[job.cb] = response if current is None else max(current, response)
        done[job.cb] += 1

    if policy == "multi":
        _run_multi(callbacks, jobs, threads, groups or [None] * len(callbacks), quantum, finish, intervals)
    else:
        _run_single(callbacks, policy, jobs, finish, intervals)
    return ExecutorRun(tuple(worst), tuple(done), tuple(intervals))


def _run_single(callbacks, policy, jobs, finish, intervals) -> None:
    now, nxt = 0, 0
    ready: list[tuple[tuple[int, ...], _Job]] = []  # fifo / pfifo / edf
    queues: list[deque[_Job]] = [deque() for _ in callbacks]  # polling: per callback, oldest first
    snapshot: deque[int] = deque()
    while True:
        while nxt < len(jobs) and jobs[nxt].release <= now:
            job = jobs[nxt]
            if policy == "polling":
                queues[job.cb].append(job)
            else:
                heapq.heappush(ready, (_key(policy, callbacks, job), job))
            nxt += 1
        job = None
        if policy == "polling":
            if not snapshot:  # a polling point: the callbacks with a job ready, in dispatch order
                snapshot.extend(
                    sorted((i for i, q in enumerate(queues) if q), key=lambda i: callbacks[i].rank)
                )
            if snapshot:
                job = queues[snapshot.popleft()].popleft()
        elif ready:
            job = heapq.heappop(ready)[1]
        if job is None:
            if nxt >= len(jobs):
                return
            now = jobs[nxt].release
            continue
        intervals.append((job.cb, 0, now, now + job.work))
        now += job.work
        finish(job, now)


def _run_multi(callbacks, jobs, threads, groups, quantum, finish, intervals) -> None:
    now, nxt = 0, 0
    ready: list[tuple[tuple[int, ...], _Job]] = []
    running: deque[tuple[_Job, int]] = deque()  # (job, thread), the GIL holder first
    free = list(range(threads - 1, -1, -1))
    slice_left = quantum
    while True:
        while nxt < len(jobs) and jobs[nxt].release <= now:
            heapq.heappush(ready, (_key("multi", callbacks, jobs[nxt]), jobs[nxt]))
            nxt += 1
        busy = {groups[job.cb] for job, _ in running if groups[job.cb] is not None}
        skipped = []
        while free and ready:
            item = heapq.heappop(ready)
            group = groups[item[1].cb]
            if group is not None and group in busy:
                skipped.append(item)
                continue
            if group is not None:
                busy.add(group)
            running.append((item[1], free.pop()))
        for item in skipped:
            heapq.heappush(ready, item)
        if not running:
            if nxt >= len(jobs):
                return
            now = jobs[nxt].release
            continue
        job, thread = running[0]
        step = min(job.left, slice_left)
        if nxt < len(jobs) and jobs[nxt].release > now:
            step = min(step, jobs[nxt].release - now)
        intervals.append((job.cb, thread, now, now + step))
        now += step
        job.left -= step
        slice_left -= step
        if job.left == 0:
            running.popleft()
            free.append(thread)
            finish(job, now)
            slice_left = quantum
        elif slice_left == 0:
            running.rotate(-1)
            slice_left = quantum
