"""Names across the files of a textual ROSMOD project, resolved once everything is read.

The dialect readers make model objects and note, in a :class:`SoftwareInfo` and a
:class:`DeploymentInfo` per file, each name they could not resolve alone: the message or service
type of a port, a node's ``<hardware>/<host>``, a component instance's ``<package>/<component>``,
a port instance's ``<component>/<port>``, a v0.2 ``node_instance``'s ``<package>/<node>``. Then
:func:`resolve_software` and :func:`resolve_deployment` check duplicate names and set each
reference, recording every failure, located at the name as written, in the run's
:class:`~.context.ImportContext`. Types of packages that are not in the project
(``std_msgs/String``) are external references, not errors.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from pyecore.ecore import EObject

from rosaadl.errors import NameResolutionError
from rosaadl.importers.rosmod_text.blocks import Stmt, Token, at
from rosaadl.importers.rosmod_text.context import ImportContext
from rosaadl.importers.rosmod_text.statements import new, qualify

__all__ = [
    "SoftwareInfo",
    "Ref",
    "DeploymentInfo",
    "ProjectModels",
    "check_unique",
    "resolve_software",
    "resolve_deployment",
]


@dataclass
class SoftwareInfo:
    """What resolution needs to know about the software besides the model objects."""

    filename: str
    # v0.2 software nodes: package → node name → [(instance, component name, stmt)]
    nodes: dict[str, dict[str, list[tuple[str, str, Stmt]]]] = field(default_factory=dict)
    # where each port type was written, for located resolution errors
    port_sites: list[tuple[EObject, str, str, int, int]] = field(default_factory=list)
    # the .msg/.srv file of each message and service read from a side file
    sources: dict[int, str] = field(default_factory=dict)


@dataclass
class Ref:
    """A name written in a deployment, to resolve: ``kind`` says what it names."""

    obj: EObject
    text: str
    token: Token
    kind: str  # "host" | "component" | "port" | "node02"
    extra: Any = None


@dataclass
class DeploymentInfo:
    """The names a deployment file refers to, with its ``using`` statement."""

    filename: str
    using: Stmt | None = None
    refs: list[Ref] = field(default_factory=list)
    # the members of top-level group blocks: (group name, the path's parts, its item)
    group_members: list[tuple[str, tuple[str, str, str], Stmt]] = field(default_factory=list)


def check_unique(
    items: Iterable[EObject], what: str, owner: str, filename: str | None, ctx: ImportContext, key=None
) -> None:
    """Record an error at each object whose name (or ``key``) an earlier one of ``items`` has."""
    items = list(items)
    all_names = [key(o) if key else o.name for o in items]
    if len(set(all_names)) == len(all_names):
        return
    seen: dict[str, EObject] = {}
    ordered = sorted(items, key=lambda o: (getattr(o, "line", 0) or 0, getattr(o, "column", 0) or 0))
    for obj in ordered:
        name = key(obj) if key else obj.name
        if name is None:
            continue
        first = seen.get(name)
        if first is None:
            seen[name] = obj
            continue
        at = f" (first defined at line {first.line})" if getattr(first, "line", None) else ""
        ctx.error(
            NameResolutionError(
                f"duplicate {what} name {name!r} in {owner}{at}",
                file=filename,
                line=getattr(obj, "line", None),
                column=getattr(obj, "column", None),
            )
        )


class _Names:
    """Name → object tables of a software model, built once for resolution."""

    def __init__(self, software: EObject | None) -> None:
        self.packages: dict[str, EObject] = {}
        self.messages: dict[str, set[str]] = {}
        self.services: dict[str, set[str]] = {}
        self.components: dict[str, dict[str, EObject]] = {}
        self.ports: dict[int, set[str]] = {}
        for package in software.packages if software is not None else []:
            name = package.name
            self.packages.setdefault(name, package)
            self.messages.setdefault(name, set()).update(m.name for m in package.messages)
            self.services.setdefault(name, set()).update(s.name for s in package.services)
            comps = self.components.setdefault(name, {})
            for comp in package.components:
                comps.setdefault(comp.name, comp)

    def port_names(self, comp: EObject) -> set[str]:
        names = self.ports.get(id(comp))
        if names is None:
            names = self.ports[id(comp)] = {p.name for p in comp.ports}
        return names


# --------------------------------------------------------------------------- software


def resolve_software(software: EObject, info: SoftwareInfo, ctx: ImportContext) -> None:
    """Duplicate names of the software, the port types and the nested field types of its packages."""
    shown = info.filename
    check_unique(software.packages, "package", "the software model", shown, ctx)
    names = _Names(software)
    packages = names.packages
    for package in software.packages:
        owner = f"package {package.name!r}"
        check_unique(package.messages, "message", owner, shown, ctx)
        check_unique(package.services, "service", owner, shown, ctx)
        check_unique(package.components, "component", owner, shown, ctx)
        for comp in package.components:
            check_unique([*comp.timers, *comp.ports], "port or timer", f"component {comp.name!r}", shown, ctx)
    for port, kind, _written, line, column in info.port_sites:
        pkg_name, _, type_name = port.type.rpartition("/")
        package = packages.get(pkg_name)
        if package is None:
            continue  # a type of a package outside the project (std_msgs/String): external
        wants_msg = kind in ("publisher", "subscriber")
        pool = (names.messages if wants_msg else names.services)[pkg_name]
        if type_name not in pool:
            what = "message" if wants_msg else "service"
            known = ", ".join(sorted(pool)) or "none"
            ctx.error(
                NameResolutionError(
                    f"unknown {what} type {port.type!r} of {kind} {port.name!r}: package {pkg_name!r} "
                    f"defines no {what} {type_name!r} (its {what}s: {known})",
                    file=shown,
                    line=line,
                    column=column,
                )
            )
    # nested field types of the project's own packages
    for package in software.packages:
        for owner, fields in (
            *((m, m.fields) for m in package.messages),
            *((s, [*s.requestFields, *s.responseFields]) for s in package.services),
        ):
            for fld in fields:
                pkg_name, _, type_name = (fld.type or "").rpartition("/")
                target = packages.get(pkg_name)
                if target is not None and type_name not in names.messages[pkg_name]:
                    ctx.error(
                        NameResolutionError(
                            # the class name as a word: "message" or "service"
                            f"{owner.eClass.name.lower()} {package.name}/{owner.name}: field "
                            f"{fld.name!r} has unknown message type {fld.type!r}",
                            file=info.sources.get(id(owner), shown),
                            line=fld.line,
                            column=fld.column,
                            path=f"{package.name}/{owner.name}",
                        )
                    )


# --------------------------------------------------------------------------- deployments


@dataclass
class ProjectModels:
    """What the project's other files gave, for a deployment's names to resolve against."""

    systems: dict[str, EObject]  # the hardware models by name
    software: EObject | None
    sw_info: SoftwareInfo | None
    software_failed: bool = False  # the software model could not be read
    failed_systems: set[str] = field(default_factory=set)  # hardware models that could not be read


def resolve_deployment(
    deployment: EObject, info: DeploymentInfo, models: ProjectModels, ctx: ImportContext
) -> None:
    """Set the hardware model, hosts, components and port references of one deployment.

    Names into a hardware model that could not be read, or into the software when it could not
    be read, are left alone: that file's own errors are already reported.
    """
    resolver = _DeploymentResolver(deployment, info, models, ctx)
    for ref in info.refs:
        if ref.kind == "host":
            resolver.host(ref)
        elif models.software_failed:
            continue  # the software model could not be read: already reported
        elif ref.kind == "component":
            resolver.component(ref)
        elif ref.kind == "port":
            resolver.port(ref)
        elif ref.kind == "node02":
            resolver.node02(ref)


class _DeploymentResolver:
    """The name tables of one deployment's resolution; one method per kind of reference."""

    def __init__(
        self, deployment: EObject, info: DeploymentInfo, models: ProjectModels, ctx: ImportContext
    ) -> None:
        self.deployment = deployment
        self.shown = info.filename
        self.systems = models.systems
        self.sw_info = models.sw_info
        self.ctx = ctx
        self.failed_systems = models.failed_systems
        self.names = _Names(models.software)
        self.host_tables: dict[int, dict[str, EObject]] = {}
        self.using = self._using(info)

    def _using(self, info: DeploymentInfo) -> EObject | None:
        deployment, systems = self.deployment, self.systems
        using = None
        if deployment.systemName is not None:
            using = systems.get(deployment.systemName)
            if using is None and deployment.systemName not in self.failed_systems:
                tok = info.using.head[1] if info.using is not None and len(info.using.head) > 1 else None
                known = ", ".join(sorted(systems)) or "none"
                self.ctx.error(
                    NameResolutionError(
                        f"unknown hardware model {deployment.systemName!r} in 'using' "
                        f"(hardware models: {known})",
                        file=self.shown,
                        line=tok.line if tok else None,
                        column=tok.column if tok else None,
                    )
                )
            else:
                deployment.system = using
        return using

    def _error(self, message: str, ref: Ref) -> None:
        self.ctx.error(NameResolutionError(message, location=at(self.shown, ref.token)))

    def _package_known(self, pkg_name: str, what: str, ref: Ref) -> bool:
        """Is ``pkg_name`` a package of the software? If not, an error at ``ref`` (of a ``what``)."""
        packages = self.names.packages
        if pkg_name in packages:
            return True
        known = ", ".join(sorted(packages)) or "none"
        self._error(
            f"{what} {ref.obj.name!r} refers to unknown package {pkg_name or ref.text!r} (packages: {known})",
            ref,
        )
        return False

    def host(self, ref: Ref) -> None:
        """A node's ``<hardware>/<host>`` (or a bare host of the ``using`` model)."""
        sys_name, _, host_name = ref.text.rpartition("/")
        if (sys_name or self.deployment.systemName) in self.failed_systems:
            return  # its hardware model could not be read: already reported
        system = self.systems.get(sys_name) if sys_name else self.using
        if sys_name and system is None:
            known = ", ".join(sorted(self.systems)) or "none"
            self._error(
                f"node {ref.obj.name!r}: unknown hardware model {sys_name!r} in ref {ref.text!r} "
                f"(hardware models: {known})",
                ref,
            )
            return
        if system is None:
            self._error(
                f"node {ref.obj.name!r}: host {ref.text!r} has no hardware model (no 'using' and no "
                "'<hardware>/<host>' ref)",
                ref,
            )
            return
        hosts = self.host_tables.get(id(system))
        if hosts is None:
            hosts = self.host_tables[id(system)] = {}
            for h in system.hosts:
                hosts.setdefault(h.name, h)
        host = hosts.get(host_name)
        if host is None:
            self._error(
                f"node {ref.obj.name!r} is on unknown host {host_name!r}: hardware model "
                f"{system.name!r} has no such host",
                ref,
            )
            return
        using = self.using
        if using is not None and system is not using:
            self.ctx.warn(
                f"node {ref.obj.name!r} uses host {ref.text!r} outside the hardware model "
                f"{using.name!r} named by 'using'",
                self.shown,
                ref.token.line,
                ref.token.column,
            )
        ref.obj.host = host

    def component(self, ref: Ref) -> None:
        """A component instance's ``<package>/<component>``."""
        pkg_name, _, comp_name = ref.text.rpartition("/")
        if not self._package_known(pkg_name, "component_instance", ref):
            return
        comp = self.names.components[pkg_name].get(comp_name)
        if comp is None:
            self._error(
                f"component_instance {ref.obj.name!r} refers to unknown component {comp_name!r} of "
                f"package {pkg_name!r}",
                ref,
            )
            return
        ref.obj.component = comp

    def port(self, ref: Ref) -> None:
        """A port instance's ``<component>/<port>``, a port of its component instance's component."""
        comp = ref.extra.component
        comp_name, _, port_name = ref.text.rpartition("/")
        if comp is None:
            return  # the instance's own ref already failed
        if comp_name != comp.name or port_name not in self.names.port_names(comp):
            self._error(
                f"port_instance {ref.obj.name!r}: {ref.text!r} is not a port of component "
                f"{comp.name!r} (expected '{comp.name}/<port>')",
                ref,
            )

    def node02(self, ref: Ref) -> None:
        """A v0.2 ``node_instance``'s ``<package>/<node>``: the node's component instances, made here."""
        sw_info, names, ctx = self.sw_info, self.names, self.ctx
        packages = names.packages
        pkg_name, _, node_name = ref.text.rpartition("/")
        nodes = (sw_info.nodes.get(pkg_name) if sw_info is not None else None) or {}
        if not self._package_known(pkg_name, "node_instance", ref):
            return
        if node_name not in nodes:
            self._error(
                f"node_instance {ref.obj.name!r} refers to unknown node {node_name!r} of package "
                f"{pkg_name!r}",
                ref,
            )
            return
        package = packages[pkg_name]
        for inst_name, comp_ref, stmt in nodes[node_name]:
            comp_pkg, _, comp_name = qualify(comp_ref, pkg_name).rpartition("/")
            target_pkg = packages.get(comp_pkg)
            comp = names.components[comp_pkg].get(comp_name) if target_pkg is not None else None
            inst = new(
                "ComponentInstance",
                name=inst_name,
                componentRef=f"{comp_pkg}/{comp_name}",
                component=comp,
                line=stmt.line,
                column=stmt.column,
            )
            if comp is None:
                ctx.error(
                    NameResolutionError(
                        f"node {node_name!r} of package {package.name!r}: component {comp_ref!r} "
                        "is not defined",
                        file=sw_info.filename if sw_info else None,
                        line=stmt.line,
                        column=stmt.column,
                    )
                )
            ref.obj.componentInstances.append(inst)
        check_unique(
            ref.obj.componentInstances,
            "component instance",
            f"node {node_name!r}",
            sw_info.filename if sw_info else None,
            ctx,
        )
