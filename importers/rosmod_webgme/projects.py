"""The entry points of the WebGME reader: the ROSMOD projects of a ``.webgmex`` export → ``rosmod.Project``.

:func:`read_webgmex` opens the archive (:mod:`.archive`), builds the tree (:mod:`.tree`), finds
the ROSMOD projects in it and maps each (:func:`map_project`): systems and deployments, then the
software, then the references across them. Every problem of every project is raised together
as one :class:`~rosaadl.importers.rosmod_text.RosmodImportError`.
"""

from __future__ import annotations

import logging
import os

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.arguments import checked
from rosaadl.errors import Diagnostic, ImportFormatError, Location, NameResolutionError, RosaadlError
from rosaadl.importers.rosmod_text.context import ImportContext, RosmodImportError
from rosaadl.importers.rosmod_webgme import deployments, software, systems
from rosaadl.importers.rosmod_webgme.archive import load_project_json
from rosaadl.importers.rosmod_webgme.mapping import SKIPPED_KINDS, Mapper
from rosaadl.importers.rosmod_webgme.tree import Node, Tree

__all__ = ["read_webgmex", "read_webgmex_projects", "project_names", "map_project"]

log = logging.getLogger(__package__)

# the folders of a project: folder kind → (kind of its items, their mapping, feature of Project)
_FOLDERS = {
    "Systems": ("System", systems.system, "systems"),
    "Deployments": ("Deployment", deployments.deployment, "deployments"),
}


def project_names(path: str | os.PathLike[str]) -> list[str]:
    """Names of the ROSMOD projects in a ``.webgmex`` archive (sorted)."""
    filename = os.fspath(path)
    tree = Tree(load_project_json(filename), filename)
    return [n.name for n in _project_nodes(tree)]


@checked
def read_webgmex(
    path: str | os.PathLike[str],
    *,
    project: str | None = None,
    warnings: list[Diagnostic] | None = None,
) -> list[EObject]:
    """Read the ROSMOD projects of a ``.webgmex`` archive (all of them, or the one named ``project``).

    Returns one ``rosmod.Project`` per WebGME project, sorted by name. Problems are raised
    together as a :class:`~rosaadl.importers.rosmod_text.RosmodImportError` whose errors name
    the archive and the element path (``AGSE/Software/motor_controller/…``).
    """
    filename = os.fspath(path)
    ctx = ImportContext(warnings, log=log)
    try:
        tree = Tree(load_project_json(filename), filename)
        nodes = _project_nodes(tree)
        if project is not None:
            chosen = [n for n in nodes if n.name == project]
            if not chosen:
                known = ", ".join(repr(n.name) for n in nodes) or "none"
                raise NameResolutionError(
                    f"no project {project!r} in the archive (projects: {known})", file=filename
                )
            nodes = chosen
        projects = [map_project(Mapper(tree, filename, ctx), node) for node in nodes]
    except RosmodImportError:
        raise
    except RosaadlError as exc:
        raise RosmodImportError([exc]) from None
    except RecursionError:
        raise RosmodImportError(
            [ImportFormatError("the project tree is nested too deeply", Location(file=filename))]
        ) from None
    ctx.raise_if_errors()
    return projects


def read_webgmex_projects(
    path: str | os.PathLike[str],
    *,
    project: str | None = None,
    warnings: list[Diagnostic] | None = None,
) -> list[EObject]:
    """:func:`read_webgmex` for what must convert or check a project: an archive that holds no
    ROSMOD project (only a META, or an empty root) is an :class:`~rosaadl.errors.ImportFormatError`
    located at the archive, never an empty result that writes nothing."""
    projects = read_webgmex(path, project=project, warnings=warnings)
    if not projects:
        raise ImportFormatError(
            "the archive holds no ROSMOD project (no node of META type Project); nothing to read",
            file=os.fspath(path),
        )
    return projects


def _project_nodes(tree: Tree) -> list[Node]:
    found: list[Node] = []
    stack = [tree.root]
    while stack:
        node = stack.pop()
        for child in node.children():
            if child.is_meta():
                continue
            if child.meta_type == "Project":
                found.append(child)
            elif child.meta_type in ("Projects", "") or child.parent is tree.root:
                stack.append(child)
    return sorted(found, key=lambda n: (n.name, n.path))


def map_project(m: Mapper, node: Node) -> EObject:
    """The ``rosmod.Project`` of the WebGME project ``node``."""
    project = model.new("rosmod.Project", name=node.name, formatVersion="webgme", path=m.filename)
    for key, value in node.project_attributes().items():
        project.properties.append(m.prop(key, value))
    software_nodes = []
    for child in m.children(node):
        kind = child.meta_type
        if kind == "Software":
            software_nodes.append(child)
        elif kind in _FOLDERS:
            item_kind, read, feature = _FOLDERS[kind]
            for item in m.children(child):
                if item.meta_type == item_kind:
                    getattr(project, feature).append(read(m, item))
                else:
                    m.unknown(child, item, project.properties)
        elif kind == "Experiments":
            m.experiments.extend((child.name, e) for e in m.children(child))
        elif kind in SKIPPED_KINDS:
            log.debug("skipped %s %s", kind, child.element_path())
        else:
            m.unknown(node, child, project.properties)
    if software_nodes:
        sw = model.new(
            "rosmod.Software", name=software_nodes[0].name, sourceFile=os.path.basename(m.filename)
        )
        if len(software_nodes) > 1:
            m.warn(node, f"{len(software_nodes)} Software folders; their packages are merged")
        for folder in software_nodes:
            software.software(m, folder, sw, project)
        project.software = sw
    deployments.resolve(m, project)
    return project
