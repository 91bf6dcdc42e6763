"""ROSMOD v0.4 ``.rml`` files: the jsonpickle JSON of ROSMOD's Python tool, read without unpickling.

The file is one ``__main__.Project`` object whose ``children`` are the ``Software`` (packages →
messages, services, components → timers and ports), ``Hardware`` (computers) and ``Deployment``
(nodes → component instances) objects; each object's ``attributes`` are a pickled ordered dict
(``__reduce__`` pairs). jsonpickle writes an object seen before as ``{"py/id": N}``, N counting
objects and lists in document order; which lists count depends on the jsonpickle version, so the
reader takes the numbering that agrees with every ``parent`` link of the file
(:func:`_object_ids`). References (a port's message, a node's computer, an instance's
component, a deployment's hardware) are set once every object exists. The ``business_logic`` of
a timer is kept as the component property ``abl:<timer>``.
"""

from __future__ import annotations

import json
from decimal import Decimal, InvalidOperation
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import NameResolutionError, ParseError
from rosaadl.fileio import JsonLimitError, loads_bounded
from rosaadl.importers import ros_msg
from rosaadl.importers.rosmod_text.context import ImportContext
from rosaadl.importers.rosmod_text.statements import (
    MAX_INTEGER,
    SCHEMES,
    new,
    new_property,
    scheme_literal,
    time_problem,
)

__all__ = ["looks_like_json", "read_v04"]

_PATH = "Project"  # the root of the element paths in messages
# the references set at the end: feature → the rosmod class it must name
_TARGETS = {"system": "rosmod.System", "host": "rosmod.Host", "component": "rosmod.Component"}


def looks_like_json(text: str) -> bool:
    """Is a ``.rml`` text the v0.4 JSON (rather than ROSMOD block text)?"""
    return text.lstrip().startswith("{")


def read_v04(text: str, shown: str, rel: str, project: EObject, ctx: ImportContext) -> None:
    """Fill ``project`` from the v0.4 file ``text`` (named ``shown``; ``rel`` is its project path)."""
    try:
        data = loads_bounded(text)
    except json.JSONDecodeError as exc:
        raise ParseError(
            f"malformed JSON: {exc.msg}", file=shown, line=exc.lineno, column=exc.colno
        ) from None
    except JsonLimitError as exc:
        raise ParseError(str(exc), file=shown) from None
    if _kind(data) != "Project":
        raise ParseError("expected a ROSMOD v0.4 project (a jsonpickle __main__.Project object)", file=shown)
    _Reader(_object_ids(data, shown), shown, rel, ctx).project(data, project)


# --------------------------------------------------------------------------- jsonpickle


def _object_ids(data: Any, shown: str) -> dict[int, Any]:
    """jsonpickle's ids of the file: the numbering that agrees with every 'parent' link."""
    anchors: list[tuple[int, dict]] = []
    stack = [data]
    while stack:
        element = stack.pop()
        for child in _children(element):
            if isinstance(child, dict) and "py/object" in child:
                parent = child.get("parent")
                if isinstance(parent, dict) and isinstance(parent.get("py/id"), int):
                    anchors.append((parent["py/id"], element))
                stack.append(child)
    for excluded in (
        frozenset({"__reduce__", "py/seq", "_inner"}),
        frozenset({"__reduce__", "py/seq", "_allowed"}),
    ):
        candidate = _id_map(data, excluded)
        if all(candidate.get(k) is e for k, e in anchors):
            return candidate
    raise ParseError("cannot resolve the jsonpickle object references (py/id) of this file", file=shown)


def _id_map(data: Any, excluded_lists: frozenset[str]) -> dict[int, Any]:
    """jsonpickle's object ids (pre-order: instances and lists, minus some list contexts)."""
    ids: dict[int, Any] = {}
    counter = 0
    stack: list[tuple[Any, str | None]] = [(data, None)]
    while stack:
        value, ctx_key = stack.pop()
        if isinstance(value, dict):
            if "py/id" in value or "py/type" in value:
                continue
            if "py/object" in value:
                ids[counter] = value
                counter += 1
            children = [(v, k) for k, v in value.items()]
            stack.extend(reversed(children))
        elif isinstance(value, list):
            if ctx_key not in excluded_lists:
                ids[counter] = value
                counter += 1
            stack.extend(reversed([(v, None) for v in value]))
    return ids


def _attrs(element: Any) -> dict[str, Any]:
    """The attributes of a jsonpickle object (none for anything that is not one)."""
    attrs = element.get("attributes") if isinstance(element, dict) else None
    pairs: list = []
    if isinstance(attrs, dict):
        reduce = attrs.get("__reduce__")
        if isinstance(reduce, list) and len(reduce) >= 2 and isinstance(reduce[1], dict):
            tup = reduce[1].get("py/tuple")
            if isinstance(tup, list) and tup and isinstance(tup[0], list):
                pairs = tup[0]
    out: dict[str, Any] = {}
    for pair in pairs:
        if isinstance(pair, list) and len(pair) == 2 and isinstance(pair[0], str):
            out[pair[0]] = pair[1]
    return out


def _children(element: Any) -> list:
    """The children of a jsonpickle object (none for anything that is not one)."""
    children = element.get("children") if isinstance(element, dict) else None
    if isinstance(children, dict) and isinstance(children.get("_inner"), list):
        return children["_inner"]
    return []


def _kind(value: Any) -> str | None:
    if isinstance(value, dict) and isinstance(value.get("py/object"), str):
        return value["py/object"].rpartition(".")[2]
    return None


def _text(value: Any) -> str | None:
    return None if value is None else str(value)


# --------------------------------------------------------------------------- the model


class _Reader:
    """One file's objects by id, the model objects made from them, and the references to set."""

    def __init__(self, ids: dict[int, Any], shown: str, rel: str, ctx: ImportContext) -> None:
        self.ids = ids
        self.shown = shown
        self.rel = rel
        self.ctx = ctx
        self.made: dict[int, EObject] = {}  # id() of a JSON object → its model object
        self.pending: list[tuple[EObject, str, Any, str]] = []  # (object, feature, reference, path)

    # -- values
    def deref(self, value: Any) -> Any:
        if isinstance(value, dict) and "py/id" in value:
            return self.ids.get(value["py/id"]) if isinstance(value["py/id"], int) else None
        return value

    def attr(self, element: dict, key: str) -> Any:
        value = self.deref(_attrs(element).get(key))
        if isinstance(value, dict) and "value" in value and "py/object" in value:
            return self.deref(value["value"])
        return value

    def name(self, element: dict) -> str | None:
        return _text(self.attr(element, "name"))

    def seconds(self, value: Any, where: str) -> Decimal | None:
        if value in (None, ""):
            return None
        try:
            number = Decimal(str(value))
        except InvalidOperation:
            problem = "expected a number of seconds"
        else:
            problem = time_problem(number)
            if problem is None:
                return number
        self.ctx.error(ParseError(f"{where}: {problem}, found {value!r}", file=self.shown, path=where))
        return None

    def integer(self, value: Any, where: str) -> int | None:
        if value in (None, ""):
            return None
        try:
            number = Decimal(str(value))
        except InvalidOperation:
            number = None
        if number is not None and number.is_finite() and abs(number) <= MAX_INTEGER:
            return int(number)
        self.ctx.error(
            ParseError(f"{where}: expected an integer, found {value!r}", file=self.shown, path=where)
        )
        return None

    # -- elements
    def project(self, data: dict, project: EObject) -> None:
        project.name = self.name(data) or project.name
        for top in _children(data):
            top = self.deref(top)
            kind = _kind(top)
            if kind == "Software":
                self.software(top, project)
            elif kind == "Hardware":
                self.hardware(top, project)
            elif kind == "Deployment":
                self.deployment(top, project)
            else:
                self.ctx.warn(f"unknown v0.4 element {kind!r} skipped", self.shown)
        self.references()

    def software(self, top: dict, project: EObject) -> None:
        software = new("Software", name=self.name(top), sourceFile=self.rel)
        project.software = software
        for pkg_el in map(self.deref, _children(top)):
            pkg = new("Package", name=self.name(pkg_el))
            software.packages.append(pkg)
            for el in map(self.deref, _children(pkg_el)):
                k = _kind(el)
                where = f"{_PATH}/{pkg.name}/{self.name(el)}"
                if k == "Message":
                    pkg.messages.append(self.interface(el, "Message", ros_msg.fill_message, pkg.name, where))
                elif k == "Service":
                    pkg.services.append(self.interface(el, "Service", ros_msg.fill_service, pkg.name, where))
                elif k == "Component":
                    pkg.components.append(self.component(el, where))
                else:
                    self.ctx.warn(f"{where}: unknown v0.4 element {k!r} skipped", self.shown)

    def interface(self, el: dict, class_name: str, fill: Any, package: str, where: str) -> EObject:
        """A message or a service, its ``definition`` parsed by ``fill``."""
        obj = new(class_name, name=self.name(el), definition=_text(self.attr(el, "definition")))
        try:
            fill(obj, package=package, filename=self.shown, path=where)
        except ros_msg.RosMessageError as exc:
            self.ctx.error(exc)
        return obj

    def component(self, el: dict, where: str) -> EObject:
        comp = new("Component", name=self.name(el), datatype=_text(self.attr(el, "type")))
        self.made[id(el)] = comp
        for sub in map(self.deref, _children(el)):
            sk = _kind(sub)
            sub_where = f"{where}/{self.name(sub)}"
            if sk == "Timer":
                comp.timers.append(
                    new(
                        "Timer",
                        name=self.name(sub),
                        period=self.seconds(self.attr(sub, "period"), sub_where),
                        priority=self.integer(self.attr(sub, "priority"), sub_where),
                        deadline=self.seconds(self.attr(sub, "deadline"), sub_where),
                    )
                )
                logic = self.attr(sub, "business_logic")
                if logic:
                    comp.properties.append(new_property(f"abl:{self.attr(sub, 'name')}", str(logic)))
            elif sk in ("Publisher", "Subscriber", "Client", "Server"):
                port = new(sk, name=self.name(sub))
                if sk in ("Subscriber", "Server"):
                    port.priority = self.integer(self.attr(sub, "priority"), sub_where)
                    port.deadline = self.seconds(self.attr(sub, "deadline"), sub_where)
                ref_key = "message_reference" if sk in ("Publisher", "Subscriber") else "service_reference"
                self.pending.append((port, "type", _attrs(sub).get(ref_key), sub_where))
                comp.ports.append(port)
            else:
                self.ctx.warn(f"{sub_where}: unknown v0.4 element {sk!r} skipped", self.shown)
        return comp

    def hardware(self, top: dict, project: EObject) -> None:
        system = new("System", name=self.name(top), sourceFile=self.rel)
        self.made[id(top)] = system
        project.systems.append(system)
        for el in map(self.deref, _children(top)):
            host = new(
                "Host",
                name=self.name(el),
                ipAddress=_text(self.attr(el, "ip_address")),
                username=_text(self.attr(el, "username")),
                sshKey=_text(self.attr(el, "sshkey")),
                deploymentPath=_text(self.attr(el, "deployment_path")),
                installPath=_text(self.attr(el, "install_path")),
                architecture=_text(self.attr(el, "arch")),
            )
            profile = self.attr(el, "network_profile")
            if profile:
                host.properties.append(new_property("network_profile", str(profile)))
            self.made[id(el)] = host
            system.hosts.append(host)

    def deployment(self, top: dict, project: EObject) -> None:
        dep = new("Deployment", name=self.name(top), sourceFile=self.rel)
        project.deployments.append(dep)
        where = f"{_PATH}/{dep.name}"
        self.pending.append((dep, "system", _attrs(top).get("hardware_reference"), where))
        for el in map(self.deref, _children(top)):
            node = new(
                "Node",
                name=self.name(el),
                priority=self.integer(self.attr(el, "priority"), where),
                arguments=_text(self.attr(el, "cmd_args")) or None,
            )
            dpath = self.attr(el, "deployment_path")
            if dpath:
                node.properties.append(new_property("deployment_path", str(dpath)))
            dep.nodes.append(node)
            self.pending.append((node, "host", _attrs(el).get("computer_reference"), f"{where}/{node.name}"))
            for sub in map(self.deref, _children(el)):
                node.componentInstances.append(self.instance(sub, f"{where}/{node.name}"))

    def instance(self, sub: dict, where: str) -> EObject:
        inst = new("ComponentInstance", name=self.name(sub))
        scheme = self.attr(sub, "scheduling_scheme")
        if scheme in SCHEMES:
            inst.schedulingScheme = scheme_literal(scheme)
        elif scheme:
            inst.properties.append(new_property("scheduling_scheme", str(scheme)))
        logging_value = self.attr(sub, "logging")
        if isinstance(logging_value, dict):
            for key in sorted(logging_value):
                inst.logging.append(new_property(key, str(logging_value[key]).lower()))
        self.pending.append(
            (inst, "component", _attrs(sub).get("component_reference"), f"{where}/{inst.name}")
        )
        return inst

    def references(self) -> None:
        """Set every noted reference, now that each object it can name exists."""
        for obj, feature, raw, where in self.pending:
            holder = self.deref(raw)
            target_el = (
                self.deref(holder.get("value")) if isinstance(holder, dict) and "value" in holder else None
            )
            if target_el is None:
                if feature in ("host", "component"):
                    self.ctx.error(
                        NameResolutionError(
                            f"{where}: the {feature} reference is missing", file=self.shown, path=where
                        )
                    )
                continue
            if feature == "type":
                name = self.attr(target_el, "name")
                pkg_el = self.deref(target_el.get("parent")) if isinstance(target_el, dict) else None
                pkg_name = self.attr(pkg_el, "name") if isinstance(pkg_el, dict) else None
                obj.type = f"{pkg_name}/{name}" if pkg_name else str(name)
                continue
            target = self.made.get(id(target_el))
            expected = _TARGETS[feature]
            if target is None or not model.is_a(target, expected):
                self.ctx.error(
                    NameResolutionError(
                        f"{where}: the {feature} reference does not name a "
                        f"{expected.rpartition('.')[2].lower()}",
                        file=self.shown,
                        path=where,
                    )
                )
                continue
            setattr(obj, feature, target)
            if feature == "system":
                obj.systemName = target.name
            elif feature == "host":
                system = target.eContainer()
                obj.hostRef = f"{system.name}/{target.name}"
            elif feature == "component":
                obj.componentRef = f"{target.eContainer().name}/{target.name}"
