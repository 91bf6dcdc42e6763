"""What is known of a ROS 2 system, whichever way it was learnt: read in ``rclpy`` sources and
launch files (:mod:`.reading`), or seen in a running graph (``rosaadl.workflow.ros2_graph``).

Plain data, no model: :mod:`.building` turns it into a ROSMOD project. Every fact keeps where it
was found (a file and line, or the graph), so that what the model cannot say is reported there.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from decimal import Decimal

from rosaadl.errors import Location

__all__ = [
    "PORT_KINDS",
    "PortFact",
    "TimerFact",
    "NodeFact",
    "InterfaceFact",
    "LaunchedNode",
    "DeploymentFact",
    "SystemFacts",
]

#: The kinds of port, named as the ROSMOD classes that hold them.
PORT_KINDS = ("Publisher", "Subscriber", "Client", "Server")


@dataclass
class PortFact:
    """A publisher, subscription, service server or client of a node."""

    kind: str  #: one of :data:`PORT_KINDS`
    type: str  #: ``pkg/Name`` (``std_msgs/String``)
    topic: str  #: the topic or service name as the node names it (relative or absolute)
    location: Location = field(default_factory=Location)
    qos: dict[str, str] = field(default_factory=dict)  #: reliability, durability, depth (as text)
    name: str = ""  #: a name for the port, unique in its node (made from the topic when empty)
    parameter: str | None = None  #: the node parameter whose value is the topic
    derived: str | None = None  #: the node parameter the topic is computed from


@dataclass
class TimerFact:
    """A timer of a node: its period in seconds, and the parameter that gives it, if any."""

    name: str
    period: Decimal | None
    location: Location = field(default_factory=Location)
    parameter: str | None = None  #: the node parameter whose value is the period
    derived: str | None = None  #: the node parameter the period is computed from


@dataclass
class NodeFact:
    """A ROS 2 node: what it creates. ``key`` names it among the facts (a class, or a graph node)."""

    key: str
    node_name: str
    namespace: str = "/"
    ports: list[PortFact] = field(default_factory=list)
    timers: list[TimerFact] = field(default_factory=list)
    location: Location = field(default_factory=Location)
    package: str = ""  #: the ROS package that holds it
    executables: tuple[str, ...] = ()  #: the executables that run it (setup.py entry points)
    parameters: dict[str, object] = field(default_factory=dict)  #: declared parameters and defaults


@dataclass
class InterfaceFact:
    """A ``.msg`` or ``.srv`` definition of an interface package."""

    package: str
    name: str
    kind: str  #: "msg" | "srv"
    text: str
    location: Location = field(default_factory=Location)


@dataclass
class LaunchedNode:
    """A ``launch_ros.actions.Node`` of a launch file, or a node of a running graph."""

    node: str  #: the :attr:`NodeFact.key` it runs
    name: str  #: the node's name once launched
    namespace: str = "/"
    remappings: dict[str, str] = field(default_factory=dict)
    parameters: dict[str, object] = field(default_factory=dict)
    location: Location = field(default_factory=Location)


@dataclass
class DeploymentFact:
    """The nodes started together: a launch file, or a running graph."""

    name: str
    nodes: list[LaunchedNode] = field(default_factory=list)
    location: Location = field(default_factory=Location)


@dataclass
class SystemFacts:
    """Everything known: the nodes, the interface definitions, the deployments, and measured
    message sizes in bytes (``pkg/Name`` → largest serialized size seen)."""

    name: str
    nodes: dict[str, NodeFact] = field(default_factory=dict)
    interfaces: list[InterfaceFact] = field(default_factory=list)
    deployments: list[DeploymentFact] = field(default_factory=list)
    message_sizes: dict[str, int] = field(default_factory=dict)
