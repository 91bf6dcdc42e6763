"""The ``executor`` analysis: callback response times under the executors that really run them,
and the reaction time and data age of cause-effect chains.

For every executor of :func:`~rosaadl.analysis.executors.executors_from_instance` it bounds the
response time of each callback with the bound of its executor kind
(:mod:`rosaadl.analysis.executor_response`): ROSMOD FIFO, PFIFO or EDF (non-preemptive), the
ROS 2 single-threaded executor (polling points), the multi-threaded executor (busy window). The
executor's thread is preempted by the threads of executors of higher or equal OS ``Priority`` on
the same core, which are added as interference; a callback's dispatch latency
(``ROS_Properties::Dispatch_Latency``: its executor, idle, starts it at most that long after its
release) is added to its bound, and so passed on as jitter to what its messages release. A
measured run that put processes on other cores than the model binds them to is analysed as it
ran (``placement``). A subscription is released by every topic that
feeds it, with the release jitter its publishers pass on (their response times); the bounds of
all executors are iterated until these jitters settle. Beside each bound it sets the preemptive-thread
WCRT of the schedulability analysis (what OSATE and Cheddar assume). Chains and their bounds come
from :mod:`rosaadl.analysis.cause_effect`. A simulation of each executor
(:mod:`rosaadl.analysis.executor_simulation`) over its first busy stretch gives the Gantt chart
of the HTML report. JSON: ``callbacks: [{"path", "executor", "kind", "wcrt"}]`` and
``chains: [{"name", "paths", "reaction_time", "data_age"}]``, times in microseconds.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

from rosaadl.analysis import executor_response as rta
from rosaadl.analysis.cause_effect import (
    CauseEffectChain,
    callback_links,
    cause_effect_chains,
    chain_bound,
    flow_callbacks,
    flow_deadline,
    release_gaps,
)
from rosaadl.analysis.executor_simulation import periodic_releases, simulate_executor
from rosaadl.analysis.executors import Callback, Executor, executors_from_instance
from rosaadl.analysis.instance_values import PropertyReader, instance_root, system_modes
from rosaadl.analysis.registry import Analysis, AnalysisContext, register
from rosaadl.analysis.rendering import csv_text, fmt, json_number, table
from rosaadl.analysis.tasks import time_base
from rosaadl.errors import Diagnostic, Location

__all__ = ["CallbackBound", "ExecutorResult", "analyze_executors", "placed", "executor_text", "executor_csv"]

_GANTT_INTERVALS = 400


@dataclass(frozen=True)
class CallbackBound:
    """A callback's response-time bound under its executor (``wcrt``) and as a preemptive thread
    (``thread_wcrt``, from the schedulability analysis), in microseconds."""

    path: str
    executor: str
    kind: str
    wcrt: Fraction | None
    thread_wcrt: Fraction | None
    deadline: Fraction | None
    #: the model gives the callback's Compute_Execution_Time (else its bound counts it as 0)
    timed: bool = True

    @property
    def met(self) -> bool | None:
        if self.deadline is None:
            return None
        return self.wcrt is not None and self.wcrt <= self.deadline

    def as_dict(self) -> dict[str, Any]:
        return {
            "path": self.path,
            "executor": self.executor,
            "kind": self.kind,
            "wcrt": json_number(self.wcrt),
            "thread_wcrt": json_number(self.thread_wcrt),
            "deadline": json_number(self.deadline),
            "met": self.met,
        }


@dataclass(frozen=True)
class ExecutorResult:
    executors: tuple[Executor, ...]
    callbacks: tuple[CallbackBound, ...]
    chains: tuple[CauseEffectChain, ...]
    #: executor path → (simulated window, its intervals (callback path, thread, start, end)), µs
    gantt: dict[str, tuple[Fraction, tuple[tuple[str, int, Fraction, Fraction], ...]]]
    diagnostics: tuple[Diagnostic, ...]

    @property
    def ok(self) -> bool:
        return all(d.severity != "error" for d in self.diagnostics)

    def as_dict(self) -> dict[str, Any]:
        return {
            "executors": [
                {"path": e.path, "kind": e.kind, "label": e.label, "processor": e.processor}
                for e in self.executors
            ],
            "callbacks": [c.as_dict() for c in self.callbacks],
            "chains": [
                {
                    "name": c.name,
                    "paths": list(c.paths),
                    "reaction_time": json_number(c.reaction_time),
                    "data_age": json_number(c.data_age),
                    "deadline": json_number(c.deadline),
                    "met": c.met,
                }
                for c in self.chains
            ],
        }


def _scaled(callbacks: Sequence[Callback], executor: Executor, base: int) -> list[rta.CallbackTiming]:
    return [
        rta.CallbackTiming(
            c.path,
            int(c.period * base),
            int(c.wcet * base),
            int((c.deadline or c.period) * base),
            c.priority,
            executor.rank(c),
            tuple(int(t * base) for t in c.streams),
            tuple(int(j * base) for j in c.jitters),
        )
        for c in callbacks
    ]


def executor_bounds(executor: Executor, interfering: Sequence[Callback]) -> dict[str, Fraction | None]:
    """Path → response-time bound (µs) of every callback of ``executor`` (None: unbounded, or
    a callback without period)."""
    timed = [c for c in executor.callbacks if c.period is not None]
    result: dict[str, Fraction | None] = {c.path: None for c in executor.callbacks}
    if not timed:
        return result
    others = [c for c in interfering if c.period is not None]
    times = [t for c in (*timed, *others) for t in (c.period, c.wcet, c.deadline or c.period)]
    times += [t for c in (*timed, *others) for t in (*c.streams, *c.jitters)]
    base = time_base(times)
    items = _scaled(timed, executor, base)
    preempt = [
        (int(t * base), int(c.wcet * base), int(c.jitters[k] * base) if k < len(c.jitters) else 0)
        for c in others
        for k, t in enumerate((c.period, *c.streams))
    ]
    horizon = max(10**7, 1000 * max(c.period for c in items))
    policy = executor.policy
    common = None
    if policy == "fifo":
        common = rta.fifo_response_time(items, preempt, horizon)
    elif policy == "multi":
        common = rta.work_conserving_response_time(items, preempt, horizon)
    for index, callback in enumerate(timed):
        if policy in ("fifo", "multi"):
            value = common
        elif policy == "pfifo":
            value = rta.np_fixed_priority_response_time(items, index, preempt, horizon)
        elif policy == "edf":
            value = rta.np_edf_response_time(items, index, preempt, horizon)
        else:
            value = rta.polling_response_time(items, index, preempt, horizon)
        result[callback.path] = Fraction(value, base) if value is not None else None
    return result


def _gantt(executor: Executor) -> tuple[Fraction, tuple[tuple[str, int, Fraction, Fraction], ...]]:
    """The executor simulated from a synchronous release over a hyperperiod, at most two of its
    longest periods (the window and the intervals of the executed work)."""
    timed = [c for c in executor.callbacks if c.period is not None and c.wcet > 0]
    if not timed:
        return Fraction(0), ()
    base = time_base([t for c in timed for t in (c.period, c.wcet, c.deadline or c.period, *c.streams)])
    items = _scaled(timed, executor, base)
    span = min(math.lcm(*(c.period for c in items)), 2 * max(c.period for c in items))
    run = simulate_executor(
        items,
        executor.policy,
        periodic_releases(items, span),
        threads=executor.threads,
        groups=[c.group for c in timed],
        quantum=5000 * base,
    )
    merged: list[tuple[int, int, int, int]] = []
    for cb, thread, start, end in run.intervals:  # slices of one job that follow each other: one bar
        if merged and merged[-1][:2] == (cb, thread) and merged[-1][3] == start:
            merged[-1] = (cb, thread, merged[-1][2], end)
        else:
            merged.append((cb, thread, start, end))
    return Fraction(span, base), tuple(
        (timed[cb].path, thread, Fraction(start, base), Fraction(end, base))
        for cb, thread, start, end in merged[:_GANTT_INTERVALS]
    )


#: Release streams of a callback: (minimum inter-arrival time in µs, the callbacks whose output
#: releases it, from the stream's origin to its last writer).
Streams = tuple[tuple[Fraction, tuple[str, ...]], ...]

#: Rounds of the release-jitter iteration before a still-growing bound is given up.
_JITTER_ROUNDS = 30


def _arrival_streams(root: Any, executors: Sequence[Executor], mode: Any) -> dict[str, Streams]:
    """The release streams of the callbacks without ``Period`` (subscriptions, as ROSMOD's): every
    topic connection that feeds a callback adds the streams of its writer (of the fastest one,
    where any callback of a ROSMOD component may write it), each extended by that writer, so a
    subscription fed over two topics counts the messages of both — Casini et al., ECRTS 2019,
    join such inputs as the sum (OR) of their event models — and a message released by a chain
    of callbacks knows the callbacks whose response times make its release jitter. A callback no
    topic releases takes, as before, the least period of the callbacks linked to it inside its
    node; so does a writer met again around a cycle of subscriptions (no jitter)."""
    everything = [c for e in executors for c in e.callbacks]
    periods = {c.path: c.period for c in everything}
    links = callback_links(root, everything, mode)
    changed = True
    while changed:
        changed = False
        for link in links:
            source, target = periods[link.source.path], link.destination
            current = periods[target.path]
            if target.period is None and source is not None and (current is None or source < current):
                periods[target.path] = source
                changed = True
    topics: dict[str, dict[int, list[Callback]]] = {}
    for link in links:
        if link.connection is not None:
            feeding = topics.setdefault(link.destination.path, {})
            feeding.setdefault(id(link.connection), []).append(link.source)
    known: dict[str, Streams] = {}

    def streams(callback: Callback, visiting: frozenset[str]) -> Streams:
        if callback.period is not None:
            return ((callback.period, ()),)
        if callback.path in known:
            return known[callback.path]
        fallback = periods[callback.path]
        if callback.path in visiting or callback.path not in topics:
            return ((fallback, ()),) if fallback is not None else ()
        result: list[tuple[Fraction, tuple[str, ...]]] = []
        for writers in topics[callback.path].values():
            options = [
                tuple((period, (*chain, w.path)) for period, chain in streams(w, visiting | {callback.path}))
                for w in writers
            ]
            options = [o for o in options if o]
            if options:
                result.extend(min(options, key=lambda o: (min(p for p, _ in o), -len(o))))
        if not result and fallback is not None:
            result.append((fallback, ()))
        known[callback.path] = tuple(sorted(result))
        return known[callback.path]

    return {c.path: found for c in everything if c.period is None if (found := streams(c, frozenset()))}


def _with_jitter(
    executors: Sequence[Executor], arrivals: dict[str, Streams], bounds: dict[str, Fraction | None]
) -> tuple[tuple[Executor, ...], set[str]]:
    """The executors with the release streams of their subscriptions, each with its release
    jitter: the sum of the response-time bounds ``bounds`` of the callbacks that release it (the
    output jitter of a callback is its release jitter plus its response time: the holistic
    analysis of Tindell & Clark, as pyCPA propagates it in Casini et al.'s artefact); a callback
    not yet in ``bounds`` adds none. Also the executors a stream of unknown jitter (a writer
    without bound) leaves without bound."""
    result, unknown = [], set()
    for executor in executors:
        callbacks = []
        for c in executor.callbacks:
            found = arrivals.get(c.path)
            if found:
                streams = []
                for period, chain in found:
                    jitters = [bounds.get(w, Fraction(0)) for w in chain]
                    if any(j is None for j in jitters):
                        unknown.add(executor.path)
                        jitters = []
                    streams.append((period, sum(jitters, Fraction(0))))
                streams.sort()
                c = replace(
                    c, period=streams[0][0], deadline=c.deadline or streams[0][0],
                    streams=tuple(p for p, _ in streams[1:]), jitters=tuple(j for _, j in streams),
                )  # fmt: skip
            callbacks.append(c)
        result.append(replace(executor, callbacks=tuple(callbacks)))
    return tuple(result), unknown


def _all_bounds(
    executors: Sequence[Executor], unknown: set[str], known: dict[Any, dict[str, Fraction | None]]
) -> dict[str, Fraction | None]:
    """Every callback's bound, each executor's computed once for its callbacks and those that
    preempt it (``known``, kept across the rounds of the jitter iteration)."""
    bounds: dict[str, Fraction | None] = {}
    for executor in executors:
        if executor.path in unknown:
            bounds.update({c.path: None for c in executor.callbacks})
            continue
        interfering = [
            c
            for other in executors
            if other is not executor and other.processor and other.processor == executor.processor
            if other.priority >= executor.priority
            for c in other.callbacks
        ]
        key = (executor, tuple(interfering))
        if key not in known:
            known[key] = executor_bounds(executor, interfering)
        bounds.update(
            {
                c.path: bound + c.dispatch_latency if bound is not None else None
                for c in executor.callbacks
                for bound in (known[key][c.path],)
            }
        )
    return bounds


def _settled_bounds(
    executors: Sequence[Executor], arrivals: dict[str, Streams]
) -> tuple[dict[str, Fraction | None], set[str], set[str]]:
    """Every callback's bound with the release jitter of its streams, iterated from no jitter
    until no bound grows (bounds only grow with jitter); the callbacks of an executor whose
    bounds still grow after :data:`_JITTER_ROUNDS` rounds get none. Also the executors left
    without bound that way (unsettled) and by a publisher without bound (unknown)."""
    bounds: dict[str, Fraction | None] = {}
    known: dict[Any, dict[str, Fraction | None]] = {}
    for _ in range(_JITTER_ROUNDS):
        current, unknown = _with_jitter(executors, arrivals, bounds)
        found = _all_bounds(current, unknown, known)
        if found == bounds:
            return bounds, set(), unknown
        bounds = found
    current, unknown = _with_jitter(executors, arrivals, bounds)
    found = _all_bounds(current, unknown, known)
    growing = {e.path for e in current for c in e.callbacks if found.get(c.path) != bounds.get(c.path)}
    for executor in current:
        if executor.path in growing:
            found.update({c.path: None for c in executor.callbacks})
    return found, growing, unknown


def _thread_wcrts(root: Any, schedulability: Any) -> dict[str, Fraction]:
    from rosaadl.analysis.latency.flows import thread_response_times

    return thread_response_times(root, schedulability)


def placed(executors: Sequence[Executor], placement: Mapping[str, str]) -> tuple[Executor, ...]:
    """``executors`` on the cores ``placement`` gives their processes (process path → core; an
    executor of a process it does not name keeps its bound processor)."""
    result = []
    for executor in executors:
        owner = next((p for p in placement if executor.path == p or executor.path.startswith(p + ".")), None)
        result.append(replace(executor, processor=placement[owner]) if owner is not None else executor)
    return tuple(result)


def analyze_executors(
    source: Any, *, schedulability: Any = None, limit: int = 100, placement: Mapping[str, str] | None = None
) -> ExecutorResult:
    """Callback response times under their executors and cause-effect chain bounds (module doc);
    with ``placement`` (process path → core), the processes on those cores (:func:`placed`)."""
    from rosaadl.analysis.latency.transmission import connection_transmission_us

    root = instance_root(source)
    mode = system_modes(root)[0]
    diagnostics: list[Diagnostic] = []
    declared = executors_from_instance(root, diagnostics, mode)
    if placement:
        declared = placed(declared, placement)
    arrivals = _arrival_streams(root, declared, mode)
    executors, _ = _with_jitter(declared, arrivals, {})  # the model's periods, for the report
    bounds, unsettled, unknown = _settled_bounds(declared, arrivals)
    thread_wcrt = _thread_wcrts(root, schedulability)
    rows = []
    gantt = {}
    for executor in executors:
        gantt[executor.path] = _gantt(executor)
        for callback in executor.callbacks:
            wcrt = bounds.get(callback.path)
            if callback.period is None:
                diagnostics.append(
                    Diagnostic(
                        "warning",
                        "callback has no Period; no response-time bound",
                        Location(path=callback.path),
                    )
                )
            elif wcrt is None and executor.path in unknown:
                diagnostics.append(
                    Diagnostic(
                        "error", "a callback whose messages release it has no bound: no response-time "
                        "bound", Location(path=callback.path),
                    )
                )  # fmt: skip
            elif wcrt is None and executor.path in unsettled:
                diagnostics.append(
                    Diagnostic(
                        "error", f"the release jitter of executor {executor.path} does not settle: "
                        "no response-time bound", Location(path=callback.path),
                    )
                )  # fmt: skip
            elif wcrt is None:
                diagnostics.append(
                    Diagnostic(
                        "error", f"executor {executor.path} is overloaded: no response-time bound",
                        Location(path=callback.path),
                    )
                )  # fmt: skip
            rows.append(
                CallbackBound(
                    callback.path,
                    executor.path,
                    callback.kind,
                    wcrt,
                    thread_wcrt.get(callback.path),
                    callback.deadline,
                    callback.timed,
                )
            )
    everything = [c for e in executors for c in e.callbacks]
    reader = PropertyReader(diagnostics)
    transmissions: dict[int, Fraction] = {}  # a connection's, once for every chain through it

    def sent(conn: Any) -> Fraction:
        if id(conn) not in transmissions:
            transmissions[id(conn)] = connection_transmission_us(conn, reader, mode)
        return transmissions[id(conn)]

    def bound(callback: Callback) -> Fraction | None:
        return bounds.get(callback.path)

    links = callback_links(root, everything, mode)
    gaps = release_gaps(links, bound)
    chains = []
    for ci in _component_instances(root):
        for flow in ci.endToEndFlows:
            members = flow_callbacks(flow, everything)
            if len(members) >= 2:
                joined = [link for a, b in zip(members, members[1:], strict=False) for link in links
                          if link.source is a and link.destination is b]  # fmt: skip
                name = flow.flow or flow.name
                chains.append(
                    chain_bound(name, members, joined, bound, sent, flow_deadline(reader, flow, mode), gaps)
                )
    for path in cause_effect_chains(links, limit):
        members = [path[0].source] + [link.destination for link in path]
        name = " -> ".join(c.path.partition(".")[2] or c.path for c in (members[0], members[-1]))
        chains.append(chain_bound(name, members, path, bound, sent, gaps=gaps))
    for chain in chains:
        if chain.met is False:
            diagnostics.append(
                Diagnostic(
                    "error",
                    f"reaction time {fmt(chain.reaction_time)} us of {chain.name} exceeds its "
                    f"Latency {fmt(chain.deadline)} us",
                    Location(path=chain.paths[0]),
                )
            )
    return ExecutorResult(executors, tuple(rows), tuple(chains), gantt, tuple(diagnostics))


def _component_instances(root: Any) -> Any:
    from rosaadl.model import component_instances

    return component_instances(root)


def executor_text(result: ExecutorResult) -> list[str]:
    """The ``Executors`` section of the text report."""
    lines = ["Callbacks under their executors (us)", ""]
    rows = [[c.path, c.executor.rpartition(".")[2], c.kind, c.wcrt, c.thread_wcrt, c.deadline, c.met]
            for c in result.callbacks]  # fmt: skip
    lines += table(["callback", "executor", "kind", "wcrt", "thread wcrt", "deadline", "met"], rows)
    lines += ["", "Cause-effect chains (us)", ""]
    rows = [[c.name, c.reaction_time, c.data_age, c.deadline, c.met] for c in result.chains]
    lines += table(["chain", "reaction time", "data age", "deadline", "met"], rows)
    lines.append("")
    return lines


def executor_csv(result: ExecutorResult, base: str) -> dict[str, str]:
    """``<base>__Executors.csv`` (one row per callback) and ``<base>__Chains.csv``."""
    callbacks: list[list[Any]] = [
        ["Callback", "Executor", "Kind", "WCRT (us)", "Thread WCRT (us)", "Deadline (us)", "Met"]
    ]
    callbacks += [
        [c.path, c.executor, c.kind, c.wcrt, c.thread_wcrt, c.deadline, c.met] for c in result.callbacks
    ]
    chains: list[list[Any]] = [
        ["Chain", "Callbacks", "Reaction time (us)", "Data age (us)", "Deadline (us)", "Met"]
    ]
    chains += [
        [c.name, " ".join(c.paths), c.reaction_time, c.data_age, c.deadline, c.met] for c in result.chains
    ]
    return {f"{base}__Executors.csv": csv_text(callbacks), f"{base}__Chains.csv": csv_text(chains)}


def _run(context: AnalysisContext) -> ExecutorResult | None:
    result = analyze_executors(context.root, schedulability=context.result("sched"))
    return result if result.executors else None


register(
    Analysis(
        name="executor",
        json_key="executor",
        order=65,
        run=_run,
        text=executor_text,
        csv=executor_csv,
        aliases=("executors",),
        description="callback response times under ROSMOD and ROS 2 executors; chain reaction time, data age",
    )
)
