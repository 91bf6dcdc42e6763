"""Cause-effect chains of callbacks: maximum reaction time and maximum data age.

A chain runs from a callback that takes a sensor's data to one that drives an actuator, over the
model's links between callbacks:

* a topic: a port connection from a thread to a thread (through processes, across boards; from
  a port of a ROSMOD component, any callback of the component may be the writer),
  whose bus transmission is the latency analysis's (``Transmission_Time`` or bytes /
  ``SEI::BandWidthCapacity``, plus the ``Latency`` of the connection and of the buses);
* inside a node: a flow path of the process from an in port to an out port joins the callback
  the in port feeds to the callback that feeds the out port (they share the node's state; the
  second reads what the first last wrote).

Chains are the model's end-to-end flows (their ``Latency`` is the chain's deadline) and every
maximal path of callbacks over these links (from callbacks no callback feeds to callbacks that
feed none), at most ``limit`` of them.

**Maximum reaction time** (the time from an input to the first output that reflects it):
Davare et al., DAC 2007, ``sum_k (T_k + R_k)``, with the refinement of Teper, Günzel, Ueter,
von der Brüggen & Chen, RTSS 2022 (event-triggered links): a callback released by the
arrival of its input (a subscription: event-triggered link) adds only its response time
``R_k``, a timer callback (time-triggered link, it samples the latest data) ``T_k + R_k``;
plus the transmission of every topic on the way. **Maximum data age** (the time from an input
to the last output still based on it) equals the maximum reaction time: Günzel, Teper, von der
Brüggen, Chen, ECRTS 2023 (their main result: maximum reaction time and maximum data age
are equal), so the same bound bounds both. Times are exact microseconds.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rosaadl.analysis.executors import Callback
from rosaadl.analysis.instance_values import PropertyReader, SystemMode, category_of

__all__ = [
    "ChainLink",
    "CauseEffectChain",
    "callback_links",
    "cause_effect_chains",
    "chain_bound",
    "release_gaps",
    "flow_callbacks",
    "flow_deadline",
]


@dataclass(frozen=True)
class ChainLink:
    """A link between two callbacks: over a topic (``connection``) or inside a node (None)."""

    source: Callback
    destination: Callback
    connection: Any = None


@dataclass(frozen=True)
class CauseEffectChain:
    """A chain with its bounds in microseconds (None: a callback on it has no bound)."""

    name: str
    paths: tuple[str, ...]
    reaction_time: Fraction | None
    data_age: Fraction | None
    deadline: Fraction | None = None
    transmission: Fraction = Fraction(0)

    @property
    def met(self) -> bool | None:
        if self.deadline is None or self.reaction_time is None:
            return None
        return self.reaction_time <= self.deadline


def _touches(conn: Any, feature: Any) -> bool:
    return any(r.source is feature or r.destination is feature for r in conn.connectionReferences)


def _thread_of(end: Any) -> Any | None:
    current = end
    while current is not None:
        if hasattr(current, "componentInstances") and category_of(current) == "thread":
            return current
        current = current.eContainer()
    return None


def _writers(end: Any, callbacks: Sequence[Callback]) -> list[Any]:
    """The threads that may write a connection's source: its thread, or, for a port of a ROSMOD
    component (a thread group, whose publishers any of its callbacks may use), every callback
    thread of that component."""
    thread = _thread_of(end)
    if thread is not None:
        return [thread]
    owner = end.eContainer() if end is not None else None
    while owner is not None and not hasattr(owner, "componentInstances"):
        owner = owner.eContainer()
    if owner is None or category_of(owner) not in ("threadGroup", "thread group"):
        return []
    inside = []
    for callback in callbacks:
        current = callback.thread.eContainer() if callback.thread is not None else None
        while current is not None and current is not owner:
            current = current.eContainer()
        if current is owner:
            inside.append(callback.thread)
    return inside


def callback_links(root: Any, callbacks: Sequence[Callback], mode: SystemMode) -> list[ChainLink]:
    """The links between callbacks: port connections, then the flow paths inside processes."""
    from rosaadl.model import component_instances

    by_thread = {id(c.thread): c for c in callbacks}
    connections = [
        conn
        for ci in component_instances(root)
        for conn in ci.connectionInstances
        if getattr(getattr(conn, "kind", None), "name", "") in ("portConnection", "") and mode.active(conn)
    ]
    links: list[ChainLink] = []
    seen: set[tuple[int, int]] = set()

    def add(src: Callback | None, dst: Callback | None, conn: Any) -> None:
        if src is None or dst is None or src is dst or (id(src), id(dst)) in seen:
            return
        seen.add((id(src), id(dst)))
        links.append(ChainLink(src, dst, conn))

    for conn in connections:
        dst = by_thread.get(id(_thread_of(conn.destination)))
        for src in _writers(conn.source, callbacks):
            add(by_thread.get(id(src)), dst, conn)
    for process in component_instances(root):
        if category_of(process) != "process":
            continue
        for flow in process.flowSpecifications:
            if flow.source is None or flow.destination is None:
                continue
            readers = [_thread_of(c.destination) for c in connections if _touches(c, flow.source)]
            writers = [_thread_of(c.source) for c in connections if _touches(c, flow.destination)]
            for reader in readers:
                for writer in writers:
                    if reader is not None and writer is not None:
                        add(by_thread.get(id(reader)), by_thread.get(id(writer)), None)
    return links


def cause_effect_chains(links: Sequence[ChainLink], limit: int = 100) -> list[list[ChainLink]]:
    """Every maximal path over ``links`` (cycles cut), in link order, at most ``limit``."""
    successors: dict[int, list[ChainLink]] = {}
    fed: set[int] = set()
    starts: list[Callback] = []
    for link in links:
        successors.setdefault(id(link.source), []).append(link)
        fed.add(id(link.destination))
    for link in links:
        if id(link.source) not in fed and all(s is not link.source for s in starts):
            starts.append(link.source)
    chains: list[list[ChainLink]] = []

    def extend(path: list[ChainLink], visited: list[Callback]) -> None:
        if len(chains) >= limit:
            return
        nexts = [
            n for n in successors.get(id(visited[-1]), []) if all(n.destination is not v for v in visited)
        ]
        if not nexts:
            if path:
                chains.append(list(path))
            return
        for link in nexts:
            path.append(link)
            visited.append(link.destination)
            extend(path, visited)
            visited.pop()
            path.pop()

    for start in starts:
        extend([], [start])
    return chains


def release_gaps(
    links: Sequence[ChainLink], wcrt: Callable[[Callback], Fraction | None]
) -> Callable[[Callback], Fraction | None]:
    """The longest time between two releases of a callback (µs; None: unbounded or unknown): a
    timer's period; a subscription fed over topics waits at most, for each writer ``w``, the
    writer's own longest gap plus its response time ``R_w`` (the release jitter a writer passes on
    is at most its response time); a callback no topic of the model feeds keeps its ``Period``
    (the minimum inter-arrival time the model states). A cycle of subscriptions has no bound."""
    writers: dict[int, list[Callback]] = {}
    for link in links:
        if link.connection is not None:
            writers.setdefault(id(link.destination), []).append(link.source)
    known: dict[int, Fraction | None] = {}

    def gap(callback: Callback, visiting: frozenset[int] = frozenset()) -> Fraction | None:
        key = id(callback)
        if key in known:
            return known[key]
        if key in visiting:
            return None
        feeding = writers.get(key, [])
        if callback.kind == "timer" or not feeding:
            result = callback.period
        else:
            result = Fraction(0)
            for writer in feeding:
                before, response = gap(writer, visiting | {key}), wcrt(writer)
                if before is None or response is None:
                    result = None
                    break
                result = max(result, before + response)
        known[key] = result
        return result

    return gap


def chain_bound(
    name: str,
    callbacks: Sequence[Callback],
    links: Sequence[ChainLink],
    wcrt: Callable[[Callback], Fraction | None],
    transmission: Callable[[Any], Fraction],
    deadline: Fraction | None = None,
    gaps: Callable[[Callback], Fraction | None] | None = None,
) -> CauseEffectChain:
    """The reaction time and data age bound of the chain ``callbacks`` joined by ``links`` (see
    the module doc): ``sum_k S_k + R_k`` plus transmissions. The sampling term ``S_k`` is the
    period of a timer (a time-triggered link), 0 for a callback released by the chain's own
    message over a topic (an event-triggered link), and otherwise — a callback that reads what
    the previous one stored inside the node while another event releases it — the longest gap
    between its releases (:func:`release_gaps`; Davare et al.'s ``T_k`` with the trigger's
    jitter): the data waits at most until the reader's next release. An unknown gap leaves the
    chain without a bound. ``gaps``: :func:`release_gaps` over every link of the model (by
    default over the chain's own links only)."""
    total: Fraction | None = Fraction(0)
    sent = sum((transmission(link.connection) for link in links if link.connection is not None), Fraction(0))
    gap = gaps or release_gaps(links, wcrt)
    over_topic = {(id(link.source), id(link.destination)) for link in links if link.connection is not None}
    for index, callback in enumerate(callbacks):
        response = wcrt(callback)
        if response is None or total is None:
            total = None
            continue
        triggered = index > 0 and (id(callbacks[index - 1]), id(callback)) in over_topic
        if index == 0 and callback.kind != "timer":
            sampling: Fraction | None = Fraction(0)  # released by the chain's input itself
        elif triggered and callback.kind != "timer":
            sampling = Fraction(0)
        else:
            sampling = gap(callback)
        if sampling is None:
            total = None
            continue
        total += sampling + response
    if total is not None:
        total += sent
    return CauseEffectChain(name, tuple(c.path for c in callbacks), total, total, deadline, sent)


def flow_callbacks(flow: Any, callbacks: Sequence[Callback]) -> list[Callback]:
    """The callbacks an end-to-end flow instance goes through, in order."""
    by_thread = {id(c.thread): c for c in callbacks}
    result: list[Callback] = []
    for element in flow.flowElements:
        ends = (
            [element.source, element.destination] if hasattr(element, "connectionReferences") else [element]
        )
        for end in ends:
            callback = by_thread.get(id(_thread_of(end))) if end is not None else None
            if callback is not None and (not result or result[-1] is not callback):
                result.append(callback)
    return result


def flow_deadline(reader: PropertyReader, flow: Any, mode: SystemMode) -> Fraction | None:
    value = reader.seconds(flow, "Communication_Properties::Latency", mode)
    return value * 1_000_000 if value is not None else None
