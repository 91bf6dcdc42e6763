"""The topics and services of a ROSMOD deployment as AADL connections.

A topic is a publisher and a subscriber of the same message type (and, for WebGME ports, of the
same advertised ``<port>.Topic``); a client is connected to the first server of its service
type. Ends in one node are connected inside its process; ends in two nodes are exported as
features of both processes and joined by a port (or subprogram access) connection of the
deployment's system, bound with ``Actual_Connection_Binding`` to the network both hosts are
linked to, else to the ROS virtual bus.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.transforms.engine import Context
from rosaadl.transforms.rosmod_to_aadl.rules import State
from rosaadl.transforms.rosmod_to_aadl.vocabulary import CONNECTION_BINDING, MESSAGE_TYPE, TOPIC_NAME

__all__ = ["connect_topics"]


def _topic_key(port: EObject, settings: dict[str, str]) -> tuple[str | None, str | None]:
    return port.type, settings.get(f"{port.name}.Topic")


def connect_topics(ctx: Context, st: State, deployment: EObject, impl: EObject) -> None:
    """Port connections for the topics (and access connections for the services) of a deployment."""
    f = st.factory
    plan = st.plan
    ends: dict[str, list[tuple[EObject, EObject, EObject]]] = {
        "Publisher": [],
        "Subscriber": [],
        "Client": [],
        "Server": [],
    }
    settings: dict[int, dict[str, str]] = {}
    for node in deployment.nodes:
        for inst in node.componentInstances:
            comp = inst.component
            if id(comp) not in settings:
                settings[id(comp)] = {p.key: p.value for p in comp.properties if p.key}
            for port in comp.ports:
                ends[port.eClass.name].append((node, inst, port))
    subscribers: dict[tuple[str | None, str | None], list[tuple[EObject, EObject, EObject]]] = {}
    for end in ends["Subscriber"]:
        key = _topic_key(end[2], settings[id(end[1].component)])
        if key[0]:
            subscribers.setdefault(key, []).append(end)
    servers: dict[tuple[str | None, str | None], list[tuple[EObject, EObject, EObject]]] = {}
    for end in ends["Server"]:
        key = _topic_key(end[2], settings[id(end[1].component)])
        if key[0]:
            servers.setdefault(key, []).append(end)
    members = plan.scope(deployment, "impl")
    bus = plan.extra[(id(deployment), "bus")]
    exported: dict[tuple[int, int, int], str] = {}
    connections: list[EObject] = []
    bindings: list[tuple[str, str]] = []

    def export(node: EObject, inst: EObject, port: EObject, outward: bool, access: str | None) -> str:
        key = (id(node), id(inst), id(port))
        found = exported.get(key)
        if found is not None:
            return found
        process = ctx.resolve(node, "node")
        process_type, process_impl = process[0], process[1]
        scope = plan.scope(node)
        inner = plan.names[id(inst)]
        name = scope.take(f"{inner}_{port.name}")
        source = ctx.resolve(port)[0]
        if access is None:
            feature = f.feature(
                name, "event data port", direction="out" if outward else "in", classifier=source.classifier
            )
            ends_ = (f"{inner}.{source.name}", name) if outward else (name, f"{inner}.{source.name}")
            link = f.conn(scope.take(f"{name}_link"), "port", *ends_)
        else:
            feature = f.feature(name, "subprogram access", access=access, classifier=source.classifier)
            inside = f"{inner}.{source.name}"
            ends_ = (inside, name) if access == "provides" else (name, inside)
            link = f.conn(scope.take(f"{name}_link"), "access", *ends_, "subprogram")
        if port.type and source.classifier is None:
            f.pa(feature, MESSAGE_TYPE, f.string(port.type))
        f.add(process_type, "features", feature)
        f.add(process_impl, "connections", link)
        exported[key] = name
        return name

    def connect(kind: str, source: tuple, destination: tuple, label: str | None) -> None:
        src_node, src_inst, src_port = source
        dst_node, dst_inst, dst_port = destination
        service = kind == "access"
        type_part = (src_port.type or "").rpartition("/")[2]
        if src_node is dst_node:
            scope = plan.scope(src_node)
            name = scope.take(f"{'service' if service else 'topic'}_{type_part}")
            inner_src = f"{plan.names[id(src_inst)]}.{ctx.resolve(src_port)[0].name}"
            inner_dst = f"{plan.names[id(dst_inst)]}.{ctx.resolve(dst_port)[0].name}"
            link = f.conn(name, kind, inner_src, inner_dst, "subprogram" if service else None)
            if label:
                f.pa(link, TOPIC_NAME, f.string(label))
            f.add(ctx.resolve(src_node, "node")[1], "connections", link)
            bindings.append((f"{plan.names[id(src_node)]}.{name}", bus))
            return
        if service:
            out_name = export(src_node, src_inst, src_port, True, "provides")
            in_name = export(dst_node, dst_inst, dst_port, False, "requires")
        else:
            out_name = export(src_node, src_inst, src_port, True, None)
            in_name = export(dst_node, dst_inst, dst_port, False, None)
        name = members.take(f"{'service' if service else 'topic'}_{type_part}")
        link = f.conn(
            name,
            kind,
            f"{plan.names[id(src_node)]}.{out_name}",
            f"{plan.names[id(dst_node)]}.{in_name}",
            "subprogram" if service else None,
        )
        if label:
            f.pa(link, TOPIC_NAME, f.string(label))
        carrier = _carrier(st, deployment, src_node.host, dst_node.host) or bus
        # on the connection itself: a contained association per topic would make every property
        # look-up of the instance scan them all
        f.pa(link, CONNECTION_BINDING, f.listing([f.reference(carrier)]))
        connections.append(link)

    for publisher in ends["Publisher"]:
        key = _topic_key(publisher[2], settings[id(publisher[1].component)])
        for subscriber in subscribers.get(key, []) if key[0] else []:
            connect("port", publisher, subscriber, _topic_label(key))
    for client in ends["Client"]:
        key = _topic_key(client[2], settings[id(client[1].component)])
        candidates = servers.get(key, []) if key[0] else []
        if len(candidates) > 1:
            ctx.warn(
                f"client {client[2].name!r} of {client[1].name!r}: {len(candidates)} servers of "
                f"{client[2].type!r} in deployment {deployment.name!r}; connected to the first",
                client[1],
            )
        if candidates:
            connect("access", candidates[0], client, _topic_label(key))
    f.add(impl, "connections", *connections)
    for applies_to, carrier in bindings:
        f.pa(impl, CONNECTION_BINDING, f.listing([f.reference(carrier)]), applies_to=applies_to)


def _topic_label(key: tuple[str | None, str | None]) -> str | None:
    return key[1].rpartition("/")[2] if key[1] else None


def _carrier(st: State, deployment: EObject, a: EObject | None, b: EObject | None) -> str | None:
    """``hw.network`` for a network both hosts are linked to (same hardware model), else None."""
    if a is None or b is None or a is b:
        return None
    system = st.plan.systems.get(id(a))
    if system is None or system is not st.plan.systems.get(id(b)):
        return None
    nets_a = [link.network for link in system.links if link.host is a and link.network is not None]
    nets_b = {id(link.network) for link in system.links if link.host is b and link.network is not None}
    for network in nets_a:
        if id(network) in nets_b:
            hw = st.plan.extra[(id(deployment), f"system:{id(system)}")]
            return f"{hw}.{st.plan.names[id(network)]}"
    return None
