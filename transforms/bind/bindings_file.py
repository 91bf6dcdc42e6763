"""The bindings file: which robot each ROSMOD deployment runs on, and which library node and core
each of its nodes is bound to.

:func:`parse_bindings` reads the JSON text (``docs/workflow.md`` gives the format) into a
:class:`BindingsFile` of :class:`DeploymentSpec` s, each member remembering where it is written
(file, line and path, such as ``deployments.pioneer_3dx.nodes.usb_cam_node.core``), so that
every problem found when binding is a :class:`BindingError` located at its entry. Reading the
file is the workflow's (:func:`rosaadl.workflow.binding.read_bindings`).
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from rosaadl.errors import Location, ParseError, TransformationError

__all__ = [
    "BINDINGS_VERSION",
    "MAX_BINDINGS_BYTES",
    "ROS_BUS",
    "BindingError",
    "BindingsFile",
    "DeploymentSpec",
    "NodeSpec",
    "RobotLink",
    "fail",
    "parse_bindings",
]

#: The version of the bindings file format this module reads.
BINDINGS_VERSION = 1
#: Larger bindings files are refused (a real one is a few kilobytes).
MAX_BINDINGS_BYTES = 1 << 20
#: What ``topic_bus`` names for the ROS virtual bus (its default).
ROS_BUS = "ros::ROSbus"

_DEPLOYMENT_KEYS = {"robot", "topic_bus", "nodes", "robot_connections"}
_NODE_KEYS = {"library", "core", "ports"}
_LINK_KEYS = {"node", "port", "robot_port", "bus"}


class BindingError(TransformationError):
    """The bindings file and the project or the library do not agree (located at the entry)."""

    stage = "bind"


def fail(where: Location, message: str) -> BindingError:
    """The error of an entry of the bindings file."""
    return BindingError(message, where)


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
