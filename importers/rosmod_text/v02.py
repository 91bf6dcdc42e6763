"""ROSMOD v0.2 workspaces: packages of inline messages, services, components and nodes.

A v0.2 project has the v0.3 folders (or its three files side by side), but its ``.rml`` holds a
single workspace whose packages carry ``messages``, ``services``, ``components`` and ``nodes``
blocks; its hardware uses ``host`` blocks (read by :func:`.v03.read_hardware`, they have the
v0.3 body) and its deployments ``host_instance`` blocks. Mapping onto ``rosmod.ecore``:

* inline ``msg``/``srv`` fields (``type name;``, ``type NAME = value;``) are parsed as ROS
  message fields, and the definition is kept as ``.msg`` text;
* ``provides S;`` / ``requires S;`` become a server ``S_server`` / client ``S_client`` (the
  names ROSMOD v0.3 gave them when the AGSE project was upgraded);
* software nodes are kept as package properties ``node:<name>`` (JSON object instance →
  ``pkg/Component``); each ``node_instance`` of a ``host_instance`` becomes a deployment
  ``Node`` whose component instances resolution makes from that software node;
* ``host_instance`` properties are kept as deployment properties ``host_instance:<host>``.
"""

from __future__ import annotations

import json

from pyecore.ecore import EObject

from rosaadl.errors import NameResolutionError, ParseError
from rosaadl.importers import ros_msg
from rosaadl.importers.rosmod_text import v03
from rosaadl.importers.rosmod_text.blocks import Stmt, at
from rosaadl.importers.rosmod_text.context import ImportContext
from rosaadl.importers.rosmod_text.resolution import DeploymentInfo, Ref, SoftwareInfo, check_unique
from rosaadl.importers.rosmod_text.statements import (
    located,
    name_of,
    new,
    new_property,
    qualify,
    skip,
    typed_head,
)

__all__ = ["is_v02", "package", "host_instance"]

_LEGACY_BLOCKS = frozenset({"messages", "services", "components", "nodes"})


def is_v02(stmts: list[Stmt]) -> bool:
    """Does a software model have a package with v0.2 blocks (``messages``, ``components``, …)?"""
    for stmt in stmts:
        if stmt.keyword == "package" and stmt.body and any(c.keyword in _LEGACY_BLOCKS for c in stmt.body):
            return True
    return False


# --------------------------------------------------------------------------- software (.rml)


def package(stmt: Stmt, info: SoftwareInfo, ctx: ImportContext) -> EObject:
    """A v0.2 ``package`` block: its ``messages``, ``services``, ``components`` and ``nodes``."""
    filename = info.filename
    name = name_of(stmt, filename, "package")
    pkg = new("Package", **located({"name": name}, stmt))
    info.nodes[name] = {}
    for block in stmt.body or []:
        kw = block.keyword
        if block.body is None:
            skip(ctx, block, filename, f"package {name!r}")
            continue
        keyword, read = _BLOCKS.get(kw, (None, None))
        for item in block.body:
            try:
                if read is not None and item.keyword == keyword:
                    read(item, pkg, info, ctx)
                else:
                    skip(ctx, item, filename, f"package {name!r}", within=kw)
            except ParseError as exc:
                ctx.error(exc)
    return pkg


def _message(item: Stmt, pkg: EObject, info: SoftwareInfo, ctx: ImportContext) -> None:
    filename = info.filename
    msg_name = name_of(item, filename, "msg")
    specs, text = _fields(item.body or [], pkg.name, filename, ctx)
    msg = new("Message", **located({"name": msg_name, "definition": text}, item))
    msg.fields.extend(ros_msg.fields_to_model(specs))
    check_unique(msg.fields, "field", f"message {msg_name!r}", filename, ctx)
    pkg.messages.append(msg)


def _service(item: Stmt, pkg: EObject, info: SoftwareInfo, ctx: ImportContext) -> None:
    filename = info.filename
    srv_name = name_of(item, filename, "srv")
    request: list = []
    response: list = []
    texts = {"request": "", "response": ""}
    for part in item.body or []:
        if part.keyword in ("request", "response") and part.body is not None:
            specs, text = _fields(part.body, pkg.name, filename, ctx)
            (request if part.keyword == "request" else response).extend(specs)
            texts[part.keyword] = text
        else:
            skip(ctx, part, filename, f"srv {srv_name!r}")
    srv = new(
        "Service",
        **located({"name": srv_name, "definition": texts["request"] + "---\n" + texts["response"]}, item),
    )
    srv.requestFields.extend(ros_msg.fields_to_model(request))
    srv.responseFields.extend(ros_msg.fields_to_model(response))
    pkg.services.append(srv)


def _fields(stmts: list[Stmt], pkg_name: str, filename: str, ctx: ImportContext) -> tuple[list, str]:
    """Inline v0.2 fields (``type name;`` / ``type NAME = value;``) → (FieldSpecs, .msg text)."""
    specs: list[ros_msg.FieldSpec] = []
    lines: list[str] = []
    for item in stmts:
        if item.body is not None or len(item.head) < 2 or item.head[-1].kind != "word":
            ctx.error(
                ParseError(
                    f"malformed field {item.key!r}: expected '<type> <name>;'",
                    location=at(filename, item),
                )
            )
            continue
        type_text = "".join(t.text for t in item.head[:-1])
        line_text = f"{type_text} {item.head[-1].text}"
        if item.value is not None:
            line_text += f"={item.value_text}"
        try:
            spec = ros_msg.parse_field(
                line_text, package=pkg_name, filename=filename, line=item.line, column=item.column
            )
        except ParseError as exc:
            ctx.error(exc)
            continue
        if spec is not None:
            specs.append(spec)
            lines.append(line_text)
    return specs, "".join(line + "\n" for line in lines)


def _component(item: Stmt, pkg: EObject, info: SoftwareInfo, ctx: ImportContext) -> None:
    comp = new("Component", **located({"name": name_of(item, info.filename, "component")}, item))
    for sub in item.body or []:
        try:
            _component_item(sub, comp, pkg.name, info, ctx)
        except ParseError as exc:
            ctx.error(exc)
    pkg.components.append(comp)


def _component_item(item: Stmt, comp: EObject, pkg_name: str, info: SoftwareInfo, ctx: ImportContext) -> None:
    """``provides S;`` / ``requires S;``, or a timer or port statement as in v0.3."""
    kw = item.keyword
    if kw not in ("provides", "requires"):
        v03.component_item(item, comp, pkg_name, info, ctx)
        return
    service = name_of(item, info.filename, f"{kw} statement")
    cls, suffix = ("Server", "_server") if kw == "provides" else ("Client", "_client")
    port = new(cls, **located({"name": service + suffix, "type": qualify(service, pkg_name)}, item))
    comp.ports.append(port)
    kind = "server" if kw == "provides" else "client"
    info.port_sites.append((port, kind, service, item.head[1].line, item.head[1].column))


def _node(item: Stmt, pkg: EObject, info: SoftwareInfo, ctx: ImportContext) -> None:
    """A software node: its component instances, kept for the deployments (and as a property)."""
    filename = info.filename
    node_name = name_of(item, filename, "node")
    instances = []
    for sub in item.body or []:
        if sub.keyword != "component":
            skip(ctx, sub, filename, f"node {node_name!r}")
            continue
        comp_ref, inst, _ = typed_head(sub, filename, "component instance")
        instances.append((inst, comp_ref, sub))
    nodes = info.nodes[pkg.name]
    if node_name in nodes:
        ctx.error(
            NameResolutionError(
                f"duplicate node name {node_name!r} in package {pkg.name!r}",
                location=at(filename, item),
            )
        )
    nodes[node_name] = instances
    pkg.properties.append(
        new_property(
            f"node:{node_name}",
            json.dumps({inst: qualify(ref, pkg.name) for inst, ref, _ in instances}),
            item,
        )
    )


# the blocks of a v0.2 package: block keyword → (keyword of its items, reader of one item)
_BLOCKS = {
    "messages": ("msg", _message),
    "services": ("srv", _service),
    "components": ("component", _component),
    "nodes": ("node", _node),
}


# --------------------------------------------------------------------------- deployment (.rdp)


def host_instance(
    stmt: Stmt, deployment: EObject, shown: str, info: DeploymentInfo, ctx: ImportContext
) -> None:
    """A ``host_instance`` block: its properties and the ``node_instance`` nodes it runs."""
    host_name = name_of(stmt, shown, "host_instance")
    props: dict[str, str] = {}
    for item in stmt.body or []:
        if item.keyword == "properties" and item.body is not None:
            for setting in item.body:
                if setting.value is None:
                    skip(ctx, setting, shown, f"host_instance {host_name!r}")
                else:
                    props[setting.key] = setting.value_text
        elif item.keyword == "nodes" and item.body is not None:
            for sub in item.body:
                if sub.keyword != "node_instance" or sub.body is None:
                    skip(ctx, sub, shown, f"host_instance {host_name!r}")
                    continue
                deployment.nodes.append(_node_instance(sub, stmt, shown, info, ctx))
        else:
            skip(ctx, item, shown, f"host_instance {host_name!r}")
    deployment.properties.append(new_property(f"host_instance:{host_name}", json.dumps(props), stmt))


def _node_instance(stmt: Stmt, host: Stmt, shown: str, info: DeploymentInfo, ctx: ImportContext) -> EObject:
    """A ``node_instance`` on the host of ``host``; its ``reference`` names a software node."""
    host_name = host.head[1].text
    node = new("Node", **located({"name": name_of(stmt, shown, "node_instance"), "hostRef": host_name}, stmt))
    info.refs.append(Ref(node, host_name, host.head[1], "host"))
    reference = None
    for setting in stmt.body or []:
        if setting.value is None:
            skip(ctx, setting, shown, f"node_instance {node.name!r}")
        elif setting.key == "reference" and reference is None:
            reference = setting
        elif setting.key == "cmdline_arguments" and not node.eIsSet("arguments"):
            node.arguments = setting.value_text
        else:
            node.properties.append(new_property(setting.key, setting.value_text, setting))
    if reference is None:
        ctx.error(
            ParseError(
                f'node_instance {node.name!r} has no reference = "<package>/<node>";',
                location=at(shown, stmt),
            )
        )
    else:
        node.properties.insert(0, new_property("reference", reference.value_text, reference))
        info.refs.append(Ref(node, reference.value_text, reference.value_token, "node02"))
    return node
