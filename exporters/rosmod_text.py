"""ROSMOD v0.3 textual projects from ``rosmod.ecore`` models.

:func:`write_project` writes a project folder in the layout and syntax of ROSMOD's own v0.3
projects, which :func:`rosaadl.importers.rosmod_text.read_project` reads back:

```
<project>.rosmod                     "This is a ROSMOD Project"
01-Software/<software>.rml           packages, components (ports, timers, callback settings)
01-Software/msg/<package>.<Name>.msg message definitions (ROS .msg text, as in the model)
01-Software/srv/<package>.<Name>.srv service definitions
01-Software/abl/<package>.<component>.<port>.abl   "abl:<port>" component settings
01-Software/pnp/<package>.<component>.<port>.pnp   "pnp:<port>" component settings
02-Hardware/<hardware>.rhw           hosts (address, user, ssh key, paths, architecture, os)
02-Hardware/snp/<hardware>[.<host>].snp            "snp" settings of a hardware model or host
03-Deployment/<deployment>.rdp       using <hardware>; nodes, component instances, logging, groups
```

A port instance's group is written as it was read (:mod:`rosaadl.importers.rosmod_text.groups`):
inside the ``port_instance`` (``group = "G";``), or, for a group the deployment keeps as a
``group:G`` property, as a top-level ``group G { <node>/<component instance>/<port> … }`` block
after the nodes, its paths in the order of that property and then in model order. A port
instance such a block makes when it is read (named after its port, ``ref`` ``<component>/<port>``)
is written only in the block.

The output is deterministic (model order, fixed layout), every file is made before the first
one is written and each is written atomically; a name that cannot be written (not a ROSMOD
word, or a file name that would leave the output folder) is an :class:`ExportError` naming the
element, and nothing is written then.

What v0.3 text cannot hold is left out, each with a warning: settings of projects, packages and
deployments (v0.2 software nodes and host instances, WebGME containers and experiments; a
deployment's ``group:G`` settings are its group blocks),
component settings other than ``<port or timer>.<key>``, ``abl:``/``pnp:`` files, WebGME
scheduling schemes of components, operations, latching, networks, links and interfaces,
nodes without a host. :func:`text_normal_form` gives the project as its written text reads
back (those facts removed, names and file locations left to the folder), so that
``text_normal_form(p)`` and ``text_normal_form(read_project(written))`` are equal models.
"""

from __future__ import annotations

import logging
import os
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from decimal import Decimal
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl import fileio
from rosaadl import model as _model
from rosaadl.arguments import checked
from rosaadl.errors import Diagnostic, ExportError, Location
from rosaadl.importers.rosmod_text.groups import GROUP_KEY, port_of

__all__ = ["render_project", "write_project", "text_normal_form", "MARKER_TEXT"]

log = logging.getLogger(__name__)

#: Content of the ``<project>.rosmod`` marker file of ROSMOD projects.
MARKER_TEXT = "This is a ROSMOD Project"

_WORD = re.compile(r"[A-Za-z0-9_~+\-]+\Z")  # a name written as one word (no '.', which side files use)
_VALUE_WORD = re.compile(r"[A-Za-z0-9_.~+\-]+\Z")  # a value the reader takes back as written
_KEY = re.compile(r"[A-Za-z0-9_.~+\-?!@#$%^&*()\[\]<>|,:']+(?: [A-Za-z0-9_.~+\-?!@#$%^&*()\[\]<>|,:']+)*\Z")
_FILE_STEM = re.compile(r"[^\x00-\x1f/\\:*?\"<>|]+\Z")
_HOST_ATTRIBUTES = (
    ("ip_address", "ipAddress", True),
    ("username", "username", True),
    ("sshkey", "sshKey", True),
    ("deployment_path", "deploymentPath", True),
    ("install_path", "installPath", True),
    ("arch", "architecture", False),
    ("os", "os", False),
)
_HOST_KEYS = frozenset(
    {"ip_address", "username", "sshkey", "deployment_path", "install_path", "arch", "architecture", "os"}
)
_TIMER_KEYS = frozenset({"period", "priority", "deadline"})
_CALLBACK_KEYS = frozenset({"priority", "deadline"})
_NODE_KEYS = frozenset({"ref", "priority", "cmd_args"})
_INSTANCE_KEYS = frozenset({"ref", "scheduling_scheme"})
_SCHEMES = frozenset({"FIFO", "PFIFO", "EDF"})


def _given(obj: EObject, feature: str) -> object:
    """A feature's value when it is set, else None (an unset priority reads 0 in pyecore)."""
    return obj.eGet(feature) if obj.eIsSet(feature) else None


def _where(obj: EObject) -> str:
    parts = []
    current = obj
    while current is not None:
        name = getattr(current, "name", None) if current.eClass.findEStructuralFeature("name") else None
        parts.append(f"{current.eClass.name}({name or ''})")
        current = current.eContainer()
    return "/".join(reversed(parts))


def _error(message: str, obj: EObject) -> ExportError:
    return ExportError(message, Location(path=_where(obj)))


def _word(name: str | None, obj: EObject, what: str) -> str:
    if not name or not _WORD.match(name):
        raise _error(
            f"cannot write {what} {name!r}: a ROSMOD name is one word of letters, digits and _ ~ + -",
            obj,
        )
    return name


def _stem(name: str | None, obj: EObject, what: str) -> str:
    text = name or ""
    if (
        not text
        or not _FILE_STEM.match(text)
        or text.strip() != text
        or text.startswith(".")
        or text.endswith(".")
        or len(text) > 200
    ):
        raise _error(f"cannot write {what} {name!r}: it cannot be a file name in the project folder", obj)
    return text


def _quote(text: str) -> str:
    return (
        '"' + text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n").replace("\t", "\\t") + '"'
    )


def _value(text: str | None) -> str:
    """A value as the reader takes it back: a plain word as it is, anything else quoted."""
    text = text or ""
    return text if _VALUE_WORD.match(text) else _quote(text)


def _key_ok(key: str | None) -> bool:
    return bool(key) and bool(_KEY.match(key)) and "//" not in key and "/*" not in key


def _seconds(value: Decimal) -> str:
    return format(Decimal(value), "f")


# =========================================================================== what is written


@dataclass
class _Plan:
    """The decisions of one write, shared by the writer and :func:`text_normal_form`."""

    warnings: list[Diagnostic] | None = None
    dropped: list[tuple[EObject, str]] = field(default_factory=list)

    def drop(self, obj: EObject, message: str) -> None:
        self.dropped.append((obj, message))
        diag = Diagnostic(
            "warning", f"not written (v0.3 text has no place for it): {message}", Location(path=_where(obj))
        )
        log.warning("%s", diag)
        if self.warnings is not None:
            self.warnings.append(diag)


@dataclass
class _ComponentSettings:
    blocks: dict[str, list[EObject]]  # port/timer name → its "<name>.<key>" settings
    side: list[tuple[str, str, EObject]]  # (kind, port name, setting) of abl/pnp files, sorted
    kept: list[EObject]  # the settings in the order a reader gives them back


def _component_settings(comp: EObject, plan: _Plan) -> _ComponentSettings:
    members = {m.name: m for m in [*comp.ports, *comp.timers]}
    blocks: dict[str, list[EObject]] = {}
    side: dict[tuple[str, str], EObject] = {}
    for prop in comp.properties:
        key = prop.key or ""
        kind, colon, target = key.partition(":")
        if colon and kind in ("abl", "pnp") and target in members:
            if (kind, target) in side:
                plan.drop(prop, f"component {comp.name!r}: a second {key!r} setting")
            else:
                side[(kind, target)] = prop
            continue
        name, dot, rest = key.partition(".")
        member = members.get(name) if dot else None
        if member is not None and _key_ok(rest):
            reserved = (
                _TIMER_KEYS
                if member.eClass.name == "Timer"
                else (_CALLBACK_KEYS if member.eClass.name in ("Subscriber", "Server") else frozenset())
            )
            if rest not in reserved:
                blocks.setdefault(name, []).append(prop)
                continue
        plan.drop(prop, f"component {comp.name!r}: setting {key!r}")
    ordered_side = [(k, t, side[(k, t)]) for k, t in sorted(side)]
    kept = [p for m in [*comp.ports, *comp.timers] for p in blocks.get(m.name, [])]
    kept += [p for _, _, p in ordered_side]
    return _ComponentSettings(blocks, ordered_side, kept)


def _host_settings(host: EObject, plan: _Plan) -> tuple[list[EObject], EObject | None]:
    """(settings written in the host block, the 'snp' setting written as a side file)."""
    out: list[EObject] = []
    snp = None
    for prop in host.properties:
        key = prop.key or ""
        if key == "snp" and snp is None:
            snp = prop
        elif not _key_ok(key) or key == "snp":
            plan.drop(prop, f"host {host.name!r}: setting {key!r}")
        elif key in _HOST_KEYS and not _host_key_set(host, key):
            plan.drop(prop, f"host {host.name!r}: setting {key!r} would read back as its attribute")
        else:
            out.append(prop)
    return out, snp


def _host_key_set(host: EObject, key: str) -> bool:
    attribute = {"arch": "architecture", "architecture": "architecture"}.get(key)
    if attribute is None:
        attribute = next(a for k, a, _ in _HOST_ATTRIBUTES if k == key)
    return host.eGet(attribute) is not None


def _node_settings(node: EObject, plan: _Plan) -> list[EObject]:
    out = []
    for prop in node.properties:
        key = prop.key or ""
        if not _key_ok(key):
            plan.drop(prop, f"node {node.name!r}: setting {key!r}")
        elif key in _NODE_KEYS and (
            (key == "priority" and _given(node, "priority") is None)
            or (key == "cmd_args" and node.arguments is None)
        ):
            plan.drop(prop, f"node {node.name!r}: setting {key!r} would read back as its attribute")
        else:
            out.append(prop)
    return out


def _instance_settings(inst: EObject, plan: _Plan) -> tuple[list[EObject], list[EObject]]:
    logging_items = []
    for prop in inst.logging:
        if _key_ok(prop.key):
            logging_items.append(prop)
        else:
            plan.drop(prop, f"component_instance {inst.name!r}: logging setting {prop.key!r}")
    out = []
    for prop in inst.properties:
        key = prop.key or ""
        if not _key_ok(key) or key == "logging":
            plan.drop(prop, f"component_instance {inst.name!r}: setting {key!r}")
        elif (
            key == "scheduling_scheme"
            and not inst.eIsSet("schedulingScheme")
            and (prop.value or "") in _SCHEMES
        ):
            plan.drop(
                prop, f"component_instance {inst.name!r}: setting {key!r} would read back as its attribute"
            )
        else:
            out.append(prop)
    return logging_items, out


def _host_system(host: EObject | None) -> EObject | None:
    return host.eContainer() if host is not None else None


def _using(deployment: EObject) -> str | None:
    if deployment.systemName:
        return deployment.systemName
    if deployment.system is not None:
        return deployment.system.name
    for node in deployment.nodes:
        system = _host_system(node.host)
        if system is not None:
            return system.name
    return None


def _host_ref(node: EObject) -> str | None:
    if node.hostRef:
        return node.hostRef
    if node.host is not None:
        return f"{node.host.eContainer().name}/{node.host.name}"
    return None


def _component_ref(inst: EObject) -> str | None:
    if inst.componentRef:
        return inst.componentRef
    if inst.component is not None:
        return f"{inst.component.eContainer().name}/{inst.component.name}"
    return None


def _unique(items: Iterable[EObject], what: str, owner: EObject) -> None:
    seen: set[str] = set()
    for item in items:
        if item.name in seen:
            raise _error(
                f"two {what}s are named {item.name!r}; the written project would not read back", item
            )
        seen.add(item.name)


@dataclass
class _GroupBlocks:
    """The groups a deployment writes as top-level blocks, and how its port instances are written."""

    settings: list[EObject]  # the deployment's "group:G" settings written as blocks
    paths: dict[str, list[tuple[str, EObject]]]  # group → (path, port instance), in written order
    members: set[int]  # the port instances of those groups: no "group =" of their own
    implied: set[int]  # the members a block makes when it is read: not written as port_instance


def _group_blocks(deployment: EObject) -> _GroupBlocks:
    """The ``group:G`` settings of ``deployment`` that are written as blocks (see the module
    documentation): a group name that is a ROSMOD word, with at least one port instance on a node
    that is written, each the only one of its component instance for its port."""
    listed: dict[str, list[str]] = {}
    settings: dict[str, EObject] = {}
    for prop in deployment.properties:
        key = prop.key or ""
        name = key[len(GROUP_KEY) :]
        if key.startswith(GROUP_KEY) and _VALUE_WORD.match(name) and name not in listed:
            listed[name] = (prop.value or "").split("\n")
            settings[name] = prop
    found: dict[str, list[tuple[str, EObject]]] = {name: [] for name in listed}
    implied: set[int] = set()
    for node in deployment.nodes:
        if _host_ref(node) is None:
            continue
        for inst in node.componentInstances:
            comp_name = inst.component.name if inst.component is not None else None
            if comp_name is None and inst.componentRef:
                comp_name = inst.componentRef.rpartition("/")[2]
            stands_for = [port_of(p) for p in inst.portInstances]
            for port in inst.portInstances:
                port_name = port_of(port)
                if port.group not in found or stands_for.count(port_name) > 1:
                    continue
                found[port.group].append((f"{node.name}/{inst.name}/{port_name}", port))
                if port.name == port_name and port.port == f"{comp_name}/{port_name}":
                    implied.add(id(port))
    paths = {}
    for name, members in found.items():
        if members:
            rank = {path: k for k, path in enumerate(listed[name])}
            paths[name] = sorted(members, key=lambda m, r=rank: r.get(m[0], len(r)))
    member_ids = {id(port) for members in paths.values() for _, port in members}
    return _GroupBlocks([settings[name] for name in paths], paths, member_ids, implied & member_ids)


# =========================================================================== rendering


class _Writer:
    def __init__(self, project: EObject, plan: _Plan) -> None:
        self.project = project
        self.plan = plan
        self.files: dict[str, str] = {}

    def add(self, relative: str, text: str) -> None:
        if relative in self.files:
            raise ExportError(f"two parts of the project would be written to {relative!r}")
        self.files[relative] = text

    def run(self) -> dict[str, str]:
        project = self.project
        name = _stem(project.name or "project", project, "the project")
        self.add(f"{name}.rosmod", MARKER_TEXT)
        for prop in project.properties:
            self.plan.drop(prop, f"project setting {prop.key!r}")
        if project.software is not None:
            self.software(project.software)
        _unique(project.systems, "hardware model", project)
        for system in project.systems:
            self.system(system)
        _unique(project.deployments, "deployment", project)
        for deployment in project.deployments:
            self.deployment(deployment)
        return self.files

    # -- software
    def software(self, software: EObject) -> None:
        name = _stem(software.name or "software", software, "the software model")
        lines = ["/*", " * ROSMOD Software Model", " */", ""]
        _unique(software.packages, "package", software)
        for package in software.packages:
            pkg = _word(package.name, package, "package")
            for prop in package.properties:
                self.plan.drop(prop, f"package {package.name!r}: setting {prop.key!r}")
            _unique(package.messages, "message", package)
            _unique(package.services, "service", package)
            _unique(package.components, "component", package)
            for msg in package.messages:
                self.add(f"01-Software/msg/{pkg}.{_word(msg.name, msg, 'message')}.msg", msg.definition or "")
            for srv in package.services:
                self.add(f"01-Software/srv/{pkg}.{_word(srv.name, srv, 'service')}.srv", srv.definition or "")
            lines += [f"// ROSMOD Package - {pkg}", f"package {pkg}", "{"]
            for comp in package.components:
                lines += self.component(comp, pkg)
            lines += ["}", ""]
        self.add(f"01-Software/{name}.rml", "\n".join(lines))

    def component(self, comp: EObject, pkg: str) -> list[str]:
        name = _word(comp.name, comp, "component")
        _unique([*comp.ports, *comp.timers], "port or timer", comp)
        settings = _component_settings(comp, self.plan)
        if comp.eIsSet("schedulingScheme"):
            self.plan.drop(comp, f"component {comp.name!r}: scheduling scheme {comp.schedulingScheme.name}")
        datatype = f" : {_word(comp.datatype, comp, 'datatype')}" if comp.datatype else ""
        lines = [f"  // ROSMOD Component - {name}", f"  component {name}{datatype}", "  {"]
        for port in comp.ports:
            kind = port.eClass.name
            port_name = _word(port.name, port, kind.lower())
            type_name = port.type or ""
            parts = type_name.split("/")
            if len(parts) != 2 or not all(_WORD.match(p) for p in parts):
                raise _error(
                    f"cannot write the type {port.type!r} of {kind.lower()} {port.name!r}: "
                    "expected 'package/Type'",
                    port,
                )
            body: list[str] = []
            if kind in ("Subscriber", "Server"):
                if _given(port, "priority") is not None:
                    body.append(f"priority = {port.priority};")
                if _given(port, "deadline") is not None:
                    body.append(f"deadline = {_seconds(port.deadline)};")
                if port.operation is not None:
                    self.plan.drop(port, f"{kind.lower()} {port.name!r}: operation {port.operation!r}")
            if kind == "Publisher" and _given(port, "latching") is not None:
                self.plan.drop(port, f"publisher {port.name!r}: latching {port.latching}")
            body += self.settings(settings.blocks.get(port.name, []), member=True)
            lines.append(f"    // ROSMOD {kind} - {port_name}")
            head = f"    {kind.lower()} <{type_name}> {port_name}"
            if body:
                lines += [head, "    {", *(f"      {b}" for b in body), "    }"]
            else:
                lines.append(head + ";")
        for timer in comp.timers:
            timer_name = _word(timer.name, timer, "timer")
            body = []
            if _given(timer, "period") is not None:
                body.append(f"period = {_seconds(timer.period)};")
            if _given(timer, "priority") is not None:
                body.append(f"priority = {timer.priority};")
            if _given(timer, "deadline") is not None:
                body.append(f"deadline = {_seconds(timer.deadline)};")
            if timer.operation is not None:
                self.plan.drop(timer, f"timer {timer.name!r}: operation {timer.operation!r}")
            body += self.settings(settings.blocks.get(timer.name, []), member=True)
            lines += [f"    // ROSMOD Timer - {timer_name}", f"    timer {timer_name}", "    {"]
            lines += [f"\t{b}" for b in body]
            lines.append("    }")
        lines.append("  }")
        for kind, target, prop in settings.side:
            self.add(f"01-Software/{kind}/{pkg}.{name}.{target}.{kind}", prop.value or "")
        return lines

    @staticmethod
    def settings(props: Iterable[EObject], *, member: bool = False) -> list[str]:
        """``key = value;`` lines; ``member`` settings (``<port>.<key>``) are written without
        the port's name, inside the port's block."""
        out = []
        for prop in props:
            key = prop.key or ""
            if member:
                key = key.partition(".")[2]
            out.append(f"{key} = {_value(prop.value)};")
        return out

    # -- hardware
    def system(self, system: EObject) -> None:
        name = _stem(system.name, system, "the hardware model")
        lines = ["/*", " * ROSMOD Hardware Model", " */", ""]
        for network in system.networks:
            self.plan.drop(network, f"network {network.name!r}")
        for link in system.links:
            self.plan.drop(link, f"link {link.name!r}")
        _unique(system.hosts, "host", system)
        snp_system = None
        for prop in system.properties:
            if prop.key == "snp" and snp_system is None:
                snp_system = prop
            else:
                self.plan.drop(prop, f"hardware model {system.name!r}: setting {prop.key!r}")
        for host in system.hosts:
            host_name = _word(host.name, host, "host")
            for interface in host.interfaces:
                self.plan.drop(interface, f"interface {interface.name!r} of host {host.name!r}")
            settings, snp = _host_settings(host, self.plan)
            lines += [f"// Hardware - {host_name}", f"hardware {host_name}", "{"]
            for key, attribute, quoted in _HOST_ATTRIBUTES:
                value = host.eGet(attribute)
                if value is not None:
                    lines.append(f"  {key} = {_quote(value) if quoted else _value(value)};")
            lines += [f"  {line}" for line in self.settings(settings)]
            lines += ["}", ""]
            if snp is not None:
                self.add(f"02-Hardware/snp/{name}.{host_name}.snp", snp.value or "")
        if snp_system is not None:
            self.add(f"02-Hardware/snp/{name}.snp", snp_system.value or "")
        self.add(f"02-Hardware/{name}.rhw", "\n".join(lines))

    # -- deployment
    def deployment(self, deployment: EObject) -> None:
        name = _stem(deployment.name, deployment, "the deployment")
        groups = _group_blocks(deployment)
        for prop in deployment.properties:
            if not any(prop is kept for kept in groups.settings):
                self.plan.drop(prop, f"deployment {deployment.name!r}: setting {prop.key!r}")
        lines = ["/*", " * ROSMOD Deployment Model", " */", ""]
        using = _using(deployment)
        if using is not None:
            shown = using if _VALUE_WORD.match(using) else _quote(using)
            lines += [f"// ROSMOD Hardware Model - {using}", f"using {shown};", ""]
        _unique(deployment.nodes, "node", deployment)
        for node in deployment.nodes:
            lines += self.node(node, groups)
        for group, members in groups.paths.items():
            lines += [f"// ROSMOD Group - {group}", f"group {group}", "{"]
            for path, port in members:
                _word(port_of(port), port, "port")
                lines.append(f"    {path}")
            lines += ["}", ""]
        self.add(f"03-Deployment/{name}.rdp", "\n".join(lines))

    def node(self, node: EObject, groups: _GroupBlocks) -> list[str]:
        ref = _host_ref(node)
        if ref is None:
            self.plan.drop(node, f"node {node.name!r}: a v0.3 node needs a host and this one has none")
            return []
        name = _word(node.name, node, "node")
        props = [f"ref = {_quote(ref)};"]
        if _given(node, "priority") is not None:
            props.append(f"priority = {node.priority};")
        if node.arguments is not None:
            props.append(f"cmd_args = {_quote(node.arguments)};")
        props += self.settings(_node_settings(node, self.plan))
        lines = [f"// ROSMOD Node - {name}", f"node {name}", "{", "  properties", "  {"]
        lines += [f"    {p}" for p in props]
        lines.append("  }")
        _unique(node.componentInstances, "component instance", node)
        for inst in node.componentInstances:
            lines += self.instance(inst, groups)
        lines += ["}", ""]
        return lines

    def instance(self, inst: EObject, groups: _GroupBlocks) -> list[str]:
        name = _word(inst.name, inst, "component instance")
        ref = _component_ref(inst)
        if ref is None:
            raise _error(f"component instance {inst.name!r} names no component", inst)
        logging_items, settings = _instance_settings(inst, self.plan)
        props = [f"ref = {_quote(ref)};"]
        if inst.eIsSet("schedulingScheme"):
            props.append(f"scheduling_scheme = {inst.schedulingScheme.name};")
        body = [f"\t{p}" for p in props]
        if logging_items:
            body += ["\tlogging", "\t{"]
            body += [f"\t  {line}" for line in self.settings(logging_items)]
            body.append("\t}")
        body += [f"\t{line}" for line in self.settings(settings)]
        lines = [f"  component_instance {name}", "  {", "      properties", "      {", *body, "      }"]
        _unique(inst.portInstances, "port instance", inst)
        for port in inst.portInstances:
            port_name = _word(port.name, port, "port instance")
            if id(port) in groups.implied:
                continue  # its group block makes it
            items = []
            if port.port is not None:
                items.append(f"ref = {_quote(port.port)};")
            if port.group is not None and id(port) not in groups.members:
                items.append(f"group = {_quote(port.group)};")
            lines += [f"      port_instance {port_name}", "      {", *(f"\t{i}" for i in items), "      }"]
        lines.append("  }")
        return lines


def render_project(project: EObject, *, warnings: list[Diagnostic] | None = None) -> dict[str, str]:
    """The files of ``project`` as v0.3 text: relative path → text (nothing is written)."""
    if not isinstance(project, EObject) or project.eClass.name != "Project":
        raise ExportError("expected a rosmod Project to write")
    return _Writer(project, _Plan(warnings)).run()


@checked
def write_project(
    project: EObject, out_dir: str | os.PathLike[str], *, warnings: list[Diagnostic] | None = None
) -> list[Path]:
    """Write ``project`` as a ROSMOD v0.3 project folder ``out_dir``; the paths written.

    Every text is made first; an :class:`ExportError` (a name that cannot be written) leaves no
    output at all. Files are written all-or-nothing and never outside ``out_dir``.
    """
    files = render_project(project, warnings=warnings)
    targets = [(fileio.safe_join(out_dir, *relative.split("/")), text) for relative, text in files.items()]
    written = fileio.write_files(targets)
    log.info("wrote %d ROSMOD file(s) to %s", len(written), out_dir)
    return written


# =========================================================================== normal form


def text_normal_form(project: EObject) -> EObject:
    """A copy of ``project`` as its v0.3 text reads back (see the module documentation): what the
    writer leaves out removed, settings in the order the reader gives them, file locations, the
    project's name and path (the folder's) and the format version left out."""
    copy = _model.loads_xmi(_model.dumps_xmi(project))
    plan = _Plan(None)
    copy.name = None
    copy.path = None
    copy.formatVersion = None
    copy.properties.clear()
    software = copy.software
    if software is not None:
        software.sourceFile = None
        for package in software.packages:
            package.properties.clear()
            for items, suffix in ((package.messages, ".msg"), (package.services, ".srv")):
                ordered = sorted(items, key=lambda x, s=suffix: f"{package.name}.{x.name}{s}")
                items.clear()
                items.extend(ordered)
                for item in items:
                    if item.definition is None:
                        item.definition = ""
            for comp in package.components:
                settings = _component_settings(comp, plan)
                comp.properties.clear()
                comp.properties.extend(settings.kept)
                comp.schedulingScheme = comp.eClass.findEStructuralFeature(
                    "schedulingScheme"
                ).get_default_value()
                for element in [*comp.timers, *comp.ports]:
                    if element.eClass.findEStructuralFeature("operation") is not None:
                        element.operation = None
                    if element.eClass.name == "Publisher":
                        element.latching = False
    for system in copy.systems:
        system.sourceFile = None
        snp = next((p for p in system.properties if p.key == "snp"), None)
        system.properties.clear()
        if snp is not None:
            system.properties.append(snp)
        system.links.clear()
        system.networks.clear()
        for host in system.hosts:
            host.interfaces.clear()
            settings, host_snp = _host_settings(host, plan)
            host.properties.clear()
            host.properties.extend(settings)
            if host_snp is not None:
                host.properties.append(host_snp)
    systems = {s.name: s for s in copy.systems}
    for deployment in copy.deployments:
        deployment.sourceFile = None
        groups = _group_blocks(deployment)
        _as_group_blocks_read_back(deployment, groups)
        using = _using(deployment)
        deployment.systemName = using
        deployment.system = systems.get(using) if using is not None else None
        for node in list(deployment.nodes):
            ref = _host_ref(node)
            if ref is None:
                deployment.nodes.remove(node)
                continue
            node.hostRef = ref
            settings = _node_settings(node, plan)
            node.properties.clear()
            node.properties.extend(settings)
            for inst in node.componentInstances:
                inst.componentRef = _component_ref(inst)
                logging_items, inst_settings = _instance_settings(inst, plan)
                inst.logging.clear()
                inst.logging.extend(logging_items)
                inst.properties.clear()
                inst.properties.extend(inst_settings)
    return copy


def _as_group_blocks_read_back(deployment: EObject, groups: _GroupBlocks) -> None:
    """``deployment``'s settings and port instances as its written group blocks read back: the
    ``group:G`` settings list their paths as written, and the port instances a block makes come
    after the others of their component instance, in the order of the blocks."""
    deployment.properties.clear()
    deployment.properties.extend(groups.settings)
    order: dict[int, int] = {}
    for prop, members in zip(groups.settings, groups.paths.values(), strict=True):
        prop.value = "\n".join(path for path, _ in members)
        for _, port in members:
            if id(port) in groups.implied:
                order[id(port)] = len(order)
    for node in deployment.nodes:
        for inst in node.componentInstances:
            made = sorted((p for p in inst.portInstances if id(p) in order), key=lambda p: order[id(p)])
            if made:
                kept = [p for p in inst.portInstances if id(p) not in order]
                inst.portInstances.clear()
                inst.portInstances.extend([*kept, *made])
