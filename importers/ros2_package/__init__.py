"""ROS 2 ``rclpy`` packages → a ROSMOD project, read statically (nothing is run or imported).

``rosaadl import ros2-package DIR... -o MODEL`` and ``rosaadl check DIR``: the folders given are
packages (holding ``package.xml``) or workspaces holding them. In each package: the manifest
(:mod:`.sources`), the nodes of its Python modules (:mod:`.node_classes`), its ``setup.py`` entry
points and Python launch files (:mod:`.launching`), its ``.msg``/``.srv`` files. The facts
(:mod:`.facts`) become a ROSMOD project (:mod:`.building`) that converts to AADL with
``transforms.rosmod_to_aadl``. Everything the sources do not say for certain is a warning at its
file and line; when no node at all could be read, :func:`read_ros2_packages` raises one error
listing every problem.

>>> project = read_ros2_packages(["ws/src"], warnings=[])   # doctest: +SKIP
"""

from __future__ import annotations

import ast
import os
from collections.abc import Sequence
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl.errors import Diagnostic, ImportFormatError, Location
from rosaadl.importers.ros2_package.building import build_project
from rosaadl.importers.ros2_package.facts import (
    DeploymentFact,
    InterfaceFact,
    LaunchedNode,
    NodeFact,
    SystemFacts,
)
from rosaadl.importers.ros2_package.launching import (
    EntryPoint,
    LaunchAction,
    cmake_programs,
    entry_points,
    launch_actions,
    setup_cfg_entry_points,
)
from rosaadl.importers.ros2_package.node_classes import ModuleNodes, class_files, read_module
from rosaadl.importers.ros2_package.package_classes import abstract_classes, outside_classes, resolved_imports
from rosaadl.importers.ros2_package.sources import (
    MAX_DEPTH,
    find_packages,
    package_files,
    parse_python,
    read_manifest,
    read_text,
)
from rosaadl.importers.ros2_package.statements import mark_assignments

__all__ = ["read_ros2_packages", "read_facts", "is_ros2_package_folder"]

_OTHER_LAUNCH = (".launch.xml", ".launch.yaml", ".launch.yml", ".launch")
_CPP = (".cpp", ".cc", ".cxx", ".hpp", ".hh", ".h")


def is_ros2_package_folder(path: Path) -> bool:
    """Does ``path`` hold a ROS 2 package (``package.xml``), itself or a few levels down?"""
    if (path / "package.xml").is_file():
        return True
    for depth in range(1, 4):
        pattern = "/".join(["*"] * depth) + "/package.xml"
        try:
            if any(p.is_file() for p in path.glob(pattern)):
                return True
        except OSError:
            return False
    return False


def _module_name(relative: Path) -> str:
    parts = list(relative.with_suffix("").parts)
    if parts and parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


class _Package:
    """What one package holds, read file by file."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.modules: dict[str, ModuleNodes] = {}
        self.entries: list[EntryPoint] = []
        self.launches: list[tuple[str, list[LaunchAction]]] = []


def _read_package(
    folder: Path, name: str, roots: list[Path], facts: SystemFacts, warnings: list[Diagnostic]
) -> _Package:
    package = _Package(name)
    cpp = 0
    sources: list[tuple[ast.Module, Path, Path]] = []  # the modules, read once all are parsed
    for path in package_files(folder):
        shown = str(path)
        relative = path.relative_to(folder)
        lowered = path.name.lower()
        if path.suffix in (".msg", ".srv") and relative.parts[0] in ("msg", "srv"):
            text = read_text(path, shown, roots, warnings)
            if text is not None:
                facts.interfaces.append(
                    InterfaceFact(name, path.stem, path.suffix[1:], text, Location(shown, 1))
                )
            continue
        if lowered.endswith(_OTHER_LAUNCH):
            warnings.append(
                Diagnostic(
                    "warning",
                    "an XML or YAML launch file: only Python launch files are read",
                    Location(shown),
                )
            )
            continue
        if path.suffix in _CPP:
            cpp += 1
            continue
        if relative.parts == ("setup.cfg",) or relative.parts == ("CMakeLists.txt",):
            text = read_text(path, shown, roots, warnings)
            if text is not None:
                read = setup_cfg_entry_points if path.suffix == ".cfg" else cmake_programs
                package.entries.extend(read(text, shown, warnings))
            continue
        if path.suffix != ".py":
            continue
        text = read_text(path, shown, roots, warnings)
        tree = parse_python(text, shown, warnings) if text is not None else None
        if tree is None:
            continue
        try:
            if not _read_source(package, tree, path, relative, warnings):
                sources.append((tree, path, relative))
        except RecursionError:
            _too_deep(shown, warnings)
    _read_modules(package, sources, facts, warnings)
    if cpp:
        warnings.append(
            Diagnostic(
                "warning",
                f"package {name!r} has {cpp} C/C++ source file(s): only Python (rclpy) nodes are read; "
                "its C++ nodes are not imported",
                Location(str(folder / "package.xml")),
            )
        )
    return package


def _too_deep(shown: str, warnings: list[Diagnostic]) -> None:
    warnings.append(
        Diagnostic("warning", "the source nests too deeply to be read; not read", Location(shown))
    )


def _read_source(package: _Package, tree, path: Path, relative: Path, warnings: list[Diagnostic]) -> bool:
    """Read a ``setup.py`` (entry points) or a launch file of ``package``; False for a module."""
    shown = str(path)
    if relative.parts == ("setup.py",):
        package.entries.extend(entry_points(tree, shown, warnings))
    elif path.name.lower().endswith(".launch.py") or relative.parts[0] == "launch":
        name = path.name.removesuffix(".py").removesuffix(".launch")
        package.launches.append((name, launch_actions(tree, shown, warnings)))
    else:
        return False
    return True


def _read_modules(
    package: _Package,
    sources: list[tuple[ast.Module, Path, Path]],
    facts: SystemFacts,
    warnings: list[Diagnostic],
) -> None:
    """The nodes of the package's modules, a class deriving from a node class of another module
    of the package read with that class's methods (:mod:`.package_classes`)."""
    modules: dict[str, tuple[ast.Module, dict[str, str], str]] = {}
    for tree, path, relative in sources:
        mark_assignments(tree)
        name = _module_name(relative)
        modules[name] = (
            tree,
            resolved_imports(tree, name, is_package=relative.name == "__init__.py"),
            str(path),
        )
    try:
        outside = outside_classes(modules)
        abstract = abstract_classes(modules, outside)
    except RecursionError:
        outside, abstract = {}, set()
    files = class_files(outside)
    constants = {q.rpartition(".")[0]: item.constants for q, item in outside.items()}
    for tree, path, relative in sources:
        name = _module_name(relative)
        try:
            found = read_module(
                tree,
                str(path),
                package.name,
                warnings,
                imports=dict(modules[name][1]),
                outside=outside,
                bases_only={q.rpartition(".")[2] for q in abstract if q.rpartition(".")[0] == name},
                files=files,
                constants=constants.get(name),
            )
        except RecursionError:
            _too_deep(str(path), warnings)
            continue
        package.modules[name] = found
        for node in found.nodes:
            facts.nodes[node.key] = node


def _executables(packages: dict[str, _Package]) -> dict[tuple[str, str], list[NodeFact]]:
    """(package, executable) → the nodes its entry point's function makes."""
    found: dict[tuple[str, str], list[NodeFact]] = {}
    for package in packages.values():
        for entry in package.entries:
            module = package.modules.get(entry.module)
            if module is None:
                continue
            made = module.functions.get(entry.function) or []
            nodes = [module.classes[n] for n in dict.fromkeys(made) if n in module.classes] or (
                module.nodes if len(module.nodes) == 1 else []
            )
            for node in nodes:
                node.executables = (*node.executables, entry.executable)
            found[(package.name, entry.executable)] = nodes
    return found


def _deployments(packages: dict[str, _Package], facts: SystemFacts, warnings: list[Diagnostic]) -> None:
    executables = _executables(packages)
    for package in packages.values():
        for name, actions in package.launches:
            deployment = DeploymentFact(name)
            for action in actions:
                nodes = executables.get((action.package, action.executable))
                if not nodes:
                    warnings.append(
                        Diagnostic(
                            "warning",
                            f"launches {action.package}/{action.executable}, whose node is not among the "
                            "packages read; left out",
                            action.location,
                        )
                    )
                    continue
                if len(nodes) > 1:
                    warnings.append(
                        Diagnostic(
                            "warning",
                            f"{action.package}/{action.executable} makes several nodes "
                            f"({', '.join(n.node_name for n in nodes)}); the launch name is given to each",
                            action.location,
                        )
                    )
                for node in nodes:
                    launched_name = action.name if action.name and len(nodes) == 1 else node.node_name
                    deployment.nodes.append(
                        LaunchedNode(
                            node.key,
                            launched_name,
                            action.namespace or node.namespace,
                            dict(action.remappings),
                            dict(action.parameters),
                            action.location,
                        )
                    )
            if deployment.nodes:
                facts.deployments.append(deployment)


def read_facts(paths: Sequence[str | os.PathLike[str]], warnings: list[Diagnostic]) -> SystemFacts:
    """The ROS 2 facts of the packages in ``paths`` (folders); findings go to ``warnings``."""
    folders = [Path(p) for p in paths]
    roots = []
    for folder in folders:
        try:
            roots.append(folder.resolve())
        except (OSError, RuntimeError):
            warnings.append(
                Diagnostic("warning", "the folder cannot be resolved; not read", Location(str(folder)))
            )
    package_folders = find_packages(folders, warnings)
    if not package_folders:
        warnings.append(
            Diagnostic(
                "warning",
                f"no package.xml in the folder or its subfolders (down to {MAX_DEPTH} levels)",
                Location(", ".join(map(str, folders))),
            )
        )
    packages: dict[str, _Package] = {}
    first = folders[0].resolve().name if folders else "ros2"
    facts = SystemFacts(first or "ros2")
    for folder in package_folders:
        manifest = read_manifest(folder, roots, warnings)
        if manifest is None:
            continue
        if manifest.name in packages:
            warnings.append(
                Diagnostic(
                    "warning",
                    f"a second package named {manifest.name!r}; not read",
                    Location(str(folder / "package.xml")),
                )
            )
            continue
        packages[manifest.name] = _read_package(folder, manifest.name, roots, facts, warnings)
    if len(packages) == 1:
        facts.name = next(iter(packages))
    _deployments(packages, facts, warnings)
    return facts


def read_ros2_packages(paths: Sequence[str | os.PathLike[str]], warnings: list[Diagnostic]) -> EObject:
    """The ROSMOD project of the ROS 2 packages in ``paths`` (see the module docstring).

    Raises :class:`ImportFormatError` listing every problem when no node could be read.
    """
    found: list[Diagnostic] = []
    facts = read_facts(paths, found)
    if not facts.nodes:
        errors = [Diagnostic("error", d.message, d.location) for d in found]
        where = ", ".join(str(p) for p in paths)
        raise ImportFormatError(
            "no ROS 2 node could be read (no Node subclass or rclpy.create_node in the Python sources)",
            Location(where),
            errors=[*errors, Diagnostic("error", "no ROS 2 node could be read", Location(where))],
        )
    project = build_project(facts, found)
    warnings.extend(found)
    return project
