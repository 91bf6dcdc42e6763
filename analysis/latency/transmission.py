"""What the buses and protocols a connection is bound to add to its latency.

OSATE's rules (``FlowLatencyAnalysisSwitch.processActualConnectionBindings*`` and
``fillInQueuingTimes``), for every bus or virtual bus of the connection's
``Actual_Connection_Binding``, and recursively for what a virtual bus is bound to:

* a **periodic** bus or protocol (``Period`` set) samples the message: a *sampling
  protocol/bus* row of that period (and an empty *queued* row);
* a bus or protocol with a ``Transmission_Time`` (``Fixed`` + ``PerByte`` × bytes) transmits in
  that time (*transmission time*), else in its ``Latency`` (*specified*); the bytes are the
  connection's data size plus the ``Data_Size`` of each protocol on the way (its overhead);
  rosaadl also reads the bytes over ``SEI::BandWidthCapacity`` when a physical bus has neither
  (OSATE leaves the transmission out there);
* a bus or protocol **without a period** is shared: once every flow of the system mode is
  walked, each connection bound to it waits, at worst, for the transmissions of the other
  connections bound to it that the flows met (*queued*, best case 0), and its sampling period
  is 0;
* the protocols a connection (or a bound protocol) names by ``Required_Virtual_Bus_Class``,
  when it is bound to no virtual bus, count as classifiers (read on the declarative model,
  :mod:`.declarative`), recursively through their own required protocols: a periodic one
  samples (as above; an aperiodic one adds no waiting), and, when the connection is bound to
  some hardware, each transmits the message wrapped in the ``Data_Size`` of the protocols
  above it, and its own ``Data_Size`` wraps the message the bound buses carry
  (``computeTotalDataSize``). A connection bound to nothing transmits nothing.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from rosaadl.analysis.busload import data_size_kbyte
from rosaadl.analysis.instance_values import PropertyReader, SystemMode, category_of
from rosaadl.analysis.latency.model import Contributor
from rosaadl.model import qualified_name

__all__ = ["Transmission", "connection_transmission_us"]

_US = 1_000_000
_PERIODIC = frozenset(
    {
        "thread",
        "threadGroup",
        "process",
        "system",
        "device",
        "virtualProcessor",
        "virtualBus",
        "bus",
        "abstract",
    }
)


def _is_instance(obj: Any) -> bool:
    return hasattr(obj, "componentInstances") or hasattr(obj, "connectionReferences")


def _label(bus: Any) -> str:
    """``bus net``, ``protocol tdma``; a required protocol by its classifier's qualified name."""
    from rosaadl.analysis.latency.contributors import contributor_label

    if not _is_instance(bus):
        return f"protocol {qualified_name(bus)}"
    return contributor_label(bus, "bus")


class Transmission:
    """Transmission rows of the connections of one system mode, and their bus queuing."""

    def __init__(self, reader: PropertyReader, mode: SystemMode, declarative: Any = None) -> None:
        self.reader = reader
        self.mode = mode
        self.declarative = declarative  #: a DeclarativeValues for required protocols (or None)
        self.waiting: list[tuple[Any, Any, Contributor]] = []  # (bus, connection, connection row)
        self.max_times: dict[tuple[int, int], Fraction] = {}

    def us(self, obj: Any, name: str, part: str = "max") -> Fraction:
        value = self._number(obj, name, "sec", part)
        return value * _US if value is not None and value > 0 else Fraction(0)

    # ------------------------------------------------------------------ instances and classifiers

    def _value(self, target: Any, name: str) -> Any:
        """Property ``name`` of a bound instance, or of a required protocol's classifier."""
        if _is_instance(target):
            return self.reader.value(target, name, self.mode)
        return self.declarative.classifier_value(target, name) if self.declarative is not None else None

    def _number(self, target: Any, name: str, unit: str, part: str = "max") -> Fraction | None:
        raw = self._value(target, name)
        if raw is None:
            return None
        return self.reader.convert(target if _is_instance(target) else None, name, raw, unit, part=part)

    def _data_bytes(self, target: Any) -> Fraction:
        """``Data_Size`` (else ``Source_Data_Size``) in bytes: a protocol's overhead."""
        for name in ("Memory_Properties::Data_Size", "Memory_Properties::Source_Data_Size"):
            size = self._number(target, name, "KByte")
            if size is not None:
                return size * 1000
        return Fraction(0)

    def required(self, obj: Any) -> list[Any]:
        """The protocol classifiers ``obj`` names by ``Required_Virtual_Bus_Class``."""
        if self.declarative is None:
            return []
        names = self._value(obj, "Deployment_Properties::Required_Virtual_Bus_Class") or []
        found = []
        for name in names if isinstance(names, list) else [names]:
            classifier = self.declarative.classifier(name) if isinstance(name, str) else None
            if classifier is not None:
                found.append(classifier)
        return found

    def bindings(self, obj: Any) -> list[Any]:
        """The components ``obj`` is bound to: buses and virtual buses, and any other hardware
        (a processor, memory or device carrying the messages) as OSATE takes every target of
        ``Actual_Connection_Binding``."""
        bound = self.reader.targets(obj, "Deployment_Properties::Actual_Connection_Binding", self.mode) or []
        return [b for b in bound if hasattr(b, "componentInstances")]

    def add_to(self, conn: Any, row: Contributor) -> None:
        """Add the sampling and transmission rows of ``conn``'s buses under ``row``."""
        self._sampling(conn, conn, row, set())
        source = conn.source
        size = data_size_kbyte(self.reader, source, self.mode) if source is not None else None
        self._transmission(conn, (size or Fraction(0)) * 1000, row, conn, set())

    def _sampling(self, obj: Any, conn: Any, row: Contributor, seen: set[int]) -> None:
        bound = self.bindings(obj) if _is_instance(obj) else []
        if not any(category_of(b) == "virtualBus" for b in bound):
            for protocol in self.required(obj):
                if id(protocol) in seen:
                    continue
                period = self.us(protocol, "Timing_Properties::Period")
                if period > 0:
                    self._periodic_rows(protocol, period, row)
                self._sampling(protocol, conn, row, seen | {id(protocol)})
        for bus in bound:
            if id(bus) in seen:
                self.reader.report("error", "virtual buses are bound in a cycle", conn)
                continue
            period = (
                self.us(bus, "Timing_Properties::Period") if category_of(bus) in _PERIODIC else Fraction(0)
            )
            if period > 0:
                self._periodic_rows(bus, period, row)
            else:
                self.waiting.append((bus, conn, row))
            if category_of(bus) == "virtualBus":
                self._sampling(bus, conn, row, seen | {id(bus)})

    def _periodic_rows(self, bus: Any, period: Fraction, row: Contributor) -> None:
        """A periodic bus or protocol samples the message (and queues nothing)."""
        sampling = Contributor(bus, _label(bus), "sampling", period=period)
        sampling.best_method = sampling.worst_method = "sampled_protocol"
        queued = Contributor(bus, _label(bus), "queuing")
        queued.best_method = queued.worst_method = "queued"
        row.subs.extend([sampling, queued])

    def _transmission(self, obj: Any, size: Fraction, row: Contributor, conn: Any, seen: set[int]) -> None:
        bound = self.bindings(obj)
        if not bound:
            return
        if not any(category_of(b) == "virtualBus" for b in bound):
            protocols = self.required(obj)
            if protocols:
                row.comment("Adding required virtual bus contributions to bound bus")
                size = self._required_size(protocols, size, row, conn, seen)
        for bus in bound:
            if id(bus) in seen:
                continue
            wrapped = size + self._data_bytes(bus)
            self._time(bus, wrapped, row, conn)
            if category_of(bus) == "virtualBus":
                self._transmission(bus, wrapped, row, conn, seen | {id(bus)})

    def _required_size(
        self, protocols: list[Any], size: Fraction, row: Contributor, conn: Any, seen: set[int]
    ) -> Fraction:
        """The transmission rows of required protocols, and the bytes the bound hardware then
        carries: the message and every protocol's ``Data_Size`` (``computeTotalDataSize``)."""
        total = size
        for protocol in protocols:
            if id(protocol) in seen:
                continue
            overhead = self._data_bytes(protocol)
            wrapped = size + overhead
            self._time(protocol, wrapped, row, conn)
            total += overhead
            nested = self.required(protocol)
            if nested:
                inner = self._required_size(nested, wrapped, row, conn, seen | {id(protocol)})
                total += inner - wrapped
        return total

    def transfer(self, bus: Any, size: Fraction) -> tuple[Fraction, Fraction, str]:
        """(min, max, how) of sending ``size`` bytes over ``bus``."""
        record = self._value(bus, "Communication_Properties::Transmission_Time")
        where = bus if _is_instance(bus) else None
        if isinstance(record, dict) and (
            record.get("Fixed") is not None or record.get("PerByte") is not None
        ):
            low = high = Fraction(0)
            for key, factor in (("Fixed", Fraction(1)), ("PerByte", size)):
                value = record.get(key)
                if value is None:
                    continue
                low += (
                    (self.reader.convert(where, "Transmission_Time", value, "sec", part="min") or 0)
                    * _US
                    * factor
                )
                high += (self.reader.convert(where, "Transmission_Time", value, "sec") or 0) * _US * factor
            return low, high, "Transmission_Time"
        if category_of(bus) == "bus":
            capacity = self.reader.number(bus, "SEI::BandWidthCapacity", "KBytesps", self.mode)
            if capacity is not None and capacity > 0:
                time = size / (capacity * 1000) * _US
                return time, time, "SEI::BandWidthCapacity"
        return Fraction(0), Fraction(0), ""

    def _raw_us(self, obj: Any, name: str, part: str = "max") -> Fraction:
        """A time in µs as written, negative values kept (OSATE tests them against 0 only)."""
        value = self._number(obj, name, "sec", part)
        return value * _US if value is not None else Fraction(0)

    def _time(self, bus: Any, size: Fraction, row: Contributor, conn: Any) -> None:
        """The transmission row of ``bus`` (``processTransmissionTime``): none when neither its
        ``Latency`` nor its transfer time is set; a negative value gives a row of 0 by an
        unknown method (*no sampling/queuing latency*)."""
        latency_best = self._raw_us(bus, "Communication_Properties::Latency", "min")
        latency_worst = self._raw_us(bus, "Communication_Properties::Latency")
        low, high, how = self.transfer(bus, size)
        if latency_worst == 0 and high == 0:
            return
        sub = Contributor(bus, _label(bus), "transmission")
        sub.specified_best, sub.specified_worst = latency_best, latency_worst
        if high > 0:
            sub.worst, sub.worst_method = high, "transmission"
            sub.comment(
                "Using data transfer time"
                if how == "Transmission_Time"
                else "Data size over SEI::BandWidthCapacity"
            )
            if size == 0:
                sub.comment("Data size = 0. Possibly data type on port missing")
        elif latency_worst > 0:
            sub.worst, sub.worst_method = latency_worst, "specified"
            sub.comment("Using specified bus latency")
        if sub.worst_method != "unknown" and _is_instance(bus):
            self.max_times[(id(bus), id(conn))] = sub.worst
        if low > 0:
            sub.best, sub.best_method = low, "transmission"
        elif latency_best > 0:
            sub.best, sub.best_method = latency_best, "specified"
        row.subs.append(sub)

    def fill_queuing(self, bound: dict[int, list[Any]]) -> None:
        """Add the waiting time of each connection on each shared bus (``fillInQueuingTimes``):
        ``bound`` maps a bus to every connection bound to it in the system mode."""
        for bus, conn, row in self.waiting:
            others = bound.get(id(bus), [])
            total = sum((self.max_times.get((id(bus), id(c)), Fraction(0)) for c in others), Fraction(0))
            wait = total - self.max_times.get((id(bus), id(conn)), Fraction(0))
            queued = Contributor(bus, _label(bus), "queuing", worst=max(wait, Fraction(0)))
            queued.best_method = queued.worst_method = "queued"
            sampling = Contributor(bus, _label(bus), "sampling")
            sampling.best_method = sampling.worst_method = "sampled_protocol"
            row.subs.extend([queued, sampling])
        self.waiting = []


def connection_transmission_us(conn: Any, reader: PropertyReader, mode: SystemMode) -> Fraction:
    """The worst time a message of ``conn`` spends between its ends, in µs: the connection's own
    ``Latency``, plus the sampling period of each periodic bus or protocol it is bound to and the
    transmission over each (:meth:`Transmission.add_to`); waiting on a shared bus is left out (it
    needs every flow of the mode, :meth:`Transmission.fill_queuing`)."""
    transmission = Transmission(reader, mode)
    row = Contributor(conn, "", "connection")
    transmission.add_to(conn, row)
    own = transmission.us(conn, "Communication_Properties::Latency")
    return own + sum((sub.total(True) + sub.period for sub in row.subs), Fraction(0))
