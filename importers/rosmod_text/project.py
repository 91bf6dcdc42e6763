"""The entry points of the textual ROSMOD reader: a project folder (or one file) → ``rosmod.Project``.

:func:`read_project` finds the files of a project (:class:`_Layout`: the v0.3 folders
``01-Software/``, ``02-Hardware/``, ``03-Deployment/`` or their older ``-Configuration`` names,
or the files side by side), reads the software model in its dialect (v0.4 JSON, v0.1, v0.2 or
v0.3, told apart by its first statements), each ``.rhw`` hardware model with its ``snp/`` side
files and each ``.rdp`` deployment, then resolves the names across files; every problem is
collected and raised together as one :class:`~.context.RosmodImportError`.
:func:`is_rosmod_project` says whether a path looks like a project at all.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl.arguments import checked, expect_path
from rosaadl.errors import Diagnostic, ParseError
from rosaadl.fileio import existing
from rosaadl.importers.rosmod_text import groups, v01, v02, v03, v04
from rosaadl.importers.rosmod_text.blocks import Stmt, at, parse_blocks
from rosaadl.importers.rosmod_text.context import ImportContext, RosmodImportError
from rosaadl.importers.rosmod_text.files import read_text, shown_path, side_files
from rosaadl.importers.rosmod_text.resolution import (
    DeploymentInfo,
    ProjectModels,
    SoftwareInfo,
    check_unique,
    resolve_deployment,
    resolve_software,
)
from rosaadl.importers.rosmod_text.statements import new, new_property, skip

__all__ = ["read_project", "read_software_file", "is_rosmod_project"]

_SOFTWARE_DIRS = ("01-Software", "01-Software-Configuration")
_HARDWARE_DIRS = ("02-Hardware", "02-Hardware-Configuration")
_DEPLOYMENT_DIRS = ("03-Deployment", "03-Deployment-Configuration")
_SOFTWARE_SUFFIXES = (".rml", ".rosml")

# the reader of a package statement in each block dialect
_PACKAGE_READERS = {"0.1": v01.package, "0.2": v02.package, "0.3": v03.package}


def is_rosmod_project(path: str | os.PathLike[str]) -> bool:
    """True for a folder that holds a ROSMOD textual project (marker, standard folders or model files)."""
    root = expect_path(path)
    try:
        if root.is_file():
            return root.suffix.lower() in _SOFTWARE_SUFFIXES
        if not root.is_dir():
            return False
    except OSError:  # a name the system cannot look up (too long): not a project
        return False
    if any(p.suffix == ".rosmod" for p in root.iterdir() if p.is_file()):
        return True
    if any((root / n).is_dir() for n in _SOFTWARE_DIRS):
        return True
    return any(p.suffix.lower() in _SOFTWARE_SUFFIXES for p in root.iterdir() if p.is_file())


def read_software_file(
    path: str | os.PathLike[str], *, warnings: list[Diagnostic] | None = None, strict: bool = False
) -> EObject:
    """A project holding the software of one ``.rml`` (any version) or ``.rosml`` file."""
    source = expect_path(path)
    if not _Layout.exists(source, os.fspath(path)) or not source.is_file():
        raise RosmodImportError([ParseError("expected a .rml or .rosml file", file=os.fspath(path))])
    return read_project(path, warnings=warnings, strict=strict)


@checked
def read_project(
    path: str | os.PathLike[str], *, warnings: list[Diagnostic] | None = None, strict: bool = False
) -> EObject:
    """Read a ROSMOD textual project (folder) or a single ``.rml``/``.rosml`` file into a ``rosmod.Project``.

    Raises :class:`RosmodImportError` listing every located problem; warnings (skipped
    statements, skipped side files, a host defined twice in one ``.rhw`` — the later definition
    wins, as in ROSMOD) are logged and appended to ``warnings`` when given. With ``strict``,
    a repeated host is an error like every other duplicate name.
    """
    ctx = ImportContext(warnings, strict)
    layout = _Layout.of(os.fspath(path))
    project = new("Project", name=layout.name, path=layout.given)
    # the software model
    software = sw_info = None
    version = None
    software_failed = False
    for sw_file in layout.sw_files:
        rel = layout.rel(sw_file)
        shown = layout.shown(rel) if layout.root.is_dir() else layout.given
        try:
            text = read_text(sw_file, shown)
            if v04.looks_like_json(text):
                version = "0.4"
                v04.read_v04(text, shown, rel, project, ctx)
                continue
            stmts = parse_blocks(text, shown)
            version = _block_dialect(stmts)
            software, sw_info = _read_software(stmts, version, sw_file.stem, rel, shown, ctx)
            project.software = software
            if version == "0.3":  # messages and services live in msg/ and srv/ beside the .rml
                v03.load_interfaces(software, sw_file.parent, layout.folder, layout.shown_root, sw_info, ctx)
        except ParseError as exc:
            ctx.error(exc)
            software_failed = True
    # the hardware models
    systems: dict[str, EObject] = {}
    failed_systems: set[str] = set()  # hardware models that could not be read: no cascade errors
    legacy_hw = False
    for hw_file in layout.hw_files:
        rel = layout.rel(hw_file)
        shown = layout.shown(rel)
        try:
            stmts = parse_blocks(read_text(hw_file, shown), shown)
            system = v03.read_hardware(stmts, hw_file.stem, rel, shown, ctx)
            if any(s.keyword == "host" for s in stmts):
                legacy_hw = True
            project.systems.append(system)
            systems[system.name] = system
        except ParseError as exc:
            ctx.error(exc)
            failed_systems.add(hw_file.stem)
    _read_snp(layout, systems, ctx)
    # the deployments
    deployments = []
    for dp_file in layout.dp_files:
        rel = layout.rel(dp_file)
        shown = layout.shown(rel)
        try:
            stmts = parse_blocks(read_text(dp_file, shown), shown, listings=groups.LISTINGS)
            deployment, info = _read_deployment(stmts, dp_file.stem, rel, shown, ctx)
            project.deployments.append(deployment)
            deployments.append((deployment, info))
        except ParseError as exc:
            ctx.error(exc)
    # names across files
    if software is not None and sw_info is not None:
        resolve_software(software, sw_info, ctx)
    models = ProjectModels(systems, project.software, sw_info, software_failed, failed_systems)
    for deployment, info in deployments:
        resolve_deployment(deployment, info, models, ctx)
        groups.resolve_groups(deployment, info, software_failed, ctx)
    if version is None:  # no software model: tell v0.2 from v0.3 by the hardware/deployment syntax
        legacy_dp = any(p.key.startswith("host_instance:") for d in project.deployments for p in d.properties)
        version = "0.2" if (legacy_hw or legacy_dp) else "0.3"
    project.formatVersion = version
    ctx.raise_if_errors()
    return project


# --------------------------------------------------------------------------- the files of a project


@dataclass(frozen=True)
class _Layout:
    """The model files of a project and how to name them in messages."""

    given: str  # the path as the user gave it
    root: Path
    folder: Path  # the folder paths are relative to
    shown_root: str  # that folder as the user named it
    name: str
    sw_files: list[Path]
    hw_files: list[Path]
    dp_files: list[Path]

    @staticmethod
    def exists(root: Path, given: str) -> bool:
        """Whether ``root`` exists; a path the system cannot look up is a located error."""
        try:
            return existing(root, ParseError)
        except ParseError as exc:
            raise RosmodImportError([exc]) from None

    @classmethod
    def of(cls, given: str) -> _Layout:
        root = expect_path(given)
        if not cls.exists(root, given):
            raise RosmodImportError([ParseError("no such file or folder", file=given)])
        if root.is_file():
            return cls(given, root, root.parent, os.path.dirname(given), root.stem, [root], [], [])
        sw_dir = _pick_dir(root, _SOFTWARE_DIRS, given, "software")
        hw_dir = _pick_dir(root, _HARDWARE_DIRS, given, "hardware")
        dp_dir = _pick_dir(root, _DEPLOYMENT_DIRS, given, "deployment")
        sw_files = [p for p in side_files(sw_dir or root, "") if p.suffix.lower() in _SOFTWARE_SUFFIXES]
        hw_files = side_files(hw_dir or root, ".rhw")
        dp_files = side_files(dp_dir or root, ".rdp")
        if not (sw_files or hw_files or dp_files):
            raise RosmodImportError(
                [ParseError("not a ROSMOD project: no .rml, .rosml, .rhw or .rdp files found", file=given)]
            )
        if len(sw_files) > 1:
            raise RosmodImportError(
                [
                    ParseError(
                        f"a ROSMOD project has one software model; found {len(sw_files)}: "
                        f"{', '.join(p.name for p in sw_files)}",
                        file=shown_path(given, sw_files[1].relative_to(root)),
                    )
                ]
            )
        return cls(given, root, root, given, root.resolve().name, sw_files, hw_files, dp_files)

    def rel(self, path: Path) -> str:
        return path.relative_to(self.folder).as_posix()

    def shown(self, rel: Path | str) -> str:
        return shown_path(self.shown_root, rel)


def _pick_dir(root: Path, names: Sequence[str], shown_root: str, what: str) -> Path | None:
    found = [root / n for n in names if (root / n).is_dir()]
    if len(found) > 1:
        raise RosmodImportError(
            [
                ParseError(
                    f"two {what} folders ({', '.join(p.name for p in found)}); expected one", file=shown_root
                )
            ]
        )
    return found[0] if found else None


# --------------------------------------------------------------------------- one file each


def _block_dialect(stmts: list[Stmt]) -> str:
    """The version of a software model written in blocks: "0.1", "0.2" or "0.3"."""
    if v01.is_v01(stmts):
        return "0.1"
    if v02.is_v02(stmts):
        return "0.2"
    return "0.3"


def _read_software(
    stmts: list[Stmt], version: str, name: str, rel: str, shown: str, ctx: ImportContext
) -> tuple[EObject, SoftwareInfo]:
    """The ``Software`` of a ``.rml``/``.rosml`` file written in blocks, in dialect ``version``."""
    info = SoftwareInfo(filename=shown)
    software = new("Software", name=name, sourceFile=rel)
    read_package = _PACKAGE_READERS[version]
    for stmt in stmts:
        try:
            if stmt.keyword == "workspace" and version == "0.1":
                software.name = v01.workspace_name(stmt, shown)
            elif stmt.keyword == "package" and stmt.body is not None:
                software.packages.append(read_package(stmt, info, ctx))
            else:
                skip(ctx, stmt, shown)
        except ParseError as exc:
            ctx.error(exc)
    return software, info


def _read_snp(layout: _Layout, systems: dict[str, EObject], ctx: ImportContext) -> None:
    """The ``snp/<hardware>[.<host>].snp`` files beside the hardware models, as ``snp`` properties."""
    if not layout.hw_files:
        return
    snp_dir = layout.hw_files[0].parent / "snp"
    for sys_name, system in systems.items():
        if not snp_dir.is_dir():
            continue
        for snp in side_files(snp_dir, ".snp"):
            parts = snp.name[:-4].split(".")
            shown = layout.shown(snp.relative_to(layout.folder))
            if parts[0] != sys_name or len(parts) > 2:
                continue
            try:
                text = read_text(snp, shown)
            except ParseError as exc:
                ctx.error(exc)
                continue
            if len(parts) == 1:
                system.properties.append(new_property("snp", text))
            else:
                host = next((h for h in system.hosts if h.name == parts[1]), None)
                if host is None:
                    ctx.warn(f"skipped {snp.name!r}: no host {parts[1]!r} in {sys_name!r}", shown)
                else:
                    host.properties.append(new_property("snp", text))


def _read_deployment(
    stmts: list[Stmt], name: str, rel: str, shown: str, ctx: ImportContext
) -> tuple[EObject, DeploymentInfo]:
    """The ``Deployment`` of a ``.rdp`` file: ``using``, v0.3 ``node``, v0.2 ``host_instance`` and
    top-level ``group`` blocks."""
    deployment = new("Deployment", name=name, sourceFile=rel)
    info = DeploymentInfo(filename=shown)
    for stmt in stmts:
        try:
            if stmt.keyword == "using" and stmt.body is None and stmt.value is None:
                ref = "".join(t.text for t in stmt.head[1:])
                if not ref:
                    raise ParseError("expected 'using <hardware model>;'", location=at(shown, stmt))
                if info.using is not None:
                    raise ParseError(
                        f"a second 'using' (the first is at line {info.using.line})",
                        location=at(shown, stmt),
                    )
                deployment.systemName = ref
                info.using = stmt
            elif stmt.keyword == "node" and stmt.body is not None:
                deployment.nodes.append(v03.node(stmt, shown, info, ctx))
            elif stmt.keyword == "host_instance" and stmt.body is not None:
                v02.host_instance(stmt, deployment, shown, info, ctx)
            elif stmt.keyword == "group" and stmt.body is not None:
                groups.read_group(stmt, deployment, shown, info, ctx)
            else:
                skip(ctx, stmt, shown)
        except ParseError as exc:
            ctx.error(exc)
    check_unique(deployment.nodes, "node", f"deployment {name!r}", shown, ctx)
    return deployment, info
