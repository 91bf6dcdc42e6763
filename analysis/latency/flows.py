"""End-to-end flow latency of an instance, per flow, system operation mode and system kind.

:func:`analyze_latency` runs OSATE's flow latency analysis (``FlowLatencyAnalysisSwitch``):
for every end-to-end flow of the instance, in every system operation mode it is active in, the
contributors of its elements (:mod:`.contributors`, :mod:`.transmission`), their totals for an
asynchronous and for a synchronous system (:mod:`.totals`), and OSATE's summary against the
flow's ``Latency`` (``LatencyReportEntry.genResult``). A model without end-to-end flows gets
flows derived from its topic chains (:mod:`.chains`): the same analysis, with the worst-case
response times of the schedulability analysis as the threads' response times.
"""

from __future__ import annotations

import logging
from collections.abc import Iterable, Sequence
from fractions import Fraction
from typing import Any

from rosaadl.analysis.demand import ResourceDemand
from rosaadl.analysis.instance_values import (
    PropertyReader,
    SystemMode,
    category_of,
    instance_root,
    system_modes,
)
from rosaadl.analysis.latency.chains import chain_elements, refine_by_threads, thread_chains
from rosaadl.analysis.latency.contributors import FlowWalk, flatten_flow, is_connection
from rosaadl.analysis.latency.declarative import DeclarativeValues
from rosaadl.analysis.latency.model import (
    Contributor,
    LatencyChain,
    LatencyHop,
    LatencyPreferences,
    LatencyResult,
    method_word,
    number,
)
from rosaadl.analysis.latency.totals import actual_latency
from rosaadl.analysis.latency.transmission import Transmission
from rosaadl.errors import Diagnostic, Location, ModelError
from rosaadl.model import component_instances, instance_path

__all__ = ["analyze_latency", "flow_active", "summary"]

log = logging.getLogger(__name__)
_US = 1_000_000
_MODES = (("async", False), ("sync", True))


def _ms(value: Fraction) -> str:
    """OSATE's ``bestDecPoint``: two decimals under 10, one under 1000, none beyond."""
    ms = float(value / 1000)
    if ms == 0:
        return "0.0"
    if abs(ms) < 10:
        return f"{ms:.2f}"
    return f"{ms:.1f}" if abs(ms) < 1000 else f"{ms:.0f}"


def summary(
    actual: tuple[Fraction, Fraction],
    specified: tuple[Fraction, Fraction],
    expected: tuple[Fraction, Fraction],
) -> list[tuple[str, str]]:
    """OSATE's end-to-end summary lines (``LatencyReportEntry.genResult``), in its words:
    ``actual``, ``specified`` and ``expected`` are (min, max) latencies."""
    low, high = actual
    spec_low, spec_high = specified
    exp_low, exp_high = expected
    if exp_high <= 0:
        return [("WARNING", "Expected end to end latency is not specified")]
    a_low, a_high, s_low, s_high, e_low, e_high = map(
        _ms, (low, high, spec_low, spec_high, exp_low, exp_high)
    )
    bound = f"expected maximum end to end latency {e_high}ms"
    issues: list[tuple[str, str]] = []
    if spec_low > exp_high:
        issues.append(
            (
                "ERROR",
                f"Minimum specified flow latency total {s_low}ms exceeds expected maximum latency {e_high}ms",
            )
        )
    elif spec_low < exp_low:
        issues.append(
            (
                "WARNING",
                f"Minimum specified flow latency total {s_low}ms less than expected minimum end to end "
                f"latency {e_low}ms (better response time)",
            )
        )
    if low > exp_high:
        issues.append(("ERROR", f"Minimum actual latency total {a_low}ms exceeds {bound}"))
    elif low < exp_low:
        issues.append(
            (
                "WARNING",
                f"Minimum actual latency total {a_low}ms less than expected minimum end to end latency "
                f"{e_low}ms (faster actual minimum response time)",
            )
        )
    else:
        issues.append(
            (
                "INFO",
                f"Minimum actual latency total {a_low}ms is greater or equal to expected minimum end to end "
                f"latency {e_low}ms",
            )
        )
    if high <= 0:
        return issues
    if exp_high < spec_high:
        issues.append(("ERROR", f"Maximum specified flow latency total {s_high}ms exceeds {bound}"))
    if exp_high < high:
        issues.append(("ERROR", f"Maximum actual latency total {a_high}ms exceeds {bound}"))
    else:
        issues.append(("INFO", f"Maximum actual latency total {a_high}ms is less or equal to {bound}"))
    jitter = f"expected end to end latency jitter {e_low}..{e_high}ms"
    if spec_high - spec_low > exp_high - exp_low:
        issues.append(("WARNING", f"Jitter of specified latency total {s_low}..{s_high}ms exceeds {jitter}"))
    if high - low > exp_high - exp_low:
        issues.append(("WARNING", f"Jitter of actual latency total {a_low}..{a_high}ms exceeds {jitter}"))
    if low > exp_low and exp_high > high:
        issues.append(("INFO", f"Jitter of actual flow latency {a_low}..{a_high}ms is within {jitter}"))
    return issues


def _hops(rows: list[Contributor], revision: str, major_frame: bool = True) -> tuple[LatencyHop, ...]:
    hops: list[LatencyHop] = []

    def add(row: Contributor, depth: int) -> None:
        for sub in row.subs:
            add(sub, depth + 1)
        hops.append(
            LatencyHop(
                row.kind,
                instance_path(row.element) or row.label.partition(" ")[2],
                row.shown(False),
                row.shown(True),
                "; ".join(row.comments),
                row.label,
                method_word(row.best_method, revision, major_frame),
                method_word(row.worst_method, revision, major_frame),
                depth,
                row.specified_best,
                row.specified_worst,
            )
        )

    for row in rows:
        add(row, 0)
    return tuple(hops)


def _bound_connections(root: Any, reader: PropertyReader, mode: SystemMode) -> dict[int, list[Any]]:
    """Every bus or virtual bus → the active connections bound to it, through virtual buses."""
    bound: dict[int, list[Any]] = {}
    for ci in component_instances(root):
        for conn in ci.connectionInstances:
            if not mode.active(conn):
                continue
            todo = list(reader.targets(conn, "Deployment_Properties::Actual_Connection_Binding", mode) or [])
            seen: set[int] = set()
            while todo:
                bus = todo.pop(0)
                if id(bus) in seen or not hasattr(bus, "componentInstances"):
                    continue
                seen.add(id(bus))
                bound.setdefault(id(bus), []).append(conn)
                if category_of(bus) == "virtualBus":
                    todo.extend(
                        reader.targets(bus, "Deployment_Properties::Actual_Connection_Binding", mode) or []
                    )
    return bound


def _threads(elements: list[Any]) -> tuple[str, ...]:
    """The threads a flow goes through, in order: its thread elements and the threads at the ends
    of its connections."""
    from rosaadl.analysis.latency.chains import thread_of
    from rosaadl.analysis.latency.contributors import component_of

    paths: list[str] = []

    def add(thread: Any | None) -> None:
        if thread is not None and category_of(thread) == "thread":
            path = instance_path(thread)
            if not paths or paths[-1] != path:
                paths.append(path)

    for element in elements:
        if is_connection(element):
            add(thread_of(element.source))
            add(thread_of(element.destination))
        else:
            add(component_of(element))
    return tuple(paths)


def _specs(
    root: Any, chains: Iterable[Any] | None, limit: int, reader: PropertyReader
) -> tuple[list[tuple[str, Any, list[Any]]], bool]:
    """(name, flow or None, elements) of what to analyse, and whether they are topic chains (or
    flows refined by the threads of their topics)."""
    diagnostics = reader.diagnostics
    specs: list[tuple[str, Any, list[Any]]] = []
    derived = False
    if chains is None:
        flows = [f for ci in component_instances(root) for f in ci.endToEndFlows]
        if flows:
            chains = flows
        else:
            chains = thread_chains(root, limit)
            derived = True
    for item in chains:
        if hasattr(item, "flowElements"):
            elements, refined = refine_by_threads(root, flatten_flow(item), reader)
            if not elements:
                continue
            derived = derived or refined
            # OSATE's name for a flow: its path below the root (``Sampled.signal``)
            name = instance_path(item).partition(".")[2] or item.flow or item.name
            specs.append((name, item, elements))
            continue
        threads = []
        for element in item:
            if isinstance(element, str):
                from rosaadl.model import find_instance

                try:
                    element = find_instance(root, element)
                except ModelError as exc:
                    diagnostics.append(Diagnostic("error", exc.message, exc.location))
                    threads = []
                    break
            if category_of(element) != "thread":
                diagnostics.append(
                    Diagnostic(
                        "error",
                        "a latency chain element is not a thread",
                        Location(path=instance_path(element)),
                    )
                )
                threads = []
                break
            threads.append(element)
        if threads:
            name = " -> ".join(instance_path(t).partition(".")[2] or t.name for t in threads)
            specs.append((name, None, chain_elements(root, threads, diagnostics)))
            derived = True
    return specs, derived


def flow_active(flow: Any, elements: list[Any], som: SystemMode, declarative: DeclarativeValues) -> bool:
    """Whether an end-to-end flow exists in a system operation mode, as OSATE's instantiation
    decides it: the flow is in the modes its declaration names (``in modes``, against the
    current mode of the component declaring it) and every element of it exists in the mode (a
    connection or subcomponent ``in modes`` leaves the flow out where it is absent)."""
    if not som.active(flow) or not all(som.active(e) for e in elements):
        return False
    modes = declarative.flow_modes(flow) if som.modes else []
    if not modes:
        return True
    current = som.current_mode(flow.eContainer())
    if current is None:
        return True
    return (current.name or current.mode or "").lower() in modes


def thread_response_times(root: Any, schedulability: Any) -> dict[str, Fraction]:
    """Each thread's worst-case response time in µs from the schedulability analysis (run on
    ``root`` when ``schedulability`` is None); a lower bound bounds nothing and is left out."""
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
    preferences: LatencyPreferences | None = None,
) -> LatencyResult:
    """Best and worst end-to-end latency of flows, for an asynchronous and a synchronous system.

    ``chains``: end-to-end flow instances, or sequences of thread instances or instance paths
    (topic chains); by default the model's end-to-end flows, else every maximal thread path (at
    most ``limit``). ``schedulability`` gives the worst-case response times used for topic
    chains (computed when not given). ``preferences``: OSATE's latency preferences.
    """
    prefs = preferences or LatencyPreferences()
    root = instance_root(source)
    diagnostics: list[Diagnostic] = []
    reader = PropertyReader(diagnostics)
    specs, derived = _specs(root, chains, limit, reader)
    if not specs and chains is None:
        # OSATE's words (an error there: its analysis has nothing to report; here a warning, as
        # the other analyses of the run may still have something to say)
        diagnostics.append(
            Diagnostic(
                "warning",
                "No end-to-end flow instances were found",
                Location(path=instance_path(root)),
            )
        )
    response_times = thread_response_times(root, schedulability) if derived and specs else {}
    results: list[LatencyChain] = []
    soms = system_modes(root)
    declarative = DeclarativeValues(root)
    demand = ResourceDemand(root, [])  # the processor speeds a Reference_Processor asks for, read once
    for som in soms:
        for mode_name, synchronous in _MODES:
            transmission = Transmission(reader, som, declarative)
            walk = FlowWalk(reader, som, prefs, transmission, response_times, declarative, derived, demand)
            entries = []
            for name, flow, elements in specs:
                if flow is not None and not flow_active(flow, elements, som, declarative):
                    continue
                entries.append((name, flow, elements, walk.contributors(elements)))
            if transmission.waiting and not prefs.revision.startswith("2014"):
                transmission.fill_queuing(_bound_connections(root, reader, som))
            for name, flow, elements, rows in entries:
                results.append(
                    _entry(
                        name,
                        flow,
                        elements,
                        rows,
                        synchronous,
                        mode_name,
                        prefs,
                        reader,
                        som,
                        diagnostics,
                        len(soms) > 1,
                    )
                )
    log.debug("latency of %d flows", len(specs))
    system = (getattr(root, "classifier", None) or "").rpartition("::")[2] or getattr(root, "name", "") or ""
    unique = list({(d.severity, d.message, d.location.path): d for d in diagnostics}.values())
    return LatencyResult(tuple(results), tuple(unique), prefs, system)


def _entry(
    name: str,
    flow: Any,
    elements: list[Any],
    rows: list[Contributor],
    synchronous: bool,
    mode_name: str,
    prefs: LatencyPreferences,
    reader: PropertyReader,
    som: SystemMode,
    diagnostics: list[Diagnostic],
    modal: bool,
) -> LatencyChain:
    best, worst = actual_latency(rows, synchronous, prefs.major_frame, prefs.revision)
    spec_best = sum((r.specified_total(False) for r in rows), Fraction(0))
    spec_worst = sum((r.specified_total(True) for r in rows), Fraction(0))
    expected_best = expected_worst = Fraction(0)
    if flow is not None:
        low = reader.seconds(flow, "Communication_Properties::Latency", som, part="min")
        high = reader.seconds(flow, "Communication_Properties::Latency", som)
        expected_best = low * _US if low is not None else Fraction(0)
        expected_worst = high * _US if high is not None else Fraction(0)
    issues = (
        summary((best, worst), (spec_best, spec_worst), (expected_best, expected_worst))
        if flow is not None
        else []
    )
    path = instance_path(flow) if flow is not None else _threads(elements)[0] if _threads(elements) else ""
    chain = LatencyChain(
        name,
        _threads(elements),
        _hops(rows, prefs.revision, prefs.major_frame),
        best,
        worst,
        expected_worst or None,
        mode_name,
        expected_best or None,
        spec_best,
        spec_worst,
        tuple(issues),
        som.name if modal else "",
        path,
    )
    if chain.met is False:
        diagnostics.append(
            Diagnostic(
                "error",
                f"end-to-end latency {number(worst)} us of {name} ({mode_name}) exceeds its Latency "
                f"{number(expected_worst)} us",
                Location(path=path),
            )
        )
    return chain
