"""Port groups written as top-level ``group`` blocks of a deployment (``.rdp``).

A ROSMOD group names the port instances that talk to each other, so that two instances of one
publisher each reach only their own subscribers. Two forms are written:

* inside a port instance, ``port_instance p { ref = "<component>/<port>"; group = "G"; }``
  (ROSMOD v0.3's ``ROSMOD_Deployment.g4``; read by :func:`.v03.node`);
* a top-level block after the nodes or host instances, one port path per line and no separator
  (ROSMOD's v0.2 ``Deployment.g4``, ``group: 'group' group_id '{' (port)+ '}'``, written by its
  ``rdp.tmpl``; the orbiter projects of ROSMOD's v0.3-era samples have them)::

      group G
      {
          <node>/<component instance>/<port>
      }

  ROSMOD's reader (``ROS_Deployment_Builder.enterPort``) splits a path at ``/`` into the node
  instance, the component instance on it and the port of that instance's component.

Both give the same model (:func:`read_group`, then :func:`resolve_groups` once the names are
resolved): each listed port's ``PortInstance`` gets ``group = G`` (the one a ``port_instance``
block already made for that port, or a new one named after the port with ``port =
"<component>/<port>"``). A port instance has one group: a port listed twice, or in a block and
in a ``port_instance`` with another group, is an error. Which form was read is kept on the
deployment as the property ``group:G`` (:data:`GROUP_KEY`), its value the paths as written, one
a line: :mod:`rosaadl.exporters.rosmod_text` writes such a group back as a block in that order.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.errors import NameResolutionError, ParseError
from rosaadl.importers.rosmod_text.blocks import Stmt, at, is_punct
from rosaadl.importers.rosmod_text.context import ImportContext
from rosaadl.importers.rosmod_text.resolution import DeploymentInfo
from rosaadl.importers.rosmod_text.statements import name_of, new, new_property

__all__ = ["GROUP_KEY", "LISTINGS", "read_group", "resolve_groups", "port_of"]

#: The prefix of the deployment property that keeps a group read as a top-level block.
GROUP_KEY = "group:"

#: The keywords of the top-level blocks of a ``.rdp`` file that list names (for ``parse_blocks``).
LISTINGS = ("group",)

_PATH = "<node>/<component_instance>/<port>"


def port_of(port_instance: EObject) -> str | None:
    """The name of the port a port instance stands for: its ref's last part, else its own name."""
    if port_instance.port:
        return port_instance.port.rpartition("/")[2]
    return port_instance.name


def read_group(stmt: Stmt, deployment: EObject, shown: str, info: DeploymentInfo, ctx: ImportContext) -> None:
    """A top-level ``group G { paths }`` block: the property ``group:G`` and its members in ``info``."""
    name = name_of(stmt, shown, "group")
    key = GROUP_KEY + name
    first = next((p for p in deployment.properties if p.key == key), None)
    if first is not None:
        raise ParseError(
            f"duplicate group name {name!r} in deployment {deployment.name!r} (first defined at line "
            f"{first.line})",
            location=at(shown, stmt),
        )
    if not stmt.body:
        ctx.warn(f"group {name!r} lists no port; skipped", shown, stmt.line, stmt.column)
        return
    paths = []
    bad_line = None  # one error a line: "a / b / c" is five malformed items
    for item in stmt.body:
        parts = _path(item)
        if parts is None:
            if item.line == bad_line:
                continue
            bad_line = item.line
            ctx.error(
                ParseError(
                    f"malformed member {item.key!r} of group {name!r}: expected {_PATH}",
                    location=at(shown, item),
                )
            )
            continue
        paths.append("/".join(parts))
        info.group_members.append((name, parts, item))
    deployment.properties.append(new_property(key, "\n".join(paths), stmt))


def _path(item: Stmt) -> tuple[str, str, str] | None:
    """``node/instance/port`` as its three names, or None when the item is not written so."""
    head = item.head
    if len(head) != 5 or not all(is_punct(head[k], "/") for k in (1, 3)):
        return None
    if not all(head[k].kind == "word" for k in (0, 2, 4)):
        return None
    return head[0].text, head[2].text, head[4].text


def resolve_groups(
    deployment: EObject, info: DeploymentInfo, software_failed: bool, ctx: ImportContext
) -> None:
    """Give each port listed by a group block its group (see the module documentation).

    Names into a software model that could not be read, or through a component instance whose
    component did not resolve, are left alone: those errors are already reported.
    """
    if software_failed or not info.group_members:
        return
    shown = info.filename
    nodes: dict[str, EObject] = {}
    for node in deployment.nodes:
        nodes.setdefault(node.name, node)
    listed: dict[int, Stmt] = {}  # port instance → the item that gave its group
    for group, parts, item in info.group_members:
        path = "/".join(parts)
        try:
            port = _port_instance(nodes, deployment.name, group, parts, item, shown)
            if port is None:
                continue
            if port.group is not None and (id(port) in listed or port.group != group):
                earlier = listed.get(id(port))
                raise NameResolutionError(
                    f"group {group!r}: {path!r} is already in group {port.group!r} (line "
                    f"{earlier.line if earlier is not None else port.line}); a port instance has one group",
                    location=at(shown, item),
                )
        except NameResolutionError as exc:
            ctx.error(exc)
            continue
        port.group = group
        listed[id(port)] = item


def _port_instance(
    nodes: dict[str, EObject],
    deployment: str,
    group: str,
    parts: tuple[str, str, str],
    item: Stmt,
    shown: str,
) -> EObject | None:
    """The port instance ``node/instance/port`` names in ``group`` (made when the instance has none
    for that port); None when an error already reported keeps it from resolving."""
    node_name, inst_name, port_name = parts
    path = "/".join(parts)
    where = f"group {group!r}: "
    node = nodes.get(node_name)
    if node is None:
        raise NameResolutionError(
            f"{where}{path!r} names no node of deployment {deployment!r}", location=at(shown, item)
        )
    inst = next((i for i in node.componentInstances if i.name == inst_name), None)
    if inst is None:
        if not node.componentInstances and any(p.key == "reference" for p in node.properties):
            return None  # a v0.2 node whose software node did not resolve: already reported
        raise _unknown(
            f"{where}node {node_name!r} has no component instance {inst_name!r}",
            "component instances",
            node.componentInstances,
            item,
            shown,
        )
    comp = inst.component
    if comp is None:
        return None  # the instance's own ref did not resolve: already reported
    if port_name not in {p.name for p in comp.ports}:
        raise _unknown(
            f"{where}{port_name!r} is not a port of component {comp.name!r} of {node_name}/{inst_name}",
            "ports",
            comp.ports,
            item,
            shown,
        )
    port = next((p for p in inst.portInstances if port_of(p) == port_name), None)
    if port is not None:
        return port
    if any(p.name == port_name for p in inst.portInstances):
        raise NameResolutionError(
            f"{where}{path!r} would make a port instance {port_name!r}, but {node_name}/{inst_name} "
            "has a port instance of that name for another port",
            location=at(shown, item),
        )
    port = new(
        "PortInstance", name=port_name, port=f"{comp.name}/{port_name}", line=item.line, column=item.column
    )
    inst.portInstances.append(port)
    return port


def _unknown(message: str, what: str, known: list[EObject], item: Stmt, shown: str) -> NameResolutionError:
    """An error at ``item``: ``message``, and the names ``known`` of ``what`` there are."""
    names = ", ".join(k.name for k in known) or "none"
    return NameResolutionError(f"{message} (its {what}: {names})", location=at(shown, item))
