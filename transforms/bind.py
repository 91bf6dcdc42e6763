"""Bind the deployments of a ROSMOD project to a robot of the component library.

A ROSMOD project says which components run in which node on which host, and at what rates
(timer periods); it knows nothing of the boards' cores or of the nodes' execution times. The
component library knows both: robots made of boards, chips and cores (``library/hardware``), and
nodes with one platform-dependent implementation (PDM) per core type, carrying the execution
times measured there (``library/nodes``). :func:`bind_deployment` joins them, following an
explicit bindings file (``read_bindings``; the example's ``examples/tracking/bindings.json``),
into an AADL deployment package shaped like the library's ``sys_tracking``:

* the library robot (``"robot": "pioneer_3dx::Pioneer_3DX.impl"``) as the subcomponent
  ``robot``;
* one process per ROSMOD component instance, of the library node named for it
  (``"library": "nd_usb_cam::usb_cam_nd"``), in the PDM whose ``Reference_Processor`` is the
  type of the core it is bound to (``"core": "OdroidXU4.Exynos_SOC.little_procs_cluster.
  little_proc1"`` is an ``Exynos_5422::ARM_A7``, so ``usb_cam_nd.xu4_a7``), bound to that core
  with ``Actual_Processor_Binding``;
* one port connection per topic, as ROSMOD matches them (a publisher and a subscriber of the
  same message type, and of the same ``<port>.Topic`` setting when there is one), between the
  library ports that carry the topic's message type, bound with ``Actual_Connection_Binding``
  to the ROS virtual bus (``ROSbus: virtual bus ros::ROSbus.impl``) or to a bus of the robot;
* the connections between nodes and the robot's own ports the bindings file lists (the camera
  stream, the velocity commands), bound to the robot bus it names;
* the rates of the ROSMOD model on the library threads: a thread that handles a subscriber's
  messages runs at the rate of the topic (its publisher's rate), a thread that publishes runs at
  the rate of the component's timer (the fastest, when it has several; a component without a
  timer publishes from its fastest subscriber callback); the other threads of the node and the
  node itself run at the node's fastest rate. ROSMOD's deadlines and priorities go with the
  rates (the subscriber's own, or the timer's), a node's priority on its process. So the CPU
  load of a thread is the PDM's execution time over the ROSMOD period.

The input is the ROSMOD project itself, not the AADL that :mod:`~rosaadl.transforms.rosmod_to_aadl`
makes of it: every fact the binding needs (components, their timers, ports and message types,
nodes, deployments, which publisher feeds which subscriber) is a first-class element of the
ROSMOD model, whereas the converted AADL holds generic threads and processors that the library
nodes and boards replace, and would have to be read back into these facts.

:func:`propose_binding` searches a better binding of an overloaded deployment over the cores of
its own robot (:func:`rosaadl.analysis.deployment.search_deployment`), where a node's demand on a
core is the execution time of its PDM for that core type, and binds the deployment again with the
cores found.

Every problem of the bindings file (unknown robot, library node, core path, port or bus, a core
of a type the node has no PDM for, a ROSMOD node without binding) is a :class:`BindingError`
located at the file, line and entry (``deployments.pioneer_3dx.nodes.usb_cam_node.core``).
"""

from __future__ import annotations

import json
import logging
import os
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from decimal import Decimal
from fractions import Fraction
from pathlib import Path
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.errors import Diagnostic, Location, ParseError, TransformationError
from rosaadl.transforms.rosmod_to_aadl import NameScope, aadl_identifier, given, seconds_to_time

__all__ = [
    "BINDINGS_VERSION",
    "MAX_BINDINGS_BYTES",
    "ROS_BUS",
    "BindingError",
    "BindingsFile",
    "DeploymentSpec",
    "NodeSpec",
    "RobotLink",
    "Core",
    "ThreadTiming",
    "BoundNode",
    "BoundTopic",
    "BoundDeployment",
    "Proposal",
    "read_bindings",
    "parse_bindings",
    "robot_cores",
    "bind_deployment",
    "bind_project",
    "propose_binding",
]

log = logging.getLogger(__name__)

#: The version of the bindings file format this module reads.
BINDINGS_VERSION = 1
#: Larger bindings files are refused (a real one is a few kilobytes).
MAX_BINDINGS_BYTES = 1 << 20
#: What ``topic_bus`` names for the ROS virtual bus, and the classifier of its subcomponent.
ROS_BUS = "ros::ROSbus"
_ROS_BUS_IMPL = "ros::ROSbus.impl"
_ROS_BUS_NAMES = frozenset({"ros::rosbus", "ros::rosbus.impl"})

_ROBOT = "robot"
_ROSBUS_SUB = "ROSbus"
_PORT_CATEGORIES = frozenset({"event data port", "data port", "event port"})

_DEPLOYMENT_KEYS = {"robot", "topic_bus", "nodes", "robot_connections"}
_NODE_KEYS = {"library", "core", "ports"}
_LINK_KEYS = {"node", "port", "robot_port", "bus"}


class BindingError(TransformationError):
    """The bindings file and the project or the library do not agree (located at the entry)."""

    stage = "bind"


# =========================================================================== the bindings file


@dataclass(frozen=True)
class NodeSpec:
    """How one ROSMOD node (or one component instance of it) is bound."""

    key: str  #: ``node`` or ``node/component_instance``
    library: str  #: ``Pkg::Type`` (the PDM follows the core) or ``Pkg::Type.impl`` (that PDM)
    core: str  #: core path inside the robot
    ports: Mapping[str, str | None]  #: ROSMOD port → library port (None: not connected)
    where: Mapping[str, Location]  #: field name ("", "library", "core", "ports.x") → location


@dataclass(frozen=True)
class RobotLink:
    """A connection between a node's library port and a port of the robot."""

    node: str
    port: str
    robot_port: str
    bus: str | None
    where: Mapping[str, Location]


@dataclass(frozen=True)
class DeploymentSpec:
    """The binding of one ROSMOD deployment."""

    name: str
    robot: str  #: ``Pkg::Robot.impl``
    topic_bus: str  #: :data:`ROS_BUS` or the path of a bus inside the robot
    nodes: Mapping[str, NodeSpec]
    robot_links: tuple[RobotLink, ...]
    where: Mapping[str, Location]


@dataclass(frozen=True)
class BindingsFile:
    """A bindings file: one :class:`DeploymentSpec` per ROSMOD deployment it binds."""

    file: str | None
    deployments: Mapping[str, DeploymentSpec]


class _Lines:
    """Line numbers of JSON members, found by their key path (first match along the path)."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.starts = [0] + [m.end() for m in re.finditer("\n", text)]

    def line(self, keys: Iterable[str | int]) -> int | None:
        pos = 0
        found = None
        for key in keys:
            if isinstance(key, int):
                continue  # list items: the line of the list's key is close enough
            match = re.compile(re.escape(json.dumps(key, ensure_ascii=False)) + r"\s*:").search(
                self.text, pos
            )
            if match is None:
                break
            pos = match.end()
            found = match.start()
        if found is None:
            return None
        low, high = 0, len(self.starts)
        while low + 1 < high:
            mid = (low + high) // 2
            if self.starts[mid] <= found:
                low = mid
            else:
                high = mid
        return low + 1


class _Reader:
    def __init__(self, file: str | None, text: str) -> None:
        self.file = file
        self.lines = _Lines(text)

    def where(self, keys: tuple[str | int, ...]) -> Location:
        path = ".".join(str(k) if isinstance(k, str) else f"[{k}]" for k in keys).replace(".[", "[")
        return Location(file=self.file, line=self.lines.line(keys), path=path or None)

    def fail(self, keys: tuple[str | int, ...], message: str) -> BindingError:
        return BindingError(message, self.where(keys))

    def obj(self, value: Any, keys: tuple[str | int, ...], allowed: set[str], required: set[str]) -> dict:
        if not isinstance(value, dict):
            raise self.fail(keys, f"expected an object, got {_kind(value)}")
        unknown = sorted(set(value) - allowed)
        if unknown:
            raise self.fail(
                (*keys, unknown[0]),
                f"unknown member {unknown[0]!r} (expected {', '.join(sorted(allowed))})",
            )
        missing = sorted(required - set(value))
        if missing:
            raise self.fail(keys, f"missing member {missing[0]!r}")
        return value

    def string(self, value: Any, keys: tuple[str | int, ...], *, null: bool = False) -> str | None:
        if value is None and null:
            return None
        if not isinstance(value, str) or not value.strip():
            raise self.fail(keys, f"expected a non-empty string, got {_kind(value)}")
        if len(value) > 1000 or any(ord(c) < 32 for c in value):
            raise self.fail(keys, "expected a name or path (at most 1000 characters, no control characters)")
        return value.strip()


def _kind(value: Any) -> str:
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, int | float):
        return "a number"
    if isinstance(value, str):
        return "an empty string" if not value.strip() else "a string"
    if isinstance(value, list):
        return "a list"
    return "an object"


def _no_duplicates(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in pairs:
        if key in out:
            raise _Duplicate(key)
        out[key] = value
    return out


class _Duplicate(Exception):
    def __init__(self, key: str) -> None:
        super().__init__(key)
        self.key = key


def _reject_constant(name: str) -> Any:
    raise ValueError(f"{name} is not a JSON number")


def parse_bindings(text: str | bytes, file: str | None = None) -> BindingsFile:
    """A bindings file from its text (see ``docs/workflow.md`` for the format)::

        {"version": 1,
         "deployments": {
           "<ROSMOD deployment>": {
             "robot": "pioneer_3dx::Pioneer_3DX.impl",
             "topic_bus": "ros::ROSbus",                       (default; or a bus of the robot)
             "nodes": {"<node>" or "<node>/<component instance>": {
                          "library": "nd_usb_cam::usb_cam_nd",
                          "core": "OdroidXU4.Exynos_SOC.little_procs_cluster.little_proc1",
                          "ports": {"<ROSMOD port>": "<library port>" or null}}},   (optional)
             "robot_connections": [{"node": "<node key>", "port": "<library port>",
                                    "robot_port": "<robot port>", "bus": "<robot bus>"}]}}}

    Syntax errors are :class:`~rosaadl.errors.ParseError` s at file:line:column; a wrong member
    is a :class:`BindingError` at its line and path. Whether the names exist is checked when
    binding.
    """
    if isinstance(text, bytes):
        if len(text) > MAX_BINDINGS_BYTES:
            raise ParseError(f"bindings file larger than {MAX_BINDINGS_BYTES} bytes", file=file)
        try:
            text = text.decode("utf-8-sig")
        except UnicodeDecodeError as exc:
            raise ParseError(f"not UTF-8 text (byte {exc.start})", file=file) from None
    if len(text) > MAX_BINDINGS_BYTES:
        raise ParseError(f"bindings file larger than {MAX_BINDINGS_BYTES} characters", file=file)
    try:
        data = json.loads(text, object_pairs_hook=_no_duplicates, parse_constant=_reject_constant)
    except json.JSONDecodeError as exc:
        raise ParseError(f"not valid JSON: {exc.msg}", file=file, line=exc.lineno, column=exc.colno) from None
    except _Duplicate as exc:
        raise ParseError(f"member {exc.key!r} given twice in one object", file=file) from None
    except ValueError as exc:
        raise ParseError(f"not valid JSON: {exc}", file=file) from None
    except RecursionError:
        raise ParseError("not a bindings file: JSON nested too deeply", file=file) from None
    reader = _Reader(file, text)
    top = reader.obj(data, (), {"version", "deployments"}, {"deployments"})
    version = top.get("version", BINDINGS_VERSION)
    if version != BINDINGS_VERSION or isinstance(version, bool):
        raise reader.fail(("version",), f"unsupported version {version!r} (this rosaadl reads version 1)")
    deployments = top["deployments"]
    if not isinstance(deployments, dict) or not deployments:
        raise reader.fail(("deployments",), "expected an object with one member per deployment")
    specs: dict[str, DeploymentSpec] = {}
    for name, body in deployments.items():
        specs[name] = _deployment_spec(reader, name, body)
    return BindingsFile(file=file, deployments=specs)


def _deployment_spec(reader: _Reader, name: str, body: Any) -> DeploymentSpec:
    base: tuple[str | int, ...] = ("deployments", name)
    body = reader.obj(body, base, _DEPLOYMENT_KEYS, {"robot", "nodes"})
    robot = reader.string(body["robot"], (*base, "robot"))
    bus = reader.string(body.get("topic_bus", ROS_BUS), (*base, "topic_bus"))
    nodes_value = body["nodes"]
    if not isinstance(nodes_value, dict) or not nodes_value:
        raise reader.fail((*base, "nodes"), "expected an object with one member per ROSMOD node")
    nodes: dict[str, NodeSpec] = {}
    for key, entry in nodes_value.items():
        keys = (*base, "nodes", key)
        entry = reader.obj(entry, keys, _NODE_KEYS, {"library", "core"})
        ports_value = entry.get("ports", {})
        if not isinstance(ports_value, dict):
            raise reader.fail((*keys, "ports"), f"expected an object, got {_kind(ports_value)}")
        ports = {
            reader.string(k, (*keys, "ports", k)) or k: reader.string(v, (*keys, "ports", k), null=True)
            for k, v in ports_value.items()
        }
        where = {
            "": reader.where(keys),
            "library": reader.where((*keys, "library")),
            "core": reader.where((*keys, "core")),
            **{f"ports.{k}": reader.where((*keys, "ports", k)) for k in ports},
        }
        nodes[key] = NodeSpec(
            key=reader.string(key, keys) or key,
            library=reader.string(entry["library"], (*keys, "library")) or "",
            core=reader.string(entry["core"], (*keys, "core")) or "",
            ports=ports,
            where=where,
        )
    links_value = body.get("robot_connections", [])
    if not isinstance(links_value, list):
        raise reader.fail((*base, "robot_connections"), f"expected a list, got {_kind(links_value)}")
    links = []
    for index, entry in enumerate(links_value):
        keys = (*base, "robot_connections", index)
        entry = reader.obj(entry, keys, _LINK_KEYS, {"node", "port", "robot_port"})
        links.append(
            RobotLink(
                node=reader.string(entry["node"], (*keys, "node")) or "",
                port=reader.string(entry["port"], (*keys, "port")) or "",
                robot_port=reader.string(entry["robot_port"], (*keys, "robot_port")) or "",
                bus=reader.string(entry.get("bus"), (*keys, "bus"), null=True),
                where={"": reader.where(keys), "bus": reader.where((*keys, "bus"))},
            )
        )
    where = {
        "": reader.where(base),
        "robot": reader.where((*base, "robot")),
        "topic_bus": reader.where((*base, "topic_bus")),
        "nodes": reader.where((*base, "nodes")),
    }
    return DeploymentSpec(
        name=name,
        robot=robot or "",
        topic_bus=bus or ROS_BUS,
        nodes=nodes,
        robot_links=tuple(links),
        where=where,
    )


def read_bindings(path: str | os.PathLike[str]) -> BindingsFile:
    """Read a bindings file (:func:`parse_bindings`); a missing or unreadable file is a located
    :class:`~rosaadl.errors.ParseError`."""
    source = Path(path)
    try:
        size = source.stat().st_size
        if size > MAX_BINDINGS_BYTES:
            raise ParseError(f"bindings file larger than {MAX_BINDINGS_BYTES} bytes", file=str(source))
        data = source.read_bytes()
    except OSError as exc:
        raise ParseError(f"cannot read the bindings file: {exc.strerror or exc}", file=str(source)) from None
    return parse_bindings(data, str(source))


# =========================================================================== the library side


@dataclass(frozen=True)
class Core:
    """A core (a processor without processor subcomponents) of a robot."""

    path: str  #: inside the robot: ``OdroidXU4.Exynos_SOC.little_procs_cluster.little_proc1``
    classifier: str  #: ``Exynos_5422::ARM_A7.impl``
    types: tuple[str, ...]  #: its type and the types it extends, lower case (``exynos_5422::arm_a7``)

    @property
    def kind(self) -> str:
        """The core's type as written: ``Exynos_5422::ARM_A7``."""
        return (
            self.classifier.partition(".")[0]
            if "." in self.classifier.rpartition("::")[2]
            else self.classifier
        )


def _literal(value: Any) -> str:
    return str(getattr(value, "literal", None) or getattr(value, "name", None) or value or "")


def _classifier(model: EObject, name: str, context: EObject | None = None) -> EObject | None:
    return _model.find_classifier(model, name, context) if name else None


def _type_chain(model: EObject, classifier: EObject | None) -> list[EObject]:
    """A classifier's type (for an implementation) and the types it extends, most specific first."""
    chain: list[EObject] = []
    current = classifier
    if current is not None and current.eClass.name == "ComponentImplementation":
        type_name = current.type or current.name.partition(".")[0]
        current = _classifier(model, type_name, current)
    while current is not None and current not in chain:
        chain.append(current)
        current = _classifier(model, current.extended, current) if current.extended else None
    return chain


def _impl_chain(model: EObject, impl: EObject) -> list[EObject]:
    chain: list[EObject] = []
    current: EObject | None = impl
    while current is not None and current not in chain:
        chain.append(current)
        current = _classifier(model, current.extended, current) if current.extended else None
    return chain


@dataclass
class _Robot:
    """What the binding needs to know of the robot: its cores, its ports and its buses."""

    name: str  # qualified
    cores: list[Core]
    ports: dict[str, EObject]  # lower-case name → feature instance of the robot
    buses: dict[str, str]  # lower-case path → path of a bus or virtual bus inside the robot


def _robot(model: EObject, robot: str) -> _Robot:
    """The robot's cores, ports and buses, from an instance of it (removed afterwards)."""
    from rosaadl.transforms.instantiate import instantiate

    system = instantiate(model, robot, diagnostics=[])
    try:
        prefix = (system.name or "") + "."
        cores, buses = [], {}
        for obj in _model.walk(system):
            if obj.eClass.name != "ComponentInstance":
                continue
            category = _literal(obj.category)
            path = _model.instance_path(obj).removeprefix(prefix)
            if category in ("bus", "virtual bus"):
                buses[path.lower()] = path
            elif category == "processor" and not any(
                _literal(c.category) == "processor" for c in obj.componentInstances
            ):
                classifier = _classifier(model, obj.classifier or "")
                types = tuple(_model.qualified_name(t).lower() for t in _type_chain(model, classifier))
                cores.append(Core(path, obj.classifier or "", types))
        ports = {
            f.name.lower(): f for f in system.featureInstances if _literal(f.category) in _PORT_CATEGORIES
        }
        return _Robot(robot, cores, ports, buses)
    finally:
        model.instances.remove(system)


def robot_cores(model: EObject, robot: str) -> list[Core]:
    """The cores of a robot (``Pkg::Robot.impl``, a system implementation of the loaded model),
    in model order; a located :class:`~rosaadl.errors.RosaadlError` when it does not instantiate."""
    return _robot(model, robot).cores


@dataclass
class _Library:
    """What the binding needs to know of one library node type."""

    type: EObject
    qualified: str
    ports: dict[str, EObject]  # lower-case name → port feature of the type chain
    pdms: list[tuple[EObject, str | None]]  # (implementation, its Reference_Processor qualified, lower)


class _Catalogue:
    def __init__(self, model: EObject) -> None:
        from rosaadl.lookup import PropertyLookup

        self.model = model
        self.lookup = PropertyLookup(model)
        self._nodes: dict[str, _Library] = {}

    def reference(self, impl: EObject) -> str | None:
        value = self.lookup.value(impl, "Reference_Processor")
        name = getattr(value, "classifier", None) if value is not None else None
        if not name:
            return None
        found = _classifier(self.model, name, impl)
        return (_model.qualified_name(found) if found is not None else name).lower()

    def node(self, name: str) -> _Library | None:
        """The library node type ``Pkg::Type`` (or the type of ``Pkg::Type.impl``)."""
        found = _classifier(self.model, name)
        if found is None or _literal(found.category) != "process":
            return None
        node_type = (
            _type_chain(self.model, found)[0] if found.eClass.name == "ComponentImplementation" else found
        )
        key = _model.qualified_name(node_type).lower()
        cached = self._nodes.get(key)
        if cached is not None:
            return cached
        ports: dict[str, EObject] = {}
        for classifier in _type_chain(self.model, node_type):
            for feature in classifier.features:
                if _literal(feature.category) in _PORT_CATEGORIES:
                    ports.setdefault(feature.name.lower(), feature)
        package = node_type.eContainer()
        pdms = []
        for impl in package.classifiers:
            if impl.eClass.name != "ComponentImplementation" or _literal(impl.category) != "process":
                continue
            if (impl.type or impl.name.partition(".")[0]).lower() != node_type.name.lower():
                continue
            reference = self.reference(impl)
            if reference is not None:
                pdms.append((impl, reference))
        entry = _Library(node_type, _model.qualified_name(node_type), ports, pdms)
        self._nodes[key] = entry
        return entry


# =========================================================================== the ROSMOD side


@dataclass
class _Instance:
    """A ROSMOD component instance in a deployment, with its binding."""

    node: EObject
    inst: EObject
    key: str
    spec: NodeSpec
    process: str = ""
    library: _Library | None = None
    pdm: EObject | None = None
    core: Core | None = None
    port_map: dict[str, str | None] = field(default_factory=dict)  # ROSMOD port → library port


@dataclass
class _Rate:
    period: Decimal
    deadline: Decimal | None
    priority: int | None
    source: str


def _message_name(type_name: str | None) -> str:
    return (type_name or "").rpartition("/")[2].lower()


def _classifier_type_name(classifier: str | None) -> str:
    return (classifier or "").rpartition("::")[2].partition(".")[0].lower()


def _topic_key(port: EObject) -> tuple[str | None, str | None]:
    """ROSMOD's match of a publisher and a subscriber: the message type and, where the component
    sets it (``<port>.Topic``, WebGME projects), the topic name."""
    component = port.eContainer()
    topic = None
    for prop in getattr(component, "properties", ()):
        if prop.key == f"{port.name}.Topic":
            topic = prop.value
    return port.type, topic


# =========================================================================== binding


@dataclass(frozen=True)
class ThreadTiming:
    """The ROSMOD timing set on one library thread (or on the node's process: ``thread`` "")."""

    thread: str
    period: Decimal  #: seconds
    deadline: Decimal | None
    priority: int | None
    source: str  #: where the period comes from (``timer frame_timer``, ``topic tracking/Image``, ...)


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

    def text(self) -> str:
        """The package as AADL text (what :func:`rosaadl.exporters.aadl_text.write_model` writes)."""
        from rosaadl.exporters.aadl_text import write_unit

        return write_unit(self.package)

    @property
    def file_name(self) -> str:
        from rosaadl.exporters.aadl_text import unit_file_name

        return unit_file_name(self.package)

    def node(self, process: str) -> BoundNode:
        for node in self.nodes:
            if node.process == process:
                return node
        raise KeyError(process)


def _fail(where: Location, message: str) -> BindingError:
    return BindingError(message, where)


def _deployment(project: EObject, name: str, spec: DeploymentSpec) -> EObject:
    for deployment in project.deployments:
        if deployment.name == name:
            return deployment
    known = ", ".join(sorted(d.name for d in project.deployments)) or "none"
    raise _fail(spec.where[""], f"the project has no deployment {name!r} (it has: {known})")


def _instances(deployment: EObject, spec: DeploymentSpec) -> list[_Instance]:
    """The component instances of a deployment, each with its entry of the bindings file."""
    used: set[str] = set()
    out = []
    for node in deployment.nodes:
        several = len(node.componentInstances) > 1
        for inst in node.componentInstances:
            keys = [f"{node.name}/{inst.name}"] + ([] if several else [node.name])
            key = next((k for k in keys if k in spec.nodes), None)
            if key is None:
                wanted = " or ".join(repr(k) for k in reversed(keys))
                raise _fail(
                    spec.where["nodes"],
                    f"no binding for ROSMOD node {node.name!r} (component instance {inst.name!r} of "
                    f"{getattr(inst.component, 'name', '?')!r}); add a member {wanted}",
                )
            if inst.component is None:
                raise _fail(spec.nodes[key].where[""], f"component instance {inst.name!r} has no component")
            used.add(key)
            out.append(_Instance(node, inst, key, spec.nodes[key]))
    for key, entry in spec.nodes.items():
        if key not in used:
            known = ", ".join(sorted({n.name for n in deployment.nodes})) or "none"
            raise _fail(
                entry.where[""],
                f"deployment {deployment.name!r} has no ROSMOD node {key!r} (it has: {known})",
            )
    return out


def _choose_pdm(item: _Instance, catalogue: _Catalogue, cores: dict[str, Core]) -> None:
    spec = item.spec
    library = catalogue.node(spec.library)
    if library is None:
        raise _fail(
            spec.where["library"],
            f"{spec.library!r} is not a process type or implementation of the library (expected a node such "
            "as 'nd_usb_cam::usb_cam_nd')",
        )
    core = cores.get(spec.core.lower())
    if core is None:
        shown = ", ".join(c.path for c in list(cores.values())[:12])
        raise _fail(spec.where["core"], f"the robot has no core {spec.core!r} (its cores: {shown})")
    available = (
        ", ".join(f"{impl.name.partition('.')[2]} ({ref})" for impl, ref in library.pdms)
        or "no platform-dependent implementation"
    )
    named = _classifier(catalogue.model, spec.library)
    if named is not None and named.eClass.name == "ComponentImplementation":
        reference = catalogue.reference(named)
        if reference is not None and reference not in core.types:
            raise _fail(
                spec.where["core"],
                f"{_model.qualified_name(named)} was measured on {reference}, but core {core.path} is a "
                f"{core.kind}; bind it to such a core or name the node type {library.qualified}",
            )
        pdm = named
    else:
        matches = [impl for impl, ref in library.pdms if ref in core.types]
        if not matches:
            raise _fail(
                spec.where["core"],
                f"{library.qualified} has no platform-dependent implementation for core {core.path} "
                f"({core.kind}); it has: {available}",
            )
        if len(matches) > 1:
            names = ", ".join(_model.qualified_name(m) for m in matches)
            raise _fail(
                spec.where["library"],
                f"{library.qualified} has several implementations for {core.kind} ({names}); name one",
            )
        pdm = matches[0]
    item.library, item.pdm, item.core = library, pdm, core


def _map_ports(item: _Instance) -> None:
    """ROSMOD publishers/subscribers → library ports: as the bindings file says, else the one
    port of the same direction whose data type has the message's name."""
    assert item.library is not None
    spec = item.spec
    component = item.inst.component
    ports = {p.name: p for p in component.ports if p.eClass.name in ("Publisher", "Subscriber")}
    for name in spec.ports:
        if name not in ports:
            known = ", ".join(sorted(ports)) or "none"
            raise _fail(
                spec.where[f"ports.{name}"],
                f"component {component.name!r} has no publisher or subscriber {name!r} (it has: {known})",
            )
    for name, port in ports.items():
        direction = "out" if port.eClass.name == "Publisher" else "in"
        if name in spec.ports:
            target = spec.ports[name]
            if target is None:
                item.port_map[name] = None
                continue
            feature = item.library.ports.get(target.lower())
            if feature is None or _literal(feature.direction) != direction:
                candidates = [
                    f.name for f in item.library.ports.values() if _literal(f.direction) == direction
                ]
                raise _fail(
                    spec.where[f"ports.{name}"],
                    f"{item.library.qualified} has no {direction} port {target!r} (its {direction} ports: "
                    f"{', '.join(candidates) or 'none'})",
                )
            item.port_map[name] = feature.name
            continue
        message = _message_name(port.type)
        if not message:  # an untyped port carries no topic ROSMOD could match
            item.port_map[name] = None
            continue
        candidates = [
            f
            for f in item.library.ports.values()
            if _literal(f.direction) == direction and _classifier_type_name(f.classifier) == message
        ]
        if len(candidates) != 1:
            listed = ", ".join(
                f"{f.name}: {f.classifier or 'no type'}"
                for f in item.library.ports.values()
                if _literal(f.direction) == direction
            )
            what = "no" if not candidates else "several"
            raise _fail(
                spec.where[""],
                f"ROSMOD {port.eClass.name.lower()} {name!r} <{port.type}> of {component.name!r}: "
                f"{item.library.qualified} has {what} {direction} port of a data type named "
                f"{_message_name(port.type) or '?'!r} ({direction} ports: {listed or 'none'}); "
                'map it in "ports"',
            )
        item.port_map[name] = candidates[0].name


def _topics(items: list[_Instance]) -> list[tuple[_Instance, EObject, _Instance, EObject]]:
    """(publisher instance, publisher, subscriber instance, subscriber) for every topic."""
    subscribers: dict[tuple[str | None, str | None], list[tuple[_Instance, EObject]]] = {}
    for item in items:
        for port in item.inst.component.ports:
            if port.eClass.name == "Subscriber" and port.type:
                subscribers.setdefault(_topic_key(port), []).append((item, port))
    out = []
    for item in items:
        for port in item.inst.component.ports:
            if port.eClass.name == "Publisher" and port.type:
                for sub_item, sub in subscribers.get(_topic_key(port), []):
                    out.append((item, port, sub_item, sub))
    return out


def _rates(
    items: list[_Instance], topics: list[tuple[_Instance, EObject, _Instance, EObject]]
) -> dict[tuple[int, str], _Rate]:
    """The rate of every publisher and subscriber of the deployment (key: id(instance), port)."""
    rates: dict[tuple[int, str], _Rate] = {}
    feeds: dict[tuple[int, str], list[tuple[int, str]]] = {}
    for pub_item, pub, sub_item, sub in topics:
        feeds.setdefault((id(sub_item), sub.name), []).append((id(pub_item), pub.name))
    for _round in range(2 * sum(len(i.inst.component.ports) for i in items) + 2):
        changed = False
        for item in items:
            component = item.inst.component
            for port in component.ports:
                key = (id(item), port.name)
                if port.eClass.name == "Subscriber":
                    found = [rates[f] for f in feeds.get(key, []) if f in rates]
                    if not found:
                        continue
                    fastest = min(found, key=lambda r: r.period)
                    rate = _Rate(
                        fastest.period,
                        given(port, "deadline"),
                        given(port, "priority"),
                        f"topic {port.type} (published every {fastest.period} s)",
                    )
                elif port.eClass.name == "Publisher":
                    timers = [t for t in component.timers if given(t, "period")]
                    if timers:
                        timer = min(timers, key=lambda t: t.period)
                        rate = _Rate(
                            timer.period,
                            given(timer, "deadline"),
                            given(timer, "priority"),
                            f"timer {timer.name}",
                        )
                    else:
                        subs = [
                            (rates[(id(item), p.name)], p)
                            for p in component.ports
                            if p.eClass.name == "Subscriber" and (id(item), p.name) in rates
                        ]
                        if not subs:
                            continue
                        source, sub = min(subs, key=lambda s: s[0].period)
                        rate = _Rate(
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
    for classifier in _impl_chain(model, impl):
        for conn in classifier.connections:
            seen.setdefault((conn.name or "").lower(), conn)
    return list(seen.values())


def _threads_of(model: EObject, impl: EObject) -> list[str]:
    seen: dict[str, str] = {}
    for classifier in reversed(_impl_chain(model, impl)):  # declaration order of the PIM first
        for sub in classifier.subcomponents:
            if _literal(sub.category) == "thread":
                seen.setdefault(sub.name.lower(), sub.name)
    return list(seen.values())


def _timings(model: EObject, item: _Instance, rates: dict[tuple[int, str], _Rate]) -> list[ThreadTiming]:
    """The ROSMOD timing of each thread of the node's PDM, then of the process (thread "")."""
    assert item.pdm is not None
    by_port: dict[str, _Rate] = {}
    for rosmod_port, library_port in item.port_map.items():
        rate = rates.get((id(item), rosmod_port))
        if library_port is not None and rate is not None:
            current = by_port.get(library_port.lower())
            if current is None or rate.period < current.period:
                by_port[library_port.lower()] = rate
    threads = _threads_of(model, item.pdm)
    linked: dict[str, list[_Rate]] = {t.lower(): [] for t in threads}
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


def _topic_bus(spec: DeploymentSpec, robot: _Robot) -> str:
    """The carrier of the topics: ``ROSbus`` or ``robot.<bus>``."""
    if spec.topic_bus.lower() in _ROS_BUS_NAMES:
        return _ROSBUS_SUB
    found = robot.buses.get(spec.topic_bus.lower())
    if found is None:
        raise _fail(
            spec.where["topic_bus"],
            f"{spec.topic_bus!r} is neither {ROS_BUS} nor a bus of {robot.name} "
            f"(its buses: {', '.join(robot.buses.values()) or 'none'})",
        )
    return f"{_ROBOT}.{found}"


def _robot_link(
    link: RobotLink, by_key: dict[str, _Instance], robot: _Robot, names: NameScope
) -> tuple[EObject, str | None]:
    """The port connection of a robot link, and the bus it is bound to (None: not bound)."""
    item = by_key.get(link.node)
    if item is None:
        raise _fail(link.where[""], f"{link.node!r} is not a node of this deployment's bindings")
    assert item.library is not None
    feature = item.library.ports.get(link.port.lower())
    if feature is None:
        raise _fail(
            link.where[""],
            f"{item.library.qualified} has no port {link.port!r} "
            f"(its ports: {', '.join(f.name for f in item.library.ports.values())})",
        )
    robot_port = robot.ports.get(link.robot_port.lower())
    if robot_port is None:
        raise _fail(
            link.where[""],
            f"{robot.name} has no port {link.robot_port!r} "
            f"(its ports: {', '.join(p.name for p in robot.ports.values()) or 'none'})",
        )
    node_end, robot_end = f"{item.process}.{feature.name}", f"{_ROBOT}.{robot_port.name}"
    node_out = _literal(feature.direction) == "out"
    if node_out == (_literal(robot_port.direction) == "out"):
        raise _fail(
            link.where[""],
            f"{node_end} and {robot_end} are both {_literal(feature.direction)} ports; a connection "
            "needs an out port and an in port",
        )
    source, destination = (node_end, robot_end) if node_out else (robot_end, node_end)
    connection = _new(
        "Connection",
        name=names.take(f"{_ROBOT}_{robot_port.name}"),
        kind="port",
        source=source,
        destination=destination,
    )
    if link.bus is None:
        return connection, None
    bus = robot.buses.get(link.bus.lower())
    if bus is None:
        raise _fail(
            link.where["bus"],
            f"{robot.name} has no bus {link.bus!r} (its buses: {', '.join(robot.buses.values()) or 'none'})",
        )
    return connection, f"{_ROBOT}.{bus}"


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
    library: EObject | None = None,
    *,
    package_name: str | None = None,
) -> BoundDeployment:
    """Bind the ROSMOD deployment ``spec.name`` of ``project`` (a ``rosmod.Project``) as ``spec``
    says, to the library of ``library`` (an ``AadlModel`` holding the component library; read
    when None). The package is named ``package_name`` (default ``<deployment>_bound``); its root
    system implementation is named after the project.

    Raises :class:`BindingError` at the bindings file's entry for what does not agree.
    """
    if not isinstance(project, EObject) or project.eClass.name != "Project":
        raise BindingError("expected a rosmod Project to bind")
    if library is None:
        from rosaadl.importers.aadl_text import read_files

        library = read_files([], include_library=True)
    deployment = _deployment(project, spec.name, spec)
    found = _classifier(library, spec.robot)
    if (
        found is None
        or found.eClass.name != "ComponentImplementation"
        or _literal(found.category) != "system"
    ):
        raise _fail(
            spec.where["robot"],
            f"{spec.robot!r} is not a system implementation of the library "
            "(expected a robot such as 'pioneer_3dx::Pioneer_3DX.impl')",
        )
    robot = _robot(library, _model.qualified_name(found))
    if not robot.cores:
        raise _fail(spec.where["robot"], f"{robot.name} has no processor to bind nodes to")
    cores = {c.path.lower(): c for c in robot.cores}
    catalogue = _Catalogue(library)
    warnings: list[Diagnostic] = []

    items = _instances(deployment, spec)
    members = NameScope([_ROBOT, _ROSBUS_SUB])
    for item in items:
        _choose_pdm(item, catalogue, cores)
        _map_ports(item)
        several = len(item.node.componentInstances) > 1
        item.process = members.take(f"{item.node.name}_{item.inst.name}" if several else item.node.name)
        for port in item.inst.component.ports:
            if port.eClass.name in ("Client", "Server"):
                warnings.append(
                    Diagnostic(
                        "warning",
                        f"{port.eClass.name.lower()} {port.name!r} of {item.inst.component.name!r} is not "
                        "bound: library nodes have no service ports",
                        item.spec.where[""],
                    )
                )
    topics = _topics(items)
    rates = _rates(items, topics)
    bus_path = _topic_bus(spec, robot)

    project_name = aadl_identifier(project.name or "deployment")
    pkg_name = package_name or f"{aadl_identifier(spec.name)}_bound"
    package = _new("AadlPackage", name=pkg_name)
    system_type = _new("ComponentType", name=project_name, category="system")
    impl = _new("ComponentImplementation", name=f"{project_name}.impl", type=project_name, category="system")
    impl.subcomponents.append(_new("Subcomponent", name=_ROBOT, category="system", classifier=robot.name))
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
        _pa(impl, "Actual_Processor_Binding", _reference(f"{_ROBOT}.{item.core.path}"), item.process)
        timings = _timings(library, item, rates)
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


def bind_project(
    project: EObject, bindings: BindingsFile, library: EObject | None = None
) -> dict[str, BoundDeployment]:
    """Every deployment of the bindings file, bound (:func:`bind_deployment`), in file order."""
    if library is None:
        from rosaadl.importers.aadl_text import read_files

        library = read_files([], include_library=True)
    return {name: bind_deployment(project, spec, library) for name, spec in bindings.deployments.items()}


# =========================================================================== a better binding


@dataclass
class Proposal:
    """What the deployment search proposes for a bound deployment."""

    search: Any  #: the :class:`~rosaadl.analysis.deployment.DeploymentResult`
    cores: dict[str, str]  #: process → core path inside the robot (empty when nothing passes)
    bound: BoundDeployment | None  #: the deployment bound to those cores (None when nothing passes)
    demands: dict[str, dict[str, Fraction]]  #: process → core path → its load there (1 = 100 %)

    @property
    def feasible(self) -> bool:
        return bool(self.search.feasible) and self.bound is not None


def _execution_times(
    project: EObject, bound: BoundDeployment, model: EObject
) -> dict[str, dict[str, dict[str, Fraction]]]:
    """process → core path (in the robot) → thread (relative) → CET in seconds, for every core
    whose type the node has a PDM for: the deployment bound, per core type, to a core of that type
    for every node that can run there, instantiated, its execution times read."""
    from rosaadl.analysis.resources import PropertyReader
    from rosaadl.transforms.instantiate import instantiate

    catalogue = _Catalogue(model)
    by_type: dict[str, list[Core]] = {}
    for core in bound.cores:
        by_type.setdefault(core.types[0] if core.types else core.classifier.lower(), []).append(core)
    out: dict[str, dict[str, dict[str, Fraction]]] = {node.process: {} for node in bound.nodes}
    taken = {u.name.lower() for u in model.units}
    for index, (_type, cores) in enumerate(sorted(by_type.items())):
        able = {}
        for node in bound.nodes:
            library = catalogue.node(node.library)
            if library is not None and any(ref in cores[0].types for _impl, ref in library.pdms):
                able[node.process] = node
        if not able:
            continue
        nodes = {
            n.spec.key: replace(n.spec, core=cores[0].path, library=n.library)
            if n.process in able
            else n.spec
            for n in bound.nodes
        }
        name = f"{bound.package.name}_on_{index}"
        while name.lower() in taken:
            name += "_"
        variant = bind_deployment(project, replace(bound.spec, nodes=nodes), model, package_name=name)
        from rosaadl.importers.aadl_text import read_string

        read_string(variant.text(), f"<{name}>", model=model)
        unit = _model.find_unit(model, name)
        system = None
        try:
            system = instantiate(model, variant.root, diagnostics=[])
            reader = PropertyReader()
            prefix = f"{system.name}."
            for process in _model.instance_children(system):
                if process.eClass.name != "ComponentInstance" or process.name not in able:
                    continue
                times: dict[str, Fraction] = {}
                for obj in _model.walk(process):
                    if obj is process or obj.eClass.name != "ComponentInstance":
                        continue
                    if _literal(obj.category) != "thread":
                        continue
                    cet = reader.seconds(obj, "Timing_Properties::Compute_Execution_Time")
                    if cet is not None:
                        relative = (
                            _model.instance_path(obj).removeprefix(prefix).removeprefix(process.name + ".")
                        )
                        times[relative] = cet
                for core in cores:
                    out[process.name][core.path] = times
        finally:
            if system is not None:
                model.instances.remove(system)
            if unit is not None:
                model.units.remove(unit)
    log.debug("execution times per core type: %s", {p: len(c) for p, c in out.items()})
    return out


def _demands(
    instance: EObject, times: dict[str, dict[str, dict[str, Fraction]]]
) -> dict[str, dict[str, Fraction]]:
    """process → core → Σ CET / Period: the load each process would put on each core."""
    from rosaadl.analysis.resources import PropertyReader

    reader = PropertyReader()
    root = f"{instance.name}."
    periods: dict[str, Fraction] = {}
    for obj in _model.walk(instance):
        if obj.eClass.name == "ComponentInstance" and _literal(obj.category) == "thread":
            period = reader.seconds(obj, "Timing_Properties::Period")
            if period:
                periods[_model.instance_path(obj).removeprefix(root)] = period
    return {
        process: {
            core: sum(
                (cet / periods[f"{process}.{t}"] for t, cet in cets.items() if f"{process}.{t}" in periods),
                Fraction(0),
            )
            for core, cets in per_core.items()
        }
        for process, per_core in times.items()
    }


def propose_binding(
    project: EObject,
    bound: BoundDeployment,
    instance: EObject,
    *,
    package_name: str | None = None,
    **search: Any,
) -> Proposal:
    """Search the cores of the deployment's robot for a binding of its nodes that passes the CPU
    load and schedulability checks (:func:`~rosaadl.analysis.deployment.search_deployment`, with
    each node's execution times on each core taken from its PDM for that core type), and bind
    the deployment to the cores found, in the package ``package_name`` (default
    ``<deployment>_proposed``).

    ``instance`` is the instance of ``bound`` (its model, which holds the library, is used to read
    the other PDMs); ``search`` passes keyword arguments to the search.
    """
    from rosaadl.analysis.deployment import search_deployment

    model = instance.eContainer()
    if model is None or model.eClass.name != "AadlModel":
        raise BindingError("the instance of the bound deployment is not in an AadlModel with the library")
    root = instance.name or ""
    times = _execution_times(project, bound, model)
    processes = [f"{root}.{node.process}" for node in bound.nodes]
    processors = [f"{root}.{_ROBOT}.{core.path}" for core in bound.cores]
    given_times = {
        f"{root}.{process}": {f"{root}.{_ROBOT}.{core}": cets for core, cets in per_core.items()}
        for process, per_core in times.items()
    }
    result = search_deployment(instance, processes, processors, execution_times=given_times, **search)
    prefix = f"{root}.{_ROBOT}."
    demands = _demands(instance, times)
    if not result.feasible:
        return Proposal(result, {}, None, demands)
    cores = {p.process.removeprefix(root + "."): p.processor.removeprefix(prefix) for p in result.placements}
    nodes = {
        node.spec.key: replace(node.spec, core=cores[node.process], library=node.library)
        for node in bound.nodes
    }
    name = package_name or f"{aadl_identifier(bound.name)}_proposed"
    proposed = bind_deployment(project, replace(bound.spec, nodes=nodes), model, package_name=name)
    return Proposal(result, cores, proposed, demands)
