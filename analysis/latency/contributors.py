"""The contributors of an end-to-end flow, element by element, as OSATE's flow latency analysis
lists them (``FlowLatencyAnalysisSwitch.mapComponentInstance`` / ``mapConnectionInstance``).

For a component (a flow specification's component, or a component named in the flow):

* **sampling**: a periodic component (``Period`` set; a thread, device or abstract component
  unless it is sporadic, timed or aperiodic) that is the first of the flow contributes a *first
  sampling* row of 0 (OSATE does not add the initial sampling delay and says so); later on, a
  periodic component reading a data port (or abstract feature) samples it: *sampling* over a
  sampled connection (with the sender's period when the receiver's is a multiple of it:
  under-sampling), *delayed sampling* over a delayed connection, nothing over an immediate one
  (OSATE keeps an empty row there, and checks the chain of immediate connections against the
  deadline of its last thread);
* **processing**: worst case ``SEI::Response_Time``, else the maximum
  ``Compute_Execution_Time`` (preference ``ET``) or the assigned ``Deadline`` (``DL``), else
  the ``Latency`` specified on the flow specification (*specified*), else the assigned
  ``Deadline``; best case the minimum response or execution time, else the specified minimum.
  Execution times are read on the flow's input port for an event-driven thread when set there;
* **queuing**: an incoming event (data) port with an assigned ``Queue_Size``, or a data port of
  an event-driven thread or device (queue of 1), waits ``Queue_Size`` × the period (sporadic and
  periodic) or × the worst processing time; the best case is 0 with an empty queue (``EQ``) or
  the full queue (``FQ``);
* an aperiodic first component in an ARINC 653 partition starts with the partition's row.

For a connection: the partition output delay when the flow leaves a partition (``MF``: at the
next major frame, ``PE``: at the end of the partition window), the connection's own row with the
transmission over its bound buses and virtual buses under it (:mod:`.transmission`), the
``Latency`` specified on it, whether both ends share a processor (synchronous) or clock, and the
partition the flow enters (*partition offset* with an ARINC 653 schedule, else *partition major
frame*).

The September 2014 rules (``revision="2014"``, ``"2014-early"``) differ where the flow latency
examples' reports show it: the first partition row comes with periodic components too, there is
no partition output row, immediate connections leave no row, and the worst processing time is
the execution time, else the assigned deadline, else the specified latency, whatever the
preference.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from rosaadl.analysis.instance_values import PropertyReader, SystemMode, category_of
from rosaadl.analysis.latency.declarative import DeclarativeValues
from rosaadl.analysis.latency.model import Contributor
from rosaadl.analysis.latency.transmission import Transmission
from rosaadl.model import instance_path

__all__ = ["FlowWalk", "flatten_flow", "component_of", "contributor_label"]

_US = 1_000_000
_LATENCY_CATEGORIES = frozenset(
    {"bus", "virtualBus", "device", "processor", "virtualProcessor", "system", "memory", "abstract"}
)
_PERIOD_CATEGORIES = frozenset(
    {"thread", "threadGroup", "process", "system", "device", "virtualProcessor", "virtualBus", "abstract"}
)
_DEADLINE_CATEGORIES = _PERIOD_CATEGORIES - {"virtualBus"}
_EXEC_CATEGORIES = frozenset({"thread", "device", "subprogram", "abstract"})
_EVENT_DRIVEN = frozenset({"sporadic", "timed", "aperiodic"})


def flatten_flow(flow: Any) -> list[Any]:
    """The elements of an end-to-end flow, the elements of nested end-to-end flows in place."""
    out: list[Any] = []
    for element in flow.flowElements:
        if hasattr(element, "flowElements"):
            out.extend(flatten_flow(element))
        else:
            out.append(element)
    return out


def is_connection(element: Any) -> bool:
    return hasattr(element, "connectionReferences")


def component_of(element: Any) -> Any:
    """The component of a flow element: itself, or the component holding a flow specification,
    feature or connection end."""
    current = element
    while current is not None and not hasattr(current, "componentInstances"):
        current = current.eContainer()
    return current


def contributor_label(element: Any, kind: str) -> str:
    """OSATE's ``getContributorType`` + ``getFullComponentContributorName``: ``thread s.task1``,
    ``connection a.o -> b.i``, ``protocol rosbus``, ``partition part1``."""
    if is_connection(element):
        return f"connection {element.name}"
    category = category_of(element)
    word = {"virtualBus": "protocol", "virtualProcessor": "partition"}.get(category)
    if word is None:
        word = "".join(" " + c.lower() if c.isupper() else c for c in category) if category else "component"
    path = instance_path(element).partition(".")[2] or element.name
    return f"{word} {path}"


class FlowWalk:
    """Builds the contributors of flows, one instance and system mode at a time."""

    def __init__(
        self,
        reader: PropertyReader,
        mode: SystemMode,
        preferences: Any,
        transmission: Transmission,
        response_times: dict[str, Fraction] | None = None,
        declarative: DeclarativeValues | None = None,
        derived: bool = False,
        demand: Any = None,
    ) -> None:
        self.reader = reader
        self.declarative = declarative
        self.derived = derived  #: topic chains and refined flows: threads without times add nothing
        self.demand = demand  #: the processor speeds (a ResourceDemand) a Reference_Processor asks for
        self.mode = mode
        self.prefs = preferences
        self.legacy = preferences.revision.startswith("2014")
        self.transmission = transmission
        self.response_times = response_times or {}

    # ------------------------------------------------------------------ properties
    def us(self, obj: Any, name: str, part: str = "max") -> Fraction:
        value = self.reader.seconds(obj, name, self.mode, part=part) if obj is not None else None
        return value * _US if value is not None and value > 0 else Fraction(0)

    def assigned(self, obj: Any, name: str) -> bool:
        return obj is not None and self.reader.value(obj, name, self.mode) is not None

    def declared(self, obj: Any, name: str) -> bool | None:
        """Whether an association of ``name`` reaches ``obj`` (OSATE's "assigned": the default
        value does not count); None when the instance has no declarative model to tell."""
        if self.declarative is None:
            return None
        return self.declarative.declared(obj, name)

    def dispatch(self, component: Any) -> str:
        return (self.reader.enum(component, "Thread_Properties::Dispatch_Protocol", self.mode) or "").lower()

    def timing(self, connection: Any) -> str:
        if connection is None:
            return ""
        kind = getattr(getattr(connection, "kind", None), "name", "portConnection")
        if kind not in ("portConnection", ""):
            return ""
        return (
            self.reader.enum(connection, "Communication_Properties::Timing", self.mode) or "sampled"
        ).lower()

    def period(self, component: Any) -> Fraction:
        if category_of(component) not in _PERIOD_CATEGORIES:
            return Fraction(0)
        return self.us(component, "Timing_Properties::Period")

    def deadline(self, component: Any) -> Fraction:
        """The component's ``Deadline``; where the instance has none (rosaadl's instances carry
        the default values of the properties a model associates somewhere, and a model may
        associate no ``Deadline`` at all), its default value, the ``Period``, as OSATE evaluates
        it today. The reports of OSATE 2.2-2.4 (revision ``2018``) and 2014 show no deadline
        there, an instance read without its declarative model (an ``.aaxl2`` file) is taken
        with the values it carries, and in topic chains and flows refined by threads (rosaadl's)
        a thread without execution time (a ROS publisher or subscriber) adds nothing."""
        if category_of(component) not in _DEADLINE_CATEGORIES:
            return Fraction(0)
        if self.reader.value(component, "Timing_Properties::Deadline", self.mode) is None:
            declarative = self.declarative is not None and self.declarative.lookup() is not None
            if self.prefs.revision == "current" and declarative and not self.derived:
                return self.period(component)
            return Fraction(0)
        return self.us(component, "Timing_Properties::Deadline")

    def is_periodic(self, component: Any) -> bool:
        if self.period(component) <= 0:
            return False
        if category_of(component) in ("thread", "device", "abstract"):
            return self.dispatch(component) not in _EVENT_DRIVEN
        return True

    # ------------------------------------------------------------------ partitions
    def partition(self, component: Any) -> Any | None:
        """The virtual processor (ARINC 653 partition) a component is bound to, or None."""
        current = component
        while current is not None and hasattr(current, "componentInstances"):
            bound = self.reader.targets(current, "Actual_Processor_Binding", self.mode) or []
            for target in bound:
                if category_of(target) == "virtualProcessor":
                    return target
            if bound:
                return None
            current = current.eContainer()
        return None

    def module(self, partition: Any) -> Any | None:
        bound = self.reader.targets(partition, "Actual_Processor_Binding", self.mode) or []
        if bound:
            return bound[0]
        parent = partition.eContainer()
        return parent if parent is not None and hasattr(parent, "componentInstances") else None

    def partition_period(self, partition: Any) -> Fraction:
        """``ARINC653::Module_Major_Frame`` of the module, else the partition's ``Period``, else its
        own major frame (``FlowLatencyUtil.getPartitionPeriod``)."""
        module = self.module(partition)
        if module is not None and category_of(module) in ("processor", "virtualProcessor", "abstract"):
            frame = self.us(module, "ARINC653::Module_Major_Frame")
            if frame:
                return frame
        return self.us(partition, "Timing_Properties::Period") or self.us(
            partition, "ARINC653::Module_Major_Frame"
        )

    def schedule(self, partition: Any) -> list[tuple[Any, Fraction]]:
        """(partition, duration) of the module's ``ARINC653::Module_Schedule`` windows."""
        module = self.module(partition)
        if module is None or category_of(module) not in ("processor", "virtualProcessor", "abstract"):
            return []
        windows = self.reader.value(module, "ARINC653::Module_Schedule", self.mode) or []
        out = []
        for window in windows if isinstance(windows, list) else []:
            if not isinstance(window, dict) or window.get("Partition") is None:
                continue
            target = window.get("Partition")
            duration = window.get("Duration")
            seconds = (
                self.reader.convert(module, "Module_Schedule", duration, "sec")
                if duration is not None
                else None
            )
            out.append((target, (seconds or Fraction(0)) * _US))
        return out

    def partition_row(self, partition: Any, element: Any, start: bool) -> Contributor:
        """A partition's contributor: *partition offset* (with its window's offset and duration)
        when the module has a schedule naming it, else *partition major frame*."""
        windows = self.schedule(partition)
        duration, offset, found = Fraction(0), Fraction(0), False
        for target, length in windows:
            if target is partition or getattr(target, "name", target) == partition.name:
                duration, found = length, True
                break
            offset += length
        if not windows:
            duration = self.us(partition, "Timing_Properties::Execution_Time")
        row = Contributor(partition, contributor_label(partition, "partition"), "partition")
        row.period = self.partition_period(partition)
        if windows and not found:
            module = self.module(partition)
            row.comment(
                f"Partition not found in ARINC653 schedule of processor {getattr(module, 'name', '')}"
            )
        if duration > 0:
            row.partition_offset = offset if found else Fraction(0)
            row.partition_duration = duration
            row.best_method = row.worst_method = "partition_schedule"
        else:
            row.best_method = row.worst_method = "partition_frame"
        if self.legacy:  # the 2014 rows show the partition's period
            row.best = row.worst = row.period
        return row

    # ------------------------------------------------------------------ the walk
    def contributors(self, elements: list[Any]) -> list[Contributor]:
        rows: list[Contributor] = []
        for index, element in enumerate(elements):
            if is_connection(element):
                self.connection(elements, index, rows)
            else:
                self.component(elements, index, rows)
        return rows

    def previous_connection(self, elements: list[Any], index: int) -> Any | None:
        return elements[index - 1] if index > 0 and is_connection(elements[index - 1]) else None

    def component(self, elements: list[Any], index: int, rows: list[Contributor]) -> None:
        element = elements[index]
        component = component_of(element)
        if component is None:
            return
        is_spec = not hasattr(element, "componentInstances")
        has_latency = is_spec or category_of(component) in _LATENCY_CATEGORIES
        spec_best = (
            self.us(element, "Communication_Properties::Latency", "min") if has_latency else Fraction(0)
        )
        spec_worst = self.us(element, "Communication_Properties::Latency") if has_latency else Fraction(0)
        period = self.period(component)
        deadline = self.deadline(component)
        # OSATE's isAssignedDeadline: a Deadline defaulted to the Period is not assigned
        declared = self.declared(component, "Timing_Properties::Deadline") if deadline > 0 else False
        deadline_assigned = deadline > 0 and declared is not False
        periodic = self.is_periodic(component)
        if period <= 0 and self.dispatch(component) == "periodic":
            self.reader.report("error", "periodic thread has no Period; it is not sampled", component)
        previous = self.previous_connection(elements, index)
        incoming = (
            previous.destination
            if previous is not None and hasattr(previous.destination, "direction")
            else None
        )
        label = contributor_label(component, "component")
        response_best, response_worst = self.times(element, component, periodic, "SEI::Response_Time")
        exec_best, exec_worst = self.times(
            element, component, periodic, "Timing_Properties::Compute_Execution_Time"
        )
        if (response_worst == 0) and instance_path(component) in self.response_times:
            response_worst = self.response_times[instance_path(component)]
            response_best = exec_best
        check_immediate = False
        if self.legacy and not rows:
            partition = self.partition(component)
            if partition is not None:
                first = self.partition_row(partition, element, start=True)
                first.comment(f"Initial {_ms(period)}ms partition latency not added")
                rows.append(first)
        if periodic:
            if incoming is not None:
                category = str(getattr(getattr(incoming, "category", None), "name", incoming.category or ""))
                if category in ("dataPort", "abstractFeature", "data port", "abstract feature"):
                    row = Contributor(component, label, "sampling", period=period)
                    timing = self.timing(previous)
                    if timing == "delayed":
                        row.best_method = row.worst_method = "delayed"
                    elif timing == "immediate":
                        row.kind = "immediate"
                        if not self._next_immediate(elements, index):
                            check_immediate = True
                        if self.legacy:
                            row = None
                    else:
                        before = self.previous_component(elements, index)
                        before_period = (
                            self.us(before, "Timing_Properties::Period") if before is not None else 0
                        )
                        if period > 0 and before_period > 0 and period % before_period == 0:
                            row.period = before_period
                        row.best_method = row.worst_method = "sampled"
                    if row is not None:
                        if self.legacy and row.kind == "sampling":
                            row.best = row.worst = row.period
                        rows.append(row)
            elif index > 0 and not is_connection(elements[index - 1]) and rows:
                # two threads of one node in a refined flow (no connection between them): the
                # later one samples what the earlier one left (rosaadl; OSATE's flows alternate)
                row = Contributor(component, label, "sampling", period=period)
                row.best_method = row.worst_method = "sampled"
                rows.append(row)
            else:
                row = Contributor(component, label, "sampling", period=period)
                row.best_method = row.worst_method = "first"
                row.comment(f"Initial {_ms(period)}ms sampling latency not added")
                rows.append(row)
        elif not rows and not self.legacy:
            partition = self.partition(component)
            if partition is not None:
                first = self.partition_row(partition, element, start=True)
                rows.append(first)
        processing = Contributor(component, label, "processing")
        worst, worst_method = Fraction(0), "unknown"
        if self.legacy:
            for value, method in (
                (response_worst, "response"),
                (exec_worst, "processing"),
                (deadline, "deadline"),
            ):
                if value:
                    worst, worst_method = value, method
                    break
        elif response_worst:
            worst, worst_method = response_worst, "response"
        elif exec_worst:
            if not self.prefs.worst_case_deadline:
                worst, worst_method = exec_worst, "processing"
            elif not deadline_assigned:
                worst, worst_method = exec_worst, "processing"
                processing.comment("Using execution time as deadline was not set")
        if not worst and deadline_assigned and self.prefs.worst_case_deadline and not self.legacy:
            worst, worst_method = deadline, "deadline"
        if not worst and spec_worst:
            worst, worst_method = spec_worst, "specified"
        elif not worst and deadline and not self.legacy and not self.derived:
            # neither execution time nor flow latency: the deadline, defaulted to the period
            # (rosaadl's topic chains: a thread without times, a ROS publisher, adds nothing)
            worst, worst_method = deadline, "deadline"
            processing.comment("Using deadline as execution time was not set")
        best, best_method = Fraction(0), "unknown"
        if response_best:
            best, best_method = response_best, "response"
        elif exec_best:
            best, best_method = exec_best, "processing"
        if not best and spec_best:
            best, best_method = spec_best, "specified"
        if incoming is not None and not self.legacy:
            queue = self.queuing(component, incoming, period, worst, best)
            if queue is not None:
                rows.append(queue)
        if category_of(component) == "thread" and not worst:
            self.reader.report(
                "warning",
                "thread has no Compute_Execution_Time, Deadline or flow Latency; its processing counts as 0",
                component,
            )
        processing.best, processing.worst = best, worst
        processing.best_method, processing.worst_method = best_method, worst_method
        processing.specified_best, processing.specified_worst = spec_best, spec_worst
        if check_immediate and deadline > 0:
            processing.immediate_deadline = deadline
        if spec_worst and worst > spec_worst:
            processing.comment("max actual latency exceeds max flow latency")
        if spec_best and best > spec_best:
            processing.comment("min actual latency exceeds min flow latency")
        rows.append(processing)

    def _next_immediate(self, elements: list[Any], index: int) -> bool:
        after = elements[index + 1] if index + 1 < len(elements) else None
        return after is not None and is_connection(after) and self.timing(after) == "immediate"

    def previous_component(self, elements: list[Any], index: int) -> Any | None:
        if index >= 2 and not is_connection(elements[index - 2]):
            return component_of(elements[index - 2])
        return None

    def times(self, element: Any, component: Any, periodic: bool, name: str) -> tuple[Fraction, Fraction]:
        """A time range of the component, or of the flow's input event port when the component is
        event driven and the port has it (``getTimeInMilliSec2``)."""
        if not periodic and element is not component:
            port = getattr(element, "source", None)
            category = str(getattr(getattr(port, "category", None), "name", "")) if port is not None else ""
            if category in ("eventPort", "eventDataPort") and self.assigned(port, name):
                scale = self.processor_scale(component)
                return self.us(port, name, "min") * scale, self.us(port, name) * scale
        if category_of(component) in _EXEC_CATEGORIES:
            scale = self.processor_scale(component)
            return self.us(component, name, "min") * scale, self.us(component, name) * scale
        return Fraction(0), Fraction(0)

    def processor_scale(self, component: Any) -> Fraction:
        """OSATE's ``AnalysisUtils.scaleTimeRange``: times given for the component's
        ``Reference_Processor`` scale by its MIPS over the MIPS of the physical processor the
        component is bound to (``SEI::MIPSCapacity``, else ``Processor_Capacity``); 1 when
        either is unknown."""
        if not self.reader.value(component, "Reference_Processor", self.mode):
            return Fraction(1)
        if self.demand is None:
            return Fraction(1)
        reference = self.demand.reference_mips(component, self.mode)
        processor = self.demand.bindings.physical_processor(component, self.mode)
        capacity = self.reader.mips_capacity(processor, self.mode) if processor is not None else 0
        if not reference or not capacity:
            return Fraction(1)
        return Fraction(reference) / Fraction(capacity)

    def queuing(
        self, component: Any, incoming: Any, period: Fraction, worst: Fraction, best: Fraction
    ) -> Contributor | None:
        size = Fraction(0)
        row = Contributor(component, contributor_label(component, "component"), "queuing")
        category = str(getattr(getattr(incoming, "category", None), "name", ""))
        dispatch = self.dispatch(component)
        queue_size = self.reader.number(incoming, "Communication_Properties::Queue_Size", None, self.mode)
        declared = (
            self.declared(incoming, "Communication_Properties::Queue_Size")
            if queue_size is not None
            else False
        )
        if declared is None:
            # no declarative model to tell: the predeclared default (1) reads as unassigned
            declared = queue_size != 1
        if declared:
            # OSATE counts an assigned Queue_Size only (0 included: no queue, whatever the port)
            size = queue_size or Fraction(0)
        elif (
            category == "dataPort"
            and category_of(component) in ("thread", "device", "abstract")
            and dispatch in _EVENT_DRIVEN
        ):
            size = Fraction(1)
            row.comment("Data port as queue size 1 for sporadic, aperiodic, timed dispatch")
        if not size:
            return None
        per_element = period if dispatch in ("sporadic", "periodic") else worst
        if dispatch in ("sporadic", "periodic"):
            row.comment("Sporadic or periodic has period delay per queue element")
        row.worst = size * per_element
        if self.prefs.best_case_empty_queue:
            row.best = Fraction(0)
            row.comment("Assume best case empty queue")
        else:
            row.best = size * (period if dispatch in ("sporadic", "periodic") else best)
            row.comment("Assume best case full queue")
        row.best_method = row.worst_method = "queued"
        return row

    def hardware(self, component: Any) -> Any | None:
        if component is None:
            return None
        if category_of(component) in ("device", "processor"):
            return component
        from rosaadl.analysis.instance_values import bound_processor

        return bound_processor(component, self.mode, self.reader)

    def connection(self, elements: list[Any], index: int, rows: list[Contributor]) -> None:
        conn = elements[index]
        spec_best = self.us(conn, "Communication_Properties::Latency", "min")
        spec_worst = self.us(conn, "Communication_Properties::Latency")
        source, destination = component_of(conn.source), component_of(conn.destination)
        src_hw, dst_hw = self.hardware(source), self.hardware(destination)
        src_part = self.partition(source) if source is not None else None
        dst_part = self.partition(destination) if destination is not None else None
        if src_part is not None and src_part is not dst_part and not self.legacy:
            out = self.partition_row(src_part, conn, start=False)
            if out.partition_duration > 0:
                out.kind = "partition output"
                out.best_method = out.worst_method = "partition_output"
                if not out.period:
                    out.period = out.partition_duration
                    out.comment("No partition period/rate. Using partition duration")
                rows.append(out)
        timing = self.timing(conn)
        row = Contributor(conn, contributor_label(conn, "connection"), "connection")
        row.timing = timing
        self.transmission.add_to(conn, row)
        if spec_worst > 0:
            row.worst_method = "specified"
            row.specified_worst = spec_worst
        if spec_best > 0:
            row.best_method = "specified"
            row.specified_best = spec_best
        if not row.subs:
            if spec_worst > 0:
                row.worst = spec_worst
            if spec_best > 0:
                row.best = spec_best
        else:
            row.comment("Adding latency subtotal from protocols and hardware - shown with ()")
        if src_hw is not None and dst_hw is not None:
            src_time = self._reference_time(src_hw)
            dst_time = self._reference_time(dst_hw)
            if src_hw is dst_hw:
                row.sync = "synchronous"
            elif src_time is not None and dst_time is not None:
                row.sync = "synchronous" if src_time is dst_time else "asynchronous"
        elif src_part is not None and dst_part is not None and src_part is dst_part:
            row.sync = "synchronous"
        rows.append(row)
        if self.legacy:  # the 2014 rows list the buses after their connection
            for sub in row.subs:
                sub.kind = "transmission"
                rows.append(sub)
            row.subs = []
        if dst_part is not None and src_part is not dst_part:
            entered = self.partition_row(dst_part, conn, start=False)
            if entered.partition_duration > 0 and not entered.period and not self.legacy:
                # a window without a major frame or period repeats after its own duration
                entered.period = entered.partition_duration
                entered.comment("No partition period. Using partition duration")
            rows.append(entered)

    def _reference_time(self, hardware: Any) -> Any | None:
        targets = self.reader.targets(hardware, "Timing_Properties::Reference_Time", self.mode)
        return targets[0] if targets else None


def _ms(value: Fraction) -> str:
    from rosaadl.analysis.busload import java_double

    return java_double(value / 1000)
