"""Binding-dependent values: associations declared ``in binding (P::cpu)``.

Such an association applies only to a component bound to a processor (or memory, bus, ...) of a
named classifier or of one that extends it. A lookup receives the binding as a callback that
gives the classifiers a component is bound to (instantiation reads them from
``Actual_Processor_Binding``; a caller of :meth:`~rosaadl.lookup.PropertyLookup.value` names
them with ``in_binding``).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any

from pyecore.ecore import EObject

from rosaadl.errors import ModelError
from rosaadl.resolution import Resolver

from .associations import Associations

if TYPE_CHECKING:
    from .nodes import ComponentNode

__all__ = ["Binding", "binding_applies", "fixed_binding"]

#: the classifiers a component (node) is bound to
Binding = Callable[["ComponentNode"], list[EObject]]


def binding_applies(
    assoc: Associations, pa: EObject, node: ComponentNode | None, binding: Binding | None
) -> bool:
    """Whether association ``pa`` applies to ``node`` under ``binding``: always when it has no
    ``in binding``, else when the node is bound to a named classifier or one that extends it."""
    if not assoc.values(pa)[2]:
        return True
    classifiers = binding(node) if binding is not None else None
    if not classifiers:
        return False
    for name in pa.inBinding:
        wanted = assoc.resolver.classifier(name, pa)
        if wanted is None:
            continue
        for cls in classifiers:
            if cls is wanted or any(c is wanted for c in assoc.chain_holders(cls)):
                return True
    return False


def fixed_binding(
    resolver: Resolver, in_binding: str | EObject | Iterable[str | EObject] | None, context: EObject
) -> Binding | None:
    """The binding of a caller that names the classifiers (by name from ``context``, or as
    elements); None when it names none. An unknown name is a :class:`ModelError`."""
    if in_binding is None:
        return None
    if isinstance(in_binding, (str, EObject)):
        items = [in_binding]
    elif isinstance(in_binding, Iterable):
        items = list(in_binding)
    else:
        raise ModelError(f"in_binding: expected classifiers or their names, got {in_binding!r}")
    classifiers = []
    for item in items:
        cls = item if isinstance(item, EObject) else resolver.classifier(item, context)
        if cls is None and isinstance(item, str):
            raise ModelError(f"binding classifier {item!r} not found")
        if cls is not None:
            classifiers.append(cls)

    def binding(_node: Any) -> list[EObject]:
        return classifiers

    return binding
