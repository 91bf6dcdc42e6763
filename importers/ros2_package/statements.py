"""Where the calls of a Python module are, read from its syntax tree alone: the calls of a
statement outside nested functions, the blocks of a compound statement with the condition each
runs under, calls made once per item of a comprehension, the name a call is assigned to, and
what a later attribute store makes unknown. Used by the node reader
(:mod:`.node_classes`) to find the ``create_*`` calls and the names they are kept under."""

from __future__ import annotations

import ast

from rosaadl.importers.ros2_package.evaluation import UNKNOWN, Known

__all__ = [
    "forget_changed",
    "assigned_attribute",
    "cancels",
    "calls_in",
    "blocks_of",
    "comprehended",
    "mark_assignments",
]


def forget_changed(target: ast.expr | None, names: dict[str, Known]) -> None:
    """``qos.depth = 1`` or ``self.qos.depth = 1`` changes what ``qos`` (``self.qos``) holds: no
    longer known."""
    while isinstance(target, (ast.Attribute, ast.Subscript)):
        inner = target.value
        if isinstance(inner, ast.Name):
            names[inner.id] = Known(UNKNOWN)
        elif (
            isinstance(inner, ast.Attribute)
            and isinstance(inner.value, ast.Name)
            and inner.value.id == "self"
        ):
            names["self." + inner.attr] = Known(UNKNOWN)
        target = inner


def assigned_attribute(call: ast.Call, *, raw: bool = False) -> str | None:
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


def cancels(method: ast.FunctionDef | None, attribute: str) -> bool:
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


def calls_in(stmt: ast.stmt) -> list[ast.Call]:
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


def blocks_of(stmt: ast.stmt) -> list[tuple[list[ast.stmt], str | None]]:
    """The blocks of a compound statement, each with the condition it runs under (None: as
    often as the statement itself). ``if __name__ == '__main__':`` is no condition: the module
    runs as a script."""
    if isinstance(stmt, ast.If):
        test = ast.unparse(stmt.test)
        if test in ("__name__ == '__main__'", '__name__ == "__main__"'):
            return [(stmt.body, None), (stmt.orelse, "not " + test)]
        return [(stmt.body, test), (stmt.orelse, f"not ({test})")]
    parts = [(getattr(stmt, name, None) or [], None) for name in ("body", "finalbody")]
    if isinstance(stmt, ast.Try):
        parts.append((stmt.orelse, "no exception is raised"))
    for handler in getattr(stmt, "handlers", None) or []:
        parts.append(
            (handler.body, f"{ast.unparse(handler.type) if handler.type else 'an exception'} is raised")
        )
    return parts


def comprehended(stmt: ast.stmt) -> set[int]:
    """The ids of the calls in ``stmt`` made inside a comprehension (once per item)."""
    found: set[int] = set()
    for node in ast.walk(stmt):
        if isinstance(node, (ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp)):
            found.update(id(n) for n in ast.walk(node) if isinstance(n, ast.Call))
    return found


def mark_assignments(tree: ast.Module) -> None:
    """Mark each call assigned to a name in ``tree`` with its assignment (a port's or timer's
    name in the code); done for every module of a package before any is read, since a class
    reads the methods of its base classes in other modules."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and isinstance(node.value, ast.Call):
            node.value._rosaadl_parent = node  # type: ignore[attr-defined]
