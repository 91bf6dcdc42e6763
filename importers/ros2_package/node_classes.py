"""The ROS 2 nodes an ``rclpy`` module defines, read with ``ast`` (the module is never run).

A node is a class deriving from ``rclpy.node.Node`` (directly or through a class of the same
module), or a function that makes one with ``rclpy.create_node(name)`` / ``Node(name)``. In it:
``create_publisher``, ``create_subscription``, ``create_service``, ``create_client`` (type,
name, QoS) and ``create_timer`` (period: a literal, a constant, or a parameter's default, through
the names and helper methods :mod:`.evaluation` follows). Whatever these calls say that is not
known from the source (a computed topic, a type from a variable, a call in a loop) and every
such call outside a node is a warning at its file and line; nothing is guessed.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass, field

from rosaadl.errors import Diagnostic, Location
from rosaadl.importers.ros2_package.building import period_seconds
from rosaadl.importers.ros2_package.evaluation import UNKNOWN, Known, Scope, evaluate, stored_names
from rosaadl.importers.ros2_package.facts import NodeFact, PortFact, TimerFact

__all__ = ["ModuleNodes", "read_module", "dotted", "module_imports"]

#: The node methods that create the constructs read, and the positions of their arguments.
CREATES = {
    "create_publisher": ("Publisher", ("msg_type", "topic", "qos_profile")),
    "create_subscription": ("Subscriber", ("msg_type", "topic", "callback", "qos_profile")),
    "create_service": ("Server", ("srv_type", "srv_name", "callback")),
    "create_client": ("Client", ("srv_type", "srv_name")),
    "create_timer": ("Timer", ("timer_period_sec", "callback")),
}
_NODE_BASES = ("rclpy.node.Node",)
_NODE_FACTORIES = ("rclpy.create_node", "rclpy.node.Node")
#: The QoS presets of ``rclpy.qos`` (rmw_qos_profiles.h): reliability, durability, depth.
_PRESETS = {
    "qos_profile_sensor_data": ("best_effort", "volatile", "5"),
    "qos_profile_system_default": ("system_default", "system_default", ""),
    "qos_profile_services_default": ("reliable", "volatile", "10"),
    "qos_profile_parameters": ("reliable", "volatile", "1000"),
}


@dataclass
class ModuleNodes:
    """The nodes of one module, and the names of its classes and functions that make them."""

    nodes: list[NodeFact] = field(default_factory=list)
    classes: dict[str, NodeFact] = field(default_factory=dict)
    functions: dict[str, list[str]] = field(default_factory=dict)  #: function → node classes it makes


def dotted(node: ast.expr, imports: dict[str, str]) -> str | None:
    """``a.b.C`` for a name or attribute chain, its first name replaced by what it was imported as."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if not isinstance(node, ast.Name):
        return None
    parts.append(imports.get(node.id, node.id))
    return ".".join(reversed(parts))


def module_imports(tree: ast.Module) -> dict[str, str]:
    """What each name a module imports stands for: ``{"Node": "rclpy.node.Node", "np": "numpy"}``
    (relative imports left out)."""
    found: dict[str, str] = {}
    for stmt in ast.walk(tree):
        if isinstance(stmt, ast.Import):
            for alias in stmt.names:
                if alias.asname:
                    found[alias.asname] = alias.name
                else:
                    found.setdefault(alias.name.split(".")[0], alias.name.split(".")[0])
        elif isinstance(stmt, ast.ImportFrom) and stmt.module and not stmt.level:
            for alias in stmt.names:
                found[alias.asname or alias.name] = f"{stmt.module}.{alias.name}"
    return found


def _interface_type(qualified: str | None) -> str | None:
    """``std_msgs/String`` for ``std_msgs.msg.String`` (or ``.srv.``); None for anything else."""
    if not qualified:
        return None
    parts = qualified.split(".")
    if len(parts) == 3 and parts[1] in ("msg", "srv") and parts[0] and parts[2]:
        return f"{parts[0]}/{parts[2]}"
    return None


def _argument(call: ast.Call, names: tuple[str, ...], wanted: str) -> ast.expr | None:
    index = names.index(wanted)
    if index < len(call.args) and not any(isinstance(a, ast.Starred) for a in call.args[: index + 1]):
        return call.args[index]
    for keyword in call.keywords:
        if keyword.arg == wanted:
            return keyword.value
    return None


class _Reader:
    def __init__(self, tree: ast.Module, file: str, warnings: list[Diagnostic], package: str) -> None:
        self.tree = tree
        self.file = file
        self.warnings = warnings
        self.package = package
        self.imports = module_imports(tree)
        self.constants = self._module_constants()
        self.consumed: set[int] = set()  # ids of the create_* calls read into a node
        self.result = ModuleNodes()

    def at(self, node: ast.AST) -> Location:
        return Location(
            file=self.file, line=getattr(node, "lineno", None), column=getattr(node, "col_offset", 0) + 1
        )

    def warn(self, message: str, node: ast.AST) -> None:
        self.warnings.append(Diagnostic("warning", message, self.at(node)))

    def _module_constants(self) -> dict[str, Known]:
        names: dict[str, Known] = {}
        for stmt in self.tree.body:
            if isinstance(stmt, (ast.Assign, ast.AnnAssign)):
                targets = stmt.targets if isinstance(stmt, ast.Assign) else [stmt.target]
                value = evaluate(stmt.value, Scope(names))
                for target in targets:
                    if isinstance(target, ast.Name):
                        names[target.id] = value if isinstance(value, Known) else Known(UNKNOWN)
        return names

    # ------------------------------------------------------------------ classes

    def node_classes(self) -> list[ast.ClassDef]:
        classes = [s for s in self.tree.body if isinstance(s, ast.ClassDef)]
        found: dict[str, ast.ClassDef] = {}
        changed = True
        while changed:
            changed = False
            for cls in classes:
                if cls.name in found:
                    continue
                for base in cls.bases:
                    name = dotted(base, self.imports)
                    if name in _NODE_BASES or name in found:
                        found[cls.name] = cls
                        changed = True
                        break
        return [c for c in classes if c.name in found]

    def methods(self, cls: ast.ClassDef, by_name: dict[str, ast.ClassDef]) -> dict[str, ast.FunctionDef]:
        """The methods of ``cls``, with those of its node base classes of the module."""
        methods: dict[str, ast.FunctionDef] = {}
        for base in cls.bases:
            if isinstance(base, ast.Name) and base.id in by_name and by_name[base.id] is not cls:
                methods.update(self.methods(by_name[base.id], by_name))
        for stmt in cls.body:
            if isinstance(stmt, ast.FunctionDef):
                methods[stmt.name] = stmt
        return methods

    def read_class(self, cls: ast.ClassDef, by_name: dict[str, ast.ClassDef]) -> NodeFact:
        methods = self.methods(cls, by_name)
        names = dict(self.constants)
        for stmt in cls.body:
            if (
                isinstance(stmt, ast.Assign)
                and len(stmt.targets) == 1
                and isinstance(stmt.targets[0], ast.Name)
            ):
                value = evaluate(stmt.value, Scope(names))
                names[stmt.targets[0].id] = value if isinstance(value, Known) else Known(UNKNOWN)
        fact = NodeFact(
            key=f"{self.package}:{self.file}:{cls.name}",
            node_name=cls.name,
            location=self.at(cls),
            package=self.package,
        )
        parameters = self.parameters(list(methods.values()), names)
        fact.parameters = parameters
        scope = Scope(names, parameters, methods)
        init = methods.get("__init__")
        node_name = self.node_name(init, scope) if init is not None else None
        if node_name is None:
            self.warn(
                f"class {cls.name}: the node name is not a literal given to Node.__init__; "
                f"the class name is used",
                init or cls,
            )
        else:
            fact.node_name = node_name
        ordered = ([init] if init is not None else []) + [m for m in methods.values() if m is not init]
        attributes: dict[str, Known] = {}
        for method in ordered:
            self.block(method.body, scope.with_names(attributes), fact, ("self",), attributes, in_loop=False)
        return fact

    def parameters(self, functions: list[ast.FunctionDef], names: dict[str, Known]) -> dict[str, object]:
        """Every ``declare_parameter(name, default)`` (and ``declare_parameters``) whose name and
        default are known: name → default."""
        found: dict[str, object] = {}
        scope = Scope(names)
        for function in functions:
            for node in ast.walk(function):
                if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)):
                    continue
                if node.func.attr == "declare_parameter" and node.args:
                    name = evaluate(node.args[0], scope)
                    default = evaluate(node.args[1], scope) if len(node.args) > 1 else UNKNOWN
                    if isinstance(name, Known) and isinstance(name.value, str) and isinstance(default, Known):
                        found[name.value] = default.value
                elif node.func.attr == "declare_parameters":
                    self._declare_parameters(node, scope, found)
        return found

    def _declare_parameters(self, call: ast.Call, scope: Scope, found: dict[str, object]) -> None:
        args = {k.arg: k.value for k in call.keywords}
        namespace = evaluate(args.get("namespace", call.args[0] if call.args else None), scope)
        listed = args.get("parameters", call.args[1] if len(call.args) > 1 else None)
        prefix = (
            namespace.value if isinstance(namespace, Known) and isinstance(namespace.value, str) else None
        )
        if prefix is None or not isinstance(listed, (ast.List, ast.Tuple)):
            return
        for item in listed.elts:
            if isinstance(item, ast.Tuple) and len(item.elts) >= 2:
                name, default = evaluate(item.elts[0], scope), evaluate(item.elts[1], scope)
                if isinstance(name, Known) and isinstance(name.value, str) and isinstance(default, Known):
                    found[f"{prefix}.{name.value}" if prefix else name.value] = default.value

    def node_name(self, init: ast.FunctionDef, scope: Scope) -> str | None:
        for node in ast.walk(init):
            if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)):
                continue
            if node.func.attr != "__init__":
                continue
            receiver = node.func.value
            args = list(node.args)
            if not (
                isinstance(receiver, ast.Call)
                and isinstance(receiver.func, ast.Name)
                and receiver.func.id == "super"
            ):
                args = args[1:]  # Node.__init__(self, name)
            given = args[0] if args else next((k.value for k in node.keywords if k.arg == "node_name"), None)
            value = evaluate(given, scope)
            if isinstance(value, Known) and isinstance(value.value, str) and value.value:
                return value.value
            return None
        return None

    # ------------------------------------------------------------------ statements

    def block(
        self,
        body: list[ast.stmt],
        scope: Scope,
        fact: NodeFact,
        receivers: tuple[str, ...],
        attributes: dict[str, Known],
        *,
        in_loop: bool,
    ) -> None:
        """Read the create_* calls of ``body`` in order, knowing the names assigned before each."""
        names = dict(scope.names)
        for stmt in body:
            current = scope.with_names(names)
            if isinstance(stmt, (ast.For, ast.AsyncFor, ast.While)):
                self.block(stmt.body, current, fact, receivers, attributes, in_loop=True)
                self.block(stmt.orelse, current, fact, receivers, attributes, in_loop=in_loop)
                for name in stored_names(stmt):
                    names[name] = Known(UNKNOWN)
                continue
            if isinstance(stmt, (ast.If, ast.With, ast.AsyncWith, ast.Try)):
                for part in _blocks(stmt):
                    self.block(part, current, fact, receivers, attributes, in_loop=in_loop)
                for name in stored_names(stmt):
                    names[name] = Known(UNKNOWN)
                continue
            if isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                continue
            for call in _calls(stmt):
                self.create(call, current, fact, receivers, in_loop=in_loop)
            if isinstance(stmt, ast.Assign) and len(stmt.targets) == 1:
                target = stmt.targets[0]
                value = evaluate(stmt.value, current)
                known = value if isinstance(value, Known) else Known(UNKNOWN)
                if isinstance(target, ast.Name):
                    names[target.id] = known
                elif (
                    isinstance(target, ast.Attribute)
                    and isinstance(target.value, ast.Name)
                    and target.value.id == "self"
                ):
                    names["self." + target.attr] = known
                    attributes["self." + target.attr] = known
            else:
                for name in stored_names(stmt):
                    names[name] = Known(UNKNOWN)

    def create(
        self, call: ast.Call, scope: Scope, fact: NodeFact, receivers: tuple[str, ...], *, in_loop: bool
    ) -> None:
        func = call.func
        if not (isinstance(func, ast.Attribute) and func.attr in CREATES):
            return
        if not (isinstance(func.value, ast.Name) and func.value.id in receivers):
            return  # named by the final sweep
        self.consumed.add(id(call))
        kind, names = CREATES[func.attr]
        if in_loop:
            self.warn(f"{func.attr} in a loop: how many it makes is not known; not imported", call)
            return
        if kind == "Timer":
            self.timer(call, scope, fact, names)
            return
        type_expr = _argument(call, names, names[0])
        type_name = _interface_type(dotted(type_expr, self.imports)) if type_expr is not None else None
        if type_name is None:
            shown = ast.unparse(type_expr) if type_expr is not None else "nothing"
            self.warn(
                f"{func.attr}: the {'service' if kind in ('Server', 'Client') else 'message'} type {shown} "
                "is not a class imported from a <package>.msg/.srv module; not imported",
                call,
            )
            return
        topic_expr = _argument(call, names, names[1])
        topic = evaluate(topic_expr, scope)
        if not isinstance(topic, Known) or not isinstance(topic.value, str) or not topic.value:
            shown = ast.unparse(topic_expr) if topic_expr is not None else "nothing"
            self.warn(f"{func.attr}: the name {shown} is not known from the source; not imported", call)
            return
        qos = {}
        if "qos_profile" in names:
            qos = self.qos(_argument(call, names, "qos_profile"), scope, call)
        port = PortFact(kind, type_name, topic.value, self.at(call), qos)
        port.name = _assigned_attribute(call, self.tree) or ""
        fact.ports.append(port)

    def timer(self, call: ast.Call, scope: Scope, fact: NodeFact, names: tuple[str, ...]) -> None:
        expr = _argument(call, names, names[0])
        value = evaluate(expr, scope)
        period = None
        parameter = derived = None
        if isinstance(value, Known):
            parameter, derived = value.parameter, value.derived
            period = period_seconds(value.value)
        callback = _argument(call, names, "callback")
        attribute = _assigned_attribute(call, self.tree, raw=True)
        if (
            attribute
            and isinstance(callback, ast.Attribute)
            and _cancels(scope.methods.get(callback.attr), attribute)
        ):
            self.warn(
                f"one-shot timer {attribute} (its callback {callback.attr} cancels it): "
                "not a periodic timer; left out",
                call,
            )
            return
        if period is None and not (isinstance(value, Known) and value.parameter):
            shown = ast.unparse(expr) if expr is not None else "nothing"
            self.warn(f"create_timer: the period {shown} is not known from the source", call)
        name = _assigned_attribute(call, self.tree) or (
            callback.attr if isinstance(callback, ast.Attribute) else f"timer_{call.lineno}"
        )
        fact.timers.append(TimerFact(name, period, self.at(call), parameter, derived))

    def qos(self, expr: ast.expr | None, scope: Scope, call: ast.Call) -> dict[str, str]:
        if expr is None:
            return {}
        value = evaluate(expr, scope)
        if isinstance(value, Known) and isinstance(value.value, int) and not isinstance(value.value, bool):
            return {"depth": str(value.value), "reliability": "reliable", "durability": "volatile"}
        name = dotted(expr, self.imports)
        preset = _PRESETS.get((name or "").rpartition(".")[2])
        if preset:
            return {k: v for k, v in zip(("reliability", "durability", "depth"), preset, strict=True) if v}
        if isinstance(expr, ast.Call) and (dotted(expr.func, self.imports) or "").endswith("QoSProfile"):
            found = {}
            for keyword in expr.keywords:
                if keyword.arg in ("reliability", "durability") and isinstance(keyword.value, ast.Attribute):
                    found[keyword.arg] = keyword.value.attr.lower()
                elif keyword.arg == "depth":
                    depth = evaluate(keyword.value, scope)
                    if isinstance(depth, Known) and isinstance(depth.value, int):
                        found["depth"] = str(depth.value)
            return found
        self.warn(f"{call.func.attr}: the QoS {ast.unparse(expr)} is not known from the source", call)  # type: ignore[attr-defined]
        return {}

    # ------------------------------------------------------------------ functions

    def read_function(self, function: ast.FunctionDef) -> NodeFact | None:
        """A node made in a function: ``node = rclpy.create_node('name')`` then ``node.create_*``."""
        receivers = []
        fact = None
        for stmt in ast.walk(function):
            if (
                isinstance(stmt, ast.Assign)
                and len(stmt.targets) == 1
                and isinstance(stmt.targets[0], ast.Name)
                and isinstance(stmt.value, ast.Call)
                and dotted(stmt.value.func, self.imports) in _NODE_FACTORIES
            ):
                name = evaluate(stmt.value.args[0] if stmt.value.args else None, Scope(self.constants))
                if not (isinstance(name, Known) and isinstance(name.value, str)):
                    self.warn("a node is made with a name not known from the source; not imported", stmt)
                    continue
                receivers.append(stmt.targets[0].id)
                fact = fact or NodeFact(
                    key=f"{self.package}:{self.file}:{function.name}",
                    node_name=name.value,
                    location=self.at(stmt),
                    package=self.package,
                )
        if fact is None:
            return None
        fact.parameters = self.parameters([function], dict(self.constants))
        scope = Scope(dict(self.constants), fact.parameters, {})
        self.block(function.body, scope, fact, tuple(receivers), {}, in_loop=False)
        return fact

    def read(self) -> ModuleNodes:
        classes = self.node_classes()
        by_name = {c.name: c for c in classes}
        for cls in classes:
            fact = self.read_class(cls, by_name)
            self.result.nodes.append(fact)
            self.result.classes[cls.name] = fact
        for stmt in self.tree.body:
            if isinstance(stmt, ast.FunctionDef):
                made = [
                    n.func.id
                    for n in ast.walk(stmt)
                    if isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id in by_name
                ]
                self.result.functions[stmt.name] = made
                fact = self.read_function(stmt)
                if fact is not None:
                    self.result.nodes.append(fact)
                    self.result.functions[stmt.name] = [*made, stmt.name]
                    self.result.classes[stmt.name] = fact
        for node in ast.walk(self.tree):
            if (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Attribute)
                and node.func.attr in CREATES
                and id(node) not in self.consumed
            ):
                self.warn(
                    f"{node.func.attr} on {ast.unparse(node.func.value)}, which is not a node this reader "
                    "knows (a Node subclass's self, or a node made in the same function); not imported",
                    node,
                )
        return self.result


def _assigned_attribute(call: ast.Call, tree: ast.Module, *, raw: bool = False) -> str | None:
    """``x`` when ``call`` is assigned to ``self.x`` or ``x`` (the port's or timer's name in the
    code, without leading and trailing underscores unless ``raw``)."""
    parent = getattr(call, "_rosaadl_parent", None)
    if isinstance(parent, ast.Assign) and len(parent.targets) == 1:
        target = parent.targets[0]
        name = (
            target.attr
            if isinstance(target, ast.Attribute)
            else target.id
            if isinstance(target, ast.Name)
            else ""
        )
        return (name if raw else name.strip("_")) or None
    return None


def _cancels(method: ast.FunctionDef | None, attribute: str) -> bool:
    """Does ``method`` call ``self.<attribute>.cancel()`` (a one-shot timer's callback)?"""
    if method is None:
        return False
    for node in ast.walk(method):
        if (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Attribute)
            and node.func.attr in ("cancel", "destroy")
            and isinstance(node.func.value, ast.Attribute)
            and node.func.value.attr == attribute
        ):
            return True
    return False


def _calls(stmt: ast.stmt) -> list[ast.Call]:
    """The calls in ``stmt`` outside nested functions and lambdas, outermost first."""
    found = []
    stack: list[ast.AST] = [stmt]
    while stack:
        node = stack.pop(0)
        if (
            isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef))
            and node is not stmt
        ):
            continue
        if isinstance(node, ast.Call):
            found.append(node)
        stack.extend(ast.iter_child_nodes(node))
    return found


def _blocks(stmt: ast.stmt) -> list[list[ast.stmt]]:
    parts = [getattr(stmt, name, None) or [] for name in ("body", "orelse", "finalbody")]
    for handler in getattr(stmt, "handlers", None) or []:
        parts.append(handler.body)
    return parts


def _mark_parents(tree: ast.Module) -> None:
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and isinstance(node.value, ast.Call):
            node.value._rosaadl_parent = node  # type: ignore[attr-defined]


def read_module(tree: ast.Module, file: str, package: str, warnings: list[Diagnostic]) -> ModuleNodes:
    """The nodes ``tree`` (the module ``file`` of ROS package ``package``) defines."""
    _mark_parents(tree)
    return _Reader(tree, file, warnings, package).read()
