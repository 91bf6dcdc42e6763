"""Binding one ROSMOD deployment: the AADL deployment package of a robot of the library running
the library's nodes, as the bindings file says.

The package is shaped like the library's ``sys_tracking``: the robot as subcomponent ``robot``;
one process per ROSMOD component instance, in the PDM of its library node for the type of its
core, bound to that core with ``Actual_Processor_Binding``; one port connection per topic,
bound with ``Actual_Connection_Binding`` to the ROS virtual bus (``ROSbus``) or to a bus of the
robot; the connections between nodes and the robot's ports the file lists; the ROSMOD rates on
the library threads (:mod:`.rates`), so that a thread's CPU load is its PDM's execution time over
the ROSMOD period.
"""

from __future__ import annotations

import logging
from collections.abc import Iterable
from dataclasses import dataclass, field
from decimal import Decimal
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.errors import Diagnostic
from rosaadl.transforms.bind.bindings_file import (
    ROS_BUS,
    BindingError,
    DeploymentSpec,
    NodeSpec,
    RobotLink,
    fail,
)
from rosaadl.transforms.bind.library import Catalogue, Core, Robot, classifier_named, inspect_robot, literal
from rosaadl.transforms.bind.matching import InstanceBinding, choose_pdm, instance_bindings, map_ports
from rosaadl.transforms.bind.rates import ThreadTiming, port_rates, thread_timings, topic_pairs
from rosaadl.transforms.rosmod_to_aadl.names import NameScope, aadl_identifier
from rosaadl.transforms.rosmod_to_aadl.values import seconds_to_time

__all__ = ["ROBOT", "BoundDeployment", "BoundNode", "BoundTopic", "bind_deployment"]

log = logging.getLogger(__name__)

#: The name of the robot's subcomponent in a bound deployment.
ROBOT = "robot"
_ROSBUS_SUB = "ROSbus"
_ROS_BUS_IMPL = "ros::ROSbus.impl"
_ROS_BUS_NAMES = frozenset({"ros::rosbus", "ros::rosbus.impl"})


@dataclass(frozen=True)
class BoundNode:
    """A ROSMOD component instance as a library node process bound to a core."""

    process: str  #: subcomponent name in the deployment
    rosmod_node: str
    component_instance: str
    component: str
    library: str  #: ``nd_usb_cam::usb_cam_nd``
    implementation: str  #: the PDM: ``nd_usb_cam::usb_cam_nd.xu4_a7``
    core: str  #: core path inside the robot
    core_type: str  #: ``Exynos_5422::ARM_A7``
    timings: tuple[ThreadTiming, ...]
    spec: NodeSpec


@dataclass(frozen=True)
class BoundTopic:
    """A topic as a port connection between two node processes."""

    connection: str
    message_type: str
    source: str  #: ``process.port``
    destination: str
    bus: str  #: ``ROSbus`` or ``robot.<bus>``


@dataclass
class BoundDeployment:
    """The AADL deployment package of one bound ROSMOD deployment."""

    name: str  #: the ROSMOD deployment
    package: EObject  #: the ``AadlPackage``
    root: str  #: ``Pkg::System.impl``, to instantiate
    robot: str
    nodes: tuple[BoundNode, ...]
    topics: tuple[BoundTopic, ...]
    cores: tuple[Core, ...]  #: every core of the robot
    spec: DeploymentSpec
    warnings: list[Diagnostic] = field(default_factory=list)

    def node(self, process: str) -> BoundNode:
        """The bound node of a process; a :class:`BindingError` when there is none."""
        for node in self.nodes:
            if node.process == process:
                return node
        known = ", ".join(n.process for n in self.nodes) or "none"
        raise BindingError(f"deployment {self.name!r} has no process {process!r} (its processes: {known})")


def _deployment(project: EObject, name: str, spec: DeploymentSpec) -> EObject:
    """The ROSMOD deployment the entry binds."""
    for deployment in project.deployments:
        if deployment.name == name:
            return deployment
    known = ", ".join(sorted(d.name for d in project.deployments)) or "none"
    raise fail(spec.where[""], f"the project has no deployment {name!r} (it has: {known})")


def _new(class_name: str, /, **values: Any) -> EObject:
    return _model.new(class_name, **{k: v for k, v in values.items() if v is not None})


def _pa(holder: EObject, prop: str, value: EObject, applies_to: str | None = None) -> None:
    assoc = _new("PropertyAssociation", property=prop)
    assoc.ownedValues.append(_new("ModalPropertyValue", value=value))
    if applies_to:
        assoc.appliesTo.append(applies_to)
    holder.ownedPropertyAssociations.append(assoc)


def _reference(path: str) -> EObject:
    value = _new("ListValue")
    value.ownedItems.append(_new("ReferenceValue", path=path))
    return value


def _time(seconds: Decimal) -> EObject:
    number, unit, _exact = seconds_to_time(seconds)
    return _new("IntegerValue", value=number, unit=unit)


def _topic_bus(spec: DeploymentSpec, robot: Robot) -> str:
    """The carrier of the topics: ``ROSbus`` or ``robot.<bus>``."""
    if spec.topic_bus.lower() in _ROS_BUS_NAMES:
        return _ROSBUS_SUB
    found = robot.buses.get(spec.topic_bus.lower())
    if found is None:
        raise fail(
            spec.where["topic_bus"],
            f"{spec.topic_bus!r} is neither {ROS_BUS} nor a bus of {robot.name} "
            f"(its buses: {', '.join(robot.buses.values()) or 'none'})",
        )
    return f"{ROBOT}.{found}"


def _robot_link(
    link: RobotLink, by_key: dict[str, InstanceBinding], robot: Robot, names: NameScope
) -> tuple[EObject, str | None]:
    """The port connection of a robot link, and the bus it is bound to (None: not bound)."""
    item = by_key.get(link.node)
    if item is None:
        raise fail(link.where[""], f"{link.node!r} is not a node of this deployment's bindings")
    assert item.library is not None
    feature = item.library.ports.get(link.port.lower())
    if feature is None:
        raise fail(
            link.where[""],
            f"{item.library.qualified} has no port {link.port!r} "
            f"(its ports: {', '.join(f.name for f in item.library.ports.values())})",
        )
    robot_port = robot.ports.get(link.robot_port.lower())
    if robot_port is None:
        raise fail(
            link.where[""],
            f"{robot.name} has no port {link.robot_port!r} "
            f"(its ports: {', '.join(p.name for p in robot.ports.values()) or 'none'})",
        )
    node_end, robot_end = f"{item.process}.{feature.name}", f"{ROBOT}.{robot_port.name}"
    node_out = literal(feature.direction) == "out"
    if node_out == (literal(robot_port.direction) == "out"):
        raise fail(
            link.where[""],
            f"{node_end} and {robot_end} are both {literal(feature.direction)} ports; a connection "
            "needs an out port and an in port",
        )
    source, destination = (node_end, robot_end) if node_out else (robot_end, node_end)
    connection = _new(
        "Connection",
        name=names.take(f"{ROBOT}_{robot_port.name}"),
        kind="port",
        source=source,
        destination=destination,
    )
    if link.bus is None:
        return connection, None
    bus = robot.buses.get(link.bus.lower())
    if bus is None:
        raise fail(
            link.where["bus"],
            f"{robot.name} has no bus {link.bus!r} (its buses: {', '.join(robot.buses.values()) or 'none'})",
        )
    return connection, f"{ROBOT}.{bus}"


def _set_timings(impl: EObject, process: str, timings: Iterable[ThreadTiming]) -> None:
    for timing in timings:
        target = f"{process}.{timing.thread}" if timing.thread else process
        _pa(impl, "Period", _time(timing.period), target)
        if timing.deadline is not None:
            _pa(impl, "Deadline", _time(timing.deadline), target)
        if timing.priority is not None:
            _pa(impl, "Priority", _new("IntegerValue", value=int(timing.priority)), target)


def bind_deployment(
    project: EObject,
    spec: DeploymentSpec,
    library: EObject,
    *,
    package_name: str | None = None,
) -> BoundDeployment:
    """Bind the ROSMOD deployment ``spec.name`` of ``project`` (a ``rosmod.Project``) as ``spec``
    says, to the library of ``library`` (an ``AadlModel`` holding the component library:
    :func:`rosaadl.workflow.binding.bind_project` reads it). The package is named
    ``package_name`` (default ``<deployment>_bound``); its root system implementation is named
    after the project.

    Raises :class:`BindingError` at the bindings file's entry for what does not agree.
    """
    if not _model.is_a(project, "rosmod.Project"):
        raise BindingError("expected a rosmod Project to bind")
    deployment = _deployment(project, spec.name, spec)
    found = classifier_named(library, spec.robot)
    if (
        found is None
        or not _model.is_a(found, "ComponentImplementation")
        or literal(found.category) != "system"
    ):
        raise fail(
            spec.where["robot"],
            f"{spec.robot!r} is not a system implementation of the library "
            "(expected a robot such as 'pioneer_3dx::Pioneer_3DX.impl')",
        )
    robot = inspect_robot(library, _model.qualified_name(found))
    if not robot.cores:
        raise fail(spec.where["robot"], f"{robot.name} has no processor to bind nodes to")
    cores = {c.path.lower(): c for c in robot.cores}
    catalogue = Catalogue(library)
    warnings: list[Diagnostic] = []

    items = instance_bindings(deployment, spec)
    members = NameScope([ROBOT, _ROSBUS_SUB])
    for item in items:
        choose_pdm(item, catalogue, cores)
        map_ports(item)
        several = len(item.node.componentInstances) > 1
        item.process = members.take(f"{item.node.name}_{item.inst.name}" if several else item.node.name)
        for port in item.inst.component.ports:
            if _model.is_a(port, "rosmod.Client", "rosmod.Server"):
                warnings.append(
                    Diagnostic(
                        "warning",
                        f"{port.eClass.name.lower()} {port.name!r} of {item.inst.component.name!r} is not "
                        "bound: library nodes have no service ports",
                        item.spec.where[""],
                    )
                )
    topics = topic_pairs(items)
    rates = port_rates(items, topics)
    bus_path = _topic_bus(spec, robot)

    project_name = aadl_identifier(project.name or "deployment")
    pkg_name = package_name or f"{aadl_identifier(spec.name)}_bound"
    package = _new("AadlPackage", name=pkg_name)
    system_type = _new("ComponentType", name=project_name, category="system")
    impl = _new("ComponentImplementation", name=f"{project_name}.impl", type=project_name, category="system")
    impl.subcomponents.append(_new("Subcomponent", name=ROBOT, category="system", classifier=robot.name))
    if bus_path == _ROSBUS_SUB:
        impl.subcomponents.append(
            _new("Subcomponent", name=_ROSBUS_SUB, category="virtual bus", classifier=_ROS_BUS_IMPL)
        )
    for item in items:
        assert item.pdm is not None
        impl.subcomponents.append(
            _new(
                "Subcomponent",
                name=item.process,
                category="process",
                classifier=_model.qualified_name(item.pdm),
            )
        )

    names = NameScope([sub.name for sub in impl.subcomponents])
    bound_topics: list[BoundTopic] = []
    carriers: list[tuple[str, str]] = []
    for pub_item, pub, sub_item, sub in topics:
        out_port, in_port = pub_item.port_map.get(pub.name), sub_item.port_map.get(sub.name)
        if out_port is None or in_port is None:
            continue
        name = names.take(f"topic_{pub.type.rpartition('/')[2]}")
        source, destination = f"{pub_item.process}.{out_port}", f"{sub_item.process}.{in_port}"
        impl.connections.append(
            _new("Connection", name=name, kind="port", source=source, destination=destination)
        )
        carriers.append((name, bus_path))
        bound_topics.append(BoundTopic(name, pub.type, source, destination, bus_path))
    by_key = {item.key: item for item in items}
    for link in spec.robot_links:
        connection, carrier = _robot_link(link, by_key, robot, names)
        impl.connections.append(connection)
        if carrier is not None:
            carriers.append((connection.name, carrier))

    bound_nodes = []
    for item in items:
        assert item.core is not None and item.library is not None and item.pdm is not None
        _pa(impl, "Actual_Processor_Binding", _reference(f"{ROBOT}.{item.core.path}"), item.process)
        timings = thread_timings(library, item, rates)
        if not timings:
            warnings.append(
                Diagnostic(
                    "warning",
                    f"{item.inst.component.name!r} has no timer and no subscriber fed by one: the library's "
                    "periods are kept",
                    item.spec.where[""],
                )
            )
        _set_timings(impl, item.process, timings)
        bound_nodes.append(
            BoundNode(
                process=item.process,
                rosmod_node=item.node.name,
                component_instance=item.inst.name,
                component=item.inst.component.name,
                library=item.library.qualified,
                implementation=_model.qualified_name(item.pdm),
                core=item.core.path,
                core_type=item.core.kind,
                timings=tuple(timings),
                spec=item.spec,
            )
        )
    for name, carrier in carriers:
        _pa(impl, "Actual_Connection_Binding", _reference(carrier), name)

    withs = {robot.name.rpartition("::")[0]}
    withs.update(node.implementation.rpartition("::")[0] for node in bound_nodes)
    if bus_path == _ROSBUS_SUB:
        withs.add("ros")
    package.withs.extend(sorted(withs, key=str.lower))
    package.classifiers.extend([system_type, impl])
    log.info(
        "bound deployment %s to %s: %d nodes, %d topics", spec.name, robot.name, len(items), len(bound_topics)
    )
    return BoundDeployment(
        name=spec.name,
        package=package,
        root=f"{pkg_name}::{project_name}.impl",
        robot=robot.name,
        nodes=tuple(bound_nodes),
        topics=tuple(bound_topics),
        cores=tuple(robot.cores),
        spec=spec,
        warnings=warnings,
    )
