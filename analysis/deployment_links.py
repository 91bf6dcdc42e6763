"""What a deployment problem reads from the model's links: cause-effect chains and pinned units.

**Chains.** The cause-effect chains are the executor analysis's
(:mod:`rosaadl.analysis.cause_effect`): the model's end-to-end flows over callbacks, then every
maximal path of callbacks over topics and flow paths, at most 100. The executor analysis bounds
a chain's reaction time (= data age) by ``sum_k (T_k if the k-th callback is a timer) + R_k``
plus the transmission of every topic on the way. Under a binding, :class:`ChainCost` keeps:

* a **fixed part**, the same for every binding: the sampling periods ``T_k`` of its timer
  callbacks plus the execution times ``C_k`` of its callbacks (the least response time each can
  have, ``R_k >= C_k``; the executor analysis's bound adds the waiting in the executor and on
  the core, which needs the response-time analysis of the bound cores and is not modelled);
* for each topic between two different units, its **transmission** when the two units are on
  different boards: the connection's own ``Latency``, plus the ``Latency`` of the bus the solver
  loads (the model's bus of least ``SEI::BandWidthCapacity``) and the transfer of its
  ``Data_Size`` over it (``Transmission_Time``, else bytes over the capacity), as
  :mod:`rosaadl.analysis.latency.transmission` computes it for a connection bound to that bus.
  A topic inside one unit, or between units on one board, costs nothing.

So a chain's latency under a binding is linear in the "on different boards" Booleans the bus
objective already has, and equals the executor analysis's reaction time of the chain, with every
crossing topic bound to that bus, less the waiting ``sum_k (R_k - C_k)``.

**Pins.** A unit connected to a ``device`` (a port connection or an access connection, either
way) that sits on a board (a system or processor holding candidate cores, the device's nearest
such ancestor below the root) must run on a core of that board: the device's driver stays where
its hardware is. :func:`device_pins` gives these pins; the problem applies them like
``Allowed_Processor_Binding``.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rosaadl.analysis.instance_values import PropertyReader, category_of
from rosaadl.model import component_instances, instance_path, walk

__all__ = ["ChainCost", "Pin", "chain_costs", "device_pins", "unit_finder"]

_CHAIN_LIMIT = 100


@dataclass(frozen=True)
class ChainCost:
    """A chain's latency as the solver sees it (module doc), in microseconds: ``fixed_us`` plus,
    for each ``(unit, unit, µs)`` of ``links``, the µs when the two units are on different
    boards."""

    name: str
    fixed_us: Fraction
    links: tuple[tuple[int, int, Fraction], ...]

    def latency(self, board: Callable[[int], str | None]) -> Fraction:
        """The latency when unit ``u`` is on board ``board(u)`` (None: unplaced, not crossing)."""
        total = self.fixed_us
        for u, v, us in self.links:
            bu, bv = board(u), board(v)
            if bu is not None and bv is not None and bu != bv:
                total += us
        return total


@dataclass(frozen=True)
class Pin:
    """A unit held to some cores: by a device it talks to (``device`` set, ``board`` its board),
    or by the user's ``Allowed_Processor_Binding`` (``device`` empty, ``board`` the target)."""

    unit: int
    board: str
    device: str
    cores: tuple[int, ...]
    by: str = "Allowed_Processor_Binding"  #: the property restricting it, when no device does

    @property
    def reason(self) -> str:
        return f"device {self.device}" if self.device else self.by


def unit_finder(root: Any, unit_objs: Sequence[Any]) -> Callable[[Any], list[int]]:
    """A function from a feature or component instance to the units it belongs to: the unit
    holding it, else (a port of a process or thread group searched thread by thread) the units
    inside that component."""
    owner = {id(obj): u for u, obj in enumerate(unit_objs)}
    paths = [instance_path(obj) for obj in unit_objs]

    def units_of(end: Any) -> list[int]:
        obj = end
        while obj is not None and obj is not root:
            found = owner.get(id(obj))
            if found is not None:
                return [found]
            obj = obj.eContainer()
        holder = end
        while holder is not None and not hasattr(holder, "componentInstances"):
            holder = holder.eContainer()
        if holder is None or category_of(holder) not in ("process", "threadGroup", "thread group"):
            return []
        prefix = instance_path(holder) + "."
        return [u for u, p in enumerate(paths) if p.startswith(prefix)]

    return units_of


def _component(end: Any) -> Any:
    while end is not None and not hasattr(end, "componentInstances"):
        end = end.eContainer()
    return end


def _connections(root: Any, mode: Any) -> list[Any]:
    return [
        obj
        for obj in walk(root)
        if type(obj).__name__ == "ConnectionInstance"
        and obj.source is not None
        and obj.destination is not None
        and mode.active(obj)
    ]


def device_pins(root: Any, unit_objs: Sequence[Any], core_paths: Sequence[str], mode: Any) -> list[Pin]:
    """The pins of the units connected to a device on a board (module doc), in model order."""
    units_of = unit_finder(root, unit_objs)
    pins: dict[tuple[int, str], Pin] = {}
    for conn in _connections(root, mode):
        for end, other in ((conn.source, conn.destination), (conn.destination, conn.source)):
            device = _component(end)
            if device is None or category_of(device) != "device":
                continue
            holder = device.eContainer()
            while holder is not None and holder is not root:
                prefix = instance_path(holder) + "."
                cores = tuple(i for i, p in enumerate(core_paths) if p.startswith(prefix))
                if cores:
                    break
                holder = holder.eContainer()
            else:
                continue
            for u in units_of(other):
                key = (u, instance_path(device))
                if key not in pins:
                    pins[key] = Pin(u, instance_path(holder), instance_path(device), cores)
    return list(pins.values())


def _bus(root: Any, reader: PropertyReader, mode: Any) -> Any:
    """The bus the solver loads: the active bus of least ``SEI::BandWidthCapacity``."""
    best, least = None, None
    for obj in walk(root):
        if hasattr(obj, "componentInstances") and category_of(obj) == "bus" and mode.active(obj):
            capacity = reader.number(obj, "SEI::BandWidthCapacity", "KBytesps", mode)
            if capacity is not None and capacity > 0 and (least is None or capacity < least):
                best, least = obj, capacity
    return best


def chain_costs(root: Any, unit_objs: Sequence[Any], mode: Any) -> list[ChainCost]:
    """The cause-effect chains of the model as the solver costs them (module doc)."""
    from rosaadl.analysis.busload import data_size_kbyte
    from rosaadl.analysis.cause_effect import callback_links, cause_effect_chains, flow_callbacks
    from rosaadl.analysis.executors import executors_from_instance
    from rosaadl.analysis.latency.transmission import Transmission

    reader = PropertyReader([])
    callbacks = [c for e in executors_from_instance(root, [], mode) for c in e.callbacks]
    if not callbacks:
        return []
    links = callback_links(root, callbacks, mode)
    units_of = unit_finder(root, unit_objs)
    transmission = Transmission(reader, mode)
    bus = _bus(root, reader, mode)
    sent: dict[int, Fraction] = {}

    def crossing(conn: Any) -> Fraction:
        if id(conn) not in sent:
            own = transmission.us(conn, "Communication_Properties::Latency")
            if bus is not None:
                size = (data_size_kbyte(reader, conn.source, mode) or Fraction(0)) * 1000
                own += transmission.us(bus, "Communication_Properties::Latency")
                own += transmission.transfer(bus, size)[1]
            sent[id(conn)] = own
        return sent[id(conn)]

    def cost(name: str, members: Sequence[Any], joined: Sequence[Any]) -> ChainCost:
        fixed = sum(
            ((c.period if c.kind == "timer" and c.period is not None else 0) + c.wcet for c in members),
            Fraction(0),
        )
        pairs: list[tuple[int, int, Fraction]] = []
        for link in joined:
            if link.connection is None:
                continue
            u, v = units_of(link.source.thread), units_of(link.destination.thread)
            if len(u) == 1 and len(v) == 1 and u != v:
                us = crossing(link.connection)
                if us > 0:
                    pairs.append((u[0], v[0], us))
        return ChainCost(name, fixed, tuple(pairs))

    chains = []
    for obj in component_instances(root):
        for flow in obj.endToEndFlows:
            members = flow_callbacks(flow, callbacks)
            if len(members) >= 2:
                joined = [
                    link
                    for a, b in zip(members, members[1:], strict=False)
                    for link in links
                    if link.source is a and link.destination is b
                ]
                chains.append(cost(flow.flow or flow.name, members, joined))
    for path in cause_effect_chains(links, _CHAIN_LIMIT):
        members = [path[0].source] + [link.destination for link in path]
        name = " -> ".join(c.path.partition(".")[2] or c.path for c in (members[0], members[-1]))
        chains.append(cost(name, members, path))
    return chains
