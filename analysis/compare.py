"""Predicted vs measured: the analyses' figures beside what a run of the generated application
measured (``measurements.json``, :mod:`rosaadl.importers.measurements`), with the error in %.

:func:`compare_measurements` reads the results of the other analyses of the same run (``cpu``,
``bus``, ``sched``, ``latency``; run here when they were not selected) and lists one
:class:`ComparedItem` per prediction that has a measurement:

* per thread: ``execution_time_us`` (its ``Compute_Execution_Time`` upper bound vs the mean CPU
  time of its dispatches: the workload twin's fidelity) and ``cpu_load_percent`` (CET / Period
  vs mean CPU time / mean period);
* per process: ``cpu_load_percent`` (the sum of its threads' loads vs its whole CPU time from
  ``/proc``), ``callback_cpu_load_percent`` (the same prediction vs its measured threads' own
  CPU time) and ``middleware_cpu_load_percent`` (what the model does not hold: the process's
  CPU time beyond its callbacks, spent in the executor, serialization and DDS; no prediction);
  where its threads' profiles carry the speed of the CPUs they were measured on
  (``ROS_Properties::Profiled_CPU_Speed``, with ``Twin_Execution_Time``: a profile of a measured
  run) and the run gauged its CPUs too (``cpu_speed``), ``cpu_load_at_run_speed_percent``:
  :func:`load_at_speed`, the prediction with what the workload twin did not hold rescaled to the
  run's CPU speed (a warning says when the two speeds differ by more than
  :data:`SPEED_TOLERANCE`);
* per processor or core: ``cpu_load_percent`` (its threads' utilisation vs the measured load of
  what is bound to it);
* per out port with a measured topic: ``bandwidth_kbps`` (``Data_Size`` × rate, KB/s);
* per bus and virtual bus: ``bus_bandwidth_kbps``, the bus-load analysis's actual load (with the
  buses' overhead; a virtual bus bound to no bus, which that analysis does not report: the
  ``Data_Size`` × rate of the ports whose connections are bound to it) vs the measured bandwidth
  of the topics whose connections are bound to it (bound through a virtual bus included). A run on
  one machine has these topics cross processes on the loopback (or shared memory): what their
  subscribers receive per second is what the deployment puts on the bus, less the bus protocol's
  overhead. A bus none of whose connections carries a topic of the run (a device's stream) is
  not compared (a warning says so);
* per thread with a response time bound (the schedulability analysis's worst case):
  ``response_time_us``, bound = the worst case, measured = the maximum;
* per end-to-end flow: ``latency_us`` (bound = the worst case, measured = the maximum) and
  ``latency_min_us`` (bound = the best case, measured = the minimum).

A plain estimate (CPU load, bandwidth, execution time) reports its error
``(measured - predicted) / predicted × 100``. A bound the measurement passes (a response time or
latency above the worst case, a latency below the best case) is ``violated`` and an error
finding of the report (exit 1). A measured thread, process, topic or chain the model does not
hold is a warning. Registered as the ``compare`` analysis, run by ``rosaadl analyze --compare``.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rosaadl.analysis.instance_values import bound_processor, category_of
from rosaadl.analysis.registry import Analysis, AnalysisContext, register
from rosaadl.analysis.rendering import csv_text, fmt, table
from rosaadl.errors import AnalysisError, Diagnostic, Location, RosaadlError
from rosaadl.model import component_instances, find_instance, instance_path
from rosaadl.properties import property_value
from rosaadl.units import standard_units

__all__ = [
    "ComparedItem",
    "ComparisonResult",
    "SPEED_TOLERANCE",
    "load_at_speed",
    "compare_measurements",
    "compare_text",
    "compare_csv",
]

#: Profile and run whose CPU speed gauges differ by more than this part ran at different CPU
#: speeds (a warning says so).
SPEED_TOLERANCE = 0.05
_TWIN_EXECUTION_TIME = "ROS_Properties::Twin_Execution_Time"
_CPU_SPEED = "ROS_Properties::Profiled_CPU_Speed"

_HEADERS = ("path", "quantity", "predicted", "measured", "error_percent", "bound", "violated")


@dataclass(frozen=True)
class ComparedItem:
    """One prediction beside its measurement. ``bound``: the value the analysis claims the
    measurement never passes (None for an estimate); ``violated``: the measurement passed it."""

    path: str
    quantity: str
    predicted: float | None
    measured: float
    bound: float | None = None
    violated: bool = False

    @property
    def error_percent(self) -> float | None:
        """(measured − predicted) / predicted in % (None without a non-zero prediction)."""
        if not self.predicted:
            return None
        return (self.measured - self.predicted) / self.predicted * 100

    @property
    def pessimism(self) -> float | None:
        """bound ÷ measured of an upper bound (how far the worst case the analysis claims lies
        above the worst seen); None for an estimate or a lower bound."""
        if self.bound is None or self.measured <= 0 or self.quantity.endswith("_min_us"):
            return None
        return self.bound / self.measured

    def as_dict(self) -> dict[str, Any]:
        error = self.error_percent
        return {
            "path": self.path,
            "quantity": self.quantity,
            "predicted": _rounded(self.predicted),
            "measured": _rounded(self.measured),
            "error_percent": _rounded(error),
            "bound": _rounded(self.bound),
            "violated": self.violated,
        }

    def cells(self) -> list[Any]:
        return [
            self.path,
            self.quantity,
            self.predicted,
            self.measured,
            self.error_percent,
            self.bound,
            self.violated,
        ]


def _rounded(value: float | None) -> float | None:
    return None if value is None else round(float(value), 6)


@dataclass(frozen=True)
class ComparisonResult:
    """Every compared item, in a stable order, and what could not be matched."""

    items: tuple[ComparedItem, ...]
    diagnostics: tuple[Diagnostic, ...]
    source: str | None = None
    instance: str = ""  #: the root instance's name (left out of the text's paths)
    period_scale: float = 1.0  #: the run's period scale (the model compared is scaled by it)
    #: (core the run used, the processes on it) where the run placed the processes otherwise
    #: than the model binds them: the executor bounds are then those of the run's placement
    placement: tuple[tuple[str, tuple[str, ...]], ...] = ()

    @property
    def ok(self) -> bool:
        return all(d.severity != "error" for d in self.diagnostics)

    @property
    def violations(self) -> tuple[ComparedItem, ...]:
        return tuple(i for i in self.items if i.violated)

    def item(self, path: str, quantity: str) -> ComparedItem:
        for found in self.items:
            if found.quantity == quantity and path in (found.path, _below_root(found.path, self.instance)):
                return found
        raise KeyError((path, quantity))

    def as_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"items": [i.as_dict() for i in self.items]}
        if self.source:
            out["measurements"] = self.source
        out["period_scale"] = self.period_scale
        if self.placement:
            out["placement"] = [{"core": core, "processes": list(paths)} for core, paths in self.placement]
        out["pessimism"] = [
            {"path": i.path, "quantity": i.quantity, "ratio": _rounded(i.pessimism)}
            for i in self.items
            if i.pessimism is not None
        ]
        return out


# =============================================================================== matching


def _below_root(path: str, root_name: str) -> str:
    """An instance path without the root's name (``tracking_impl_Instance.a.b`` → ``a.b``; a
    root instance named as OSATE names them, ``<impl>_Instance``, also when it is another root's:
    a run of one system measures the same processes as a system that extends it)."""
    head, dot, rest = path.partition(".")
    own = head.lower() == root_name.lower() or head.endswith("_Instance")
    return rest if dot and own else path


def load_at_speed(
    load: Fraction, cet_us: Fraction, twin_us: Fraction, profiled: float, run: float
) -> Fraction:
    """A thread's CPU load ``load`` (CET / Period, %) at the CPU speed ``run`` of a profile
    measured at the speed ``profiled`` (the runs' CPU speed gauges, iterations per CPU ms):

        load' = load × (E + (C − E) × s_p / s_r) / C

    with C the CET and E (≤ C) what of it the twin held (its dispatch's CPU time up to the end of
    its loop, the same whatever the speed), while the rest (executor, serialization and
    publishing, DDS; user code where it replaced the twin, E = 0) takes longer on a slower CPU,
    in proportion as the gauge's loop does."""
    if cet_us <= 0 or profiled <= 0 or run <= 0:
        return load
    fixed = min(max(twin_us, Fraction(0)), cet_us)
    ratio = Fraction(profiled) / Fraction(run)
    return load * (fixed + (cet_us - fixed) * ratio) / cet_us


def _twin_profile(thread: Any) -> tuple[Fraction, float] | None:
    """(twin execution time in µs, CPU speed) a thread's profile carries, else None."""
    burned, speed = property_value(thread, _TWIN_EXECUTION_TIME), property_value(thread, _CPU_SPEED)
    if burned is None or not isinstance(speed, (int, float)) or speed <= 0:
        return None
    try:
        return Fraction(burned.to("us", standard_units())), float(speed)
    except (RosaadlError, AttributeError, TypeError, ValueError):
        return None


def _instance(root: Any, path: str) -> Any:
    try:
        return find_instance(root, path)
    except RosaadlError:
        return None


def _process_of(found: Any) -> str | None:
    if found is None:
        return None
    current = found.eContainer()
    while current is not None and hasattr(current, "category"):
        if category_of(current) == "process":
            return instance_path(current)
        current = current.eContainer()
    return None


class _Comparison:
    """One comparison: the measurements by path, the items found, the diagnostics."""

    def __init__(self, context: AnalysisContext, measurements: Any) -> None:
        self.context = context
        self.root = context.root
        self.name = self.root.name or ""
        self.items: list[ComparedItem] = []
        self.diagnostics: list[Diagnostic] = []
        self.threads = {_below_root(t.path, self.name): t for t in measurements.threads}
        self.processes = {_below_root(p.path, self.name): p for p in measurements.processes}
        self.topics = {_below_root(t.port, self.name): t for t in measurements.topics if t.port}
        self.chains = {_below_root(c.name, self.name): c for c in measurements.chains}
        self.used: set[tuple[str, str]] = set()
        self.placement: dict[str, str] = {}
        #: per process: its predicted load at the run's CPU speed, and its profiles' speeds
        self.at_speed: dict[str, Fraction] = {}
        self.profiled_speeds: dict[str, set[float]] = {}

    def thread(self, path: str) -> Any:
        key = _below_root(path, self.name)
        found = self.threads.get(key)
        if found is not None:
            self.used.add(("thread", key))
        return found

    def add(self, path: str, quantity: str, predicted: Any, measured: Any, bound: Any = None, *, below=False):
        if measured is None:
            return
        predicted = None if predicted is None else float(predicted)
        bound = None if bound is None else float(bound)
        violated = bound is not None and (measured < bound if below else measured > bound)
        self.items.append(ComparedItem(path, quantity, predicted, float(measured), bound, violated))
        if violated:
            side = "below its best case" if below else "above its bound"
            self.diagnostics.append(
                Diagnostic(
                    "error",
                    f"measured {quantity} {fmt(measured)} is {side} {fmt(bound)} predicted by the analyses",
                    Location(path=path),
                )
            )

    # ---------------------------------------------------------------- CPU

    def cpu(self) -> None:
        result = self.context.result("cpu")
        if result is None:
            return
        per_process: dict[str, Fraction] = {}
        thread_process: dict[str, str | None] = {}
        seen_threads: set[str] = set()
        for processor in result.processors:
            if processor.mode and processor is not _first_mode(result, processor):
                continue
            for row in processor.threads:
                if row.path in seen_threads:
                    continue
                seen_threads.add(row.path)
                instance = _instance(self.root, row.path)
                process = thread_process.setdefault(row.path, _process_of(instance))
                if process is not None and row.load_percent is not None:
                    per_process[process] = per_process.get(process, Fraction(0)) + row.load_percent
                    self.at_run_speed(process, row, instance)
                measured = self.thread(row.path)
                if measured is None:
                    continue
                if measured.execution_time_us is not None:
                    self.add(row.path, "execution_time_us", row.cet_us, measured.execution_time_us.mean)
                self.add(row.path, "cpu_load_percent", row.load_percent, measured.load_percent)
        measured_process_load = self.process_loads(per_process, thread_process)
        for processor in result.processors:
            if processor.cores or (processor.mode and processor is not _first_mode(result, processor)):
                continue
            self.core(processor, thread_process, measured_process_load)

    def at_run_speed(self, process: str, row: Any, instance: Any) -> None:
        """Add ``row``'s load to its process's load at the run's speed (:func:`load_at_speed`
        where the thread's profile carries the twin's values and the run measured its gauge)."""
        measured = self.processes.get(_below_root(process, self.name))
        run = getattr(measured, "cpu_speed", None)
        twin = _twin_profile(instance) if run and instance is not None else None
        load = row.load_percent
        if twin is not None and row.cet_us:
            load = load_at_speed(load, row.cet_us, twin[0], twin[1], run)
            self.profiled_speeds.setdefault(process, set()).add(twin[1])
        self.at_speed[process] = self.at_speed.get(process, Fraction(0)) + load

    def speed_item(self, path: str, measured: Any) -> None:
        """The process's load at the run's speed beside its measured load, and a warning when
        the run's CPU ran at another speed than its profile's."""
        speeds = self.profiled_speeds.get(path)
        if not speeds:
            return
        self.add(path, "cpu_load_at_run_speed_percent", self.at_speed[path], measured.cpu_load_percent)
        run = measured.cpu_speed
        off = sorted(s for s in speeds if abs(s / run - 1) > SPEED_TOLERANCE)
        if off:
            self.diagnostics.append(
                Diagnostic(
                    "warning",
                    f"the run's CPU ran at {run / off[0]:.2f}× the speed of the process's profile "
                    f"(gauge {fmt(run)} against {fmt(off[0])} loops per CPU ms): its executor, "
                    "serialization, DDS and user code took longer or shorter; "
                    "cpu_load_at_run_speed_percent rescales them",
                    Location(path=path),
                )
            )

    def process_loads(
        self, predicted: dict[str, Fraction], thread_process: dict[str, str | None]
    ) -> dict[str, float]:
        """Per process: total, callbacks, middleware; the measured totals by process path."""
        totals: dict[str, float] = {}
        for path in sorted(predicted):
            measured = self.processes.get(_below_root(path, self.name))
            if measured is None:
                continue
            self.used.add(("process", _below_root(path, self.name)))
            own = [
                t.load_percent
                for thread_path, process in thread_process.items()
                if process == path
                for t in [self.threads.get(_below_root(thread_path, self.name))]
                if t is not None and t.load_percent is not None
            ]
            totals[path] = measured.cpu_load_percent
            self.add(path, "cpu_load_percent", predicted[path], measured.cpu_load_percent)
            self.speed_item(path, measured)
            if own:
                callbacks = sum(own)
                self.add(path, "callback_cpu_load_percent", predicted[path], callbacks)
                self.add(
                    path, "middleware_cpu_load_percent", None, max(0.0, measured.cpu_load_percent - callbacks)
                )
        return totals

    def core(self, processor: Any, thread_process: dict[str, str | None], totals: dict[str, float]) -> None:
        """A core's measured load: the processes whose threads are all on it, whole; the
        threads of a process split over several cores, their own CPU time."""
        here = {row.path for row in processor.threads}
        if not here:
            return
        measured = 0.0
        found = False
        processes = {thread_process.get(p) for p in here}
        for process in processes:
            everywhere = {t for t, p in thread_process.items() if p == process}
            if process in totals and everywhere <= here:
                measured += totals[process]
                found = True
                continue
            for path in here & everywhere if process is not None else here:
                thread = self.threads.get(_below_root(path, self.name))
                if thread is not None and thread.load_percent is not None:
                    measured += thread.load_percent
                    found = True
        if found:
            self.add(processor.path, "cpu_load_percent", processor.utilization * 100, measured)

    # ---------------------------------------------------------------- bus, response times, latency

    def bandwidth(self) -> None:
        result = self.context.result("bus")
        if result is None:
            return
        for port in result.ports:
            topic = self.topics.get(_below_root(port.path, self.name))
            if topic is None:
                continue
            self.used.add(("topic", _below_root(port.path, self.name)))
            self.add(port.path, "bandwidth_kbps", port.kbytesps, topic.bandwidth_bytes_per_s / 1000)

    def bus_totals(self) -> None:
        """Per bus and virtual bus: the bus-load analysis's actual load (KB/s) beside the
        measured bandwidth of the topics whose connections are bound to it (see the module
        docstring)."""
        result = self.context.result("bus")
        if result is None:
            return
        sources: dict[str, set[str]] = {}
        for component in component_instances(self.root):
            for connection in component.connectionInstances:
                for target in property_value(connection, "Actual_Connection_Binding") or []:
                    if target is not None and connection.source is not None:
                        key = _below_root(instance_path(target), self.name)
                        sources.setdefault(key, set()).add(
                            _below_root(instance_path(connection.source), self.name)
                        )
        ports = {_below_root(p.path, self.name): p.kbytesps for p in result.ports}
        reported: set[str] = set()

        def carried(bus: Any) -> set[str]:
            found = set(sources.get(_below_root(bus.path, self.name), ()))
            for virtual in bus.virtual_buses:
                found |= carried(virtual)
            return found

        def compare(path: str, predicted: Any, carried_by: set[str]) -> None:
            measured = [
                self.topics[s].bandwidth_bytes_per_s / 1000 for s in sorted(carried_by) if s in self.topics
            ]
            if measured:
                self.add(path, "bus_bandwidth_kbps", predicted, sum(measured))
            else:
                self.diagnostics.append(
                    Diagnostic(
                        "warning",
                        "bus load not compared: none of the connections bound to it carries a topic of the "
                        "run (they start at devices or at ports no node publishes on)",
                        Location(path=path),
                    )
                )

        def walk(bus: Any) -> None:
            reported.add(_below_root(bus.path, self.name))
            compare(bus.path, bus.actual_kbps, carried(bus))
            for virtual in bus.virtual_buses:
                walk(virtual)

        for bus in result.modes[0].buses if result.modes else ():
            walk(bus)
        for key in sorted(set(sources) - reported):  # a virtual bus bound to no bus: its ports' loads
            try:
                target = find_instance(self.root, key)
            except RosaadlError:
                continue
            if target is None or category_of(target) != "virtualBus":
                continue
            predicted = sum((ports.get(s, Fraction(0)) for s in sources[key]), Fraction(0))
            compare(instance_path(target), predicted, sources[key])

    def response_times(self) -> None:
        result = self.context.result("sched")
        if result is None:
            return
        to_us = standard_units().factor(result.time_unit, "us")
        for domain in result.domains:
            for task in domain.tasks:
                measured = self.thread(task.path)
                if measured is None or measured.response_time_us is None:
                    continue
                bound = None if task.wcrt is None or not task.wcrt_exact else task.wcrt * to_us
                self.add(task.path, "response_time_us", bound, measured.response_time_us.max, bound)

    def latency(self) -> None:
        result = self.context.result("latency")
        if result is None:
            return
        for chain in result.chains:
            measured = self.chains.get(_below_root(chain.name, self.name))
            if measured is None or measured.latency_us is None:
                continue
            self.used.add(("chain", _below_root(chain.name, self.name)))
            if chain.mode == "async":
                # a ROS application is asynchronous: the bounds of OSATE's asynchronous flow
                # latency are the claim held to the measurement
                self.add(chain.name, "latency_us", chain.worst_us, measured.latency_us.max, chain.worst_us)
                self.add(
                    chain.name,
                    "latency_min_us",
                    chain.best_us,
                    measured.latency_us.min,
                    chain.best_us,
                    below=True,
                )
            else:
                self.add(chain.name, f"latency_{chain.mode}_us", chain.worst_us, measured.latency_us.max)

    def run_placement(self) -> dict[str, str]:
        """Process path → the core the run used (``CPU n``), when the run placed the measured
        processes of the model otherwise than the model's bindings (two processes on one core
        that the model keeps apart, or the other way round); else nothing. Every measured
        process must name its core."""
        placement: dict[str, str] = {}
        model: dict[str, str] = {}
        for process in component_instances(self.root):
            if category_of(process) != "process":
                continue
            path = instance_path(process)
            measured = self.processes.get(_below_root(path, self.name))
            if measured is None:
                continue
            if measured.core is None:
                return {}
            placement[path] = f"CPU {measured.core}"
            bound = bound_processor(process)
            model[path] = instance_path(bound) if bound is not None else path  # unbound: alone
        return placement if _groups(placement) != _groups(model) else {}

    def executor(self) -> None:
        """The executor analysis's bounds: each callback's response time (release to end) and
        each chain's data age (the measured chain: publish time on its first topic to receipt on
        its last, a part of the chain's span, so never more than its data age). Where the run
        placed the processes otherwise than the model (:meth:`run_placement`: a machine with
        fewer cores than the model), the bounds are those of the processes as they ran."""
        result = self.context.result("executor")
        if result is None:
            return
        self.placement = self.run_placement()
        if self.placement:
            from rosaadl.analysis.executor_analysis import analyze_executors

            result = analyze_executors(
                self.root, schedulability=self.context.result("sched"), placement=self.placement
            )
        untimed = self.callbacks_without_execution_times(result.callbacks)
        for callback in result.callbacks:
            measured = self.thread(callback.path)
            if measured is None or measured.response_time_us is None or callback.wcrt is None:
                continue
            bound = None if callback.path in untimed else callback.wcrt
            self.add(
                callback.path,
                "executor_response_time_us",
                callback.wcrt,
                measured.response_time_us.max,
                bound,
            )
        for chain in result.chains:
            found = [
                (key, c)
                for key, c in self.chains.items()
                if key == chain.name or key.endswith("." + chain.name)
            ]
            if len(found) != 1 or found[0][1].latency_us is None or chain.data_age is None:
                continue
            key, measured = found[0]
            self.used.add(("chain", key))
            self.add(key, "data_age_us", chain.data_age, measured.latency_us.max, chain.data_age)

    def callbacks_without_execution_times(self, callbacks: Any) -> set[str]:
        """The measured callbacks the model gives no Compute_Execution_Time (the executor
        analysis counts their execution as 0): their bound is an estimate, not a claim to hold
        a run to (a warning says so)."""
        untimed = {c.path for c in callbacks if not c.timed and self.thread(c.path) is not None}
        for path in sorted(untimed):
            self.diagnostics.append(
                Diagnostic(
                    "warning",
                    "executor bound not held to the run: the model gives the callback no "
                    "Compute_Execution_Time (counted as 0); profile its node (library add-profile)",
                    Location(path=path),
                )
            )
        return untimed

    def unmatched(self) -> None:
        for kind, table_ in (
            ("thread", self.threads),
            ("process", self.processes),
            ("topic", self.topics),
            ("chain", self.chains),
        ):
            for key in sorted(table_):
                if (kind, key) not in self.used:
                    self.diagnostics.append(
                        Diagnostic(
                            "warning",
                            f"measured {kind} {key} matches no prediction of the model",
                            Location(path=key),
                        )
                    )


def _first_mode(result: Any, processor: Any) -> Any:
    """The row of ``processor``'s path in the first system mode (a run has one mode)."""
    return next(p for p in result.processors if p.path == processor.path)


def compare_measurements(context: AnalysisContext, measurements: Any) -> ComparisonResult:
    """Every prediction of the analyses of ``context`` beside its measurement in
    ``measurements`` (a :class:`~rosaadl.importers.measurements.Measurements`)."""
    comparison = _Comparison(context, measurements)
    comparison.cpu()
    comparison.bandwidth()
    comparison.bus_totals()
    comparison.response_times()
    comparison.latency()
    comparison.executor()
    comparison.unmatched()
    return ComparisonResult(
        tuple(comparison.items),
        tuple(comparison.diagnostics),
        measurements.source,
        comparison.name,
        float(getattr(measurements, "period_scale", 1.0)),
        _placement_groups(comparison.placement),
    )


def _groups(cores: dict[str, str]) -> set[frozenset[str]]:
    """The sets of keys that share a value."""
    return {frozenset(k for k in cores if cores[k] == value) for value in cores.values()}


def _placement_groups(placement: dict[str, str]) -> tuple[tuple[str, tuple[str, ...]], ...]:
    cores: dict[str, list[str]] = {}
    for path, core in placement.items():
        cores.setdefault(core, []).append(path)
    ordered = sorted(cores.items(), key=lambda item: (len(item[0]), item[0]))  # CPU 2 before CPU 10
    return tuple((core, tuple(paths)) for core, paths in ordered)


def _run(context: AnalysisContext) -> ComparisonResult:
    measurements = context.options.get("measurements")
    if measurements is None:
        raise AnalysisError(
            "the compare analysis needs measurements (rosaadl analyze --compare measurements.json)"
        )
    return compare_measurements(context, measurements)


# =============================================================================== renderings


def compare_text(result: ComparisonResult) -> list[str]:
    """The comparison as a text table (error in %; a violated bound marked)."""
    lines = ["Predicted vs measured" + (f" ({result.source})" if result.source else "")]
    if result.period_scale != 1:
        lines.append(f"the model with its periods × {result.period_scale:g}, as the run scaled them")
    if result.placement:
        cores = "; ".join(
            f"{core}: {', '.join(_below_root(p, result.instance) for p in paths)}"
            for core, paths in result.placement
        )
        lines.append(f"executor bounds for the processes on the cores the run used ({cores})")
    rows = [[_below_root(i.path, result.instance), *i.cells()[1:], i.pessimism] for i in result.items]
    lines += table(
        ("path", "quantity", "predicted", "measured", "error %", "bound", "violated", "bound/measured"), rows
    )
    middleware = [i for i in result.items if i.quantity == "middleware_cpu_load_percent"]
    if middleware:
        lines.append(
            "middleware (executor, serialization, DDS): the CPU load of a process beyond its callbacks"
        )
    lines.append("")
    return lines


def compare_csv(result: ComparisonResult, base: str) -> dict[str, str]:
    """``<instance>__Compare.csv``: one row per compared item."""
    return {f"{base}__Compare.csv": csv_text([_HEADERS, *(i.cells() for i in result.items)])}


register(
    Analysis(
        name="compare",
        json_key="compare",
        order=90,
        run=_run,
        text=compare_text,
        csv=compare_csv,
        default=False,
        description="the analyses' predictions beside a measured run (measurements.json), error in %",
    )
)
