"""The ROSMOD → AADL rules of the hardware: systems, hosts, interfaces, networks and links.

One package per hardware model (``Unit_Kind => Hardware``) with a ``system`` implementation
holding one ``processor`` per host (IP address, user, ssh key, paths,
``Hardware_Properties::Architecture``, OS; its interfaces as ``requires bus access`` features),
one ``bus`` per network and one ``bus access`` connection per link.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import TransformationError
from rosaadl.transforms.engine import Context, source_location
from rosaadl.transforms.rosmod_to_aadl.rules import TRANSFORMATION, name_if_changed, state, unit_header
from rosaadl.transforms.rosmod_to_aadl.vocabulary import (
    ARCHITECTURE,
    DEPLOYMENT_PATH,
    INSTALL_PATH,
    IP_ADDRESS,
    NETMASK,
    OS,
    SOURCE_FILE,
    SSH_KEY,
    SUBNET,
    USERNAME,
)

__all__: list[str] = []  # its rules are declared on TRANSFORMATION


@TRANSFORMATION.rule("rosmod.System", name="hardware")
def _hardware(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = state(ctx)
    f = st.factory
    pkg = unit_header(st, src, "Hardware")
    f.text(pkg, SOURCE_FILE, src.sourceFile)
    f.settings(pkg, src.properties)
    type_name = st.plan.extra[(id(src), "type")]
    return pkg, f.ctype("system", type_name), f.cimpl("system", type_name)


@_hardware.bind
def _hardware_bind(ctx: Context, src: EObject, pkg: EObject, system: EObject, impl: EObject) -> None:
    st = state(ctx)
    f = st.factory
    classifiers: list[EObject] = [system, impl]
    subs: list[EObject] = []
    for element in (*src.hosts, *src.networks):
        for target in ctx.resolve(element):
            (subs if model.is_a(target, "Subcomponent") else classifiers).append(target)
    links = [t for link in src.links for t in ctx.resolve(link)]
    f.add(impl, "subcomponents", *subs)
    f.add(impl, "connections", *links)
    f.add(pkg, "classifiers", *classifiers)


@TRANSFORMATION.rule("rosmod.Host", name="host")
def _host(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = state(ctx)
    f = st.factory
    system = src.eContainer()
    type_name = st.plan.extra[(id(src), "type")]
    processor = f.ctype("processor", type_name)
    for prop, value in (
        (IP_ADDRESS, src.ipAddress),
        (USERNAME, src.username),
        (SSH_KEY, src.sshKey),
        (DEPLOYMENT_PATH, src.deploymentPath),
        (INSTALL_PATH, src.installPath),
        (ARCHITECTURE, src.architecture),
        (OS, src.os),
    ):
        f.text(processor, prop, value)
    f.settings(processor, src.properties)
    name = st.plan.names[id(src)]
    sub = f.sub(name, "processor", f"{st.plan.units[id(system)]}::{type_name}")
    name_if_changed(f, sub, name, src.name)
    return processor, sub


@_host.bind
def _host_bind(ctx: Context, src: EObject, processor: EObject, sub: EObject) -> None:
    st = state(ctx)
    st.factory.add(processor, "features", *(t for i in src.interfaces for t in ctx.resolve(i)))


@TRANSFORMATION.rule("rosmod.Interface", name="interface")
def _interface(ctx: Context, src: EObject) -> EObject:
    st = state(ctx)
    f = st.factory
    name = st.plan.names[id(src)]
    feature = f.feature(name, "bus access", access="requires")
    name_if_changed(f, feature, name, src.name)
    return feature


@TRANSFORMATION.rule("rosmod.Network", name="network")
def _network(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = state(ctx)
    f = st.factory
    system = src.eContainer()
    type_name = st.plan.extra[(id(src), "type")]
    bus = f.ctype("bus", type_name)
    f.text(bus, SUBNET, src.subnet)
    f.text(bus, NETMASK, src.netmask)
    name = st.plan.names[id(src)]
    sub = f.sub(name, "bus", f"{st.plan.units[id(system)]}::{type_name}")
    name_if_changed(f, sub, name, src.name)
    return bus, sub


@TRANSFORMATION.rule("rosmod.Link", name="link")
def _link(ctx: Context, src: EObject) -> EObject | None:
    st = state(ctx)
    f = st.factory
    system = src.eContainer()
    host, interface, network = src.host, src.interface, src.network
    if (
        network is None
        or interface is None
        or host is None
        or network.eContainer() is not system
        or host.eContainer() is not system
        or interface.eContainer() is not host
    ):
        raise TransformationError(
            f"link {src.name!r} does not join an interface of a host of {system.name!r} to one of its "
            "networks",
            source_location(src),
        )
    name = st.plan.names[id(src)]
    conn = f.conn(
        name,
        "access",
        st.plan.names[id(network)],
        f"{st.plan.names[id(host)]}.{st.plan.names[id(interface)]}",
        "bus",
    )
    name_if_changed(f, conn, name, src.name)
    f.text(conn, IP_ADDRESS, src.ip)
    return conn
