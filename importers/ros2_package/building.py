"""ROS 2 facts (:mod:`.facts`) → a ROSMOD project that converts to AADL with the existing
transformation (``transforms.rosmod_to_aadl``).

- A ROSMOD **component** per node as it runs: a node launched with its own name, namespace,
  remappings or parameters is a component of that name with its topics resolved and its timer
  periods taken from the launch parameters; a node class launched nowhere is a component of its
  own node name, topics resolved in the root namespace.
- Its **ports**: publishers, subscribers, servers and clients with their ``pkg/Name`` types; the
  resolved topic or service name is the component property ``<port>.Topic`` (which the
  transformation uses, with the type, to join publishers and subscribers), the QoS as
  ``<port>.Reliability``, ``<port>.Durability``, ``<port>.Depth``.
- Its **timers**: the period in seconds; a timer whose period is not known keeps no period and
  is named in a warning at the place it is created.
- The ``.msg``/``.srv`` definitions found become the messages and services of a ROSMOD package
  named after their interface package (their fields give ``Data_Size`` where fixed-size).
- Measured message sizes (a running graph) become project properties ``Data_Size:<pkg/Type>``,
  which the transformation gives as ``Data_Size`` to a type that has no fixed size.
- A **deployment** per launch file (or running graph), a ROSMOD node per launched node holding
  one instance of its component; without any, one deployment that runs every node once.

What ROS 2 does not say (the hosts, execution times) is left out: bind the model to a board
and give profiles afterwards.
"""

from __future__ import annotations

import re
from decimal import Decimal

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import Diagnostic, Location
from rosaadl.importers import ros_msg
from rosaadl.importers.ros2_package.facts import LaunchedNode, NodeFact, PortFact, SystemFacts

__all__ = ["build_project", "resolve_name", "port_names", "period_seconds"]

#: Periods from this many seconds on (about 31 years) are not taken as timer periods.
_LONGEST_PERIOD = Decimal(10**9)
_NOT_NAME = re.compile(r"[^A-Za-z0-9_]+")


def resolve_name(name: str, namespace: str = "/", node: str = "") -> str:
    """The fully qualified ROS 2 name of ``name`` in ``namespace`` for ``node`` (``~`` is the
    node's private namespace), as rcl expands topic and service names."""
    namespace = "/" + namespace.strip("/") if namespace.strip("/") else "/"
    if name.startswith("/"):
        return name
    if name.startswith("~"):
        base = namespace.rstrip("/") + "/" + node
        rest = name[1:].lstrip("/")
        return base + ("/" + rest if rest else "")
    return namespace.rstrip("/") + "/" + name


def _token(text: str) -> str:
    token = _NOT_NAME.sub("_", text).strip("_")
    return token or "port"


def port_names(ports: list[PortFact]) -> list[str]:
    """A name per port, unique in its node: the given one, else the topic as a token; a second
    port on the same name gets its kind (``chatter_subscriber``), then a number."""
    taken: set[str] = set()
    names = []
    for port in ports:
        base = port.name or _token(port.topic)
        name = base
        if name in taken:
            name = f"{base}_{port.kind.lower()}"
        number = 2
        while name in taken:
            name = f"{base}_{port.kind.lower()}_{number}"
            number += 1
        taken.add(name)
        names.append(name)
    return names


def period_seconds(value: object) -> Decimal | None:
    """A timer period in seconds from a value read in the source; None unless a positive number."""
    if isinstance(value, bool) or not isinstance(value, (int, float, Decimal)):
        return None
    if isinstance(value, int) and not 0 < value < _LONGEST_PERIOD:
        return None
    period = Decimal(str(value))
    return period if period.is_finite() and 0 < period < _LONGEST_PERIOD else None


class _Builder:
    def __init__(self, facts: SystemFacts, warnings: list[Diagnostic]) -> None:
        self.facts = facts
        self.warnings = warnings
        self.project = model.new("rosmod.Project", name=facts.name, formatVersion="ros2")
        self.project.software = model.new("rosmod.Software", name="Software")
        self.packages: dict[str, EObject] = {}
        self.components: dict[str, tuple[tuple, EObject]] = {}

    def warn(self, message: str, location: Location) -> None:
        self.warnings.append(Diagnostic("warning", message, location))

    def package(self, name: str) -> EObject:
        if name not in self.packages:
            package = model.new("rosmod.Package", name=name or self.facts.name)
            self.project.software.packages.append(package)
            self.packages[name] = package
        return self.packages[name]

    def interfaces(self) -> None:
        seen: set[tuple[str, str, str]] = set()
        for item in self.facts.interfaces:
            if (item.package, item.kind, item.name) in seen:
                continue
            seen.add((item.package, item.kind, item.name))
            kind = "rosmod.Message" if item.kind == "msg" else "rosmod.Service"
            obj = model.new(kind, name=item.name, definition=item.text)
            fill = ros_msg.fill_message if item.kind == "msg" else ros_msg.fill_service
            try:
                fill(obj, package=item.package, filename=item.location.file)
            except ros_msg.RosMessageError as exc:
                for err in exc.errors:
                    self.warn(f"{item.name}: {err.message}; its fields are left out", err.location)
                obj = model.new(kind, name=item.name)
            package = self.package(item.package)
            (package.messages if item.kind == "msg" else package.services).append(obj)

    def component(self, node: NodeFact, launched: LaunchedNode | None) -> EObject:
        """The component of ``node`` as ``launched`` runs it (resolved names, periods)."""
        name = launched.name if launched else node.node_name
        namespace = launched.namespace if launched else node.namespace
        remaps = {
            resolve_name(k, namespace, name): resolve_name(v, namespace, name)
            for k, v in (launched.remappings.items() if launched else ())
        }
        parameters = dict(node.parameters)
        if launched:
            parameters.update(launched.parameters)
        topics: list[str | None] = []
        for port in node.ports:
            topic: str | None = port.topic
            why = ""
            if port.parameter and port.parameter in parameters:
                value = parameters[port.parameter]
                topic = value if isinstance(value, str) and value else None
                why = f"parameter {port.parameter!r} is set to {value!r}, not a name"
            elif launched and port.derived in launched.parameters:
                topic = None
                why = f"it is computed from parameter {port.derived!r}, which the launch file sets"
            if topic is None:
                self.warn(
                    f"port {port.topic!r} of node {name!r}: {why}; the port is left out",
                    launched.location if launched else port.location,
                )
                topics.append(None)
                continue
            full = resolve_name(topic, namespace, name)
            topics.append(remaps.get(full, full))
        periods = []
        for timer in node.timers:
            period = timer.period
            if timer.parameter and timer.parameter in parameters:
                period = period_seconds(parameters[timer.parameter])
            elif launched and timer.derived in launched.parameters:
                period = None
                self.warn(
                    f"timer {timer.name!r} of node {name!r}: its period is computed from parameter "
                    f"{timer.derived!r}, which the launch file sets; the period is not known",
                    launched.location,
                )
            elif period is None and timer.parameter:
                self.warn(
                    f"timer {timer.name!r} of node {name!r}: parameter {timer.parameter!r} has no value; "
                    "the timer is kept without a period",
                    timer.location,
                )
            periods.append(period)
        signature = (node.key, tuple(topics), tuple(periods))
        key = _token(name)
        number = 2
        while key in self.components and self.components[key][0] != signature:
            key = f"{_token(name)}_{number}"
            number += 1
        if key in self.components:
            return self.components[key][1]
        comp = model.new("rosmod.Component", name=key)
        for port, port_name, topic in zip(node.ports, port_names(node.ports), topics, strict=True):
            if topic is None:
                continue
            comp.ports.append(model.new(f"rosmod.{port.kind}", name=port_name, type=port.type))
            comp.properties.append(model.new("rosmod.Property", key=f"{port_name}.Topic", value=topic))
            for qos in ("reliability", "durability", "depth"):
                if port.qos.get(qos):
                    comp.properties.append(
                        model.new(
                            "rosmod.Property", key=f"{port_name}.{qos.capitalize()}", value=port.qos[qos]
                        )
                    )
        timer_names = set()
        for timer, period in zip(node.timers, periods, strict=True):
            timer_name = _token(timer.name)
            while timer_name in timer_names:
                timer_name += "_"
            timer_names.add(timer_name)
            comp.timers.append(model.new("rosmod.Timer", name=timer_name, period=period))
        self.package(node.package).components.append(comp)
        self.components[key] = (signature, comp)
        return comp

    def deployments(self) -> None:
        launched_keys: set[str] = set()
        for item in self.facts.deployments:
            deployment = model.new("rosmod.Deployment", name=_token(item.name))
            for launched in item.nodes:
                node = self.facts.nodes.get(launched.node)
                if node is None:
                    continue
                launched_keys.add(node.key)
                comp = self.component(node, launched)
                ros_node = model.new("rosmod.Node", name=_token(launched.name))
                ros_node.componentInstances.append(
                    model.new("rosmod.ComponentInstance", name=comp.name, component=comp)
                )
                deployment.nodes.append(ros_node)
            if deployment.nodes:
                self.project.deployments.append(deployment)
        alone = [n for key, n in sorted(self.facts.nodes.items()) if key not in launched_keys]
        comps = [(node, self.component(node, None)) for node in alone]
        if not self.project.deployments and comps:
            deployment = model.new("rosmod.Deployment", name=_token(self.facts.name))
            for node, comp in comps:
                ros_node = model.new("rosmod.Node", name=_token(node.node_name))
                ros_node.componentInstances.append(
                    model.new("rosmod.ComponentInstance", name=comp.name, component=comp)
                )
                deployment.nodes.append(ros_node)
            self.project.deployments.append(deployment)


def build_project(facts: SystemFacts, warnings: list[Diagnostic]) -> EObject:
    """The ROSMOD project of ``facts`` (see the module docstring); findings go to ``warnings``."""
    builder = _Builder(facts, warnings)
    builder.interfaces()
    builder.deployments()
    for type_name, size in sorted(facts.message_sizes.items()):
        builder.project.properties.append(
            model.new("rosmod.Property", key=f"{ros_msg.MEASURED_SIZE}{type_name}", value=str(size))
        )
    return builder.project
