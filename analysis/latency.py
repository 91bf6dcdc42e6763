"""End-to-end latency of chains of threads over topic (port) connections.

A simplified form of OSATE's flow latency analysis, per chain ``t0 -> t1 -> ... -> tn``:

* the first thread contributes its response time: best its minimum ``Compute_Execution_Time``,
  worst its worst-case response time from the schedulability analysis (its maximum CET when the
  thread is not in an analysed scheduling domain);
* every hop ``t(i-1) -> ti`` contributes

  - the transmission on the bus the connection is bound to (``Actual_Connection_Binding``,
    through virtual buses): the bus's ``Transmission_Time`` (``Fixed`` + ``PerByte`` × bytes)
    when it has one, else bytes / ``SEI::BandWidthCapacity``, plus the ``Latency`` of the
    connection and of the bus when set; the bytes are the source port's ``Data_Size`` plus the
    data overhead of the buses on the way, as the bus load analysis counts them;
    an unbound connection transmits in no time;
  - the sampling delay of the receiving thread: up to its ``Period`` when it is periodic (best
    0, worst one period), none when it is dispatched by the arrival (sporadic, aperiodic);
  - the receiving thread's response time, as for the first thread.

Chains come from the end-to-end flow instances of the model (their expected latency is the
flow's ``Latency`` upper bound), from explicit lists of thread paths, or, when there are
neither, from every maximal path of threads over port connections. Times are exact
microseconds (:class:`~fractions.Fraction`).
"""

from __future__ import annotations

import logging
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rosaadl.analysis.busload import data_size_kbyte
from rosaadl.analysis.instance_values import (
    PropertyReader,
    SystemMode,
    bound_processor,
    category_of,
    instance_root,
    system_modes,
)
from rosaadl.analysis.registry import Analysis, AnalysisContext, register
from rosaadl.analysis.rendering import csv_text, fmt, table
from rosaadl.errors import Diagnostic, Location, ModelError
from rosaadl.model import component_instances

__all__ = ["LatencyHop", "LatencyChain", "LatencyResult", "analyze_latency", "thread_chains"]

log = logging.getLogger(__name__)

_US = 1_000_000
_EVENT_DRIVEN = frozenset({"sporadic", "aperiodic", "background", "timed", "hybrid"})


def _num(value: Fraction | None) -> float | int | None:
    if value is None:
        return None
    return int(value) if value.denominator == 1 else float(value)


@dataclass(frozen=True)
class LatencyHop:
    """One contribution to a chain's latency (``kind``: response, sampling or transmission)."""

    kind: str
    path: str
    best_us: Fraction
    worst_us: Fraction
    note: str = ""

    def as_dict(self) -> dict[str, Any]:
        return {
            "kind": self.kind,
            "path": self.path,
            "best_us": _num(self.best_us),
            "worst_us": _num(self.worst_us),
            "note": self.note,
        }


@dataclass(frozen=True)
class LatencyChain:
    """A chain of threads with its best and worst end-to-end latency in microseconds."""

    name: str
    threads: tuple[str, ...]
    hops: tuple[LatencyHop, ...]
    expected_us: Fraction | None = None

    @property
    def best_us(self) -> Fraction:
        return sum((h.best_us for h in self.hops), Fraction(0))

    @property
    def worst_us(self) -> Fraction:
        return sum((h.worst_us for h in self.hops), Fraction(0))

    @property
    def met(self) -> bool | None:
        """Whether the worst case stays within the expected latency (None: no expectation)."""
        return None if self.expected_us is None else self.worst_us <= self.expected_us

    def as_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "threads": list(self.threads),
            "best_us": _num(self.best_us),
            "worst_us": _num(self.worst_us),
            "expected_us": _num(self.expected_us),
            "met": self.met,
            "hops": [h.as_dict() for h in self.hops],
        }


@dataclass(frozen=True)
class LatencyResult:
    chains: tuple[LatencyChain, ...]
    diagnostics: tuple[Diagnostic, ...]

    @property
    def ok(self) -> bool:
        return all(d.severity != "error" for d in self.diagnostics)

    def chain(self, name: str) -> LatencyChain:
        for chain in self.chains:
            if chain.name == name:
                return chain
        raise ModelError(f"no latency chain {name!r}")

    def as_dict(self) -> dict[str, Any]:
        return {"chains": [c.as_dict() for c in self.chains]}


# =============================================================================== chains


def _thread_of(end: Any) -> Any | None:
    """The thread a connection end belongs to (None when it is not inside a thread)."""
    current = end
    while current is not None:
        if hasattr(current, "componentInstances") and category_of(current) == "thread":
            return current
        if hasattr(current, "componentInstances") and current is not end:
            return None
        current = current.eContainer()
    return None


def _thread_links(root: Any, mode: SystemMode) -> list[tuple[Any, Any, Any]]:
    """(source thread, connection, destination thread) of every port connection between threads."""
    links = []
    for ci in component_instances(root):
        for conn in ci.connectionInstances:
            kind = getattr(getattr(conn, "kind", None), "name", "")
            if kind not in ("portConnection", "") or not mode.active(conn):
                continue
            src, dst = _thread_of(conn.source), _thread_of(conn.destination)
            if src is not None and dst is not None and src is not dst:
                links.append((src, conn, dst))
    return links


def thread_chains(source: Any, limit: int = 100) -> list[list[Any]]:
    """Every maximal path of threads over port connections (from threads nothing feeds to threads
    that feed nothing; cycles are cut), in model order, at most ``limit`` of them."""
    root = instance_root(source)
    mode = system_modes(root)[0]
    links = _thread_links(root, mode)
    successors: dict[int, list[Any]] = {}
    has_input: set[int] = set()
    threads: dict[int, Any] = {}
    for src, _conn, dst in links:
        targets = successors.setdefault(id(src), [])
        if all(t is not dst for t in targets):
            targets.append(dst)
        has_input.add(id(dst))
        threads.setdefault(id(src), src)
        threads.setdefault(id(dst), dst)
    order = [ci for ci in component_instances(root) if id(ci) in threads]
    chains: list[list[Any]] = []

    def extend(path: list[Any]) -> None:
        if len(chains) >= limit:
            return
        nexts = [t for t in successors.get(id(path[-1]), []) if all(t is not p for p in path)]
        if not nexts:
            if len(path) > 1:
                chains.append(list(path))
            return
        for nxt in nexts:
            path.append(nxt)
            extend(path)
            path.pop()

    starts = [t for t in order if id(t) not in has_input] or order[:1]
    for start in starts:
        extend([start])
    return chains


# =============================================================================== the analysis


class _Latency:
    def __init__(self, root: Any, wcrt: dict[str, Fraction], diagnostics: list[Diagnostic]) -> None:
        self.root = root
        self.reader = PropertyReader(diagnostics)
        self.mode = system_modes(root)[0]
        self.wcrt = wcrt
        self.links = _thread_links(root, self.mode)

    def us(self, obj: Any, name: str, part: str = "max") -> Fraction | None:
        value = self.reader.seconds(obj, name, self.mode, part=part)
        return value * _US if value is not None else None

    def response(self, thread: Any) -> LatencyHop:
        from rosaadl.model import instance_path

        path = instance_path(thread)
        best = self.us(thread, "Timing_Properties::Compute_Execution_Time", "min")
        worst_cet = self.us(thread, "Timing_Properties::Compute_Execution_Time", "max")
        if best is None or worst_cet is None:
            self.reader.report(
                "warning", "thread has no Compute_Execution_Time; its response time counts as 0", thread
            )
            best = worst_cet = Fraction(0)
        worst = self.wcrt.get(path)
        note = "response time (WCRT from the schedulability analysis)"
        if worst is None:
            worst = worst_cet
            note = "response time (CET; no WCRT)"
        return LatencyHop("response", path, best, max(worst, best), note)

    def sampling(self, thread: Any) -> LatencyHop | None:
        from rosaadl.model import instance_path

        dispatch = (self.reader.enum(thread, "Thread_Properties::Dispatch_Protocol", self.mode) or "").lower()
        if dispatch in _EVENT_DRIVEN:
            return None
        period = self.us(thread, "Timing_Properties::Period")
        if period is None:
            self.reader.report(
                "error", "periodic thread has no Period; its sampling delay is unknown", thread
            )
            return None
        if period <= 0:
            self.reader.report("error", "Period must be positive", thread)
            return None
        return LatencyHop(
            "sampling", instance_path(thread), Fraction(0), period, "sampling delay up to the period"
        )

    def connection_between(self, src: Any, dst: Any) -> Any | None:
        for a, conn, b in self.links:
            if a is src and b is dst:
                return conn
        return None

    def transmission(self, conn: Any) -> list[LatencyHop]:
        from rosaadl.model import instance_path

        reader, mode = self.reader, self.mode
        hops = []
        path = instance_path(conn)
        own_best = self.us(conn, "Communication_Properties::Latency", "min")
        own_worst = self.us(conn, "Communication_Properties::Latency", "max")
        if own_worst is not None:
            hops.append(LatencyHop("latency", path, own_best or Fraction(0), own_worst, "connection Latency"))
        chain = self.bus_chain(conn)
        if not chain:
            src, dst = _thread_of(conn.source), _thread_of(conn.destination)
            if src is not None and dst is not None:
                a, b = bound_processor(src, mode), bound_processor(dst, mode)
                if a is not None and b is not None and _apart(self.root, a, b):
                    reader.report(
                        "warning",
                        "connection joins threads on different top-level subsystems but is not bound to "
                        "a bus (Actual_Connection_Binding); its transmission time counts as 0",
                        conn,
                    )
            return hops
        source = conn.source
        size = data_size_kbyte(reader, source, mode) if source is not None else None
        overhead = sum((data_size_kbyte(reader, bus, mode) or Fraction(0) for bus in chain), Fraction(0))
        byte_count = ((size or Fraction(0)) + overhead) * 1000
        physical = chain[-1]
        record = reader.value(physical, "Communication_Properties::Transmission_Time", mode)
        bus_path = instance_path(physical)
        if isinstance(record, dict) and (
            record.get("Fixed") is not None or record.get("PerByte") is not None
        ):
            fixed, per_byte = record.get("Fixed"), record.get("PerByte")
            best = worst = Fraction(0)
            if fixed is not None:
                best += (reader.convert(physical, "Transmission_Time", fixed, "sec", part="min") or 0) * _US
                worst += (reader.convert(physical, "Transmission_Time", fixed, "sec") or 0) * _US
            if per_byte is not None:
                low = reader.convert(physical, "Transmission_Time", per_byte, "sec", part="min") or 0
                high = reader.convert(physical, "Transmission_Time", per_byte, "sec") or 0
                best += low * _US * byte_count
                worst += high * _US * byte_count
            hops.append(
                LatencyHop(
                    "transmission", bus_path, best, worst, f"{_num(byte_count)} bytes, Transmission_Time"
                )
            )
        else:
            capacity = reader.number(physical, "SEI::BandWidthCapacity", "KBytesps", mode)
            if capacity is None or capacity <= 0:
                if category_of(physical) == "bus":  # a virtual bus bound to no bus: in-board transport
                    reader.report(
                        "warning",
                        "bus has no SEI::BandWidthCapacity or Transmission_Time; "
                        "transmission times count as 0",
                        physical,
                    )
                time = Fraction(0)
            else:
                time = byte_count / (capacity * 1000) * _US
            hops.append(
                LatencyHop("transmission", bus_path, time, time, f"{_num(byte_count)} bytes over {bus_path}")
            )
        for bus in chain:
            best = self.us(bus, "Communication_Properties::Latency", "min")
            worst = self.us(bus, "Communication_Properties::Latency", "max")
            if worst is not None:
                hops.append(
                    LatencyHop("latency", instance_path(bus), best or Fraction(0), worst, "bus Latency")
                )
        return hops

    def bus_chain(self, conn: Any) -> list[Any]:
        """The buses a connection is carried by, innermost (virtual) first, the physical bus last."""
        chain: list[Any] = []
        current = conn
        for _ in range(64):
            bound = self.reader.targets(current, "Actual_Connection_Binding", self.mode) or []
            if not bound and category_of(current) == "virtualBus":
                parent = current.eContainer()
                if parent is not None and category_of(parent) in ("bus", "virtualBus"):
                    bound = [parent]
            if not bound:
                break
            target = bound[0]
            if any(target is c for c in chain):
                self.reader.report("error", "virtual buses are bound in a cycle", conn)
                break
            kind = category_of(target)
            if kind not in ("bus", "virtualBus"):
                if kind in ("processor", "memory", "device", "system"):
                    break  # bound to hardware that is not a bus: no transmission modelled
                self.reader.report(
                    "error", f"Actual_Connection_Binding refers to {target.name}, which is not a bus", conn
                )
                break
            chain.append(target)
            if kind == "bus":
                break
            current = target
        return chain

    def chain(self, name: str, threads: Sequence[Any], expected: Fraction | None) -> LatencyChain:
        from rosaadl.model import instance_path

        hops = [self.response(threads[0])]
        for src, dst in zip(threads, threads[1:], strict=False):
            conn = self.connection_between(src, dst)
            if conn is None:
                self.reader.report(
                    "warning",
                    f"no port connection from {instance_path(src)} to {instance_path(dst)}; "
                    "the hop is counted without transmission",
                    dst,
                )
            else:
                hops.extend(self.transmission(conn))
            sampling = self.sampling(dst)
            if sampling is not None:
                hops.append(sampling)
            hops.append(self.response(dst))
        return LatencyChain(name, tuple(instance_path(t) for t in threads), tuple(hops), expected)

    def flow_threads(self, flow: Any) -> list[Any]:
        threads: list[Any] = []

        def add(thread: Any | None) -> None:
            if thread is not None and (not threads or threads[-1] is not thread):
                threads.append(thread)

        for element in flow.flowElements:
            if hasattr(element, "componentInstances"):
                if category_of(element) == "thread":
                    add(element)
            elif hasattr(element, "connectionReferences"):
                add(_thread_of(element.source))
                add(_thread_of(element.destination))
            else:
                add(_thread_of(element))
        return threads


def _apart(root: Any, a: Any, b: Any) -> bool:
    """Whether two processors lie in different subcomponents of the root (e.g. two robots)."""

    def top(obj: Any) -> Any:
        while obj.eContainer() is not None and obj.eContainer() is not root:
            obj = obj.eContainer()
        return obj

    return a is not b and top(a) is not top(b)


def _wcrt_map(root: Any, schedulability: Any) -> dict[str, Fraction]:
    if schedulability is None:
        from rosaadl.analysis.schedulability import analyze_schedulability

        try:
            schedulability = analyze_schedulability(root)
        except ModelError as exc:
            log.debug("no schedulability analysis for latency: %s", exc)
            return {}
    unit = getattr(schedulability, "time_unit", "us")
    from rosaadl.units import standard_units

    factor = standard_units().factor(unit, "us")
    result = {}
    for domain in schedulability.domains:
        for row in domain.tasks:
            if row.wcrt is not None and row.wcrt_exact:  # a lower bound bounds nothing
                result[row.path] = Fraction(row.wcrt) * factor
    return result


def analyze_latency(
    source: Any,
    chains: Iterable[Sequence[Any] | Any] | None = None,
    *,
    schedulability: Any = None,
    limit: int = 100,
) -> LatencyResult:
    """Best and worst end-to-end latency of chains of threads.

    ``chains``: sequences of thread instances or instance paths, or end-to-end flow instances;
    by default the model's end-to-end flows, else every maximal thread path (at most ``limit``).
    ``schedulability``: a :class:`~rosaadl.analysis.schedulability.SchedulabilityResult` giving
    the worst-case response times (computed when not given).
    """
    from rosaadl import model as _model

    root = instance_root(source)
    diagnostics: list[Diagnostic] = []
    analysis = _Latency(root, _wcrt_map(root, schedulability), diagnostics)
    specs: list[tuple[str, list[Any], Fraction | None]] = []
    if chains is None:
        flows = [f for ci in component_instances(root) for f in ci.endToEndFlows]
        chains = flows or thread_chains(root, limit)
    for item in chains:
        if hasattr(item, "flowElements"):
            threads = analysis.flow_threads(item)
            expected = analysis.us(item, "Communication_Properties::Latency")
            name = item.flow or item.name or _model.instance_path(item)
            if len(threads) < 1:
                diagnostics.append(
                    Diagnostic(
                        "warning",
                        "end-to-end flow goes through no thread; no latency computed",
                        Location(path=_model.instance_path(item)),
                    )
                )
                continue
            specs.append((name, threads, expected))
            continue
        threads = []
        for element in item:
            if isinstance(element, str):
                try:
                    element = _model.find_instance(root, element)
                except ModelError as exc:
                    diagnostics.append(Diagnostic("error", exc.message, exc.location))
                    threads = []
                    break
            if category_of(element) != "thread":
                diagnostics.append(
                    Diagnostic(
                        "error",
                        "a latency chain element is not a thread",
                        Location(path=_model.instance_path(element)),
                    )
                )
                threads = []
                break
            threads.append(element)
        if threads:
            name = " -> ".join(_model.instance_path(t).partition(".")[2] or t.name for t in threads)
            specs.append((name, threads, None))
    results = []
    for name, threads, expected in specs:
        chain = analysis.chain(name, threads, expected)
        if chain.met is False:
            diagnostics.append(
                Diagnostic(
                    "error",
                    f"end-to-end latency {_num(chain.worst_us)} us of {name} exceeds its Latency "
                    f"{_num(expected)} us",
                    Location(path=chain.threads[0]),
                )
            )
        results.append(chain)
    log.debug("latency of %d chains", len(results))
    return LatencyResult(tuple(results), tuple(diagnostics))


# =============================================================================== report


def latency_text(result: LatencyResult) -> list[str]:
    """The ``End-to-end latency`` section of the text report."""
    lines = ["End-to-end latency (us)", ""]
    rows = [[c.name, c.best_us, c.worst_us, c.expected_us, c.met] for c in result.chains]
    lines += table(["chain", "best", "worst", "expected", "met"], rows)
    lines.append("")
    return lines


def latency_csv(result: LatencyResult, base: str) -> dict[str, str]:
    """``<base>__Latency.csv``: every hop of every chain, then the chain's total."""
    rows: list[list[Any]] = [["Chain", "Element", "Kind", "Best (us)", "Worst (us)", "Note"]]
    for chain in result.chains:
        for hop in chain.hops:
            rows.append([chain.name, hop.path, hop.kind, hop.best_us, hop.worst_us, hop.note])
        rows.append(
            [chain.name, "Total", "", chain.best_us, chain.worst_us, f"expected {fmt(chain.expected_us)}"]
        )
    return {f"{base}__Latency.csv": csv_text(rows)}


def _run(context: AnalysisContext) -> LatencyResult:
    chains = context.options.get("latency_chains")
    return analyze_latency(context.root, chains, schedulability=context.result("sched"))


register(
    Analysis(
        name="latency",
        json_key="latency",
        order=60,
        run=_run,
        text=latency_text,
        csv=latency_csv,
        description="end-to-end latency of thread chains and flows, with the response times",
    )
)
