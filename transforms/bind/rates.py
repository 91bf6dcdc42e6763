"""The rates of a bound deployment: its topics, the rate of each publisher and subscriber, and the
ROSMOD timing of each library thread.

A publisher publishes at the period of its component's timer (the fastest), or, without one,
from its fastest subscriber callback; a subscriber receives at the rate of its fastest
publisher. A library thread connected to a node port that carries a topic runs at that topic's
rate with the ROSMOD deadline and priority that go with it; the node's other threads and its
process run at the node's fastest rate.
"""

from __future__ import annotations

from dataclasses import dataclass
from decimal import Decimal

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.transforms.bind.library import impl_chain, literal
from rosaadl.transforms.bind.matching import InstanceBinding
from rosaadl.transforms.rosmod_to_aadl.values import given

__all__ = ["Rate", "ThreadTiming", "port_rates", "thread_timings", "topic_pairs"]


@dataclass(frozen=True)
class ThreadTiming:
    """The ROSMOD timing set on one library thread (or on the node's process: ``thread`` "")."""

    thread: str
    period: Decimal  #: seconds
    deadline: Decimal | None
    priority: int | None
    source: str  #: where the period comes from (``timer frame_timer``, ``topic tracking/Image``, ...)


@dataclass
class Rate:
    """The rate of a publisher or subscriber, with the deadline and priority that go with it."""

    period: Decimal
    deadline: Decimal | None
    priority: int | None
    source: str


def _topic_key(port: EObject) -> tuple[str | None, str | None]:
    """ROSMOD's match of a publisher and a subscriber: the message type and, where the component
    sets it (``<port>.Topic``, WebGME projects), the topic name."""
    component = port.eContainer()
    topic = None
    for prop in getattr(component, "properties", ()):
        if prop.key == f"{port.name}.Topic":
            topic = prop.value
    return port.type, topic


def topic_pairs(
    items: list[InstanceBinding],
) -> list[tuple[InstanceBinding, EObject, InstanceBinding, EObject]]:
    """(publisher instance, publisher, subscriber instance, subscriber) for every topic."""
    subscribers: dict[tuple[str | None, str | None], list[tuple[InstanceBinding, EObject]]] = {}
    for item in items:
        for port in item.inst.component.ports:
            if _model.is_a(port, "rosmod.Subscriber") and port.type:
                subscribers.setdefault(_topic_key(port), []).append((item, port))
    out = []
    for item in items:
        for port in item.inst.component.ports:
            if _model.is_a(port, "rosmod.Publisher") and port.type:
                for sub_item, sub in subscribers.get(_topic_key(port), []):
                    out.append((item, port, sub_item, sub))
    return out


def port_rates(
    items: list[InstanceBinding], topics: list[tuple[InstanceBinding, EObject, InstanceBinding, EObject]]
) -> dict[tuple[int, str], Rate]:
    """The rate of every publisher and subscriber of the deployment (key: id(instance), port)."""
    rates: dict[tuple[int, str], Rate] = {}
    feeds: dict[tuple[int, str], list[tuple[int, str]]] = {}
    for pub_item, pub, sub_item, sub in topics:
        feeds.setdefault((id(sub_item), sub.name), []).append((id(pub_item), pub.name))
    for _round in range(2 * sum(len(i.inst.component.ports) for i in items) + 2):
        changed = False
        for item in items:
            component = item.inst.component
            for port in component.ports:
                key = (id(item), port.name)
                if _model.is_a(port, "rosmod.Subscriber"):
                    found = [rates[f] for f in feeds.get(key, []) if f in rates]
                    if not found:
                        continue
                    fastest = min(found, key=lambda r: r.period)
                    rate = Rate(
                        fastest.period,
                        given(port, "deadline"),
                        given(port, "priority"),
                        f"topic {port.type} (published every {fastest.period} s)",
                    )
                elif _model.is_a(port, "rosmod.Publisher"):
                    timers = [t for t in component.timers if given(t, "period")]
                    if timers:
                        timer = min(timers, key=lambda t: t.period)
                        rate = Rate(
                            timer.period,
                            given(timer, "deadline"),
                            given(timer, "priority"),
                            f"timer {timer.name}",
                        )
                    else:
                        subs = [
                            (rates[(id(item), p.name)], p)
                            for p in component.ports
                            if _model.is_a(p, "rosmod.Subscriber") and (id(item), p.name) in rates
                        ]
                        if not subs:
                            continue
                        source, sub = min(subs, key=lambda s: s[0].period)
                        rate = Rate(
                            source.period, source.deadline, source.priority, f"callback of {sub.name}"
                        )
                else:
                    continue
                if rates.get(key) != rate:
                    rates[key] = rate
                    changed = True
        if not changed:
            break
    return rates


def _connections_of(model: EObject, impl: EObject) -> list[EObject]:
    seen: dict[str, EObject] = {}
    for classifier in impl_chain(model, impl):
        for conn in classifier.connections:
            seen.setdefault((conn.name or "").lower(), conn)
    return list(seen.values())


def _threads_of(model: EObject, impl: EObject) -> list[str]:
    seen: dict[str, str] = {}
    for classifier in reversed(impl_chain(model, impl)):  # declaration order of the PIM first
        for sub in classifier.subcomponents:
            if literal(sub.category) == "thread":
                seen.setdefault(sub.name.lower(), sub.name)
    return list(seen.values())


def thread_timings(
    model: EObject, item: InstanceBinding, rates: dict[tuple[int, str], Rate]
) -> list[ThreadTiming]:
    """The ROSMOD timing of each thread of the node's PDM, then of the process (thread "")."""
    assert item.pdm is not None
    by_port: dict[str, Rate] = {}
    for rosmod_port, library_port in item.port_map.items():
        rate = rates.get((id(item), rosmod_port))
        if library_port is not None and rate is not None:
            current = by_port.get(library_port.lower())
            if current is None or rate.period < current.period:
                by_port[library_port.lower()] = rate
    threads = _threads_of(model, item.pdm)
    linked: dict[str, list[Rate]] = {t.lower(): [] for t in threads}
    for conn in _connections_of(model, item.pdm):
        ends = [conn.source or "", conn.destination or ""]
        for own, other in (ends, ends[::-1]):
            if "." in own or "." not in other:
                continue
            rate = by_port.get(own.lower())
            thread = other.partition(".")[0].lower()
            if rate is not None and thread in linked:
                linked[thread].append(rate)
    out = []
    for thread in threads:
        found = linked[thread.lower()]
        if found:
            rate = min(found, key=lambda r: r.period)
            out.append(ThreadTiming(thread, rate.period, rate.deadline, rate.priority, rate.source))
    periods = [t.period for t in out]
    if not periods:
        timers = [t.period for t in item.inst.component.timers if given(t, "period")]
        if timers:
            periods = [min(timers)]
    if periods:
        node_rate = min(periods)
        done = {t.thread.lower() for t in out}
        for thread in threads:
            if thread.lower() not in done:
                out.append(ThreadTiming(thread, node_rate, None, None, "the node's rate"))
        out.append(ThreadTiming("", node_rate, None, given(item.node, "priority"), "the node's rate"))
    order = {t.lower(): i for i, t in enumerate(threads)}
    return sorted(out, key=lambda t: order.get(t.thread.lower(), len(order)))
