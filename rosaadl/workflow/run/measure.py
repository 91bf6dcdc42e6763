"""``rosaadl run … --measure``: the nodes' trace files and ``/proc`` aggregated into
``measurements.json`` (the schema of :mod:`rosaadl.importers.measurements`, ``docs/measurements.md``).

With the node parameter ``rosaadl.trace`` true, each generated node writes
``<run folder>/trace/<node>.<pid>.trace`` (the ``Tracer`` of the generated code): a header
(``N`` its name, ``T ident thread`` its threads, ``O topic port`` its out ports) then one line
per event, times from the system-wide ``CLOCK_MONOTONIC``:
``D thread release start end cpu [fixed]``, ``P topic seq published dispatch_start``,
``R topic seq published received``. Only events inside the measured window (from the moment
every node is up to the stop) count.

* per thread: dispatches, period mean and jitter (max − min of the release intervals),
  execution time (CPU time of the dispatch's own thread), response time (release to end),
  deadline misses (the node's ``<thread>.deadline`` parameter); for a thread on a periodic
  timer, its dispatch latency (:func:`idle_dispatch_latencies`: release to start of the
  dispatches released while its executor was idle); where the workload twin ran, its
  ``twin_execution_time_us``: the mean CPU time per dispatch up to the end of the twin's loop
  (``fixed``: what the twin holds to the CET whatever the CPU's speed);
* per process: CPU load, the CPU time of its threads over the window (the scheduler's count of
  each thread, ``/proc/PID/task/TID/schedstat``, in ns; ``/proc/PID/stat``'s user + system
  time, in 10 ms ticks, where the kernel keeps no such count) and the core it was bound to
  (its CPU affinity, when it is one core); its ``cpu_speed``, the mean speed of the CPUs it
  may run on as the run gauged them (:mod:`~rosaadl.workflow.run.cpu_speed`);
* per topic: messages, rate, bytes per message (the run's monitor) and bandwidth, with the model
  port that publishes it;
* per chain (a flow of the model as processes in order): end-to-end latency, each message on the
  chain's last topic traced back through the latest message on the previous topic that its
  publisher's node had received before the publishing dispatch began (data age, as an
  asynchronous system has it).
"""

from __future__ import annotations

import bisect
import itertools
import os
import statistics
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rosaadl.importers.measurements import FORMAT, VERSION

__all__ = [
    "TRACE_FOLDER",
    "MEASUREMENTS_FILE",
    "TRACE_PARAMETERS",
    "NodeTrace",
    "ChainPlan",
    "read_trace",
    "read_traces",
    "process_cpu_seconds",
    "thread_cpu_ns",
    "cpu_seconds_between",
    "process_cpus",
    "single_cpu",
    "process_core",
    "measurements_document",
    "chain_plans",
    "planned_chains",
    "idle_dispatch_latencies",
]

#: The folder of the run folder the nodes write their traces into.
TRACE_FOLDER = "trace"
#: The file ``--measure`` writes into the run folder.
MEASUREMENTS_FILE = "measurements.json"
#: A trace file larger than this is read up to it (a run of hours at the tracking example's rates
#: is about 100 MB).
_MAX_TRACE_BYTES = 512 * 1024 * 1024


def TRACE_PARAMETERS(folder: Path) -> list[tuple[str, object]]:  # noqa: N802 - a constant of the run
    """The node parameters that switch the tracer on, writing into ``folder``."""
    return [("rosaadl.trace", True), ("rosaadl.trace_dir", str(folder))]


@dataclass
class NodeTrace:
    """What one node's trace file holds."""

    node: str = ""
    threads: dict[str, str] = field(default_factory=dict)  # ident -> thread path below the process
    ports: dict[str, str] = field(default_factory=dict)  # topic -> port path below the process
    dispatches: dict[str, list[tuple[int, int, int, int]]] = field(default_factory=dict)
    #: (start, end) of the dispatches that overlap the window but are not in it (their release
    #: or end lies outside): they kept the executor busy at the window's edges
    edges: list[tuple[int, int]] = field(default_factory=list)
    published: dict[tuple[str, int], int] = field(default_factory=dict)  # (topic, seq) -> dispatch start
    #: thread ident -> (dispatches, their CPU ns up to the end of the workload twin's loop) in
    #: the window
    twin: dict[str, tuple[int, int]] = field(default_factory=dict)
    received: dict[str, list[tuple[int, int, int]]] = field(default_factory=dict)  # topic -> (recv, seq, pub)
    bad_lines: int = 0


@dataclass(frozen=True)
class ChainPlan:
    """A flow of the model as the nodes it crosses, in order, and the topic of each step."""

    name: str
    topics: tuple[tuple[str, str, str], ...]  # (topic, publishing node, subscribing node)


def read_trace(path: Path, window: tuple[int, int] | None = None) -> NodeTrace:
    """The events of one trace file (a line cut short by a killed node is counted, not read)."""
    trace = NodeTrace()
    low, high = window if window is not None else (0, 1 << 63)
    with path.open("r", encoding="utf-8", errors="replace") as handle:
        text = handle.read(_MAX_TRACE_BYTES)
    for line in text.splitlines():
        parts = line.split(" ")
        try:
            kind = parts[0]
            if kind == "N" and len(parts) == 2:
                trace.node = parts[1]
            elif kind == "T" and len(parts) == 3:
                trace.threads[parts[1]] = parts[2]
            elif kind == "O" and len(parts) == 3:
                trace.ports[parts[1]] = parts[2]
            elif kind == "D" and len(parts) in (6, 7):
                release, start, end, cpu, *fixed = (int(p) for p in parts[2:])
                if low <= release and end <= high:
                    trace.dispatches.setdefault(parts[1], []).append((release, start, end, cpu))
                    if fixed:
                        count, total = trace.twin.get(parts[1], (0, 0))
                        trace.twin[parts[1]] = (count + 1, total + fixed[0])
                elif end >= low and start <= high:
                    trace.edges.append((start, end))
            elif kind == "P" and len(parts) == 5:
                trace.published[(parts[1], int(parts[2]))] = int(parts[4])
            elif kind == "R" and len(parts) == 5:
                seq, pub, recv = int(parts[2]), int(parts[3]), int(parts[4])
                trace.received.setdefault(parts[1], []).append((recv, seq, pub))
            else:
                trace.bad_lines += 1
        except ValueError:
            trace.bad_lines += 1
    for events in trace.received.values():
        events.sort()
    return trace


def read_traces(folder: Path, window: tuple[int, int] | None = None) -> dict[str, NodeTrace]:
    """Node full name → its trace (the files of ``folder``; a node traced twice: the later file)."""
    traces = {}
    for path in sorted(folder.glob("*.trace"), key=lambda p: p.stat().st_mtime):
        trace = read_trace(path, window)
        if trace.node:
            traces[trace.node] = trace
    return traces


def process_cpu_seconds(pid: int) -> float | None:
    """User + system CPU time of process ``pid`` so far (``/proc/PID/stat``), None when gone."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    fields = text.rpartition(")")[2].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def thread_cpu_ns(pid: int) -> dict[int, int] | None:
    """Per thread of process ``pid``: its CPU time so far in ns (``/proc/PID/task/TID/schedstat``,
    the scheduler's own count, to the nanosecond); None when the process is gone or the kernel
    keeps no such count."""
    times = {}
    try:
        tasks = list(Path(f"/proc/{pid}/task").iterdir())
    except OSError:
        return None
    for task in tasks:
        try:
            times[int(task.name)] = int(Path(task, "schedstat").read_text().split()[0])
        except (OSError, ValueError, IndexError):
            continue  # a thread that ended meanwhile
    return times or None


def cpu_seconds_between(before: dict[int, int], after: dict[int, int]) -> float:
    """The CPU time the threads of ``after`` spent since ``before`` (a thread started meanwhile:
    all of it), in seconds."""
    return sum(ns - before.get(tid, 0) for tid, ns in after.items()) / 1e9


def process_cpus(pid: int) -> set[int]:
    """The CPUs process ``pid`` may run on (its affinity; none when it is gone)."""
    try:
        return set(os.sched_getaffinity(pid))
    except OSError:
        return set()


def single_cpu(cpus: set[int]) -> int | None:
    """The CPU of an affinity of one CPU, None for several (or none)."""
    return next(iter(cpus)) if len(cpus) == 1 else None


def process_core(pid: int) -> int | None:
    """The one core process ``pid`` may run on, None when it may run on several (or is gone)."""
    return single_cpu(process_cpus(pid))


def _stats(values: list[float]) -> dict[str, float] | None:
    if not values:
        return None
    return {
        "min": round(min(values), 3),
        "mean": round(statistics.fmean(values), 3),
        "max": round(max(values), 3),
    }


def idle_dispatch_latencies(
    dispatches: Iterable[tuple[int, int, int, int]], spans: Iterable[tuple[int, int]]
) -> list[float]:
    """Start − release in µs of each of ``dispatches`` (``(release, start, end, cpu)`` in ns)
    that its timer released while its executor was idle: its release precedes its start (the
    generated code reads a timer's due time before the dispatch starts, a message's or request's
    entry after: such a dispatch has none), no other dispatch of ``spans`` (``(start, end)`` of
    every dispatch of the process, these included) was running at the release (its
    ``[start, end]`` holds it) and none started between the release and this start. What is
    left is the executor's own latency (waking up, its wait set, taking the timer, handing it to
    a thread), not the wait for another callback: ``ROS_Properties::Dispatch_Latency``."""
    ordered = sorted(spans)
    starts = [start for start, _end in ordered]
    latest_end = list(itertools.accumulate((end for _start, end in ordered), max))
    out = []
    for release, start, _end, _cpu in dispatches:
        if release >= start:
            continue
        before = bisect.bisect_left(starts, release)  # the spans that started before the release
        if before and latest_end[before - 1] >= release:
            continue  # another dispatch was running at the release
        if bisect.bisect_left(starts, start) > before:
            continue  # another dispatch started between the release and this start
        out.append((start - release) / 1000)
    return out


def _thread_row(
    process_path: str,
    thread: str,
    events: list,
    deadline_s: float | None,
    spans: list[tuple[int, int]] | None = None,
    twin: tuple[int, int] | None = None,
) -> dict[str, Any]:
    """One thread's row; ``spans``: ``(start, end)`` of every dispatch of its process when the
    thread runs on a periodic timer (its dispatch latency is measured), else None; ``twin``: the
    workload twin's (dispatches, their CPU ns up to the loop's end) where it ran."""
    events = sorted(events)
    releases = [e[0] for e in events]
    gaps = [(b - a) / 1000 for a, b in itertools.pairwise(releases)]
    responses = [(e[2] - e[0]) / 1000 for e in events]
    deadline_us = deadline_s * 1e6 if deadline_s else None
    row: dict[str, Any] = {
        "path": f"{process_path}.{thread}",
        "process": process_path,
        "dispatches": len(events),
        "period_us": None
        if not gaps
        else {"mean": round(statistics.fmean(gaps), 3), "jitter": round(max(gaps) - min(gaps), 3)},
        "execution_time_us": _stats([e[3] / 1000 for e in events]),
        "response_time_us": _stats(responses),
        "deadline_misses": sum(1 for r in responses if deadline_us and r > deadline_us),
    }
    if deadline_us:
        row["deadline_us"] = round(deadline_us, 3)
    if spans is not None:
        row["dispatch_latency_us"] = _stats(idle_dispatch_latencies(events, spans))
    if twin is not None and twin[0]:
        row["twin_execution_time_us"] = round(twin[1] / twin[0] / 1000, 3)
    return row


def _origin(traces: dict[str, NodeTrace], hops: tuple, index: int, seq: int, pub: int) -> int | None:
    """When the data of message ``seq`` (published at ``pub``) on hop ``index`` of a chain left
    the chain's first node: the publish time on the first hop, reached back through the latest
    message of the previous hop the publishing node had received when its dispatch began."""
    while index > 0:
        topic, publisher, _subscriber = hops[index]
        node = traces.get(publisher)
        started = None if node is None else node.published.get((topic, seq))
        if started is None:
            return None
        before = node.received.get(hops[index - 1][0], [])
        at = bisect.bisect_right(before, (started, 1 << 63, 1 << 63)) - 1
        if at < 0:
            return None
        _recv, seq, pub = before[at]
        index -= 1
    return pub


def chain_latencies(traces: dict[str, NodeTrace], chain: ChainPlan) -> list[float]:
    """End-to-end latencies (µs) of every message on the chain's last topic (see the docstring)."""
    hops = chain.topics
    if not hops:
        return []
    topic, _publisher, subscriber = hops[-1]
    last = traces.get(subscriber)
    if last is None:
        return []
    out = []
    for recv, seq, pub in last.received.get(topic, ()):
        origin = _origin(traces, hops, len(hops) - 1, seq, pub)
        if origin is not None and recv >= origin:
            out.append((recv - origin) / 1000)
    return out


def measurements_document(
    *,
    nodes: Iterable[Any],
    traces: dict[str, NodeTrace],
    cpu_load: dict[str, float],
    cores: dict[str, int | None],
    topics: Iterable[Any],
    chains: Iterable[ChainPlan],
    run: dict[str, Any],
    root: str | None = None,
    profiles: dict[str, tuple[str, str]] | None = None,
    cpu_speeds: dict[str, float] | None = None,
) -> dict[str, Any]:
    """The ``measurements.json`` document of a run: ``nodes`` are the plan's
    :class:`~rosaadl.workflow.run.plan.NodeLaunch` (full name, process path, parameters, the
    threads on a periodic timer: only these get a ``dispatch_latency_us``),
    ``cpu_load``, ``cores`` and ``profiles`` (the board and core a profile of the process is
    named after, :mod:`~rosaadl.workflow.run.profiles`) by node full name, ``topics`` the run's
    topic results, ``cpu_speeds`` the speed of each node's CPUs. ``run.board`` and ``run.core`` are
    set when every process has the same."""
    profiles = profiles or {}
    cpu_speeds = cpu_speeds or {}
    threads, processes, ports = [], [], {}
    for node in nodes:
        trace = traces.get(node.full_name)
        parameters = dict(node.parameters)
        if node.full_name in cpu_load:
            row: dict[str, Any] = {
                "path": node.path,
                "node": node.name,
                "cpu_load_percent": round(cpu_load[node.full_name], 4),
                "core": cores.get(node.full_name),
            }
            if node.full_name in profiles:
                board, core = profiles[node.full_name]
                row["profile"] = {"board": board, "core": core}
            if node.full_name in cpu_speeds:
                row["cpu_speed"] = cpu_speeds[node.full_name]
            processes.append(row)
        if trace is None:
            continue
        for topic, port in trace.ports.items():
            ports.setdefault(topic, f"{node.path}.{port}")
        timers = set(getattr(node, "timers", None) or ())
        spans = [(start, end) for events in trace.dispatches.values() for _r, start, end, _c in events]
        spans += trace.edges
        for ident, thread in sorted(trace.threads.items(), key=lambda item: item[1]):
            deadline = parameters.get(f"{ident}.deadline")
            deadline_s = float(deadline) if isinstance(deadline, (int, float)) and deadline else None
            threads.append(
                _thread_row(
                    node.path,
                    thread,
                    trace.dispatches.get(ident, []),
                    deadline_s,
                    spans if ident in timers else None,
                    trace.twin.get(ident),
                )
            )
    topic_rows = []
    for topic in topics:
        size = topic.bytes_per_message
        row = {
            "name": topic.name,
            "type": topic.type,
            "messages": int(topic.messages),
            "rate_hz": round(topic.rate_hz or 0.0, 4),
            "bandwidth_bytes_per_s": round((topic.rate_hz or 0.0) * (size or 0), 3),
        }
        if topic.name in ports:
            row["port"] = ports[topic.name]
        if size is not None:
            row["bytes_per_message"] = int(round(size))
        topic_rows.append(row)
    chain_rows = []
    for chain in chains:
        latencies = chain_latencies(traces, chain)
        chain_rows.append(
            {
                "name": chain.name,
                "topics": [hop[0] for hop in chain.topics],
                "samples": len(latencies),
                "latency_us": _stats(latencies),
            }
        )
    named = {tuple(p["profile"].values()) for p in processes if "profile" in p}
    if len(named) == 1 and all("profile" in p for p in processes):
        board, core = named.pop()
        run = {**run, "board": board, "core": core}
    document: dict[str, Any] = {"format": FORMAT, "version": VERSION}
    if root:
        document["model"] = {"root": root}
    document.update(
        {"run": run, "threads": threads, "processes": processes, "topics": topic_rows, "chains": chain_rows}
    )
    return document


def planned_chains(plan: Any) -> list[ChainPlan]:
    """The chains a run plan keeps (``RunPlan.chains``), as the measurement traces them."""
    return [ChainPlan(c["name"], tuple(tuple(hop) for hop in c["topics"])) for c in plan.chains]


def chain_plans(
    nodes: list[Any], topics: list[Any], flows: Iterable[tuple[str, list[str]]]
) -> list[ChainPlan]:
    """The chains of the model's flows (name, thread instance paths in order) as topics between
    the plan's nodes: each thread belongs to the node whose process path holds it; each change of
    node is one topic the first node publishes and the next subscribes to (a flow whose step has no
    such topic is left out)."""
    out = []
    for name, threads in flows:
        order: list[Any] = []
        for thread in threads:
            owner = max(
                (n for n in nodes if thread == n.path or thread.startswith(n.path + ".")),
                key=lambda n: len(n.path),
                default=None,
            )
            if owner is not None and (not order or order[-1] is not owner):
                order.append(owner)
        hops = []
        for first, second in itertools.pairwise(order):
            topic = next(
                (t for t in topics if first.full_name in t.publishers and second.full_name in t.subscribers),
                None,
            )
            if topic is None:
                hops = []
                break
            hops.append((topic.name, first.full_name, second.full_name))
        if hops:
            out.append(ChainPlan(name, tuple(hops)))
    return out
