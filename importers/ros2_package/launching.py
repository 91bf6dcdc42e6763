"""What starts the nodes: ``setup.py`` entry points (executable → module function) and the
``launch_ros.actions.Node`` actions of Python launch files, read with ``ast``.

A launch ``Node`` gives its package, executable, name, namespace, ``parameters`` (dictionaries)
and ``remappings`` (pairs); each part that is not a literal (or a constant of the file) is a
warning at its line and is left out. XML and YAML launch files are named in a warning.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass, field

from rosaadl.errors import Diagnostic, Location
from rosaadl.importers.ros2_package.evaluation import UNKNOWN, Known, Scope, evaluate
from rosaadl.importers.ros2_package.node_classes import dotted, module_imports

__all__ = ["EntryPoint", "LaunchAction", "entry_points", "launch_actions", "module_constants"]


@dataclass(frozen=True)
class EntryPoint:
    """``talker = demo_nodes.talker:main``."""

    executable: str
    module: str
    function: str


@dataclass
class LaunchAction:
    """One ``Node(...)`` of a launch file."""

    package: str
    executable: str
    name: str | None
    namespace: str
    parameters: dict[str, object] = field(default_factory=dict)
    remappings: dict[str, str] = field(default_factory=dict)
    location: Location = field(default_factory=Location)


def module_constants(tree: ast.Module) -> dict[str, Known]:
    """The module's top-level names bound to a known value."""
    names: dict[str, Known] = {}
    for stmt in tree.body:
        if isinstance(stmt, ast.Assign):
            value = evaluate(stmt.value, Scope(names))
            for target in stmt.targets:
                if isinstance(target, ast.Name):
                    names[target.id] = value if isinstance(value, Known) else Known(UNKNOWN)
    return names


def _text(node: ast.expr | None, scope: Scope) -> str | None:
    value = evaluate(node, scope)
    return value.value if isinstance(value, Known) and isinstance(value.value, str) else None


def entry_points(tree: ast.Module, file: str, warnings: list[Diagnostic]) -> list[EntryPoint]:
    """The ``console_scripts`` of the ``setup(...)`` call of a ``setup.py``."""
    scope = Scope(module_constants(tree))
    found: list[EntryPoint] = []
    for node in ast.walk(tree):
        if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "setup"):
            continue
        for keyword in node.keywords:
            if keyword.arg != "entry_points" or not isinstance(keyword.value, ast.Dict):
                continue
            for key, value in zip(keyword.value.keys, keyword.value.values, strict=True):
                if _text(key, scope) != "console_scripts" or not isinstance(value, (ast.List, ast.Tuple)):
                    continue
                for item in value.elts:
                    text = _text(item, scope)
                    if text is None or "=" not in text or ":" not in text:
                        warnings.append(
                            Diagnostic(
                                "warning",
                                f"entry point {ast.unparse(item)} is not known from the source",
                                Location(file, item.lineno, item.col_offset + 1),
                            )
                        )
                        continue
                    executable, _, target = text.partition("=")
                    module, _, function = target.strip().partition(":")
                    found.append(EntryPoint(executable.strip(), module.strip(), function.strip()))
    return found


def _pairs(node: ast.expr, scope: Scope, file: str, warnings: list[Diagnostic]) -> dict[str, str]:
    found: dict[str, str] = {}
    if not isinstance(node, (ast.List, ast.Tuple)):
        warnings.append(
            Diagnostic(
                "warning", f"remappings {ast.unparse(node)} are not a literal list; left out", _at(file, node)
            )
        )
        return found
    for item in node.elts:
        ends = item.elts if isinstance(item, (ast.Tuple, ast.List)) and len(item.elts) == 2 else None
        texts = [_text(end, scope) for end in ends] if ends else [None]
        if ends is None or None in texts:
            warnings.append(
                Diagnostic(
                    "warning", f"remapping {ast.unparse(item)} is not literal; left out", _at(file, item)
                )
            )
            continue
        found[texts[0]] = texts[1]  # type: ignore[index]
    return found


def _parameters(node: ast.expr, scope: Scope, file: str, warnings: list[Diagnostic]) -> dict[str, object]:
    found: dict[str, object] = {}
    items = node.elts if isinstance(node, (ast.List, ast.Tuple)) else [node]
    for item in items:
        if not isinstance(item, ast.Dict):
            warnings.append(
                Diagnostic(
                    "warning",
                    f"parameters {ast.unparse(item)} are not a literal dictionary (a file?); left out",
                    _at(file, item),
                )
            )
            continue
        for key, value in zip(item.keys, item.values, strict=True):
            name, known = _text(key, scope), evaluate(value, scope)
            if name is None or not isinstance(known, Known):
                warnings.append(
                    Diagnostic(
                        "warning",
                        f"parameter {ast.unparse(value)} is not literal; left out",
                        _at(file, value),
                    )
                )
                continue
            found[name] = known.value
    return found


def _at(file: str, node: ast.AST) -> Location:
    return Location(file, getattr(node, "lineno", None), getattr(node, "col_offset", 0) + 1)


_LAUNCH_NODE = ("launch_ros.actions.Node", "launch_ros.actions.node.Node")


def _forwards(call: ast.Call) -> bool:
    """Whether ``call`` passes on a ``**kwargs`` it received (``RosNode(**kwargs)``)."""
    return any(k.arg is None and isinstance(k.value, ast.Name) for k in call.keywords)


def _node_wrappers(tree: ast.Module, imports: dict[str, str]) -> list[str]:
    """Module-level functions that take ``**kwargs`` and pass them on to ``launch_ros``'s
    ``Node`` (as rosaadl's generated launch files do, to fit the prefix to the machine): a call
    of such a function is a launch ``Node`` with the caller's keywords."""
    wrappers = []
    for stmt in tree.body:
        if not isinstance(stmt, ast.FunctionDef) or stmt.args.kwarg is None:
            continue
        extra = stmt.args.kwarg.arg
        for inner in ast.walk(stmt):
            if (
                isinstance(inner, ast.Call)
                and dotted(inner.func, imports) in _LAUNCH_NODE
                and any(k.arg is None and isinstance(k.value, ast.Name) and k.value.id == extra
                        for k in inner.keywords)
            ):  # fmt: skip
                wrappers.append(stmt.name)
                break
    return wrappers


def launch_actions(tree: ast.Module, file: str, warnings: list[Diagnostic]) -> list[LaunchAction]:
    """The ``launch_ros.actions.Node(...)`` calls of a Python launch file."""
    imports = module_imports(tree)
    scope = Scope(module_constants(tree))
    for wrapper in _node_wrappers(tree, imports):
        imports[wrapper] = _LAUNCH_NODE[0]
    found: list[LaunchAction] = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call) or dotted(node.func, imports) not in _LAUNCH_NODE:
            continue
        if _forwards(node):
            continue  # a wrapper's own call: its arguments are its caller's
        args = {k.arg: k.value for k in node.keywords if k.arg}
        package, executable = _text(args.get("package"), scope), _text(args.get("executable"), scope)
        if package is None or executable is None:
            warnings.append(
                Diagnostic(
                    "warning",
                    "a launch Node whose package or executable is not literal; left out",
                    _at(file, node),
                )
            )
            continue
        name = _text(args.get("name"), scope) if "name" in args else None
        if "name" in args and name is None:
            warnings.append(
                Diagnostic(
                    "warning", "the node name is not literal; the node's own name is kept", _at(file, node)
                )
            )
        namespace = _text(args.get("namespace"), scope) if "namespace" in args else ""
        if namespace is None:
            warnings.append(
                Diagnostic(
                    "warning", "the namespace is not literal; the root namespace is kept", _at(file, node)
                )
            )
            namespace = ""
        action = LaunchAction(package, executable, name, namespace, location=_at(file, node))
        if "parameters" in args:
            action.parameters = _parameters(args["parameters"], scope, file, warnings)
        if "remappings" in args:
            action.remappings = _pairs(args["remappings"], scope, file, warnings)
        found.append(action)
    return found
