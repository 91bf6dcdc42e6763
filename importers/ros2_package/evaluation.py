"""The value of a Python expression, where the source alone decides it (no execution).

What is known: literals, names bound once to a known value (module and class constants, local
assignments before the use), ``+ - * /`` on numbers and ``+``/f-strings on text, ``float()``,
``int()``, ``str()``, ``Duration(seconds=..., nanoseconds=...)``, parameters
(``self.declare_parameter(name, default)`` and ``self.get_parameter(name).value`` give the
default; the value then says which parameter it came from, so that a launch file can override it)
and calls of a method of the same class with known arguments whose body computes its result
from them (``self.period_of('thread')``), a few calls deep. Anything else is :data:`UNKNOWN`:
the readers name it in a warning, they never guess.
"""

from __future__ import annotations

import ast
import operator
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

__all__ = ["UNKNOWN", "Known", "Scope", "evaluate", "run_body", "stored_names", "bound_once"]

#: Method calls followed into the method's body at most this deep.
MAX_CALL_DEPTH = 4
#: Largest number arithmetic is done on (no computation on huge literals).
MAX_NUMBER = 10**18
#: Longest text a string operation may produce (``'x' * 10**9`` is not computed).
MAX_TEXT = 4096


class _Unknown:
    def __repr__(self) -> str:
        return "UNKNOWN"

    def __bool__(self) -> bool:
        return False


UNKNOWN = _Unknown()


@dataclass(frozen=True)
class Known:
    """A value found in the source, and the node parameter it is the default of, if any."""

    value: object
    parameter: str | None = None  #: the value is this parameter's (its default, until set)
    derived: str | None = None  #: the value is computed from this parameter's


@dataclass
class Scope:
    """The names an expression may use, and how to read parameters and follow methods."""

    names: Mapping[str, Known] = field(default_factory=dict)
    parameters: Mapping[str, object] = field(default_factory=dict)  #: declared name → default
    methods: Mapping[str, ast.FunctionDef] = field(default_factory=dict)  #: the class's methods
    depth: int = 0
    node: str = "self"  #: the name the node goes by (``self``, or ``node`` in a function)

    def with_names(self, names: Mapping[str, Known]) -> Scope:
        return Scope({**self.names, **names}, self.parameters, self.methods, self.depth, self.node)


_BINARY: dict[type, Callable[[object, object], object]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv,
}
_PARAMETER_VALUES = (
    "value",
    "double_value",
    "integer_value",
    "string_value",
    "bool_value",
)


def _number(value: object) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _binary(op: ast.operator, left: object, right: object) -> object:
    func = _BINARY.get(type(op))
    if func is None:
        return UNKNOWN
    if _number(left) and _number(right):
        if isinstance(op, (ast.Div, ast.FloorDiv)) and right == 0:
            return UNKNOWN
        if abs(left) > MAX_NUMBER or abs(right) > MAX_NUMBER:  # type: ignore[arg-type]
            return UNKNOWN
        return func(left, right)
    if isinstance(op, ast.Add) and isinstance(left, str) and isinstance(right, str):
        return left + right if len(left) + len(right) <= MAX_TEXT else UNKNOWN
    return UNKNOWN


def _self_call(node: ast.expr, receiver: str = "self") -> ast.Call | None:
    """``node`` when it is ``self.<name>(...)`` (``receiver`` standing for ``self``)."""
    if (
        isinstance(node, ast.Call)
        and isinstance(node.func, ast.Attribute)
        and isinstance(node.func.value, ast.Name)
        and node.func.value.id == receiver
    ):
        return node
    return None


def _parameter_read(node: ast.expr, scope: Scope) -> Known | _Unknown:
    """``self.get_parameter(n).value``, ``...get_parameter_value().double_value``,
    ``self.declare_parameter(n, d).value``: the declared default of parameter ``n``."""
    while isinstance(node, ast.Attribute) and node.attr in (*_PARAMETER_VALUES, "get_parameter_value"):
        node = node.value
    if (
        isinstance(node, ast.Call)
        and isinstance(node.func, ast.Attribute)
        and node.func.attr == "get_parameter_value"
    ):
        node = node.func.value
    call = _self_call(node, scope.node)
    if call is None or not call.args:
        return UNKNOWN
    method = call.func.attr  # type: ignore[attr-defined]
    name = evaluate(call.args[0], scope)
    if not isinstance(name, Known) or not isinstance(name.value, str):
        return UNKNOWN
    if method == "declare_parameter":
        default = evaluate(call.args[1], scope) if len(call.args) > 1 else UNKNOWN
        return Known(default.value, name.value) if isinstance(default, Known) else UNKNOWN
    if method in ("get_parameter", "get_parameter_or"):
        if name.value in scope.parameters:
            return Known(scope.parameters[name.value], name.value)
        if method == "get_parameter_or" and len(call.args) > 1:
            default = evaluate(call.args[1], scope)
            return Known(default.value, name.value) if isinstance(default, Known) else UNKNOWN
    return UNKNOWN


def _method_result(call: ast.Call, scope: Scope) -> Known | _Unknown:
    """The value ``self.m(args)`` returns, computed from its body with the arguments known."""
    method = scope.methods.get(call.func.attr)  # type: ignore[attr-defined]
    if method is None or scope.depth >= MAX_CALL_DEPTH or call.keywords:
        return UNKNOWN
    params = [a.arg for a in method.args.args][1:]
    if len(call.args) > len(params) or any(isinstance(a, ast.Starred) for a in call.args):
        return UNKNOWN
    names: dict[str, Known] = {}
    for param, arg in zip(params, call.args, strict=False):
        value = evaluate(arg, scope)
        if not isinstance(value, Known):
            return UNKNOWN
        names[param] = value
    inner = Scope({**scope.names, **names}, scope.parameters, scope.methods, scope.depth + 1, scope.node)
    return run_body(method.body, inner)


def run_body(body: list[ast.stmt], scope: Scope) -> Known | _Unknown:
    """The value a function body returns: its simple assignments in order, then its first
    top-level ``return``; a name assigned anywhere else (in a branch, a loop) becomes unknown."""
    names = dict(scope.names)
    for stmt in body:
        current = scope.with_names(names)
        if isinstance(stmt, ast.Return):
            return evaluate(stmt.value, current) if stmt.value is not None else UNKNOWN
        if isinstance(stmt, ast.Assign) and len(stmt.targets) == 1 and isinstance(stmt.targets[0], ast.Name):
            value = evaluate(stmt.value, current)
            names[stmt.targets[0].id] = value if isinstance(value, Known) else Known(UNKNOWN)
        elif isinstance(stmt, ast.AnnAssign) and isinstance(stmt.target, ast.Name) and stmt.value is not None:
            value = evaluate(stmt.value, current)
            names[stmt.target.id] = value if isinstance(value, Known) else Known(UNKNOWN)
        else:
            for name in stored_names(stmt):
                names[name] = Known(UNKNOWN)
    return UNKNOWN


def stored_names(stmt: ast.AST) -> set[str]:
    """The names ``stmt`` assigns anywhere inside it: plain names, and ``self.x`` as ``"self.x"``."""
    found = set()
    for node in ast.walk(stmt):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            found.add(node.id)
        elif (
            isinstance(node, ast.Attribute)
            and isinstance(node.ctx, ast.Store)
            and isinstance(node.value, ast.Name)
            and node.value.id == "self"
        ):
            found.add("self." + node.attr)
    return found


def bound_once(node: ast.AST) -> dict[str, ast.expr]:
    """The names assigned exactly once in ``node`` (``x = ...``, nowhere else stored, no
    function parameter of that name), each with the expression it is given, in walk order."""
    counts: dict[str, int] = {}
    for inner in ast.walk(node):
        if isinstance(inner, ast.Name) and isinstance(inner.ctx, ast.Store):
            counts[inner.id] = counts.get(inner.id, 0) + 1
        elif isinstance(inner, ast.arg):
            counts[inner.arg] = counts.get(inner.arg, 0) + 2
    return {
        inner.targets[0].id: inner.value
        for inner in ast.walk(node)
        if isinstance(inner, ast.Assign)
        and len(inner.targets) == 1
        and isinstance(inner.targets[0], ast.Name)
        and counts.get(inner.targets[0].id) == 1
    }


def _duration(call: ast.Call, scope: Scope) -> Known | _Unknown:
    total = 0.0
    parameter = None
    scale = {"seconds": 1.0, "nanoseconds": 1e-9}
    for keyword in call.keywords:
        if keyword.arg not in scale:
            return UNKNOWN
        value = evaluate(keyword.value, scope)
        if not isinstance(value, Known) or not _number(value.value):
            return UNKNOWN
        total += value.value * scale[keyword.arg]  # type: ignore[operator]
        parameter = parameter or value.parameter or value.derived
    if call.args:
        return UNKNOWN
    return Known(total, None, parameter)


def evaluate(node: ast.expr | None, scope: Scope) -> Known | _Unknown:
    """The value of ``node`` in ``scope``, or :data:`UNKNOWN` (see the module docstring)."""
    if node is None:
        return UNKNOWN
    if isinstance(node, ast.Constant):
        return Known(node.value)
    if isinstance(node, ast.Name):
        found = scope.names.get(node.id)
        return found if isinstance(found, Known) and found.value is not UNKNOWN else UNKNOWN
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "self":
        found = scope.names.get("self." + node.attr)
        return found if isinstance(found, Known) and found.value is not UNKNOWN else UNKNOWN
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        operand = evaluate(node.operand, scope)
        if isinstance(operand, Known) and _number(operand.value):
            if isinstance(node.op, ast.UAdd):
                return operand
            return Known(-operand.value, None, operand.parameter or operand.derived)  # type: ignore[operator]
        return UNKNOWN
    if isinstance(node, ast.BinOp):
        left, right = evaluate(node.left, scope), evaluate(node.right, scope)
        if isinstance(left, Known) and isinstance(right, Known):
            value = _binary(node.op, left.value, right.value)
            source = left.parameter or left.derived or right.parameter or right.derived
            return Known(value, None, source) if value is not UNKNOWN else UNKNOWN
        return UNKNOWN
    if isinstance(node, ast.JoinedStr):
        parts = []
        for value in node.values:
            if isinstance(value, ast.Constant):
                parts.append(str(value.value))
            elif (
                isinstance(value, ast.FormattedValue) and value.format_spec is None and value.conversion == -1
            ):
                inner = evaluate(value.value, scope)
                if not isinstance(inner, Known) or not isinstance(inner.value, (str, int)):
                    return UNKNOWN
                parts.append(str(inner.value))
            else:
                return UNKNOWN
        text = "".join(parts)
        return Known(text) if len(text) <= MAX_TEXT else UNKNOWN
    if isinstance(node, ast.Attribute) and node.attr in _PARAMETER_VALUES:
        return _parameter_read(node, scope)
    if isinstance(node, ast.Call):
        func = node.func
        if isinstance(func, ast.Name) and func.id in ("float", "int", "str") and len(node.args) == 1:
            inner = evaluate(node.args[0], scope)
            if not isinstance(inner, Known) or node.keywords:
                return UNKNOWN
            try:
                converted = {"float": float, "int": int, "str": str}[func.id](inner.value)
                return Known(converted, inner.parameter, inner.derived)
            except (TypeError, ValueError, OverflowError):
                return UNKNOWN
        name = func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""
        if name == "Duration":
            return _duration(node, scope)
        if _self_call(node) is not None:
            if name in ("declare_parameter", "get_parameter", "get_parameter_or"):
                return UNKNOWN  # a Parameter object, not a value
            return _method_result(node, scope)
    return UNKNOWN
