"""What starts the nodes: ``setup.py`` entry points (executable → module function) and the
``launch_ros.actions.Node`` actions of Python launch files, read with ``ast``.

A launch ``Node`` gives its package, executable, name, namespace, ``parameters`` (dictionaries)
and ``remappings`` (pairs); each part that is not a literal (or a constant of the file, or a
name bound once in it) is a warning at its line and is left out. As ``launch`` runs them:

- ``LaunchConfiguration('x')`` is the ``default_value`` of the file's ``DeclareLaunchArgument
  ('x', ...)`` (or its own ``default=``), named in a warning (a command line may set another);
  a parameter value from it is read as YAML reads a scalar (``'0.2'`` → 0.2), as launch_ros does;
- a ``GroupAction`` whose actions hold ``PushRosNamespace('ns')`` (``PushROSNamespace``) puts the
  nodes after it in the group, nested groups outside in, under that namespace (a node's own
  absolute namespace excepted);
- a ``LifecycleNode`` action is a node like ``Node``;
- ``IncludeLaunchDescription`` is not followed (the included file is read as a launch file of
  its own package), ``ExecuteProcess`` and composable-node containers are not read, and a
  ``condition=`` is not decided: each is named in a warning.

XML and YAML launch files are named in a warning.
"""

from __future__ import annotations

import ast
import configparser
import re
from dataclasses import dataclass, field
from pathlib import PurePosixPath

from rosaadl.errors import Diagnostic, Location
from rosaadl.importers.ros2_package.evaluation import UNKNOWN, Known, Scope, bound_once, evaluate
from rosaadl.importers.ros2_package.node_classes import SCRIPT, dotted, keyword_argument, module_imports

__all__ = [
    "EntryPoint",
    "LaunchAction",
    "entry_points",
    "setup_cfg_entry_points",
    "cmake_programs",
    "launch_actions",
    "module_constants",
]

_LAUNCH_NODE = (
    "launch_ros.actions.Node",
    "launch_ros.actions.node.Node",
    "launch_ros.actions.LifecycleNode",
    "launch_ros.actions.lifecycle_node.LifecycleNode",
)
#: Launch actions that start what is not read here, and why.
_NOT_FOLLOWED = {
    "ExecuteProcess": "a process started from a command line is not read; what it starts is not part "
    "of this deployment",
    "ComposableNodeContainer": "composable nodes (C++ components) are not read; left out",
    "LoadComposableNodes": "composable nodes (C++ components) are not read; left out",
    "SetRemap": "a remapping for the nodes after it is not read",
    "SetParameter": "a parameter for the nodes after it is not read",
    "SetParametersFromFile": "parameters for the nodes after it are not read",
    "IncludeLaunchDescription": "an included launch description is not followed here (a launch file of "
    "a package read is read on its own); its nodes are not part of this deployment",
}
_PUSH_NAMESPACE = ("PushRosNamespace", "PushROSNamespace")


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


_SETUP = ("setup", "setuptools.setup", "distutils.core.setup")


def entry_points(tree: ast.Module, file: str, warnings: list[Diagnostic]) -> list[EntryPoint]:
    """The ``console_scripts`` of the ``setup(...)`` call of a ``setup.py`` (a dictionary or list
    bound once to a name is followed; anything else is a warning at its line)."""
    imports = module_imports(tree)
    scope = Scope(module_constants(tree))
    bound = bound_once(tree)
    found: list[EntryPoint] = []

    def warn(message: str, node: ast.AST) -> None:
        line, column = getattr(node, "lineno", None), getattr(node, "col_offset", 0) + 1
        warnings.append(Diagnostic("warning", message, Location(file, line, column)))

    def followed(expr: ast.expr) -> ast.expr:
        return bound.get(expr.id, expr) if isinstance(expr, ast.Name) else expr

    for node in ast.walk(tree):
        if not (isinstance(node, ast.Call) and dotted(node.func, imports) in _SETUP):
            continue
        for keyword in node.keywords:
            if keyword.arg is None:
                warn(
                    f"setup(**{ast.unparse(keyword.value)}): entry points given so are not read",
                    keyword.value,
                )
            if keyword.arg != "entry_points":
                continue
            table = followed(keyword.value)
            if not isinstance(table, ast.Dict):
                warn(
                    f"entry_points {ast.unparse(keyword.value)} is not a literal dictionary; not read", table
                )
                continue
            for key, value in zip(table.keys, table.values, strict=True):
                if key is None or _text(key, scope) != "console_scripts":
                    continue
                scripts = followed(value)
                if not isinstance(scripts, (ast.List, ast.Tuple)):
                    warn(f"console_scripts {ast.unparse(value)} is not a literal list; not read", scripts)
                    continue
                for item in scripts.elts:
                    text = _text(item, scope)
                    if text is None or "=" not in text or ":" not in text:
                        warn(f"entry point {ast.unparse(item)} is not known from the source", item)
                        continue
                    executable, _, target = text.partition("=")
                    module, _, function = target.strip().partition(":")
                    found.append(EntryPoint(executable.strip(), module.strip(), function.strip()))
    return found


def setup_cfg_entry_points(text: str, file: str, warnings: list[Diagnostic]) -> list[EntryPoint]:
    """The ``console_scripts`` of a ``setup.cfg``'s ``[options.entry_points]`` (setuptools'
    declarative form of ``setup(entry_points=...)``)."""
    parser = configparser.ConfigParser(interpolation=None, strict=False)
    try:
        parser.read_string(text, source=file)
    except configparser.Error as exc:
        line = getattr(exc, "lineno", None)
        warnings.append(
            Diagnostic("warning", f"setup.cfg does not read: {exc.message}; its entry points are left out",
                       Location(file, line))
        )  # fmt: skip
        return []
    scripts = parser.get("options.entry_points", "console_scripts", fallback="")
    found = []
    for line in scripts.splitlines():
        executable, equals, target = line.partition("=")
        module, colon, function = target.strip().partition(":")
        if line.strip() and equals and colon and executable.strip() and module and function.strip():
            found.append(EntryPoint(executable.strip(), module, function.strip()))
        elif line.strip():
            warnings.append(
                Diagnostic("warning", f"entry point {line.strip()!r} is not 'name = module:function'",
                           Location(file))
            )  # fmt: skip
    return found


_INSTALL_PROGRAMS = re.compile(
    r"install\s*\(\s*PROGRAMS\s+(?P<files>[^()]*?)\s+DESTINATION\s+(?P<to>[^\s()]+)[^()]*\)", re.IGNORECASE
)


def cmake_programs(text: str, file: str, warnings: list[Diagnostic]) -> list[EntryPoint]:
    """The Python scripts an ``ament_cmake_python`` package installs as executables
    (``install(PROGRAMS scripts/talker.py DESTINATION lib/${PROJECT_NAME})``): each runs its
    whole module (:data:`.node_classes.SCRIPT`), under its file name."""
    found = []
    for match in _INSTALL_PROGRAMS.finditer(text):
        if match.group("to").strip("\"'") not in ("lib/${PROJECT_NAME}", "lib/${PROJECT_NAME}/"):
            continue
        line = text.count("\n", 0, match.start()) + 1
        for item in match.group("files").split():
            path = item.strip("\"'")
            if "$" in path or not path.endswith(".py"):
                if "$" in path:
                    warnings.append(
                        Diagnostic("warning", f"installed program {path} is not a literal path; left out",
                                   Location(file, line))
                    )  # fmt: skip
                continue
            module = ".".join(PurePosixPath(path).with_suffix("").parts)
            found.append(EntryPoint(PurePosixPath(path).name, module, SCRIPT))
    return found


class _LaunchFile:
    """One launch file being read: its names, launch arguments and warnings."""

    def __init__(self, tree: ast.Module, file: str, warnings: list[Diagnostic]) -> None:
        self.file = file
        self.warnings = warnings
        self.warned = set(warnings)  # what ``warnings`` holds, for warn()'s de-duplication
        self.imports = module_imports(tree)
        for wrapper in _node_wrappers(tree, self.imports):
            self.imports[wrapper] = _LAUNCH_NODE[0]
        self.arguments: dict[str, str] = {}  # launch argument → its literal default
        self.configurations: dict[str, str] = {}  # name bound to LaunchConfiguration('x') → x
        self.names = module_constants(tree)
        self.bound: dict[str, ast.expr] = {}  # name bound once → its expression
        for name, expression in bound_once(tree).items():
            self.bound[name] = expression
            argument = self.configuration(expression)
            if argument is not None:
                self.configurations[name] = argument
            elif name not in self.names:
                value = evaluate(expression, Scope(self.names))
                self.names[name] = value if isinstance(value, Known) else Known(UNKNOWN)
        self.scope = Scope(self.names)
        for node in ast.walk(tree):
            if isinstance(node, ast.Call) and self.called(node) == "DeclareLaunchArgument":
                name = self.text(node.args[0] if node.args else keyword_argument(node, "name"), quiet=True)
                default = keyword_argument(node, "default_value")
                text = self.text(default, quiet=True) if default is not None else None
                if name is not None and text is not None:
                    self.arguments[name] = text

    def at(self, node: ast.AST) -> Location:
        return Location(self.file, getattr(node, "lineno", None), getattr(node, "col_offset", 0) + 1)

    def warn(self, message: str, node: ast.AST) -> None:
        diagnostic = Diagnostic("warning", message, self.at(node))
        if diagnostic not in self.warned:  # a pushed namespace is read once per node of its group
            self.warned.add(diagnostic)
            self.warnings.append(diagnostic)

    def called(self, call: ast.Call) -> str:
        """The last part of the name ``call`` calls (``Node``, ``GroupAction``...)."""
        return (dotted(call.func, self.imports) or "").rpartition(".")[2]

    def configuration(self, node: ast.expr | None) -> str | None:
        """``x`` for ``LaunchConfiguration('x')``."""
        if isinstance(node, ast.Call) and self.called(node) == "LaunchConfiguration" and node.args:
            name = evaluate(node.args[0], Scope(self.names))
            return name.value if isinstance(name, Known) and isinstance(name.value, str) else None
        return None

    def value(self, node: ast.expr | None, *, quiet: bool = False) -> Known | None:
        """What ``node`` is known to be when launched without arguments; None if not known."""
        argument = self.configuration(node)
        if argument is None and isinstance(node, ast.Name):
            argument = self.configurations.get(node.id)
        if argument is not None:
            default = self.arguments.get(argument)
            if default is None and isinstance(node, ast.Call):
                given = self.text(keyword_argument(node, "default"), quiet=True)
                default = given
            if default is None:
                return None
            if not quiet:
                self.warn(f"launch argument {argument!r} is taken at its default {default!r}", node)  # type: ignore[arg-type]
            return Known(default)
        value = evaluate(node, self.scope)
        return value if isinstance(value, Known) else None

    def text(self, node: ast.expr | None, *, quiet: bool = False) -> str | None:
        value = self.value(node, quiet=quiet) if node is not None else None
        return value.value if value is not None and isinstance(value.value, str) else None

    def pairs(self, node: ast.expr) -> dict[str, str]:
        found: dict[str, str] = {}
        node = self.bound.get(node.id, node) if isinstance(node, ast.Name) else node
        if not isinstance(node, (ast.List, ast.Tuple)):
            self.warn(f"remappings {ast.unparse(node)} are not a literal list; left out", node)
            return found
        for item in node.elts:
            ends = item.elts if isinstance(item, (ast.Tuple, ast.List)) and len(item.elts) == 2 else None
            texts = [self.text(end) for end in ends] if ends else [None]
            if ends is None or None in texts:
                self.warn(f"remapping {ast.unparse(item)} is not literal; left out", item)
                continue
            found[texts[0]] = texts[1]  # type: ignore[index]
        return found

    def parameters(self, node: ast.expr) -> dict[str, object]:
        found: dict[str, object] = {}
        node = self.bound.get(node.id, node) if isinstance(node, ast.Name) else node
        items = node.elts if isinstance(node, (ast.List, ast.Tuple)) else [node]
        for item in items:
            item = self.bound.get(item.id, item) if isinstance(item, ast.Name) else item
            if not isinstance(item, ast.Dict):
                self.warn(
                    f"parameters {ast.unparse(item)} are not a literal dictionary (a file?); left out", item
                )
                continue
            for key, value in zip(item.keys, item.values, strict=True):
                name = self.text(key) if key is not None else None
                known = self.value(value)
                if name is None or known is None:
                    self.warn(f"parameter {ast.unparse(value)} is not literal; left out", value)
                    continue
                from_argument = self.configuration(value) is not None or (
                    isinstance(value, ast.Name) and value.id in self.configurations
                )
                found[name] = _scalar(known.value) if from_argument else known.value
        return found


def _scalar(text: object) -> object:
    """A launch argument's text as a parameter value (YAML scalars: int, float, bool, text)."""
    if not isinstance(text, str):
        return text
    lowered = text.strip().lower()
    if lowered in ("true", "false"):
        return lowered == "true"
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            continue
    return text


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


def _group_namespaces(tree: ast.Module, launch: _LaunchFile) -> dict[int, list[str | None]]:
    """Node call (by ``id``) → the namespaces its groups push on it, outermost first (None: one
    not known). A node is in a group when it, or a name bound to it, is an item of the group's
    actions (itself or through nested groups)."""
    parents: dict[int, ast.AST] = {}
    for node in ast.walk(tree):
        for child in ast.iter_child_nodes(node):
            parents[id(child)] = node
    by_name = launch.bound

    def pushed(call: ast.Call, item: ast.AST) -> list[str | None]:
        actions = call.args[0] if call.args else keyword_argument(call, "actions")
        if not isinstance(actions, (ast.List, ast.Tuple)):
            return []
        found: list[str | None] = []
        for element in actions.elts:
            if element is item:
                break
            element = by_name.get(element.id, element) if isinstance(element, ast.Name) else element
            if isinstance(element, ast.Call) and launch.called(element) in _PUSH_NAMESPACE:
                given = element.args[0] if element.args else keyword_argument(element, "namespace")
                text = launch.text(given)
                if text is None:
                    launch.warn(f"pushed namespace {ast.unparse(element)} is not literal", element)
                found.append(text)
        return found

    def group_of(items: ast.AST) -> ast.Call | None:
        """The ``GroupAction`` call whose actions are the list ``items``."""
        holder = parents.get(id(items))
        if isinstance(holder, ast.keyword) and holder.arg == "actions":
            holder = parents.get(id(holder))
        elif isinstance(holder, ast.Call) and not (holder.args and holder.args[0] is items):
            return None
        return holder if isinstance(holder, ast.Call) and launch.called(holder) == "GroupAction" else None

    loads: dict[str, list[ast.Name]] = {}  # each name → where it is read, in ast.walk's order
    for use in ast.walk(tree):
        if isinstance(use, ast.Name) and isinstance(use.ctx, ast.Load):
            loads.setdefault(use.id, []).append(use)

    def groups(node: ast.AST, seen: frozenset[str] = frozenset()) -> list[str | None]:
        """The namespaces pushed on ``node`` by the groups around it (or around a name of it)."""
        current = node
        while id(current) in parents:
            parent = parents[id(current)]
            group = group_of(parent) if isinstance(parent, (ast.List, ast.Tuple)) else None
            if group is not None:
                return groups(group, seen) + pushed(group, current)
            target = (
                parent.targets[0] if isinstance(parent, ast.Assign) and len(parent.targets) == 1 else None
            )
            if isinstance(target, ast.Name) and target.id not in seen:
                for use in loads.get(target.id, ()):
                    outer = groups(use, seen | {target.id})
                    if outer:
                        return outer
                return []
            current = parent
        return []

    result: dict[int, list[str | None]] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and dotted(node.func, launch.imports) in _LAUNCH_NODE:
            result[id(node)] = groups(node)
    return result


def _namespace(pushed: list[str | None], own: str) -> str | None:
    """The namespace a node runs in: its own, under the pushed ones unless absolute."""
    if own.startswith("/"):
        return own
    if None in pushed:
        return None
    parts = [p.strip("/") for p in (*pushed, own) if p and p.strip("/")]  # type: ignore[union-attr]
    return "/".join(parts)


_LOOPS = (ast.For, ast.AsyncFor, ast.While, ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp)


def _repeated(tree: ast.Module) -> dict[int, str]:
    """Node calls (by ``id``) that may run several times: in a loop or comprehension, or in a
    module function called more than once → why."""
    calls: dict[str, int] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            calls[node.func.id] = calls.get(node.func.id, 0) + 1
    found: dict[int, str] = {}
    for stmt in tree.body:
        if isinstance(stmt, ast.FunctionDef) and calls.get(stmt.name, 0) > 1:
            for node in ast.walk(stmt):
                found[id(node)] = f"in {stmt.name}(), which the file calls {calls[stmt.name]} times"
    for loop in ast.walk(tree):
        if isinstance(loop, _LOOPS):
            for node in ast.walk(loop):
                found[id(node)] = "in a loop"
    return found


def launch_actions(tree: ast.Module, file: str, warnings: list[Diagnostic]) -> list[LaunchAction]:
    """The ``launch_ros.actions.Node(...)`` calls of a Python launch file (see the module docstring)."""
    launch = _LaunchFile(tree, file, warnings)
    namespaces = _group_namespaces(tree, launch)
    repeated = _repeated(tree)
    found: list[LaunchAction] = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        called = launch.called(node)
        if called in _NOT_FOLLOWED:
            launch.warn(f"{called}: {_NOT_FOLLOWED[called]}", node)
            continue
        if dotted(node.func, launch.imports) not in _LAUNCH_NODE or _forwards(node):
            continue  # a wrapper's own call: its arguments are its caller's
        args = {k.arg: k.value for k in node.keywords if k.arg}
        package, executable = launch.text(args.get("package")), launch.text(args.get("executable"))
        if package is None or executable is None:
            launch.warn("a launch Node whose package or executable is not literal; left out", node)
            continue
        if id(node) in repeated:
            launch.warn(
                f"{package}/{executable} is launched {repeated[id(node)]}: how many nodes and their "
                "names are not known; left out",
                node,
            )
            continue
        if "condition" in args:
            launch.warn(
                f"{package}/{executable} starts under a condition ({ast.unparse(args['condition'])}), "
                "which is not decided here; read as started",
                node,
            )
        name = launch.text(args.get("name")) if "name" in args else None
        if "name" in args and name is None:
            launch.warn("the node name is not literal; the node's own name is kept", node)
        namespace = launch.text(args.get("namespace")) if "namespace" in args else ""
        if namespace is None:
            launch.warn("the namespace is not literal; the root namespace is kept", node)
            namespace = ""
        full = _namespace(namespaces.get(id(node), []), namespace)
        if full is None:
            launch.warn("a namespace its group pushes is not literal; the root namespace is kept", node)
            full = namespace
        action = LaunchAction(package, executable, name, full, location=launch.at(node))
        if "parameters" in args:
            action.parameters = launch.parameters(args["parameters"])
        if "remappings" in args:
            action.remappings = launch.pairs(args["remappings"])
        found.append(action)
    return found
