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
from collections.abc import Callable
from dataclasses import dataclass, field

from rosaadl.errors import Diagnostic, Location
from rosaadl.importers.ros2_package.building import period_seconds
from rosaadl.importers.ros2_package.evaluation import (
    UNKNOWN,
    Known,
    Scope,
    bound_once,
    evaluate,
    stored_names,
)
from rosaadl.importers.ros2_package.facts import NodeFact, PortFact, TimerFact
from rosaadl.importers.ros2_package.qos import read_qos
from rosaadl.importers.ros2_package.statements import (
    assigned_attribute,
    blocks_of,
    calls_in,
    cancels,
    comprehended,
    forget_changed,
    mark_assignments,
)

__all__ = [
    "SCRIPT",
    "NODE_BASES",
    "ModuleNodes",
    "OutsideClass",
    "read_module",
    "module_constants",
    "keyword_argument",
    "dotted",
    "module_imports",
]

#: The node methods that create the constructs read, and the positions of their arguments.
CREATES = {
    "create_publisher": ("Publisher", ("msg_type", "topic", "qos_profile")),
    "create_lifecycle_publisher": ("Publisher", ("msg_type", "topic", "qos_profile")),
    "create_subscription": ("Subscriber", ("msg_type", "topic", "callback", "qos_profile")),
    "create_service": ("Server", ("srv_type", "srv_name", "callback")),
    "create_client": ("Client", ("srv_type", "srv_name")),
    "create_timer": ("Timer", ("timer_period_sec", "callback")),
}
#: The node classes of rclpy (``rclpy.lifecycle.Node`` is ``LifecycleNode``).
NODE_BASES = (
    "rclpy.node.Node",
    "rclpy.lifecycle.Node",
    "rclpy.lifecycle.LifecycleNode",
    "rclpy.lifecycle.node.LifecycleNode",
)
_NODE_FACTORIES = ("rclpy.create_node", "rclpy.node.Node")
#: Statements of a module that define rather than run.
_DEFINITIONS = (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef, ast.Import, ast.ImportFrom)
#: The name the nodes a module makes when run as a script are found under in
#: :attr:`ModuleNodes.functions` (an executable installed as a file runs the whole module).
SCRIPT = "<script>"
#: rclpy's action server and client (``rclpy.action``): ROSMOD has no action ports.
_ACTIONS = {"ActionServer": "action server", "ActionClient": "action client"}


@dataclass
class OutsideClass:
    """A node class of another module of the package, as a class of this module may derive from
    it: the class, and what names mean in its module."""

    cls: ast.ClassDef
    imports: dict[str, str]
    constants: dict[str, Known]
    local: dict[str, ast.ClassDef]  #: the node classes of its module, by name
    file: str = ""  #: its module's file


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


def keyword_argument(call: ast.Call, name: str) -> ast.expr | None:
    """The expression ``call`` gives its keyword ``name``, if any."""
    return next((k.value for k in call.keywords if k.arg == name), None)


def _argument(call: ast.Call, names: tuple[str, ...], wanted: str) -> ast.expr | None:
    index = names.index(wanted)
    if index < len(call.args) and not any(isinstance(a, ast.Starred) for a in call.args[: index + 1]):
        return call.args[index]
    for keyword in call.keywords:
        if keyword.arg == wanted:
            return keyword.value
    return None


class _Reader:
    def __init__(
        self,
        tree: ast.Module,
        file: str,
        warnings: list[Diagnostic],
        package: str,
        imports: dict[str, str] | None = None,
        outside: dict[str, OutsideClass] | None = None,
        bases_only: set[str] | None = None,
        files: dict[int, str] | None = None,
        constants: dict[str, Known] | None = None,
    ) -> None:
        self.bases_only = bases_only or set()
        self.tree = tree
        self.file = file
        self.warnings = warnings
        self.package = package
        self.imports = module_imports(tree) if imports is None else imports
        self.outside = outside or {}
        self.files = class_files(self.outside) if files is None else files
        self.constants = self._module_constants() if constants is None else dict(constants)
        self.consumed: set[int] = set()  # ids of the create_* calls read into a node
        self.result = ModuleNodes()
        self._lineages: dict[int, list[OutsideClass]] = {}  # id of a class -> its lineage

    def at(self, node: ast.AST) -> Location:
        """Where ``node`` is: in this module, or in the module of a base class it reads."""
        return Location(
            file=self.files.get(id(node), self.file),
            line=getattr(node, "lineno", None),
            column=getattr(node, "col_offset", 0) + 1,
        )

    def warn(self, message: str, node: ast.AST) -> None:
        self.warnings.append(Diagnostic("warning", message, self.at(node)))

    def value(self, expr: ast.expr | None, scope: Scope) -> Known:
        """What ``expr`` is known to be (a value, or a QoS profile); ``Known(UNKNOWN)`` if not."""
        value = evaluate(expr, scope)
        if isinstance(value, Known):
            return value
        qos = read_qos(expr, scope, self.dotted)
        return Known(qos) if qos is not None else Known(UNKNOWN)

    def dotted(self, expr: ast.expr) -> str | None:
        return dotted(expr, self.imports)

    def _module_constants(self) -> dict[str, Known]:
        names: dict[str, Known] = {}
        for stmt in self.tree.body:
            if isinstance(stmt, (ast.Assign, ast.AnnAssign)):
                targets = stmt.targets if isinstance(stmt, ast.Assign) else [stmt.target]
                value = self.value(stmt.value, Scope(names))
                for target in targets:
                    if isinstance(target, ast.Name):
                        names[target.id] = value
            elif isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                names[stmt.name] = Known(UNKNOWN)  # its body's names are its own, not the module's
            else:
                for name in stored_names(stmt):  # a name set again in a branch or loop is not known
                    names[name] = Known(UNKNOWN)
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
                    if name in NODE_BASES or name in found or name in self.outside:
                        found[cls.name] = cls
                        changed = True
                        break
        return [c for c in classes if c.name in found]

    def lineage(self, cls: ast.ClassDef, by_name: dict[str, ast.ClassDef]) -> list[OutsideClass]:
        """``cls`` and its node base classes, bases first: those of this module and those of
        other modules of the package (:class:`OutsideClass`), each with its module's names
        (found once per class: its methods, attributes, names and ``__init__`` chain use it)."""
        known = self._lineages.get(id(cls))
        if known is None:
            known = self._lineages[id(cls)] = self._find_lineage(cls, by_name)
        return known

    def _find_lineage(self, cls: ast.ClassDef, by_name: dict[str, ast.ClassDef]) -> list[OutsideClass]:
        here = OutsideClass(cls, self.imports, self.constants, by_name)
        found: list[OutsideClass] = []
        seen: set[int] = set()

        def visit(item: OutsideClass, depth: int) -> None:
            if id(item.cls) in seen or depth > 32:
                return
            seen.add(id(item.cls))
            for base in item.cls.bases:
                name = dotted(base, item.imports)
                if (
                    isinstance(base, ast.Name)
                    and base.id in item.local
                    and item.local[base.id] is not item.cls
                ):
                    visit(
                        OutsideClass(item.local[base.id], item.imports, item.constants, item.local), depth + 1
                    )
                elif name in self.outside:
                    visit(self.outside[name], depth + 1)
            found.append(item)

        visit(here, 0)
        return found

    def methods(self, cls: ast.ClassDef, by_name: dict[str, ast.ClassDef]) -> dict[str, ast.FunctionDef]:
        """The methods of ``cls``, with those of its node base classes (see :meth:`lineage`)."""
        methods: dict[str, ast.FunctionDef] = {}
        for item in self.lineage(cls, by_name):
            for stmt in item.cls.body:
                if isinstance(stmt, ast.FunctionDef):
                    methods[stmt.name] = stmt
        return methods

    def class_attributes(self, cls: ast.ClassDef, by_name: dict[str, ast.ClassDef]) -> dict[str, Known]:
        """The class attributes of ``cls`` (and of its node base classes), as the methods read
        them: ``self.rate`` → ``Known(30)``. Inside methods a class attribute is reached through
        ``self`` only, never by its bare name."""
        body: dict[str, Known] = {}
        for item in self.lineage(cls, by_name):
            for stmt in item.cls.body:
                if (
                    isinstance(stmt, ast.Assign)
                    and len(stmt.targets) == 1
                    and isinstance(stmt.targets[0], ast.Name)
                ):
                    body[stmt.targets[0].id] = self.value(stmt.value, Scope({**item.constants, **body}))
                elif (
                    isinstance(stmt, ast.AnnAssign)
                    and isinstance(stmt.target, ast.Name)
                    and stmt.value is not None
                ):
                    body[stmt.target.id] = self.value(stmt.value, Scope({**item.constants, **body}))
                elif not isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    for name in stored_names(stmt):
                        body[name] = Known(UNKNOWN)
        return {"self." + k: v for k, v in body.items()}

    def borrowed_names(self, cls: ast.ClassDef, by_name: dict[str, ast.ClassDef]) -> None:
        """Give this module the imports and constants the other modules of ``cls``'s base classes
        use (their methods are read here); a name they bind differently is known by neither."""
        for item in self.lineage(cls, by_name):
            if item.imports is self.imports:
                continue
            for table, other in ((self.imports, item.imports), (self.constants, item.constants)):
                for name, value in other.items():
                    if name not in table:
                        table[name] = value  # type: ignore[assignment]
                    elif table[name] != value:
                        table.pop(name)
                        table[name] = Known(UNKNOWN) if table is self.constants else "<conflict>"  # type: ignore[assignment]

    def read_class(
        self, cls: ast.ClassDef, by_name: dict[str, ast.ClassDef], bound: dict[str, Known]
    ) -> NodeFact:
        """The node of class ``cls``; ``bound``: what its ``__init__`` arguments are known to be
        where the module makes the node (see :meth:`constructor_arguments`)."""
        methods = self.methods(cls, by_name)
        names = {**self.constants, **self.class_attributes(cls, by_name)}
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
        chain = self.init_chain(cls, by_name, scope.with_names(bound))
        node_name = self.node_name(*chain[-1], fact) if chain else None
        if node_name is None:
            self.warn(
                f"class {cls.name}: the node name is not a literal given to Node.__init__; "
                f"the class name is used",
                init or cls,
            )
        else:
            fact.node_name = node_name
        attributes: dict[str, Known] = {}
        for method, start in chain:  # the __init__ of the class, then those it calls up its bases
            self.block(method.body, start.with_names(attributes), fact, ("self",), attributes, in_loop=False)
        for method in methods.values():
            if method is not init:
                self.block(
                    method.body, scope.with_names(attributes), fact, ("self",), attributes, in_loop=False
                )
        return fact

    def init_chain(
        self, cls: ast.ClassDef, by_name: dict[str, ast.ClassDef], scope: Scope
    ) -> list[tuple[ast.FunctionDef, Scope]]:
        """The ``__init__`` methods a node of ``cls`` runs, each with what its parameters are
        known to be: the nearest one, then the base class's one its ``super().__init__(...)``
        (or ``Base.__init__(self, ...)``) calls, and so on up to rclpy's ``Node``."""
        inits = [
            stmt
            for item in reversed(self.lineage(cls, by_name))
            for stmt in item.cls.body
            if isinstance(stmt, ast.FunctionDef) and stmt.name == "__init__"
        ]
        chain: list[tuple[ast.FunctionDef, Scope]] = []
        for index, init in enumerate(inits):
            chain.append((init, scope))
            call = _init_call(init)
            if call is None or index + 1 >= len(inits):
                break
            arguments = _init_arguments(call)
            bound = _bind(inits[index + 1], arguments, call.keywords, scope, Scope(scope.names), self.value)
            scope = scope.with_names(bound)
        return chain

    def constructor_arguments(self, cls: ast.ClassDef, init: ast.FunctionDef | None) -> dict[str, Known]:
        """The values of ``cls.__init__``'s parameters where this module makes the node
        (``LifecycleTalker('lc_talker')`` in ``main``): a parameter is known when every call of
        the class in the module gives it the same known value (an argument, or the parameter's
        default); with no call in the module, nothing is known (another module may make it)."""
        if init is None:
            return {}
        calls = [
            (function, node)
            for function in self.tree.body
            if isinstance(function, (ast.FunctionDef, ast.AsyncFunctionDef))
            for node in ast.walk(function)
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == cls.name
        ]
        if not calls:
            return {}
        seen: list[dict[str, Known]] = []
        for function, call in calls:
            scope = Scope({**self.constants, **_single_assignments(function, self)})
            seen.append(_bind(init, call.args, call.keywords, scope, Scope(self.constants), self.value))
        first = seen[0]
        return {
            n: v if all(other.get(n) == v for other in seen) else Known(UNKNOWN) for n, v in first.items()
        }

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

    def node_name(self, init: ast.FunctionDef, scope: Scope, fact: NodeFact) -> str | None:
        """The name ``init`` gives ``Node.__init__`` (its ``namespace=`` goes to ``fact``)."""
        node = _init_call(init)
        if node is None:
            return None
        args = _init_arguments(node)
        given = args[0] if args else keyword_argument(node, "node_name")
        self.namespace(node, scope, fact)
        value = evaluate(given, scope)
        if isinstance(value, Known) and isinstance(value.value, str) and value.value:
            return value.value
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
        under: str | None = None,
    ) -> None:
        """Read the create_* calls of ``body`` in order, knowing the names assigned before each;
        ``under``: the condition the body runs under, if any."""
        names = dict(scope.names)
        for stmt in body:
            current = scope.with_names(names)
            if isinstance(stmt, (ast.For, ast.AsyncFor, ast.While)):
                self.block(stmt.body, current, fact, receivers, attributes, in_loop=True, under=under)
                self.block(stmt.orelse, current, fact, receivers, attributes, in_loop=in_loop, under=under)
                for name in stored_names(stmt):
                    names[name] = Known(UNKNOWN)
                continue
            if isinstance(stmt, (ast.If, ast.With, ast.AsyncWith, ast.Try)):
                for part, condition in blocks_of(stmt):
                    inner = (
                        under
                        if condition is None
                        else condition
                        if under is None
                        else f"{under} and {condition}"
                    )
                    self.block(part, current, fact, receivers, attributes, in_loop=in_loop, under=inner)
                for name in stored_names(stmt):
                    names[name] = Known(UNKNOWN)
                continue
            if isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                continue
            looped = comprehended(stmt)
            for call in calls_in(stmt):
                self.create(
                    call, current, fact, receivers, in_loop=in_loop or id(call) in looped, under=under
                )
            if isinstance(stmt, ast.Assign) and len(stmt.targets) == 1:
                target = stmt.targets[0]
                known = self.value(stmt.value, current)
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
                    forget_changed(target, names)
            else:
                for name in stored_names(stmt):
                    names[name] = Known(UNKNOWN)
                for target in getattr(stmt, "targets", None) or [getattr(stmt, "target", None)]:
                    forget_changed(target, names)

    def create(
        self,
        call: ast.Call,
        scope: Scope,
        fact: NodeFact,
        receivers: tuple[str, ...],
        *,
        in_loop: bool,
        under: str | None = None,
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
        if under is not None:
            self.warn(f"{func.attr} runs only when {under}: imported as if it always did", call)
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
        port = PortFact(kind, type_name, topic.value, self.at(call), qos, "", topic.parameter, topic.derived)
        port.name = assigned_attribute(call) or ""
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
        attribute = assigned_attribute(call, raw=True)
        if (
            attribute
            and isinstance(callback, ast.Attribute)
            and cancels(scope.methods.get(callback.attr), attribute)
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
        name = assigned_attribute(call) or (
            callback.attr if isinstance(callback, ast.Attribute) else f"timer_{call.lineno}"
        )
        fact.timers.append(TimerFact(name, period, self.at(call), parameter, derived))

    def qos(self, expr: ast.expr | None, scope: Scope, call: ast.Call) -> dict[str, str]:
        if expr is None:
            return {}
        found = read_qos(expr, scope, self.dotted)
        if found is None:
            self.warn(f"{call.func.attr}: the QoS {ast.unparse(expr)} is not known from the source", call)  # type: ignore[attr-defined]
            return {}
        return found.as_dict()

    def action(self, call: ast.Call) -> bool:
        """Name an ``rclpy.action`` server or client in a warning (ROSMOD has no actions: an
        action is a goal, a cancel and a result service with a feedback and a status topic)."""
        name = self.dotted(call.func) or ""
        kind = _ACTIONS.get(name.rpartition(".")[2])
        if kind is None or not (name.startswith("rclpy.action") or "." not in name):
            return False
        names = ("node", "action_type", "action_name")
        type_expr = _argument(call, names, "action_type")
        action_name = evaluate(_argument(call, names, "action_name"), Scope(self.constants))
        type_name = dotted(type_expr, self.imports) if type_expr is not None else None
        parts = (type_name or "").split(".")
        shown_type = (
            f"{parts[0]}/{parts[2]}" if len(parts) == 3 and parts[1] == "action" else "of unknown type"
        )
        shown_name = (
            repr(action_name.value)
            if isinstance(action_name, Known) and isinstance(action_name.value, str)
            else "(name not known from the source)"
        )
        self.warn(
            f"{kind} {shown_name} {shown_type}: ROSMOD has no actions (its goal, cancel and result "
            "services and its feedback and status topics); not imported",
            call,
        )
        return True

    # ------------------------------------------------------------------ functions

    def read_function(self, function: ast.FunctionDef) -> list[tuple[str, NodeFact]]:
        """The nodes made in a function: ``node = rclpy.create_node('name')`` (or ``Node('name')``)
        then ``node.create_*``; each variable so bound is a node of its own (``talker`` and
        ``listener`` in one ``main``). Returns (key in the module, node) pairs, the first node
        keyed by the function's name."""
        made: dict[str, NodeFact] = {}
        constants = Scope({**self.constants, **_single_assignments(function, self)})
        for stmt in ast.walk(function):
            if not (
                isinstance(stmt, ast.Assign)
                and len(stmt.targets) == 1
                and isinstance(stmt.targets[0], ast.Name)
                and isinstance(stmt.value, ast.Call)
                and dotted(stmt.value.func, self.imports) in _NODE_FACTORIES
            ):
                continue
            call = stmt.value
            name = evaluate(call.args[0] if call.args else keyword_argument(call, "node_name"), constants)
            variable = stmt.targets[0].id
            if not (isinstance(name, Known) and isinstance(name.value, str)):
                self.warn("a node is made with a name not known from the source; not imported", stmt)
                continue
            if variable in made:
                self.warn(
                    f"{variable} is given a second node: what each creates is not known; the first is kept",
                    stmt,
                )
                continue
            key = function.name if not made else f"{function.name}:{variable}"
            made[variable] = NodeFact(
                key=f"{self.package}:{self.file}:{key}",
                node_name=name.value,
                location=self.at(stmt),
                package=self.package,
            )
            self.namespace(call, constants, made[variable])
        found = []
        parameters = self.parameters([function], dict(self.constants))
        for index, (variable, fact) in enumerate(made.items()):
            fact.parameters = parameters
            scope = Scope(dict(self.constants), fact.parameters, {}, node=variable)
            self.block(function.body, scope, fact, (variable,), {}, in_loop=False)
            found.append((function.name if index == 0 else f"{function.name}:{variable}", fact))
        return found

    def namespace(self, call: ast.Call, scope: Scope, fact: NodeFact) -> None:
        """The ``namespace=`` a node is made with (``Node.__init__`` or ``create_node``)."""
        given = keyword_argument(call, "namespace")
        if given is None:
            return
        value = evaluate(given, scope)
        if isinstance(value, Known) and isinstance(value.value, str):
            fact.namespace = "/" + value.value.strip("/")
        else:
            self.warn(
                f"the node's namespace {ast.unparse(given)} is not known from the source; "
                "the root namespace is kept",
                call,
            )

    def read(self) -> ModuleNodes:
        classes = self.node_classes()
        by_name = {c.name: c for c in classes}
        for cls in classes:
            self.borrowed_names(cls, by_name)
        for cls in classes:
            if cls.name in self.bases_only:  # read with each class deriving from it
                self.consumed.update(id(n) for n in ast.walk(cls) if isinstance(n, ast.Call))
                continue
            bound = self.constructor_arguments(cls, self.methods(cls, by_name).get("__init__"))
            fact = self.read_class(cls, by_name, bound)
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
                for key, fact in self.read_function(stmt):
                    self.result.nodes.append(fact)
                    self.result.functions[stmt.name] = [*self.result.functions[stmt.name], key]
                    self.result.classes[key] = fact
        script = [s for s in self.tree.body if not isinstance(s, _DEFINITIONS)]
        if script:  # the module's own statements, run as a script (``if __name__ == '__main__':``)
            module = ast.FunctionDef(
                name=SCRIPT,
                args=ast.arguments([], [], None, [], [], None, []),
                body=script,
                decorator_list=[],
            )
            called = dict.fromkeys(  # a fixed order (ast.walk's), not a set's
                n.func.id
                for s in script
                for n in ast.walk(s)
                if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)
            )
            made = [n for n in called if n in by_name]
            for function in sorted(set(called) & set(self.result.functions)):
                made.extend(self.result.functions[function])
            self.result.functions[SCRIPT] = made
            for key, fact in self.read_function(module):
                self.result.nodes.append(fact)
                self.result.functions[SCRIPT] = [*self.result.functions[SCRIPT], key]
                self.result.classes[key] = fact
        for node in ast.walk(self.tree):
            if isinstance(node, ast.Call) and self.action(node):
                continue
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


def _init_call(init: ast.FunctionDef) -> ast.Call | None:
    """The first ``super().__init__(...)`` / ``Base.__init__(self, ...)`` call of ``init``."""
    for node in ast.walk(init):
        if (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Attribute)
            and node.func.attr == "__init__"
        ):
            return node
    return None


def _init_arguments(call: ast.Call) -> list[ast.expr]:
    """The positional arguments of an ``__init__`` call, ``self`` left out of ``Base.__init__(self, ...)``."""
    receiver = call.func.value  # type: ignore[attr-defined]
    by_super = (
        isinstance(receiver, ast.Call) and isinstance(receiver.func, ast.Name) and receiver.func.id == "super"
    )
    return list(call.args) if by_super else list(call.args[1:])


def _bind(
    init: ast.FunctionDef,
    args: list[ast.expr],
    keywords: list[ast.keyword],
    scope: Scope,
    defaults_scope: Scope,
    value: Callable[[ast.expr | None, Scope], Known],
) -> dict[str, Known]:
    """What the parameters of ``init`` (``self`` left out) are when called with ``args`` and
    ``keywords`` read in ``scope``: a default (read in ``defaults_scope``) where not given; none
    known after a ``*args`` or ``**kwargs`` argument."""
    params = [a.arg for a in init.args.posonlyargs + init.args.args][1:]
    names = params + [a.arg for a in init.args.kwonlyargs]
    if any(isinstance(a, ast.Starred) for a in args) or any(k.arg is None for k in keywords):
        return {name: Known(UNKNOWN) for name in names}
    defaults = dict(zip(reversed(params), reversed(init.args.defaults), strict=False))
    defaults.update({a.arg: d for a, d in zip(init.args.kwonlyargs, init.args.kw_defaults, strict=True) if d})
    given: dict[str, ast.expr] = dict(zip(params, args, strict=False))
    given.update({k.arg: k.value for k in keywords if k.arg})
    return {
        name: value(given[name], scope) if name in given else value(defaults.get(name), defaults_scope)
        for name in names
    }


def _single_assignments(
    function: ast.FunctionDef | ast.AsyncFunctionDef, reader: _Reader
) -> dict[str, Known]:
    """The local names of ``function`` assigned once in it, to a value known from the module's
    constants and the names before (a name assigned twice, or otherwise stored, is left out)."""
    names: dict[str, Known] = {}
    for name, expression in bound_once(function).items():
        names[name] = reader.value(expression, Scope({**reader.constants, **names}))
    return names


def read_module(
    tree: ast.Module,
    file: str,
    package: str,
    warnings: list[Diagnostic],
    *,
    imports: dict[str, str] | None = None,
    outside: dict[str, OutsideClass] | None = None,
    bases_only: set[str] | None = None,
    files: dict[int, str] | None = None,
    constants: dict[str, Known] | None = None,
) -> ModuleNodes:
    """The nodes ``tree`` (the module ``file`` of ROS package ``package``) defines; ``imports``:
    what its names stand for (relative imports resolved), ``outside``: the node classes of the
    package's other modules by qualified name (``pkg.base.BaseNode``); ``bases_only``: the
    classes of the module that are bases of other node classes only (not nodes themselves);
    ``files``: :func:`class_files` of ``outside``, ``constants``: the module's
    :func:`module_constants`, where the caller has them already (one package's modules share
    them)."""
    if outside is None:  # a package's modules are marked once, before any is read
        mark_assignments(tree)
    return _Reader(tree, file, warnings, package, imports, outside, bases_only, files, constants).read()


def class_files(outside: dict[str, OutsideClass]) -> dict[int, str]:
    """Each AST node of the classes ``outside`` (by id) → the file of its module."""
    return {id(n): item.file for item in outside.values() for n in ast.walk(item.cls)}


def module_constants(tree: ast.Module, imports: dict[str, str]) -> dict[str, Known]:
    """The top-level names of a module bound to a known value (or QoS profile)."""
    return _Reader(tree, "", [], "", imports).constants
