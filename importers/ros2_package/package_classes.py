"""The node classes of a package across its modules: ``class Talker(BaseNode)`` in
``my_pkg/talker.py`` with ``from .base import BaseNode`` (or ``from my_pkg.base import BaseNode``)
is a node when ``BaseNode`` is one, and reads the methods ``BaseNode`` defines in ``base.py``.
A node class that others derive from and that no module of the package makes (calls) is a base
only, not a node of its own.

The modules are named as Python imports them from the package folder (``my_pkg.base``); relative
imports are resolved against that name. A base class from outside the package (other than
rclpy's node classes) is not followed.
"""

from __future__ import annotations

import ast

from rosaadl.importers.ros2_package.node_classes import (
    NODE_BASES,
    OutsideClass,
    dotted,
    module_constants,
    module_imports,
)

__all__ = ["resolved_imports", "outside_classes", "abstract_classes"]

#: Deepest chain of base classes followed across modules.
_MAX_ROUNDS = 64


def resolved_imports(tree: ast.Module, module: str, *, is_package: bool) -> dict[str, str]:
    """What each name ``tree`` imports stands for, relative imports resolved against
    ``module`` (``from .base import BaseNode`` in ``pkg.talker`` → ``pkg.base.BaseNode``)."""
    found = module_imports(tree)
    parts = module.split(".") if module else []
    here = parts if is_package else parts[:-1]
    for stmt in ast.walk(tree):
        if not (isinstance(stmt, ast.ImportFrom) and stmt.level):
            continue
        if stmt.level - 1 > len(here):
            continue
        base = here[: len(here) - (stmt.level - 1)]
        prefix = ".".join([*base, *([stmt.module] if stmt.module else [])])
        for alias in stmt.names:
            if alias.name != "*":
                found[alias.asname or alias.name] = f"{prefix}.{alias.name}" if prefix else alias.name
    return found


def outside_classes(modules: dict[str, tuple[ast.Module, dict[str, str], str]]) -> dict[str, OutsideClass]:
    """The node classes of ``modules`` (module name → its tree, resolved imports and file) by
    qualified name, each with its module's names, for the other modules to derive from."""
    classes = {
        f"{name}.{stmt.name}": (name, stmt)
        for name, (tree, _, _) in modules.items()
        for stmt in tree.body
        if isinstance(stmt, ast.ClassDef)
    }
    nodes: set[str] = set()
    for _ in range(_MAX_ROUNDS):
        added = False
        for qualified, (module, cls) in classes.items():
            if qualified in nodes:
                continue
            imports = modules[module][1]
            for base in cls.bases:
                name = dotted(base, imports)
                local = f"{module}.{base.id}" if isinstance(base, ast.Name) else None
                if name in NODE_BASES or name in nodes or local in nodes:
                    nodes.add(qualified)
                    added = True
                    break
        if not added:
            break
    found: dict[str, OutsideClass] = {}
    constants: dict[str, dict] = {}
    for qualified in sorted(nodes):
        module, cls = classes[qualified]
        tree, imports, file = modules[module]
        if module not in constants:
            constants[module] = module_constants(tree, imports)
        local = {classes[q][1].name: classes[q][1] for q in nodes if classes[q][0] == module}
        found[qualified] = OutsideClass(cls, imports, constants[module], local, file)
    return found


def abstract_classes(
    modules: dict[str, tuple[ast.Module, dict[str, str], str]], classes: dict[str, OutsideClass]
) -> set[str]:
    """The node classes (qualified names) that other node classes derive from and that no module
    of the package calls: bases only."""
    bases: set[str] = set()
    for qualified, item in classes.items():
        module = qualified.rpartition(".")[0]
        for base in item.cls.bases:
            if isinstance(base, ast.Name) and base.id in item.local:
                bases.add(f"{module}.{base.id}")
            else:
                bases.add(dotted(base, item.imports) or "")
    called: set[str] = set()
    for module, (tree, imports, _) in modules.items():
        defined = {stmt.name for stmt in tree.body if isinstance(stmt, ast.ClassDef)}
        for node in ast.walk(tree):
            if isinstance(node, ast.Call):
                if isinstance(node.func, ast.Name) and node.func.id in defined:
                    called.add(f"{module}.{node.func.id}")
                else:
                    called.add(dotted(node.func, imports) or "")
    return {q for q in classes if q in bases and q not in called}
