"""The convention's rules on hardware and deployments.

A hardware package gives a hardware model (``System``): the processors of its system
implementation are hosts (their bus accesses the hosts' interfaces), its buses networks, its
bus access connections links. A deployment package gives a deployment: its processes are
nodes, on the host their ``Actual_Processor_Binding`` names (in a hardware model the
deployment holds before the process), and the thread group subcomponents of a node's process
implementation its component instances.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.properties import Reference, own_property, property_name_matches, python_value
from rosaadl.transforms import rosmod_to_aadl as fwd
from rosaadl.transforms.engine import Context

from .convention import CONVENTION, DEPLOYMENT, HARDWARE, holder_role, placed, state, unit_kind
from .reading import (
    add,
    enum_name,
    integer,
    new,
    qualify,
    scheduling_scheme,
    set_given,
    settings,
    string,
    text,
)

__all__ = ["HardwareParts"]

_t = CONVENTION


# --------------------------------------------------------------------------- hardware


@dataclass
class HardwareParts:
    """The members of a hardware model's system implementation, by lower-case name."""

    hosts: dict[str, EObject] = field(default_factory=dict)  # processor subcomponents
    networks: dict[str, EObject] = field(default_factory=dict)  # bus subcomponents
    interfaces: dict[tuple[str, str], tuple[EObject, EObject]] = field(default_factory=dict)

    def link_ends(self, conn: EObject) -> tuple[EObject, EObject, EObject] | None:
        """(network, processor, its bus access) a connection joins, else None."""
        network = self.networks.get((conn.source or "").lower())
        host_name, _, interface_name = (conn.destination or "").partition(".")
        host = self.hosts.get(host_name.lower())
        interface = self.interfaces.get((host_name.lower(), interface_name.lower()))
        if network is None or host is None or interface is None:
            return None
        return network, host, interface[1]


def _parts(ctx: Context, impl: EObject) -> HardwareParts:
    st = state(ctx)
    key = ("hardware", id(impl))
    found = st.cache.get(key)
    if found is None:
        found = st.cache[key] = HardwareParts()
        for sub in impl.subcomponents:
            category = enum_name(sub.category)
            if category == "processor":
                found.hosts[sub.name.lower()] = sub
                ptype = st.index.find(sub.classifier, impl)
                for feature in _bus_accesses(ptype):
                    found.interfaces[(sub.name.lower(), feature.name.lower())] = (sub, feature)
            elif category == "bus":
                found.networks[sub.name.lower()] = sub
    return found


def _bus_accesses(ptype: EObject | None) -> list[EObject]:
    if ptype is None or not _model.is_a(ptype, "ComponentType"):
        return []
    return [f for f in ptype.features if enum_name(f.category) == "busAccess"]


def _platform_model(ctx: Context, unit: EObject, kind: str, **values: str | None) -> EObject:
    """The hardware model (``System``) or ``Deployment`` of a package of that ``Unit_Kind``."""
    st = state(ctx)
    made = new(
        "System" if kind == "Hardware" else kind,
        name=st.name(unit, suffix=fwd.UNIT_SUFFIXES[kind]),
        sourceFile=text(unit, fwd.SOURCE_FILE),
        **values,
    )
    made.properties.extend(settings(unit))
    if st.implementation[id(unit)] is None:
        st.warn(f"{kind.lower()} package {unit.name} has no system implementation", unit)
    return made


@_t.rule("AadlPackage", name="hardware", where=(unit_kind, "hardware"))
def _hardware(ctx: Context, unit: EObject) -> EObject:
    return _platform_model(ctx, unit, "Hardware")


@_hardware.bind
def _hardware_bind(ctx: Context, unit: EObject, system: EObject) -> None:
    impl = state(ctx).implementation[id(unit)]
    if impl is None:
        return
    subs = list(impl.subcomponents)
    add(system, "hosts", ctx.resolve_all(subs, "host"))
    add(system, "networks", ctx.resolve_all(subs, "network"))
    add(system, "links", ctx.resolve_all(impl.connections, "link"))


@_t.rule("Subcomponent", name="host", where=(placed, (HARDWARE, "processor")))
def _host(ctx: Context, sub: EObject) -> EObject:
    st = state(ctx)
    host = new("Host", name=st.name(sub))
    ptype = st.index.find(sub.classifier, sub.eContainer())
    if ptype is not None:
        set_given(
            host,
            ipAddress=text(ptype, fwd.IP_ADDRESS),
            username=text(ptype, fwd.USERNAME),
            sshKey=text(ptype, fwd.SSH_KEY),
            deploymentPath=text(ptype, fwd.DEPLOYMENT_PATH),
            installPath=text(ptype, fwd.INSTALL_PATH),
            architecture=text(ptype, fwd.ARCHITECTURE),
            os=text(ptype, fwd.OS),
        )
        host.properties.extend(settings(ptype))
        for feature in _bus_accesses(ptype):
            host.interfaces.append(ctx.lazy(_interface, sub, feature))
    return host


@_t.rule("Subcomponent", name="interface", lazy=True)
def _interface(ctx: Context, sub: EObject, feature: EObject) -> EObject:
    """The interface of one host (a processor subcomponent) on one of its type's bus accesses."""
    return new("Interface", name=state(ctx).name(feature))


@_t.rule("Subcomponent", name="network", where=(placed, (HARDWARE, "bus")))
def _network(ctx: Context, sub: EObject) -> EObject:
    st = state(ctx)
    ptype = st.index.find(sub.classifier, sub.eContainer())
    return new(
        "Network",
        name=st.name(sub),
        subnet=text(ptype, fwd.SUBNET) if ptype is not None else None,
        netmask=text(ptype, fwd.NETMASK) if ptype is not None else None,
    )


def _is_link(ctx: Context, conn: EObject) -> bool:
    return (
        enum_name(conn.kind) == "accessConnection"
        and _parts(ctx, conn.eContainer()).link_ends(conn) is not None
    )


@_t.rule("Connection", name="link", where=(holder_role, HARDWARE), when=_is_link)
def _link(ctx: Context, conn: EObject) -> EObject:
    return new("Link", name=state(ctx).name(conn), ip=text(conn, fwd.IP_ADDRESS))


@_link.bind
def _link_bind(ctx: Context, conn: EObject, link: EObject) -> None:
    network, host, interface = _parts(ctx, conn.eContainer()).link_ends(conn)
    link.host = ctx.resolve(host, "host")[0]
    link.network = ctx.resolve(network, "network")[0]
    link.interface = ctx.lazy(_interface, host, interface)


@_t.rule(
    "Connection",
    name="not_a_link",
    where=(holder_role, HARDWARE),
    when=lambda ctx, c: not _is_link(ctx, c),
)
def _not_a_link(ctx: Context, conn: EObject) -> None:
    if enum_name(conn.kind) != "accessConnection":
        state(ctx).warn(f"connection {conn.name} of {conn.eContainer().name} is not a link; skipped", conn)
    else:
        state(ctx).warn(f"connection {conn.name} does not join a bus to a processor's bus access", conn)


# --------------------------------------------------------------------------- deployments


def _hardware_model(ctx: Context, sub: EObject) -> EObject | None:
    """The hardware package whose system implementation a deployment's subcomponent is."""
    st = state(ctx)
    return st.hardware.get(qualify(sub.classifier or "", st.unit_of(sub.eContainer())).lower())


@dataclass
class _Deployed:
    """What a deployment's processes are bound with, read once per system implementation."""

    bindings: dict[str, EObject]  # process name (lower case) → its Actual_Processor_Binding
    hardware: dict[int, dict[str, EObject]]  # process → the hardware models held before it, by name


def _deployed(ctx: Context, impl: EObject) -> _Deployed:
    st = state(ctx)
    key = ("deployment", id(impl))
    found = st.cache.get(key)
    if found is None:
        bindings: dict[str, EObject] = {}
        for assoc in impl.ownedPropertyAssociations:
            if property_name_matches(assoc.property or "", fwd.PROCESSOR_BINDING):
                for target in assoc.appliesTo:
                    bindings[" ".join(target.split()).lower()] = assoc
        hardware: dict[int, dict[str, EObject]] = {}
        held: dict[str, EObject] = {}
        for sub in impl.subcomponents:
            category = enum_name(sub.category)
            if category == "system":
                unit = _hardware_model(ctx, sub)
                if unit is not None:
                    held = {**held, sub.name.lower(): unit}
            elif category == "process":
                hardware[id(sub)] = held
        found = st.cache[key] = _Deployed(bindings, hardware)
    return found


@_t.rule("AadlPackage", name="deployment", where=(unit_kind, "deployment"))
def _deployment(ctx: Context, unit: EObject) -> EObject:
    return _platform_model(ctx, unit, "Deployment", systemName=text(unit, fwd.SYSTEM_NAME))


@_deployment.bind
def _deployment_bind(ctx: Context, unit: EObject, deployment: EObject) -> None:
    impl = state(ctx).implementation[id(unit)]
    if impl is None:
        return
    nodes = []
    for sub in impl.subcomponents:
        if deployment.system is None and enum_name(sub.category) == "system":
            hardware = _hardware_model(ctx, sub)
            system = ctx.resolve(hardware, "hardware")[0] if hardware is not None else None
            if system is not None and system.name == deployment.systemName:
                deployment.system = system
        nodes.extend(ctx.resolve(sub, "node"))
    add(deployment, "nodes", nodes)


@_t.rule(
    "Subcomponent",
    name="unknown_hardware",
    where=(placed, (DEPLOYMENT, "system")),
    when=lambda ctx, s: _hardware_model(ctx, s) is None,
)
def _unknown_hardware(ctx: Context, sub: EObject) -> None:
    state(ctx).warn(f"system {sub.name} is not a hardware model of the project", sub)


def _references(assoc: EObject) -> list[str]:
    values = [python_value(v.value) for v in assoc.ownedValues]
    out: list[str] = []
    for value in values:
        items = value if isinstance(value, list) else [value]
        out.extend(" ".join(item.path.split()) for item in items if isinstance(item, Reference))
    return out


@dataclass
class _NodePlan:
    implementation: EObject | None  # the process implementation: its thread groups are the instances
    host: EObject | None = None  # the processor subcomponent the process is bound to
    hardware: EObject | None = None  # the hardware package that holds it
    instances: list[EObject] = field(default_factory=list)  # its thread group subcomponents


@_t.rule(
    "Subcomponent",
    name="node",
    where=(placed, (DEPLOYMENT, "process")),
)
def _node(ctx: Context, sub: EObject) -> EObject:
    st = state(ctx)
    impl = sub.eContainer()
    ptype_impl = st.index.find(sub.classifier, impl)
    ptype = None
    if ptype_impl is not None and _model.is_a(ptype_impl, "ComponentImplementation"):
        ptype = st.index.find(ptype_impl.type, ptype_impl)
    elif ptype_impl is not None:
        ptype, ptype_impl = ptype_impl, None
    node = new("Node", name=st.name(sub))
    if ptype is not None:
        set_given(
            node,
            priority=integer(ptype, fwd.PRIORITY),
            arguments=text(ptype, fwd.ARGUMENTS),
            hostRef=text(ptype, fwd.HOST_REF),
        )
        node.properties.extend(settings(ptype))
    plan = st.cache[("node", id(sub))] = _NodePlan(ptype_impl)
    deployed = _deployed(ctx, impl)
    assoc = deployed.bindings.get(sub.name.lower())
    if assoc is not None:
        targets = _references(assoc)
        if targets:
            hw_name, _, host_name = targets[0].partition(".")
            plan.hardware = deployed.hardware[id(sub)].get(hw_name.lower())
            if plan.hardware is not None:
                hw_impl = st.implementation[id(plan.hardware)]
                plan.host = _parts(ctx, hw_impl).hosts.get(host_name.lower())
        if plan.host is None:
            st.warn(f"process {sub.name} is bound to {targets}, which is not a host of the project", assoc)
    if ptype_impl is None:
        st.warn(f"process {sub.name} has no implementation: no component instances", sub)
        return node
    for inner in ptype_impl.subcomponents:
        if enum_name(inner.category) != "threadGroup":
            st.warn(f"{enum_name(inner.category)} {inner.name} of a node is not a component instance", inner)
            continue
        plan.instances.append(inner)
        ctx.lazy(_component_instance, sub, inner)
    return node


@_node.bind
def _node_bind(ctx: Context, sub: EObject, node: EObject) -> None:
    plan: _NodePlan = state(ctx).cache[("node", id(sub))]
    if plan.host is not None:
        node.host = ctx.resolve(plan.host, "host")[0]
        if node.hostRef is None:
            node.hostRef = f"{ctx.resolve(plan.hardware, 'hardware')[0].name}/{node.host.name}"
    add(node, "componentInstances", [ctx.lazy(_component_instance, sub, inner) for inner in plan.instances])


@_t.rule("Subcomponent", name="component_instance", lazy=True)
def _component_instance(ctx: Context, process: EObject, sub: EObject) -> EObject:
    """One component instance of a node: a thread group subcomponent of the process implementation
    of a process subcomponent (two nodes of one implementation have instances of their own)."""
    st = state(ctx)
    inst = new("ComponentInstance", name=st.name(sub), schedulingScheme=scheduling_scheme(sub))
    if _component_type(ctx, sub) is None:
        st.warn(f"thread group {sub.name}: {sub.classifier} is not a component of the project", sub)
    inst.logging.extend(settings(sub, fwd.LOGGING))
    add(inst, "portInstances", _port_instances(sub))
    inst.properties.extend(settings(sub))
    return inst


@_component_instance.bind
def _component_instance_bind(ctx: Context, process: EObject, sub: EObject, inst: EObject) -> None:
    ctype = _component_type(ctx, sub)
    if ctype is None:
        return
    inst.component, reference = _component(ctx, ctype)
    inst.componentRef = text(sub, fwd.COMPONENT_REF) or reference


def _component(ctx: Context, ctype: EObject) -> tuple[EObject, str]:
    """The component made from a thread group type, and its reference ``package/component``."""
    st = state(ctx)
    key = ("component", id(ctype))
    found = st.cache.get(key)
    if found is None:
        comp = ctx.resolve(ctype, "component")[0]
        package = ctx.resolve(st.unit_of(ctype), "package")[0]
        found = st.cache[key] = (comp, f"{package.name}/{comp.name}")
    return found


def _component_type(ctx: Context, sub: EObject) -> EObject | None:
    """The thread group type (a component of the project) a thread group subcomponent is of."""
    st = state(ctx)
    key = ("component type", id(sub))
    if key not in st.cache:
        qualified = qualify(sub.classifier or "", st.unit_of(sub.eContainer())).lower()
        st.cache[key] = st.components.get(qualified)
    return st.cache[key]


def _port_instances(sub: EObject) -> list[EObject]:
    """``ROSMOD_Properties::Port_Instances`` as ROSMOD ``PortInstance`` objects."""
    value = own_property(sub, fwd.PORT_INSTANCES)
    return [
        new(
            "PortInstance",
            name=string(item.get("Name")),
            port=string(item.get("Port_Ref")),
            group=string(item.get("Group_Name")),
        )
        for item in (value if isinstance(value, list) else [])
        if isinstance(item, dict)
    ]
