"""The ``Software`` of a WebGME ROSMOD project → ``rosmod.Software``: packages, messages, components.

A message's or service's ``Definition`` is parsed as ROS ``.msg``/``.srv`` text; components
get their timers, publishers, subscribers, clients and servers. ``External Message``/``Service``
are not project types: ports that use them get ``<Package>/<name>``. Actions, action clients
and servers, state machines and constraints become ``Action:``/``Action Client:``/``Action
Server:``/``State Machine:``/``Constraint:`` properties; libraries become project properties.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import ImportFormatError, Location
from rosaadl.importers import ros_msg
from rosaadl.importers.rosmod_webgme.mapping import SKIPPED_KINDS, Mapper, text, type_name
from rosaadl.importers.rosmod_webgme.tree import Node

__all__ = ["software"]

_LIBRARY_KINDS = ("System Library", "Source Library", "Development Library", "Library")
# the attributes of each child of a component that have a slot in its rosmod class
_SLOTS = {
    "Timer": ("Period", "Priority", "Deadline", "Operation"),
    "Publisher": ("Latching",),
    "Subscriber": ("Priority", "Deadline", "Operation"),
    "Server": ("Priority", "Deadline", "Operation"),
    "Client": (),
}
# the pointer that gives each kind of port its type
_TYPE_POINTER = {
    "Publisher": "Message",
    "Subscriber": "Message",
    "Client": "Service",
    "Server": "Service",
}


def software(m: Mapper, node: Node, software: EObject, project: EObject) -> None:
    """Add the packages of the Software folder ``node`` to ``software`` (libraries to ``project``)."""
    for child in m.children(node):
        kind = child.meta_type
        if kind == "Package":
            software.packages.append(_package(m, child))
        elif kind in _LIBRARY_KINDS:
            project.properties.append(m.prop(f"{kind}:{child.name}", m.opaque(child)))
        elif kind == "External Definitions":
            for ext in m.children(child):
                project.properties.append(
                    m.prop(f"{ext.meta_type}:{ext.name}", json.dumps({"Type": type_name(ext)}))
                )
        elif kind not in SKIPPED_KINDS:
            m.unknown(node, child, project.properties)
    for package in software.packages:
        m.warn_duplicates(node, package.messages, "message", repr(package.name))
        m.warn_duplicates(node, package.services, "service", repr(package.name))
        m.warn_duplicates(node, package.components, "component", repr(package.name))
    m.warn_duplicates(node, software.packages, "package", repr(node.name))


def _package(m: Mapper, node: Node) -> EObject:
    package = model.new("rosmod.Package", name=node.name)
    m.by_path[node.path] = package
    for key, value in node.project_attributes().items():
        package.properties.append(m.prop(key, value))
    for child in m.children(node):
        kind = child.meta_type
        if kind == "Message":
            package.messages.append(_interface(m, child, "rosmod.Message", ros_msg.fill_message, node.name))
        elif kind == "Service":
            package.services.append(_interface(m, child, "rosmod.Service", ros_msg.fill_service, node.name))
        elif kind == "Component":
            package.components.append(_component(m, child))
        elif kind in ("Action", "Advertised Message", "Advertised Service", "Advertised Action"):
            package.properties.append(m.prop(f"{kind}:{child.name}", m.opaque(child)))
        elif kind not in SKIPPED_KINDS:
            m.unknown(node, child, package.properties)
    return package


def _interface(m: Mapper, node: Node, class_name: str, fill: Callable[..., Any], package: str) -> EObject:
    """A message or a service, its ``Definition`` parsed by ``fill`` (errors located at ``node``)."""
    obj = model.new(class_name, name=node.name, definition=text(node.attribute("Definition")))
    try:
        fill(obj, package=package)
    except ros_msg.RosMessageError as exc:
        for err in exc.errors:
            loc = err.location
            m.ctx.error(
                ImportFormatError(
                    f"Definition: {err.message}",
                    Location(file=m.filename, line=loc.line, column=loc.column, path=node.element_path()),
                )
            )
    m.by_path[node.path] = obj
    return obj


def _set(obj: EObject, **values: Any) -> None:
    """Set the features whose value is not None (unset features keep the metamodel default)."""
    for key, value in values.items():
        if value is not None:
            setattr(obj, key, value)


def _component(m: Mapper, node: Node) -> EObject:
    comp = model.new("rosmod.Component", name=node.name)
    m.by_path[node.path] = comp
    m.scheme(node, comp, node.attribute("SchedulingScheme"))
    for key, value in node.project_attributes().items():
        if key != "SchedulingScheme":
            comp.properties.append(m.prop(key, value))
    libraries = node.set_members("Libraries")
    if libraries:
        comp.properties.append(m.prop("Libraries", ", ".join(sorted(lib.name for lib in libraries))))
    for child in m.children(node):
        kind = child.meta_type
        if kind == "Timer":
            timer = model.new(
                "rosmod.Timer",
                name=child.name,
                period=m.seconds(child, "Period"),
                priority=m.integer(child, "Priority"),
                deadline=m.seconds(child, "Deadline"),
                operation=text(child.attribute("Operation")) or None,
            )
            comp.timers.append(timer)
            m.by_path[child.path] = timer
        elif kind in _TYPE_POINTER:
            comp.ports.append(_port(m, child, kind, comp))
        elif kind in SKIPPED_KINDS:
            continue
        else:
            comp.properties.append(m.prop(f"{kind}:{child.name}", m.opaque(child)))
            continue
        for key, value in child.project_attributes().items():
            if key not in _SLOTS.get(kind, ()):
                comp.properties.append(m.prop(f"{child.name}.{key}", value))
    return comp


def _port(m: Mapper, child: Node, kind: str, comp: EObject) -> EObject:
    port = model.new(f"rosmod.{kind}", name=child.name)
    target = child.pointer(_TYPE_POINTER[kind])
    _set(port, type=type_name(target) if target is not None else None)
    if port.type is None:
        m.warn(child, f"{kind} {child.name!r} has no {_TYPE_POINTER[kind].lower()} type")
    if target is not None and target.meta_type.startswith("Advertised "):
        comp.properties.append(m.prop(f"{child.name}.Topic", f"{target.parent.name}/{target.name}"))
    if kind in ("Subscriber", "Server"):
        _set(
            port,
            priority=m.integer(child, "Priority"),
            deadline=m.seconds(child, "Deadline"),
            operation=text(child.attribute("Operation")) or None,
        )
    if kind == "Publisher":
        latching = child.attribute("Latching")
        _set(port, latching=None if latching is None else latching in (True, "true", "True"))
    m.by_path[child.path] = port
    return port
