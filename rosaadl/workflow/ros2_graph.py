"""A running ROS 2 graph → a ROSMOD project (``rosaadl import ros2-graph``).

Joins the graph with ``rclpy`` (imported only here, when asked; a clear error when it is not
installed), lets discovery run ``wait`` seconds, then reads every node (name, namespace), its
publishers and subscriptions with their types and QoS (reliability, durability, and history
depth where the middleware announces it: Fast DDS gives 0, which is left out), its services and
clients. ``measure`` seconds more sample every topic (a subscription taking the serialized
bytes, reliable when every publisher of the topic is reliable, else best effort, which every
publisher matches: a best-effort reader of a reliable publisher loses whole messages when one
of their fragments is lost, so that a 921 kB image published at 20 Hz was seen at 6.5 Hz, and
irregularly), volatile (which every durability matches): a topic with one publisher whose
messages come at a steady rate (:func:`steady_period`: most inter-arrival times within
:data:`STEADY` of their median, whatever a stall of the machine did to the others) gives that
publisher a timer of the measured period; the largest serialized message
seen (less the 4-byte CDR encapsulation header) becomes the ``Data_Size`` of its type where the
type has no fixed size (the project property ``Data_Size:<pkg/Type>``, which
``transforms.rosmod_to_aadl`` reads).

The graph's own infrastructure (``/rosout``, ``/parameter_events``, the parameter services
every node offers, hidden nodes such as the ``ros2`` daemon's, whose names start with ``_``) is
left out. So is what a ROSMOD model cannot hold, each with a warning on its node: a managed
(lifecycle) node's lifecycle services and ``transition_event`` topic (the node itself is
kept), an action (its server's or client's hidden ``<action>/_action/…`` services and topics,
named once as the action and its ``pkg/action/Type``), and any other hidden topic or service
(a name with a part that starts with ``_``). What the graph cannot say (the host of each node, the execution
times) is a warning: bind the model to a board and give profiles afterwards. A node that leaves
during discovery, a topic announced with two types, a topic too quiet to measure: located
warnings (the node's or topic's name as the path). No node at all: an error.

The facts become a ROSMOD project with ``importers.ros2_package.building``, as the static
reader's do, so both imports give the same model for the same system.
"""

from __future__ import annotations

import importlib
import os
import statistics
import time
from decimal import Decimal
from typing import Any

from pyecore.ecore import EObject

from rosaadl.errors import Diagnostic, ImportFormatError, Location, RosaadlError
from rosaadl.importers.ros2_package.building import build_project
from rosaadl.importers.ros2_package.facts import (
    DeploymentFact,
    LaunchedNode,
    NodeFact,
    PortFact,
    SystemFacts,
    TimerFact,
)

__all__ = [
    "read_graph",
    "observe_graph",
    "ros_type",
    "steady_period",
    "STEADY",
    "STEADY_SHARE",
    "INFRASTRUCTURE_TOPICS",
    "hidden",
    "action_of",
]

#: Topics every ROS 2 node has; not part of the application.
INFRASTRUCTURE_TOPICS = ("/rosout", "/parameter_events")
#: The services every node offers for its parameters (rclpy and rclcpp), and type descriptions.
_NODE_SERVICES = (
    "describe_parameters",
    "get_parameter_types",
    "get_parameters",
    "list_parameters",
    "set_parameters",
    "set_parameters_atomically",
    "get_type_description",
)
#: What a managed (lifecycle) node offers besides its application: services, then its topic.
_LIFECYCLE_SERVICES = (
    "change_state",
    "get_state",
    "get_available_states",
    "get_available_transitions",
    "get_transition_graph",
)
_LIFECYCLE_TOPIC = "transition_event"
#: The part of a name that makes it an action's own service or topic.
_ACTION = "/_action/"
#: What an action's type is suffixed with in the names of its services and topics.
_ACTION_SUFFIXES = ("_SendGoal", "_GetResult", "_FeedbackMessage")
_TOPIC_KINDS = ("Publisher", "Subscriber")
#: A topic is periodic when :data:`STEADY_SHARE` of its inter-arrival times are within this share
#: of their median (:func:`steady_period`).
STEADY = 0.25
#: The share of inter-arrival times that must be regular for a topic to be periodic.
STEADY_SHARE = 0.75
#: Fewest messages from which a rate is measured.
MIN_SAMPLES = 4
#: The CDR encapsulation header in front of every serialized message.
CDR_HEADER = 4


def _rclpy() -> Any:
    try:
        return importlib.import_module("rclpy")
    except ImportError as exc:
        raise RosaadlError(
            f"rclpy is not installed ({exc}): install ROS 2 (its Python client library rclpy and an "
            "RMW implementation) to read a running graph"
        ) from None


def ros_type(name: str) -> str:
    """``std_msgs/String`` for the graph's ``std_msgs/msg/String``."""
    parts = name.split("/")
    return f"{parts[0]}/{parts[-1]}" if len(parts) == 3 else name


def _full_name(name: str, namespace: str) -> str:
    return namespace.rstrip("/") + "/" + name


def _infrastructure(name: str, node: str) -> bool:
    return name in INFRASTRUCTURE_TOPICS or any(name == f"{node}/{s}" for s in _NODE_SERVICES)


def _lifecycle(name: str, node: str) -> bool:
    return name == f"{node}/{_LIFECYCLE_TOPIC}" or any(name == f"{node}/{s}" for s in _LIFECYCLE_SERVICES)


def hidden(name: str) -> bool:
    """ROS 2's rule for a hidden topic, service or node: a part of its name starts with ``_``."""
    return any(part.startswith("_") for part in name.split("/"))


def action_of(name: str, type_name: str) -> tuple[str, str | None] | None:
    """``(action, pkg/action/Type)`` when ``name`` is one of an action's own services or topics
    (``/fibonacci/_action/send_goal`` of type ``pkg/action/Fibonacci_SendGoal``), None when it is
    not; the type is None for the names typed by ``action_msgs`` (``cancel_goal``, ``status``)."""
    action, found, _rest = name.partition(_ACTION)
    if not found:
        return None
    for suffix in _ACTION_SUFFIXES:
        if type_name.endswith(suffix) and "/action/" in type_name:
            return action, type_name[: -len(suffix)]
    return action, None


def _qos(infos: list[Any], name: str, namespace: str) -> dict[str, str]:
    for info in infos:
        if info.node_name == name and info.node_namespace == namespace:
            qos = info.qos_profile
            found = {"reliability": qos.reliability.name.lower(), "durability": qos.durability.name.lower()}
            if qos.depth:  # 0: the middleware does not announce it (Fast DDS)
                found["depth"] = str(qos.depth)
            return found
    return {}


class _Observer:
    def __init__(self, rclpy: Any, node: Any, warnings: list[Diagnostic]) -> None:
        self.rclpy = rclpy
        self.node = node
        self.warnings = warnings
        self.facts = SystemFacts("ros2_graph")
        self.endpoints: dict[str, dict[str, list[Any]]] = {}

    def warn(self, message: str, path: str) -> None:
        self.warnings.append(Diagnostic("warning", message, Location(path=path)))

    def infos(self, kind: str, topic: str) -> list[Any]:
        cached = self.endpoints.setdefault(kind, {})
        if topic not in cached:
            read = (
                self.node.get_publishers_info_by_topic
                if kind == "Publisher"
                else self.node.get_subscriptions_info_by_topic
            )
            try:
                cached[topic] = list(read(topic))
            except Exception:  # noqa: BLE001 - the topic went away: no QoS known
                cached[topic] = []
        return cached[topic]

    def read_node(self, name: str, namespace: str) -> NodeFact | None:
        full = _full_name(name, namespace)
        node = self.node
        try:
            lists = {
                "Publisher": node.get_publisher_names_and_types_by_node(name, namespace),
                "Subscriber": node.get_subscriber_names_and_types_by_node(name, namespace),
                "Server": node.get_service_names_and_types_by_node(name, namespace),
                "Client": node.get_client_names_and_types_by_node(name, namespace),
            }
        except Exception as exc:  # noqa: BLE001 - rclpy's NodeNameNonExistentError and kin
            self.warn(f"the node left the graph during discovery ({exc.__class__.__name__}); left out", full)
            return None
        fact = NodeFact(key=full, node_name=name, namespace=namespace, location=Location(path=full))
        managed = False
        actions: dict[tuple[str, str], str | None] = {}
        for kind, entries in lists.items():
            for topic, types in sorted(entries):
                if _infrastructure(topic, full):
                    continue
                if _lifecycle(topic, full):
                    managed = True
                    continue
                action = action_of(topic, types[0] if len(types) == 1 else "")
                if action is not None:
                    role = "server" if kind in ("Server", "Publisher") else "client"
                    name_type = actions.get((role, action[0]))
                    actions[(role, action[0])] = name_type or action[1]
                    continue
                if hidden(topic):
                    noun = "topic" if kind in _TOPIC_KINDS else "service"
                    self.warn(f"hidden {noun} {topic} ({', '.join(types)}): left out", full)
                    continue
                if len(types) != 1:
                    self.warn(
                        f"{topic} is announced with {len(types)} types ({', '.join(types)}); left out", full
                    )
                    continue
                qos = (
                    _qos(self.infos(kind, topic), name, namespace)
                    if kind in ("Publisher", "Subscriber")
                    else {}
                )
                fact.ports.append(
                    PortFact(kind, ros_type(types[0]), topic, Location(path=f"{full} {topic}"), qos)
                )
        if managed:
            self.warn(
                "a managed (lifecycle) node: its lifecycle services and transition_event topic are "
                "left out (a ROSMOD model has no lifecycle states)",
                full,
            )
        for (role, action), type_name in sorted(actions.items()):
            typed = f" ({type_name})" if type_name else ""
            self.warn(f"action {role} {action}{typed}: a ROSMOD model has no actions; left out", full)
        return fact

    def read(self) -> None:
        own = self.node.get_fully_qualified_name()
        deployment = DeploymentFact("graph", location=Location(path="graph"))
        for name, namespace in sorted(set(self.node.get_node_names_and_namespaces())):
            full = _full_name(name, namespace)
            if full == own or hidden(full):  # hidden nodes: tools (ros2 daemon), this reader
                continue
            if full in self.facts.nodes:
                self.warn("two nodes of the same name; the second is left out", full)
                continue
            fact = self.read_node(name, namespace)
            if fact is None:
                continue
            self.facts.nodes[full] = fact
            deployment.nodes.append(LaunchedNode(full, name, namespace, location=Location(path=full)))
        self._drop_mixed_types()
        if deployment.nodes:
            self.facts.deployments.append(deployment)

    def _drop_mixed_types(self) -> None:
        """A topic whose endpoints do not agree on one type is left out everywhere, with a warning."""
        types: dict[str, set[str]] = {}
        for fact in self.facts.nodes.values():
            for port in fact.ports:
                if port.kind in _TOPIC_KINDS:
                    types.setdefault(port.topic, set()).add(port.type)
        mixed = {topic for topic, found in types.items() if len(found) > 1}
        for topic in sorted(mixed):
            self.warn(
                f"the topic's endpoints disagree on its type ({', '.join(sorted(types[topic]))}); left out",
                topic,
            )
        for fact in self.facts.nodes.values():
            fact.ports = [
                p for p in fact.ports if p.topic not in mixed or p.kind not in ("Publisher", "Subscriber")
            ]

    def measure(self, executor: Any, seconds: float) -> None:
        qos_module = importlib.import_module("rclpy.qos")
        policies = qos_module.ReliabilityPolicy
        publishers: dict[str, list[tuple[NodeFact, PortFact]]] = {}
        for fact in self.facts.nodes.values():
            for port in fact.ports:
                if port.kind == "Publisher":
                    publishers.setdefault(port.topic, []).append((fact, port))
        samples: dict[str, list[tuple[float, int]]] = {}
        for topic, ends in sorted(publishers.items()):
            type_name = ends[0][1].type
            message = _message_class(type_name)
            if message is None:
                self.warn(f"type {type_name} is not installed here: the topic is not measured", topic)
                continue
            found = samples.setdefault(topic, [])
            reliable = all(port.qos.get("reliability") == "reliable" for _, port in ends)
            profile = qos_module.QoSProfile(
                depth=100,
                reliability=policies.RELIABLE if reliable else policies.BEST_EFFORT,
                durability=qos_module.DurabilityPolicy.VOLATILE,
            )
            self.node.create_subscription(
                message,
                topic,
                lambda raw, found=found: found.append((time.monotonic(), len(raw))),
                profile,
                raw=True,
            )
        _spin(executor, seconds)
        for topic, found in sorted(samples.items()):
            self._measured(topic, publishers[topic], found, seconds)

    def _measured(
        self, topic: str, ends: list[tuple[NodeFact, PortFact]], found: list, seconds: float
    ) -> None:
        if found:
            size = max(size for _, size in found) - CDR_HEADER
            type_name = ends[0][1].type
            self.facts.message_sizes[type_name] = max(size, self.facts.message_sizes.get(type_name, 0))
        if len(found) < MIN_SAMPLES:
            self.warn(f"{len(found)} message(s) in {seconds:g} s: too few to measure a rate", topic)
            return
        times = [t for t, _ in found]
        period = steady_period(times)
        if period is None:
            mean = (times[-1] - times[0]) / (len(times) - 1)
            self.warn(f"messages come at an irregular rate (mean gap {mean * 1e3:.1f} ms): no timer", topic)
            return
        if len(ends) > 1:
            names = ", ".join(fact.key for fact, _ in ends)
            self.warn(f"several publishers ({names}): the period is not given to one", topic)
            return
        fact, port = ends[0]
        period = Decimal(str(round(period, 6)))
        token = topic.strip("/").replace("/", "_") or "topic"
        fact.timers.append(TimerFact(f"{token}_timer", period, Location(path=f"{fact.key} {topic}")))


def steady_period(times: list[float]) -> float | None:
    """The period of messages arriving at ``times`` (seconds, ascending), or None if they do not
    come at a steady rate.

    With ``m`` the median gap between successive arrivals, the rate is steady when at least
    :data:`STEADY_SHARE` of the gaps lie within ``m ± STEADY·m``; the period is the mean of those
    gaps. A stall of the machine (one long gap: a timer skips the periods it missed) or a burst
    of messages queued meanwhile changes neither, where the mean and the spread of all the gaps
    would call a periodic publisher irregular."""
    gaps = [b - a for a, b in zip(times, times[1:], strict=False)]
    if not gaps:
        return None
    median = statistics.median(gaps)
    if median <= 0:
        return None
    regular = [gap for gap in gaps if abs(gap - median) <= STEADY * median]
    if len(regular) < STEADY_SHARE * len(gaps):
        return None
    return statistics.fmean(regular)


def _message_class(type_name: str) -> Any:
    package, _, name = type_name.partition("/")
    try:
        return getattr(importlib.import_module(f"{package}.msg"), name)
    except (ImportError, AttributeError, ValueError):
        return None


def _spin(executor: Any, seconds: float) -> None:
    end = time.monotonic() + seconds
    while True:
        left = end - time.monotonic()
        if left <= 0:
            return
        executor.spin_once(timeout_sec=min(left, 0.05))


def observe_graph(
    *, wait: float = 2.0, domain_id: int | None = None, measure: float = 0.0, warnings: list[Diagnostic]
) -> SystemFacts:
    """The facts of the running graph (see the module docstring)."""
    rclpy = _rclpy()
    executors = importlib.import_module("rclpy.executors")
    context = rclpy.Context()
    rclpy.init(context=context, domain_id=domain_id)
    node = None
    try:
        node = rclpy.create_node(
            f"_rosaadl_graph_{os.getpid()}",
            context=context,
            start_parameter_services=False,
            enable_rosout=False,
        )
        executor = executors.SingleThreadedExecutor(context=context)
        executor.add_node(node)
        _spin(executor, wait)
        observer = _Observer(rclpy, node, warnings)
        observer.read()
        if measure > 0 and observer.facts.nodes:
            observer.measure(executor, measure)
        return observer.facts
    finally:
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown(context=context)


def read_graph(
    *, wait: float = 2.0, domain_id: int | None = None, measure: float = 0.0, warnings: list[Diagnostic]
) -> EObject:
    """The ROSMOD project of the running graph; an :class:`ImportFormatError` when no node is seen."""
    found: list[Diagnostic] = []
    facts = observe_graph(wait=wait, domain_id=domain_id, measure=measure, warnings=found)
    where = Location(
        path=f"ROS 2 graph, domain {domain_id if domain_id is not None else 'of the environment'}"
    )
    if not facts.nodes:
        raise ImportFormatError(
            f"no ROS 2 node was seen in {wait:g} s of discovery",
            where,
            errors=[Diagnostic("error", d.message, d.location) for d in found]
            + [Diagnostic("error", f"no ROS 2 node was seen in {wait:g} s of discovery", where)],
        )
    found.append(
        Diagnostic(
            "warning",
            "the graph does not say on which host each node runs nor how long its callbacks take: "
            "bind the model to a board and give execution-time profiles",
            where,
        )
    )
    project = build_project(facts, found)
    warnings.extend(found)
    return project
