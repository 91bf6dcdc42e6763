"""The naming plan of a ROSMOD → AADL conversion: every AADL name, chosen before any rule runs.

Choosing the names first makes them deterministic and independent of the order in which rules
run: units (one per software package, hardware model and deployment, and one for the project),
classifiers and members of each namespace (a :class:`~.names.NameScope` each), the generated
callback thread types, and the interface packages for message and service types of ROS packages
outside the project.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.transforms.rosmod_to_aadl.names import NameScope
from rosaadl.transforms.rosmod_to_aadl.vocabulary import CALLBACK_THREADS, UNIT_SUFFIXES

__all__ = ["InterfacePackage", "NamingPlan", "split_ros_type"]


def split_ros_type(type_name: str | None) -> tuple[str, str] | None:
    """``("pkg", "Type")`` of a ROS type ``pkg/Type``; None for anything else."""
    if not type_name or "/" not in type_name:
        return None
    pkg, _, name = type_name.rpartition("/")
    return (pkg, name) if pkg and name else None


@dataclass
class InterfacePackage:
    """Data types and subprograms for ROS types of packages outside the project."""

    unit: str
    scope: NameScope
    messages: dict[str, str] = field(default_factory=dict)  # "pkg/T" → classifier name
    services: dict[str, str] = field(default_factory=dict)


class NamingPlan:
    """Every AADL name of the conversion, chosen before any rule runs (deterministic, and
    independent of the order in which rules run); no unit takes a name of ``reserved_units``."""

    def __init__(self, project: EObject, reserved_units: Iterable[str] = ()) -> None:
        self.names: dict[int, str] = {}  # rosmod element → its AADL name
        self.units: dict[int, str] = {}  # Project/Package/System/Deployment → unit name
        self.positions: dict[int, int] = {}
        self.extra: dict[tuple[int, str], str] = {}  # (element, role) → AADL name
        self.scopes: dict[tuple[int, str], NameScope] = {}
        self.messages: dict[str, tuple[str, str, EObject]] = {}  # "pkg/T" → (unit, classifier, Message)
        self.services: dict[str, tuple[str, str, EObject]] = {}
        self.interfaces: dict[str, InterfacePackage] = {}
        self.callback_types: dict[tuple[int, str], str] = {}  # (package, kind) → thread type name
        self.systems: dict[int, EObject] = {}  # host → its System
        units = NameScope(reserved_units)
        software = project.software
        packages = list(software.packages) if software is not None else []
        position = 1
        for package in packages:
            self.units[id(package)] = units.take(package.name)
            self.positions[id(package)] = position
            position += 1
        project_packages = {p.name for p in packages}
        for package in packages:
            self._software(package)
        # interface packages for the types of packages outside the project (sorted: stable)
        external: dict[str, list[tuple[str, str]]] = {}
        for package in packages:
            for comp in package.components:
                for port in comp.ports:
                    parts = split_ros_type(port.type)
                    if parts is None or parts[0] in project_packages:
                        continue
                    kind = (
                        "message" if model.is_a(port, "rosmod.Publisher", "rosmod.Subscriber") else "service"
                    )
                    external.setdefault(parts[0], []).append((kind, port.type))
        for ros_pkg in sorted(external):
            iface = InterfacePackage(unit=units.take(ros_pkg), scope=NameScope())
            self.interfaces[ros_pkg] = iface
            for kind, type_name in external[ros_pkg]:
                table = iface.messages if kind == "message" else iface.services
                if type_name not in table:
                    table[type_name] = iface.scope.take(type_name.rpartition("/")[2])
        for system in project.systems:
            self.units[id(system)] = units.take(f"{system.name}{UNIT_SUFFIXES['Hardware']}")
            self.positions[id(system)] = position
            position += 1
            self._system(system)
        for deployment in project.deployments:
            self.units[id(deployment)] = units.take(f"{deployment.name}{UNIT_SUFFIXES['Deployment']}")
            self.positions[id(deployment)] = position
            position += 1
            self._deployment(deployment)
        self.units[id(project)] = units.take(f"{project.name}{UNIT_SUFFIXES['Project']}")
        self.positions[id(project)] = 0

    def scope(self, obj: EObject, role: str = "") -> NameScope:
        key = (id(obj), role)
        found = self.scopes.get(key)
        if found is None:
            found = self.scopes[key] = NameScope()
        return found

    def _software(self, package: EObject) -> None:
        unit = self.units[id(package)]
        classifiers = self.scope(package)
        for msg in package.messages:
            name = self.names[id(msg)] = classifiers.take(msg.name)
            self.messages.setdefault(f"{package.name}/{msg.name}", (unit, name, msg))
        for srv in package.services:
            name = self.names[id(srv)] = classifiers.take(srv.name)
            self.extra[(id(srv), "request")] = classifiers.take(f"{name}_Request")
            self.extra[(id(srv), "response")] = classifiers.take(f"{name}_Response")
            self.services.setdefault(f"{package.name}/{srv.name}", (unit, name, srv))
        kinds: set[str] = set()
        for comp in package.components:
            self.names[id(comp)] = classifiers.take(comp.name)
            members = self.scope(comp)
            for port in comp.ports:
                self.names[id(port)] = members.take(port.name)
            for timer in comp.timers:
                self.names[id(timer)] = members.take(timer.name)
                kinds.add("timer")
            callbacks = [p for p in comp.ports if model.is_a(p, "rosmod.Subscriber", "rosmod.Server")]
            if comp.timers or callbacks:
                self.extra[(id(comp), "queue")] = members.take("callback_queue")
            for port in callbacks:
                self.extra[(id(port), "thread")] = members.take(f"{port.name}_callback")
                kinds.add(port.eClass.name.lower())
            for element in (*comp.timers, *callbacks):
                timer = model.is_a(element, "rosmod.Timer")
                thread = self.names[id(element)] if timer else None
                thread = thread or self.extra[(id(element), "thread")]
                self.extra[(id(element), "queue_conn")] = members.take(f"{thread}_queue")
                if not timer:
                    self.extra[(id(element), "callback_conn")] = members.take(f"{thread}_call")
        for kind in ("timer", "subscriber", "server"):
            if kind in kinds:
                self.callback_types[(id(package), kind)] = classifiers.take(CALLBACK_THREADS[kind][0])

    def _system(self, system: EObject) -> None:
        classifiers = self.scope(system)
        members = self.scope(system, "impl")
        self.extra[(id(system), "type")] = classifiers.take(system.name)
        for host in system.hosts:
            self.systems[id(host)] = system
            self.names[id(host)] = members.take(host.name)
            self.extra[(id(host), "type")] = classifiers.take(host.name)
            features = self.scope(host)
            for interface in host.interfaces:
                self.names[id(interface)] = features.take(interface.name)
        for network in system.networks:
            self.names[id(network)] = members.take(network.name)
            self.extra[(id(network), "type")] = classifiers.take(network.name)
        for link in system.links:
            self.names[id(link)] = members.take(link.name)

    def _deployment(self, deployment: EObject) -> None:
        classifiers = self.scope(deployment)
        members = self.scope(deployment, "impl")
        self.extra[(id(deployment), "type")] = classifiers.take(deployment.name)
        for node in deployment.nodes:
            self.names[id(node)] = members.take(node.name)
            self.extra[(id(node), "type")] = classifiers.take(node.name)
            process = self.scope(node)
            for inst in node.componentInstances:
                self.names[id(inst)] = process.take(inst.name)
        self.extra[(id(deployment), "bus")] = members.take("ROSbus")
        systems: list[EObject] = []
        if deployment.system is not None:
            systems.append(deployment.system)
        for node in deployment.nodes:
            system = self.systems.get(id(node.host)) if node.host is not None else None
            if system is not None and system not in systems:
                systems.append(system)
        for system in systems:
            self.extra[(id(deployment), f"system:{id(system)}")] = members.take(system.name)
