"""Bus load, as OSATE's bus load analysis (``NewBusLoadAnalysis``) computes and reports it.

For every system operation mode and every physical bus (pre-order), the analysis builds the tree
of what is bound to it: the connections whose ``Actual_Connection_Binding`` names the bus, and the
virtual buses bound to it (by ``Actual_Connection_Binding``, or by being a subcomponent of it),
recursively. Then, as OSATE:

* the *data overhead* of a bus or virtual bus is its ``Data_Size`` (else ``Source_Data_Size``)
  plus the overhead of the bus it is bound to;
* a connection's *actual* load is (source feature ``Data_Size``, else ``Source_Data_Size``, + the
  overhead of the bus it is bound to) × the source's message rate, in KB/s: ``SEI::Data_Rate``,
  else ``SEI::Message_Rate``, else ``Communication_Properties::Output_Rate`` (maximum of its
  range; ``PerDispatch`` divided by the ``Period`` of the source's component), else 1 / ``Period``
  of the source's component;
* on a bus with ``SEI::Broadcast_Protocol => true``, the connections that share a source feature
  form one *broadcast group* that counts once, with the largest budget of its connections;
* a bus's *actual* is the sum of the actuals, its *required budget* the sum of the budgets, of
  the connections, broadcast groups and virtual buses bound to it; *capacity* and *budget* come
  from ``SEI::BandWidthCapacity`` and ``SEI::BandWidthBudget``;
* OSATE's warnings (no capacity, no budget) and errors (actual > capacity, budget > capacity,
  required budget > budget, connection actual > budget) with OSATE's messages.

All values are exact (KB/s means KBytesps, 1000 bytes per second, as OSATE prints it);
:meth:`BusLoadResult.csv_text` writes OSATE's CSV report, numbers printed as Java prints doubles.
:func:`port_loads` gives the bandwidth every outgoing port of a thread or device demands
(``Data_Size`` × rate, no bus overhead), the figure the library paper's Table 2 lists.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass
from decimal import Decimal
from fractions import Fraction
from typing import Any

from rosaadl.analysis.instance_values import (
    PropertyReader,
    SystemMode,
    category_of,
    instance_root,
    system_modes,
)
from rosaadl.analysis.registry import Analysis, register
from rosaadl.analysis.rendering import as_float, short_path, table
from rosaadl.errors import AnalysisError, Diagnostic, Location

__all__ = [
    "java_double",
    "message_rate",
    "data_size_kbyte",
    "ConnectionLoad",
    "BroadcastLoad",
    "BusLoad",
    "ModeBusLoad",
    "PortLoad",
    "BusLoadResult",
    "analyze_bus_load",
    "port_loads",
]

log = logging.getLogger(__name__)


# =============================================================================== number format


def java_double(value: Fraction | float | int) -> str:
    """``value`` as Java's ``Double.toString`` prints the nearest double: ``16.0``, ``0.125``,
    ``1.0E7``, ``1.0E-4`` (shortest digits that read back to the same double)."""
    number = as_float(value)  # Java too prints an infinity for a number beyond the doubles
    if number != number:
        return "NaN"
    if number in (float("inf"), float("-inf")):
        return "Infinity" if number > 0 else "-Infinity"
    if number == 0:
        return "-0.0" if str(number).startswith("-") else "0.0"
    sign = "-" if number < 0 else ""
    magnitude = abs(number)
    digits_tuple = Decimal(repr(magnitude)).normalize().as_tuple()
    digits = "".join(str(d) for d in digits_tuple.digits)
    exponent = digits_tuple.exponent + len(digits) - 1  # scientific exponent of the first digit
    if 1e-3 <= magnitude < 1e7:
        if exponent >= 0:
            whole = digits[: exponent + 1].ljust(exponent + 1, "0")
            frac = digits[exponent + 1 :] or "0"
        else:
            whole = "0"
            frac = "0" * (-exponent - 1) + digits
        return f"{sign}{whole}.{frac}"
    mantissa = digits[0] + "." + (digits[1:] or "0")
    return f"{sign}{mantissa}E{exponent}"


# =============================================================================== rates and sizes


def data_size_kbyte(reader: PropertyReader, obj: Any, mode: SystemMode | None = None) -> Fraction | None:
    """``Data_Size``, else ``Source_Data_Size``, in KByte (None when neither is set)."""
    size = reader.size_kbyte(obj, "Memory_Properties::Data_Size", mode)
    if size is None:
        size = reader.size_kbyte(obj, "Memory_Properties::Source_Data_Size", mode)
    return size


def _period_seconds(reader: PropertyReader, component: Any, mode: SystemMode | None) -> Fraction:
    if component is None:
        return Fraction(0)
    period = reader.seconds(component, "Timing_Properties::Period", mode)
    return period if period is not None and period > 0 else Fraction(0)


def message_rate(reader: PropertyReader, feature: Any, mode: SystemMode | None = None) -> Fraction:
    """Messages per second sent through ``feature`` (OSATE's outgoing message rate)."""
    for name in ("SEI::Data_Rate", "SEI::Message_Rate"):
        value = reader.value(feature, name, mode)
        if value is not None:
            rate = reader.convert(feature, name, value, "perSecond")
            return rate if rate is not None else Fraction(0)
    component = feature.eContainer()
    while component is not None and not hasattr(component, "componentInstances"):
        component = component.eContainer()
    spec = reader.value(feature, "Communication_Properties::Output_Rate", mode)
    if isinstance(spec, dict):
        value_range = spec.get("Value_Range")
        maximum = (
            reader.convert(feature, "Output_Rate", value_range, None) if value_range is not None else None
        )
        maximum = maximum if maximum is not None else Fraction(0)
        unit = spec.get("Rate_Unit")
        if unit is not None and str(unit).lower() == "perdispatch":
            period = _period_seconds(reader, component, mode)
            return maximum / period if period else Fraction(0)
        if maximum > 0:
            return maximum
    period = _period_seconds(reader, component, mode)
    return 1 / period if period else Fraction(0)


# =============================================================================== results


def _num(value: Fraction) -> float | int:
    return int(value) if value.denominator == 1 else float(value)


@dataclass(frozen=True)
class ConnectionLoad:
    """A connection bound to a bus: its budget and actual load in KB/s."""

    path: str
    name: str
    budget_kbps: Fraction
    actual_kbps: Fraction
    diagnostics: tuple[Diagnostic, ...] = ()

    def as_dict(self) -> dict[str, Any]:
        return {
            "path": self.path,
            "budget_kbps": _num(self.budget_kbps),
            "actual_kbps": _num(self.actual_kbps),
        }


@dataclass(frozen=True)
class BroadcastLoad:
    """Connections that share a source feature on a broadcast bus, counted once."""

    source: str
    budget_kbps: Fraction
    actual_kbps: Fraction
    connections: tuple[ConnectionLoad, ...]
    diagnostics: tuple[Diagnostic, ...] = ()

    @property
    def label(self) -> str:
        return f"Broadcast from {self.source}"

    def as_dict(self) -> dict[str, Any]:
        return {
            "source": self.source,
            "budget_kbps": _num(self.budget_kbps),
            "actual_kbps": _num(self.actual_kbps),
            "connections": [c.as_dict() for c in self.connections],
        }


@dataclass(frozen=True)
class BusLoad:
    """A bus or virtual bus with what is bound to it (all loads in KB/s)."""

    path: str
    name: str
    virtual: bool
    capacity_kbps: Fraction
    budget_kbps: Fraction
    required_kbps: Fraction
    actual_kbps: Fraction
    overhead_kbyte: Fraction
    virtual_buses: tuple[BusLoad, ...]
    connections: tuple[ConnectionLoad, ...]
    broadcasts: tuple[BroadcastLoad, ...]
    diagnostics: tuple[Diagnostic, ...] = ()

    @property
    def overhead_bytes(self) -> int:
        """The data overhead in whole bytes, truncated as OSATE prints it."""
        return int(self.overhead_kbyte * 1000)

    @property
    def load_percent(self) -> Fraction | None:
        return self.actual_kbps / self.capacity_kbps * 100 if self.capacity_kbps > 0 else None

    def walk(self) -> list[BusLoad]:
        """This bus and its virtual buses, pre-order."""
        out = [self]
        for vb in self.virtual_buses:
            out.extend(vb.walk())
        return out

    def as_dict(self) -> dict[str, Any]:
        return {
            "path": self.path,
            "capacity_kbps": _num(self.capacity_kbps),
            "budget_kbps": _num(self.budget_kbps),
            "required_kbps": _num(self.required_kbps),
            "actual_kbps": _num(self.actual_kbps),
            "overhead_bytes": self.overhead_bytes,
            "virtual_buses": [vb.as_dict() for vb in self.virtual_buses],
            "connections": [c.as_dict() for c in self.connections],
            "broadcasts": [b.as_dict() for b in self.broadcasts],
        }


@dataclass(frozen=True)
class ModeBusLoad:
    """The buses of one system operation mode."""

    name: str
    label: str
    buses: tuple[BusLoad, ...]


@dataclass(frozen=True)
class PortLoad:
    """The bandwidth an outgoing port demands: ``Data_Size`` × message rate (no bus overhead)."""

    path: str
    data_size_bytes: Fraction
    rate_per_second: Fraction

    @property
    def kbytesps(self) -> Fraction:
        return self.data_size_bytes * self.rate_per_second / 1000

    def as_dict(self) -> dict[str, Any]:
        return {
            "path": self.path,
            "data_size_bytes": _num(self.data_size_bytes),
            "rate_per_second": _num(self.rate_per_second),
            "kbps": _num(self.kbytesps),
        }


@dataclass(frozen=True)
class BusLoadResult:
    """Bus load per system operation mode, the ports' demands and the diagnostics."""

    instance: str
    modes: tuple[ModeBusLoad, ...]
    ports: tuple[PortLoad, ...]
    diagnostics: tuple[Diagnostic, ...]

    @property
    def ok(self) -> bool:
        return all(d.severity != "error" for d in self.diagnostics)

    def bus(self, path: str, mode: str = "") -> BusLoad:
        """A bus or virtual bus by instance path (in the first mode, or the mode with that label)."""
        for som in self.modes:
            if mode and som.label != mode:
                continue
            for bus in som.buses:
                for found in bus.walk():
                    if found.path == path:
                        return found
        where = f" in mode {mode!r}" if mode else ""
        raise AnalysisError(f"no bus or virtual bus {path!r}{where}", path=path)

    def as_dict(self) -> dict[str, Any]:
        buses = []
        for som in self.modes:
            for bus in som.buses:
                row = bus.as_dict()
                if som.label:
                    row["modes"] = som.label
                buses.append(row)
        return {"buses": buses, "ports": [p.as_dict() for p in self.ports]}

    def csv_text(self) -> str:
        """OSATE's bus load report (``<instance>__BusLoad.csv``), line for line."""
        out: list[str] = [f"Bus load analysis of {self.instance}", "", ""]
        for som in self.modes:
            if som.label:
                out.append(_item(f"Analysis results in modes {som.label}"))
            out.append(_items("Physical Bus", *_HEADS))
            for bus in som.buses:
                out.append(_items(bus.name, *_bus_values(bus)))
            out.append("")
            for bus in som.buses:
                _csv_bus(out, bus, None)
            out.append("")
        return "\n".join(out) + "\n"


_HEADS = ("Capacity (KB/s)", "Budget (KB/s)", "Required Budget (KB/s)", "Actual (KB/s)")


def _item(text: str) -> str:
    return f'"{text}"'


def _items(*texts: str) -> str:
    return ",".join(_item(t) for t in texts)


def _bus_values(bus: BusLoad) -> tuple[str, str, str, str]:
    return (
        java_double(bus.capacity_kbps),
        java_double(bus.budget_kbps),
        java_double(bus.required_kbps),
        java_double(bus.actual_kbps),
    )


def _diagnostic_lines(out: list[str], diagnostics: tuple[Diagnostic, ...]) -> None:
    for diag in diagnostics:
        out.append(_item(f"{diag.severity.upper()}: {diag.message}"))


def _csv_connection(out: list[str], connection: ConnectionLoad, bound_to: str) -> None:
    if connection.diagnostics:
        out.append(_item(f"Connection {connection.name} bound to {bound_to}"))
        _diagnostic_lines(out, connection.diagnostics)
        out.append("")


def _csv_bus(out: list[str], bus: BusLoad, bound_to: BusLoad | None) -> None:
    if bound_to is None:
        out.append(_item(f"Bus {bus.name} has data overhead of {bus.overhead_bytes} bytes"))
    else:
        out.append(
            _item(
                f"Virtual bus {bus.name} bound to {bound_to.name} "
                f"has data overhead of {bus.overhead_bytes} bytes"
            )
        )
    out.append(_items("Bound Virtual Bus/Connection", *_HEADS))
    for vb in bus.virtual_buses:
        out.append(_items(vb.name, *_bus_values(vb)))
    for item in (*bus.connections, *bus.broadcasts):
        label = item.name if isinstance(item, ConnectionLoad) else item.label
        out.append(_items(label, "", java_double(item.budget_kbps), "", java_double(item.actual_kbps)))
    out.append("")
    if bus.diagnostics:
        _diagnostic_lines(out, bus.diagnostics)
        out.append("")
    for vb in bus.virtual_buses:
        _csv_bus(out, vb, bus)
    for connection in bus.connections:
        _csv_connection(out, connection, bus.name)
    for broadcast in bus.broadcasts:
        out.append(_item(f"{broadcast.label} over bus {bus.name}"))
        out.append(_items("Included Connection", "Budget (KB/s)", "Actual (KB/s)"))
        for connection in broadcast.connections:
            out.append(
                _items(
                    connection.name, java_double(connection.budget_kbps), java_double(connection.actual_kbps)
                )
            )
        out.append("")
        if broadcast.diagnostics:
            _diagnostic_lines(out, broadcast.diagnostics)
            out.append("")
        for connection in broadcast.connections:
            _csv_connection(out, connection, broadcast.label)


# =============================================================================== the analysis


class _BusAnalysis:
    def __init__(self, root: Any, diagnostics: list[Diagnostic]) -> None:
        self.root = root
        self.diagnostics = diagnostics
        self.reader = PropertyReader([])  # property problems, merged into diagnostics at the end
        components = []
        stack = [root]
        while stack:
            ci = stack.pop()
            components.append(ci)
            stack.extend(reversed(list(ci.componentInstances)))
        self.components = components
        self.connections = [conn for ci in components for conn in ci.connectionInstances]
        self.virtual_buses = [ci for ci in components if category_of(ci) == "virtualBus"]
        self._indexes: dict[str, dict[int, tuple[list[Any], list[Any]]]] = {}

    # ------------------------------------------------------------------ bindings

    def connection_binding(self, obj: Any, mode: SystemMode) -> list[Any]:
        bound = self.reader.targets(obj, "Actual_Connection_Binding", mode) or []
        if not bound and category_of(obj) == "virtualBus" and hasattr(obj, "componentInstances"):
            parent = obj.eContainer()
            if parent is not None and category_of(parent) in ("bus", "virtualBus"):
                bound = [parent]
        return bound

    def _index(self, mode: SystemMode) -> dict[int, tuple[list[Any], list[Any]]]:
        """bus or virtual bus id → (connections, virtual buses) bound to it, in model order."""
        index = self._indexes.get(mode.name)
        if index is None:
            index = {}
            for conn in self.connections:
                if mode.active(conn):
                    for target in self.connection_binding(conn, mode):
                        index.setdefault(id(target), ([], []))[0].append(conn)
            for vb in self.virtual_buses:
                if mode.active(vb):
                    for target in self.connection_binding(vb, mode):
                        index.setdefault(id(target), ([], []))[1].append(vb)
            self._indexes[mode.name] = index
        return index

    def bound_connections(self, bus: Any, mode: SystemMode) -> list[Any]:
        return list(self._index(mode).get(id(bus), ([], []))[0])

    def bound_virtual_buses(self, bus: Any, mode: SystemMode) -> list[Any]:
        return list(self._index(mode).get(id(bus), ([], []))[1])

    # ------------------------------------------------------------------ loads

    def diag(self, severity: str, message: str, obj: Any, mode: SystemMode) -> Diagnostic:
        from rosaadl.model import instance_path

        where = f" in modes {mode.label}" if mode.label else ""
        located = Diagnostic(severity, message + where, Location(path=instance_path(obj)))
        self.diagnostics.append(located)
        return Diagnostic(severity, message, Location(path=instance_path(obj)))

    def actual(self, source: Any, overhead: Fraction, mode: SystemMode) -> Fraction:
        """(data size + overhead) × rate of a connection source, KB/s (0 for a component end)."""
        if source is None or hasattr(source, "componentInstances"):
            return Fraction(0)
        size = data_size_kbyte(self.reader, source, mode) or Fraction(0)
        return (overhead + size) * message_rate(self.reader, source, mode)

    def connection(self, conn: Any, overhead: Fraction, mode: SystemMode) -> ConnectionLoad:
        from rosaadl.model import instance_path

        actual = self.actual(conn.source, overhead, mode)
        budget = self.reader.number(conn, "SEI::BandWidthBudget", "KBytesps", mode) or Fraction(0)
        name = conn.name or ""
        diags = []
        if budget > 0:
            if actual > budget:
                diags.append(
                    self.diag(
                        "error",
                        f"Connection {name} -- Actual bandwidth > budget: "
                        f"{java_double(actual)} KB/s > {java_double(budget)} KB/s",
                        conn,
                        mode,
                    )
                )
        else:
            diags.append(self.diag("warning", f"Connection {name} has no bandwidth budget", conn, mode))
        return ConnectionLoad(instance_path(conn), name, budget, actual, tuple(diags))

    def bus(self, ci: Any, parent_overhead: Fraction, mode: SystemMode, path: tuple[int, ...]) -> BusLoad:
        from rosaadl.model import instance_path

        virtual = category_of(ci) == "virtualBus"
        overhead = parent_overhead + (data_size_kbyte(self.reader, ci, mode) or Fraction(0))
        inner_path = (*path, id(ci))
        vbs = []
        for vb in self.bound_virtual_buses(ci, mode):
            if id(vb) in inner_path:
                self.diag("error", f"virtual bus {vb.name} is bound in a cycle", vb, mode)
                continue
            vbs.append(self.bus(vb, overhead, mode, inner_path))
        bound = self.bound_connections(ci, mode)
        broadcasts: list[BroadcastLoad] = []
        if self.reader.flag(ci, "SEI::Broadcast_Protocol", mode):
            bound, broadcasts = self.broadcasts(bound, overhead, mode)
        connections = [self.connection(c, overhead, mode) for c in bound]
        actual = sum((x.actual_kbps for x in (*vbs, *connections, *broadcasts)), Fraction(0))
        required = sum((x.budget_kbps for x in (*vbs, *connections, *broadcasts)), Fraction(0))
        capacity = self.reader.number(ci, "SEI::BandWidthCapacity", "KBytesps", mode) or Fraction(0)
        budget = self.reader.number(ci, "SEI::BandWidthBudget", "KBytesps", mode) or Fraction(0)
        label = ("Virtual bus " if virtual else "Bus ") + (ci.name or "")
        diags = []
        if capacity == 0:
            diags.append(self.diag("warning", f"{label} has no capacity", ci, mode))
        elif actual > capacity:
            diags.append(
                self.diag(
                    "error",
                    f"{label} -- Actual bandwidth > capacity: {java_double(actual)} KB/s > "
                    f"{java_double(capacity)} KB/s",
                    ci,
                    mode,
                )
            )
        if budget == 0:
            diags.append(self.diag("warning", f"{label} has no bandwidth budget", ci, mode))
        else:
            if budget > capacity:
                diags.append(
                    self.diag(
                        "error",
                        f"{label} -- budget > capacity: {java_double(budget)} KB/s > "
                        f"{java_double(capacity)} KB/s",
                        ci,
                        mode,
                    )
                )
            if required > budget:
                diags.append(
                    self.diag(
                        "error",
                        f"{label} -- Required budget > budget: {java_double(required)} KB/s > "
                        f"{java_double(budget)} KB/s",
                        ci,
                        mode,
                    )
                )
        return BusLoad(
            instance_path(ci),
            ci.name or "",
            virtual,
            capacity,
            budget,
            required,
            actual,
            overhead,
            tuple(vbs),
            tuple(connections),
            tuple(broadcasts),
            tuple(diags),
        )

    def broadcasts(
        self, bound: list[Any], overhead: Fraction, mode: SystemMode
    ) -> tuple[list[Any], list[BroadcastLoad]]:
        """Group connections by source feature (groups of two or more, by source path as OSATE's
        TreeMap orders them); the others stay single connections in declaration order."""
        from rosaadl.model import instance_path

        groups: dict[str, list[Any]] = {}
        sources: dict[str, Any] = {}
        for conn in bound:
            key = instance_path(conn.source) if conn.source is not None else ""
            groups.setdefault(key, []).append(conn)
            sources[key] = conn.source
        grouped: set[int] = set()
        result = []
        for key in sorted(groups):
            members = groups[key]
            if len(members) < 2:
                continue
            grouped.update(id(c) for c in members)
            loads = tuple(self.connection(c, overhead, mode) for c in members)
            budget = max(c.budget_kbps for c in loads)
            actual = self.actual(sources[key], overhead, mode)
            diags = []
            if len({c.budget_kbps for c in loads}) > 1:
                for c, conn in zip(loads, members, strict=True):
                    diags.append(
                        self.diag(
                            "warning",
                            f"Connection {c.name} sharing broadcast source {key} has budget "
                            f"{java_double(c.budget_kbps)} KB/s; using maximum",
                            conn,
                            mode,
                        )
                    )
            result.append(BroadcastLoad(key, budget, actual, loads, tuple(diags)))
        return [c for c in bound if id(c) not in grouped], result

    def run(self) -> tuple[list[ModeBusLoad], list[PortLoad]]:
        modes = []
        for mode in system_modes(self.root):
            buses = [
                self.bus(ci, Fraction(0), mode, ()) for ci in self.components if category_of(ci) == "bus"
            ]
            modes.append(ModeBusLoad(mode.name, mode.label, tuple(buses)))
        return modes, port_loads_of(self.components, self.reader, system_modes(self.root)[0])


def port_loads_of(components: list[Any], reader: PropertyReader, mode: SystemMode | None) -> list[PortLoad]:
    from rosaadl.model import instance_path

    rows = []
    for ci in components:
        if category_of(ci) not in ("thread", "device"):
            continue
        for fi in ci.featureInstances:
            if category_of(fi) not in ("dataPort", "eventDataPort"):
                continue
            direction = getattr(getattr(fi, "direction", None), "name", "")
            if direction not in ("out", "inOut"):
                continue
            size = data_size_kbyte(reader, fi, mode)
            if size is None:
                reader.report("warning", "outgoing port has no Data_Size; its bandwidth is 0", fi)
                size = Fraction(0)
            rows.append(PortLoad(instance_path(fi), size * 1000, message_rate(reader, fi, mode)))
    return rows


def analyze_bus_load(source: Any) -> BusLoadResult:
    """OSATE's bus load analysis of an instance (``SystemInstance`` or ``AadlModel``)."""
    root = instance_root(source)
    diagnostics: list[Diagnostic] = []
    analysis = _BusAnalysis(root, diagnostics)
    modes, ports = analysis.run()
    merged = [*analysis.reader.diagnostics, *diagnostics]
    log.debug("bus load of %s: %d modes", root.name, len(modes))
    return BusLoadResult(root.name or "", tuple(modes), tuple(ports), tuple(merged))


def port_loads(source: Any) -> list[PortLoad]:
    """Bandwidth demand (``Data_Size`` × message rate) of every outgoing data port of a thread or
    device, in the first system operation mode."""
    root = instance_root(source)
    analysis = _BusAnalysis(root, [])
    return port_loads_of(analysis.components, analysis.reader, system_modes(root)[0])


# =============================================================================== renderings


def _bus_rows(rows: list[list[Any]], bus: Any, depth: int) -> None:
    indent = "  " * depth
    rows.append(
        [
            indent + short_path(bus.path),
            bus.capacity_kbps,
            bus.budget_kbps,
            bus.required_kbps,
            bus.actual_kbps,
        ]
    )
    for vb in bus.virtual_buses:
        _bus_rows(rows, vb, depth + 1)
    for conn in bus.connections:
        rows.append([indent + "  " + conn.name, "", conn.budget_kbps, "", conn.actual_kbps])
    for group in bus.broadcasts:
        rows.append([indent + "  " + group.label, "", group.budget_kbps, "", group.actual_kbps])


def bus_load_text(result: BusLoadResult) -> list[str]:
    """The ``Bus load (KB/s)`` section of the text report."""
    lines = ["Bus load (KB/s)", ""]
    for som in result.modes:
        if som.label:
            lines.append(f"in modes {som.label}")
        rows: list[list[Any]] = []
        for bus in som.buses:
            _bus_rows(rows, bus, 0)
        lines += table(["bus / virtual bus / connection", "capacity", "budget", "required", "actual"], rows)
        lines.append("")
    if result.ports:
        rows = [[short_path(p.path), p.data_size_bytes, p.rate_per_second, p.kbytesps] for p in result.ports]
        lines += table(["outgoing port", "Data_Size bytes", "rate /s", "KB/s"], rows)
        lines.append("")
    return lines


register(
    Analysis(
        name="bus",
        json_key="bus",
        order=30,
        run=lambda context: analyze_bus_load(context.root),
        text=bus_load_text,
        csv=lambda result, base: {f"{base}__BusLoad.csv": result.csv_text()},
        aliases=("busload",),
        description="load of every bus and virtual bus (OSATE's bus load analysis and its CSV report)",
    )
)
