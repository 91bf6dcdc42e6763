"""Cycles of property constants: ``A : constant aadlinteger => CC::B;`` with ``B => CC::A``.

A property constant's value may name other constants (a ``NamedValue``, alone or inside a list,
range, record or operation); the constants that name each other in a ring have no value.
:func:`constant_cycles` finds every such ring (the strongly connected components of the graph
"constant → the constants its value names", and a constant that names itself), so that the
reference check reports each once, naming its constants in order; the property lookup already
keeps a constant met again while its own value is computed as a name, so nothing loops.

Work: one visit of every constant and of every value element of its value (Tarjan's algorithm,
iterative: no recursion limit on long chains).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from pyecore.ecore import EObject

from rosaadl.model import is_a

if TYPE_CHECKING:
    from .resolver import Resolver

__all__ = ["VALUE_OPERANDS", "ConstantLink", "constant_cycles"]

#: the values directly inside a range, list, record or operation value, by value class
VALUE_OPERANDS = {
    "RangeValue": lambda expr: [e for e in (expr.minimum, expr.maximum, expr.delta) if e is not None],
    "ListValue": lambda expr: list(expr.ownedItems),
    "RecordValue": lambda expr: [f.value for f in expr.ownedFields if f.value is not None],
    "OperationValue": lambda expr: list(expr.ownedOperands),
}


@dataclass(frozen=True)
class ConstantLink:
    """A constant of a cycle and the constants of the same cycle its value names."""

    constant: EObject
    names: tuple[EObject, ...]


def constant_cycles(resolver: Resolver) -> list[list[ConstantLink]]:
    """Every cycle of property constants whose values name each other: its constants in
    declaration order, each with those of the cycle it names (``A => B; B => A``, or ``C => C``
    for a constant that names itself); the cycles in the order of their first constant."""
    constants = [
        const
        for unit in resolver.index.by_name.values()
        if is_a(unit, "PropertySet")
        for const in unit.ownedPropertyConstants
    ]
    order = {id(const): number for number, const in enumerate(constants)}
    named = {id(const): _named_constants(resolver, const, order) for const in constants}
    cycles = []
    for component in _strong_components(constants, named):
        members = {id(const) for const in component}
        cycle = [
            ConstantLink(const, tuple(n for n in named[id(const)] if id(n) in members))
            for const in sorted(component, key=lambda const: order[id(const)])
        ]
        if cycle[0].names:  # one constant: a cycle only when it names itself
            cycles.append(cycle)
    return sorted(cycles, key=lambda cycle: order[id(cycle[0].constant)])


def _named_constants(resolver: Resolver, const: EObject, order: dict[int, int]) -> list[EObject]:
    """The constants of the model the value of ``const`` names, in the value's order."""
    found: list[EObject] = []
    stack = [const.value] if const.value is not None else []
    while stack:
        expr = stack.pop()
        kind = expr.eClass.name
        if kind == "NamedValue" and expr.name:
            target = resolver.constant(expr.name, const)
            if target is not None and id(target) in order and all(t is not target for t in found):
                found.append(target)
        operands = VALUE_OPERANDS.get(kind)
        if operands is not None:
            stack.extend(reversed(operands(expr)))
    return found


def _strong_components(nodes: list[EObject], edges: dict[int, list[EObject]]) -> list[list[EObject]]:
    """Tarjan's strongly connected components, iteratively."""
    index: dict[int, int] = {}
    low: dict[int, int] = {}
    on_stack: set[int] = set()
    stack: list[EObject] = []
    components: list[list[EObject]] = []
    for start in nodes:
        if id(start) in index:
            continue
        work = [(start, 0)]
        while work:
            node, position = work.pop()
            key = id(node)
            if position == 0:
                index[key] = low[key] = len(index)
                stack.append(node)
                on_stack.add(key)
            targets = edges[key]
            if position < len(targets):
                work.append((node, position + 1))
                target = targets[position]
                if id(target) not in index:
                    work.append((target, 0))
                elif id(target) in on_stack:
                    low[key] = min(low[key], index[id(target)])
                continue
            if work:  # the caller takes the low link of what it called
                caller = id(work[-1][0])
                low[caller] = min(low[caller], low[key])
            if low[key] == index[key]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(id(member))
                    component.append(member)
                    if member is node:
                        break
                components.append(component)
    return components
