"""ROSMOD v0.3 projects: the software, hardware and deployment statements of the textual tool.

A v0.3 project is a folder with a ``<name>.rosmod`` marker, ``01-Software/`` (one ``.rml`` file
and the side files ``msg/<pkg>.<Name>.msg``, ``srv/<pkg>.<Name>.srv``, ``abl/`` and ``pnp/``),
``02-Hardware/*.rhw`` (one ``System`` per file) and ``03-Deployment/*.rdp`` (one ``Deployment``
per file); :mod:`.project` walks that layout. This module reads the statements:

* ``package P { component C : Base { timer …; publisher <pkg/Msg> p; subscriber …; client …;
  server …; } }`` (:func:`package`); the timer and port statements are v0.2's too
  (:func:`component_item`);
* the side files of the software (:func:`load_interfaces`): ``.msg``/``.srv`` definitions of the
  ``.rml``'s packages (files of a package the ``.rml`` does not define are skipped with a
  warning, as ROSMOD itself did), ``.abl``/``.pnp`` kept as component properties
  ``abl:<port>``/``pnp:<port>``;
* a ``.rhw`` file (:func:`read_hardware`): ``hardware H { ip_address = …; … }`` blocks, and
  v0.2's ``host H { … }`` blocks, which have the same body. A host defined twice is a
  redefinition: ROSMOD resolves ``<hardware>/<host>`` to the later one, so the reader keeps that
  one and warns (an error with ``strict``);
* the ``node`` blocks of a ``.rdp`` file (:func:`node`) with their component and port instances.
"""

from __future__ import annotations

from pathlib import Path

from pyecore.ecore import EObject

from rosaadl.errors import ParseError
from rosaadl.importers import ros_msg
from rosaadl.importers.rosmod_text.blocks import Stmt, at, is_punct
from rosaadl.importers.rosmod_text.context import ImportContext
from rosaadl.importers.rosmod_text.files import read_text, shown_path, side_files
from rosaadl.importers.rosmod_text.resolution import DeploymentInfo, Ref, SoftwareInfo, check_unique
from rosaadl.importers.rosmod_text.statements import (
    SCHEMES,
    integer,
    located,
    name_of,
    new,
    new_property,
    qualify,
    scheme_literal,
    seconds,
    skip,
    typed_head,
)

__all__ = ["PORT_CLASSES", "package", "component_item", "load_interfaces", "read_hardware", "node"]

#: The port statements of a component and the ``rosmod`` class each makes.
PORT_CLASSES = {
    "publisher": "Publisher",
    "subscriber": "Subscriber",
    "client": "Client",
    "server": "Server",
}


# --------------------------------------------------------------------------- software (.rml)


def package(stmt: Stmt, info: SoftwareInfo, ctx: ImportContext) -> EObject:
    """A ``package`` block of components."""
    shown = info.filename
    pkg_name = name_of(stmt, shown, "package")
    pkg = new("Package", **located({"name": pkg_name}, stmt))
    for item in stmt.body or []:
        if item.keyword == "component" and item.body is not None:
            try:
                pkg.components.append(_component(item, pkg_name, info, ctx))
            except ParseError as exc:
                ctx.error(exc)
        else:
            skip(ctx, item, shown, f"package {pkg_name!r}")
    return pkg


def _component(stmt: Stmt, pkg_name: str, info: SoftwareInfo, ctx: ImportContext) -> EObject:
    filename = info.filename
    head = stmt.head
    if len(head) < 2 or head[1].kind != "word":
        raise ParseError(
            f"malformed component: expected 'component <name> : <datatype>' (found {stmt.key!r})",
            location=at(filename, stmt),
        )
    datatype = None
    if len(head) >= 4 and is_punct(head[2], ":") and head[3].kind == "word" and len(head) == 4:
        datatype = head[3].text
    elif len(head) != 2:
        raise ParseError(
            f"malformed component: expected 'component <name> : <datatype>' (found {stmt.key!r})",
            location=at(filename, stmt),
        )
    comp = new("Component", **located({"name": head[1].text, "datatype": datatype}, stmt))
    for item in stmt.body or []:
        try:
            component_item(item, comp, pkg_name, info, ctx)
        except ParseError as exc:
            ctx.error(exc)
    return comp


def component_item(item: Stmt, comp: EObject, pkg_name: str, info: SoftwareInfo, ctx: ImportContext) -> None:
    """One statement of a component's body: a timer or a port (v0.2 components have them too)."""
    filename = info.filename
    kw = item.keyword
    if kw == "timer" and item.body is not None:
        comp.timers.append(_timer(item, filename, ctx, comp))
    elif kw in PORT_CLASSES:
        ref, name, _tok = typed_head(item, filename, kw)
        type_name = qualify(ref, pkg_name)
        port = new(PORT_CLASSES[kw], **located({"name": name, "type": type_name}, item))
        if item.body is not None:
            _callback_settings(port, item, filename, ctx, comp)
        comp.ports.append(port)
        info.port_sites.append((port, kw, ref, item.head[2].line, item.head[2].column))
    else:
        skip(ctx, item, filename, f"component {comp.name!r}")


def _timer(stmt: Stmt, filename: str, ctx: ImportContext, comp: EObject) -> EObject:
    name = name_of(stmt, filename, "timer")
    timer = new("Timer", **located({"name": name}, stmt))
    for item in stmt.body or []:
        try:
            if item.value is None:
                raise ParseError(
                    f"unexpected {item.key!r} in timer {name!r} (expected period/priority/deadline = value;)",
                    location=at(filename, item),
                )
            if item.key == "period":
                timer.period = seconds(item, filename)
            elif item.key == "deadline":
                timer.deadline = seconds(item, filename)
            elif item.key == "priority":
                timer.priority = integer(item, filename, ctx)
            else:
                ctx.warn(
                    f"timer {name!r}: unknown setting {item.key!r} kept as a component property",
                    filename,
                    item.line,
                    item.column,
                )
                comp.properties.append(new_property(f"{name}.{item.key}", item.value_text, item))
        except ParseError as exc:
            ctx.error(exc)
    return timer


def _callback_settings(port: EObject, stmt: Stmt, filename: str, ctx: ImportContext, comp: EObject) -> None:
    for item in stmt.body or []:
        try:
            if item.value is None:
                raise ParseError(
                    f"unexpected {item.key!r} in {stmt.keyword} {port.name!r} "
                    "(expected priority/deadline = value;)",
                    location=at(filename, item),
                )
            if item.key == "priority" and port.eClass.findEStructuralFeature("priority") is not None:
                port.priority = integer(item, filename, ctx)
            elif item.key == "deadline" and port.eClass.findEStructuralFeature("deadline") is not None:
                port.deadline = seconds(item, filename)
            else:
                ctx.warn(
                    f"{stmt.keyword} {port.name!r}: unknown setting {item.key!r} kept as a component "
                    "property",
                    filename,
                    item.line,
                    item.column,
                )
                comp.properties.append(new_property(f"{port.name}.{item.key}", item.value_text, item))
        except ParseError as exc:
            ctx.error(exc)


# --------------------------------------------------------------------------- side files of the software


def load_interfaces(
    software: EObject, sw_dir: Path, root: Path, shown_root: str, info: SoftwareInfo, ctx: ImportContext
) -> None:
    """The ``msg/``, ``srv/``, ``abl/`` and ``pnp/`` side files in ``sw_dir``, beside the ``.rml``."""
    packages = {p.name: p for p in software.packages}
    for kind, suffix in (("msg", ".msg"), ("srv", ".srv")):
        for path in side_files(sw_dir / kind, suffix):
            shown = shown_path(shown_root, path.relative_to(root))
            parts = path.name[: -len(suffix)].split(".")
            if len(parts) != 2 or not all(parts):
                ctx.warn(f"skipped {path.name!r}: expected a file name <package>.<Name>{suffix}", shown)
                continue
            pkg_name, name = parts
            package = packages.get(pkg_name)
            if package is None:
                ctx.warn(
                    f"skipped {path.name!r}: package {pkg_name!r} is not defined in the software model",
                    shown,
                )
                continue
            try:
                text = read_text(path, shown)
            except ParseError as exc:
                ctx.error(exc)
                continue
            # the type is declared even when its definition has errors (no cascade of
            # "unknown type" errors for the ports that use it)
            if kind == "msg":
                obj = new("Message", name=name, definition=text)
                package.messages.append(obj)
            else:
                obj = new("Service", name=name, definition=text)
                package.services.append(obj)
            info.sources[id(obj)] = shown
            try:
                fill = ros_msg.fill_message if kind == "msg" else ros_msg.fill_service
                fill(obj, package=pkg_name, filename=shown)
            except ParseError as exc:
                ctx.error(exc)
    for kind in ("abl", "pnp"):
        for path in side_files(sw_dir / kind, "." + kind):
            shown = shown_path(shown_root, path.relative_to(root))
            parts = path.name[: -len(kind) - 1].split(".")
            target = None
            if len(parts) == 3:
                package = packages.get(parts[0])
                comp = next((c for c in package.components if c.name == parts[1]), None) if package else None
                if comp is not None and any(x.name == parts[2] for x in [*comp.timers, *comp.ports]):
                    target = comp
            if target is None:
                ctx.warn(
                    f"skipped {path.name!r}: no port or timer <package>.<component>.<port> of that name",
                    shown,
                )
                continue
            try:
                target.properties.append(new_property(f"{kind}:{parts[2]}", read_text(path, shown)))
            except ParseError as exc:
                ctx.error(exc)


# --------------------------------------------------------------------------- hardware (.rhw)


# the settings of a host that have a slot in rosmod.Host (the others become properties)
_HOST_KEYS = {
    "ip_address": "ipAddress",
    "username": "username",
    "sshkey": "sshKey",
    "deployment_path": "deploymentPath",
    "install_path": "installPath",
    "arch": "architecture",
    "architecture": "architecture",
    "os": "os",
}


def read_hardware(stmts: list[Stmt], name: str, rel: str, shown: str, ctx: ImportContext) -> EObject:
    """The ``System`` of one ``.rhw`` file (``name``: the file's stem; ``rel``: its path in the project)."""
    system = new("System", name=name, sourceFile=rel)
    for stmt in stmts:
        try:
            if stmt.keyword in ("hardware", "host") and stmt.body is not None:
                host = new("Host", **located({"name": name_of(stmt, shown, stmt.keyword)}, stmt))
                for item in stmt.body:
                    if item.value is None:
                        skip(ctx, item, shown, f"host {host.name!r}")
                        continue
                    attr = _HOST_KEYS.get(item.key)
                    if attr is not None and not host.eIsSet(attr):
                        setattr(host, attr, item.value_text)
                    else:
                        host.properties.append(new_property(item.key, item.value_text, item))
                system.hosts.append(host)
            else:
                skip(ctx, stmt, shown)
        except ParseError as exc:
            ctx.error(exc)
    if ctx.strict:
        check_unique(system.hosts, "host", f"hardware model {name!r}", shown, ctx)
    else:
        # ROSMOD resolves '<hardware>/<host>' to the last definition of a host name: a repeated
        # host is a redefinition (real projects have them); keep the last one and say so.
        last: dict[str, EObject] = {h.name: h for h in system.hosts}
        for host in list(system.hosts):
            if last[host.name] is not host:
                later = last[host.name]
                ctx.warn(
                    f"host {host.name!r} is defined again at line {later.line}; the later definition "
                    "replaces this one (as in ROSMOD)",
                    shown,
                    host.line,
                    host.column,
                )
                system.hosts.remove(host)
    return system


# --------------------------------------------------------------------------- deployment (.rdp)


def _logging(block: Stmt, inst: EObject, shown: str, ctx: ImportContext) -> None:
    for item in block.body or []:
        if item.value is None:
            skip(ctx, item, shown, "logging")
            continue
        inst.logging.append(new_property(item.key, item.value_text, item))


def _component_instance(stmt: Stmt, shown: str, info: DeploymentInfo, ctx: ImportContext) -> EObject:
    inst = new("ComponentInstance", **located({"name": name_of(stmt, shown, "component_instance")}, stmt))
    for item in stmt.body or []:
        if item.keyword == "properties" and item.body is not None:
            for setting in item.body:
                if setting.keyword == "logging" and setting.body is not None:
                    _logging(setting, inst, shown, ctx)
                elif setting.value is None:
                    skip(ctx, setting, shown, f"component_instance {inst.name!r}")
                elif setting.key == "ref" and not inst.eIsSet("componentRef"):
                    inst.componentRef = setting.value_text
                    info.refs.append(Ref(inst, setting.value_text, setting.value_token, "component"))
                elif setting.key == "scheduling_scheme" and not inst.eIsSet("schedulingScheme"):
                    scheme = setting.value_text
                    if scheme in SCHEMES:
                        inst.schedulingScheme = scheme_literal(scheme)
                    else:
                        ctx.warn(
                            f"component_instance {inst.name!r}: unknown scheduling scheme {scheme!r} "
                            f"(expected {', '.join(SCHEMES)}); kept as a property",
                            shown,
                            setting.value_token.line,
                            setting.value_token.column,
                        )
                        inst.properties.append(new_property(setting.key, scheme, setting))
                else:
                    inst.properties.append(new_property(setting.key, setting.value_text, setting))
        elif item.keyword == "port_instance" and item.body is not None:
            port = new("PortInstance", **located({"name": name_of(item, shown, "port_instance")}, item))
            for setting in item.body:
                if setting.key == "ref" and setting.value is not None:
                    port.port = setting.value_text
                    info.refs.append(Ref(port, setting.value_text, setting.value_token, "port", extra=inst))
                elif setting.key == "group" and setting.value is not None:
                    port.group = setting.value_text
                else:
                    skip(ctx, setting, shown, f"port_instance {port.name!r}")
            inst.portInstances.append(port)
        else:
            skip(ctx, item, shown, f"component_instance {inst.name!r}")
    if inst.componentRef is None:
        ctx.error(
            ParseError(
                f'component_instance {inst.name!r} has no ref = "<package>/<component>";',
                location=at(shown, stmt),
            )
        )
    check_unique(inst.portInstances, "port_instance", f"component_instance {inst.name!r}", shown, ctx)
    return inst


def node(stmt: Stmt, shown: str, info: DeploymentInfo, ctx: ImportContext) -> EObject:
    """A ``node`` block of a ``.rdp`` file: its properties and component instances.

    Its properties give the host (``ref = "<hardware>/<host>"``), ``priority`` and ``cmd_args``;
    other properties are kept as they are.
    """
    node = new("Node", **located({"name": name_of(stmt, shown, "node")}, stmt))
    for item in stmt.body or []:
        try:
            if item.keyword == "properties" and item.body is not None:
                for setting in item.body:
                    if setting.value is None:
                        skip(ctx, setting, shown, f"node {node.name!r}")
                    elif setting.key == "ref" and not node.eIsSet("hostRef"):
                        node.hostRef = setting.value_text
                        info.refs.append(Ref(node, setting.value_text, setting.value_token, "host"))
                    elif setting.key == "priority" and not node.eIsSet("priority"):
                        node.priority = integer(setting, shown, ctx)
                    elif setting.key == "cmd_args" and not node.eIsSet("arguments"):
                        node.arguments = setting.value_text
                    else:
                        node.properties.append(new_property(setting.key, setting.value_text, setting))
            elif item.keyword == "component_instance" and item.body is not None:
                node.componentInstances.append(_component_instance(item, shown, info, ctx))
            else:
                skip(ctx, item, shown, f"node {node.name!r}")
        except ParseError as exc:
            ctx.error(exc)
    if node.hostRef is None:
        ctx.error(
            ParseError(
                f'node {node.name!r} has no ref = "<hardware>/<host>"; in its properties',
                location=at(shown, stmt),
            )
        )
    check_unique(node.componentInstances, "component_instance", f"node {node.name!r}", shown, ctx)
    return node
