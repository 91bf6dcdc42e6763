"""The ROSMOD → AADL rules of the deployments: deployments, nodes and component instances.

One package per deployment (``Unit_Kind => Deployment``) with one ``process`` per node
(extending ``ros::node``, ``Priority``, the component instances as thread group subcomponents)
and a ``system`` implementation, the root to instantiate, holding the hardware models its nodes
run on, a ``ros::ROSbus`` virtual bus and the processes, bound with
``Actual_Processor_Binding``; its topics are connected by :mod:`.topics`.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.errors import TransformationError
from rosaadl.transforms.engine import Context, source_location
from rosaadl.transforms.rosmod_to_aadl.rules import TRANSFORMATION, name_if_changed, state, unit_header
from rosaadl.transforms.rosmod_to_aadl.topics import connect_topics
from rosaadl.transforms.rosmod_to_aadl.values import given
from rosaadl.transforms.rosmod_to_aadl.vocabulary import (
    ARGUMENTS,
    COMPONENT_REF,
    HOST_REF,
    LOGGING,
    NODE_TYPE,
    PORT_INSTANCES,
    PRIORITY,
    PROCESSOR_BINDING,
    ROS_BUS,
    SCHEDULING_SCHEME,
    SOURCE_FILE,
    SYSTEM_NAME,
)

__all__: list[str] = []  # its rules are declared on TRANSFORMATION


@TRANSFORMATION.rule("rosmod.Deployment", name="deployment")
def _deployment(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = state(ctx)
    f = st.factory
    pkg = unit_header(st, src, "Deployment")
    f.text(pkg, SOURCE_FILE, src.sourceFile)
    f.text(pkg, SYSTEM_NAME, src.systemName)
    f.settings(pkg, src.properties)
    type_name = st.plan.extra[(id(src), "type")]
    system = f.ctype("system", type_name)
    impl = f.cimpl("system", type_name)
    subs: list[EObject] = []
    hardware = [] if src.system is None else [src.system]
    for node in src.nodes:
        system_of = st.plan.systems.get(id(node.host)) if node.host is not None else None
        if system_of is not None and system_of not in hardware:
            hardware.append(system_of)
    for hw in hardware:
        hw_unit = st.plan.units[id(hw)]
        classifier = f"{hw_unit}::{st.plan.extra[(id(hw), 'type')]}.impl"
        subs.append(f.sub(st.plan.extra[(id(src), f"system:{id(hw)}")], "system", classifier))
    subs.append(f.sub(st.plan.extra[(id(src), "bus")], "virtual bus", ROS_BUS))
    return (pkg, system, impl, *subs)


@TRANSFORMATION.rule("rosmod.Node", name="node")
def _node(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = state(ctx)
    f = st.factory
    deployment = src.eContainer()
    unit = st.plan.units[id(deployment)]
    type_name = st.plan.extra[(id(src), "type")]
    process = f.ctype("process", type_name, extended=NODE_TYPE)
    if given(src, "priority") is not None:
        f.pa(process, PRIORITY, f.integer(src.priority))
    f.text(process, ARGUMENTS, src.arguments)
    f.text(process, HOST_REF, src.hostRef)
    f.settings(process, src.properties)
    impl = f.cimpl("process", type_name, extended=f"{NODE_TYPE}.impl")
    name = st.plan.names[id(src)]
    sub = f.sub(name, "process", f"{unit}::{type_name}.impl")
    name_if_changed(f, sub, name, src.name)
    if src.host is None and src.hostRef:
        raise TransformationError(
            f"node {src.name!r} is on host {src.hostRef!r}, which does not resolve to a host of the project",
            source_location(src),
        )
    if src.host is not None and id(src.host) not in st.plan.systems:
        raise TransformationError(
            f"node {src.name!r} is on host {src.host.name!r}, which is not a host of a hardware model of "
            "this project",
            source_location(src),
        )
    return process, impl, sub


@_node.bind
def _node_bind(ctx: Context, src: EObject, process: EObject, impl: EObject, sub: EObject) -> None:
    st = state(ctx)
    st.factory.add(impl, "subcomponents", *(t for i in src.componentInstances for t in ctx.resolve(i)))


@TRANSFORMATION.rule("rosmod.ComponentInstance", name="component_instance")
def _component_instance(ctx: Context, src: EObject) -> EObject:
    st = state(ctx)
    f = st.factory
    comp = src.component
    if comp is None or id(comp) not in st.plan.names:
        ref = src.componentRef or "?"
        raise TransformationError(
            f"component_instance {src.name!r}: its component {ref!r} is not a component of this project",
            source_location(src),
        )
    package = comp.eContainer()
    classifier = f"{st.plan.units[id(package)]}::{st.plan.names[id(comp)]}.impl"
    name = st.plan.names[id(src)]
    sub = f.sub(name, "thread group", classifier)
    name_if_changed(f, sub, name, src.name)
    if src.componentRef is not None and src.componentRef != f"{package.name}/{comp.name}":
        f.pa(sub, COMPONENT_REF, f.string(src.componentRef))
    if src.eIsSet("schedulingScheme"):
        f.pa(sub, SCHEDULING_SCHEME, f.named(src.schedulingScheme.name))
    f.settings(sub, src.logging, LOGGING)
    ports = [
        f.record(
            [("Name", f.string(p.name or ""))]
            + ([("Port_Ref", f.string(p.port))] if p.port is not None else [])
            + ([("Group_Name", f.string(p.group))] if p.group is not None else [])
        )
        for p in src.portInstances
    ]
    if ports:
        f.pa(sub, PORT_INSTANCES, f.listing(ports))
    f.settings(sub, src.properties)
    return sub


@_deployment.bind
def _deployment_bind(
    ctx: Context, src: EObject, pkg: EObject, system: EObject, impl: EObject, *subs: EObject
) -> None:
    st = state(ctx)
    f = st.factory
    plan = st.plan
    classifiers: list[EObject] = [system, impl]
    nodes: list[EObject] = []
    for node in src.nodes:
        process, process_impl, node_sub = ctx.resolve(node, "node")
        classifiers.extend((process, process_impl))
        nodes.append(node_sub)
        if node.host is not None:
            hw = plan.systems[id(node.host)]
            path = f"{plan.extra[(id(src), f'system:{id(hw)}')]}.{plan.names[id(node.host)]}"
            f.pa(impl, PROCESSOR_BINDING, f.listing([f.reference(path)]), applies_to=plan.names[id(node)])
    f.add(impl, "subcomponents", *subs, *nodes)
    connect_topics(ctx, st, src, impl)
    f.add(pkg, "classifiers", *classifiers)
