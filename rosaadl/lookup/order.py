"""AADL's lookup order: which associations give a property its value on an element.

For a component (SAE AS5506C §11.3, as OSATE applies it):

1. a *contained* association (``applies to`` path) declared in an enclosing implementation or in
   the property block of an enclosing subcomponent — the outermost one wins;
2. the subcomponent's own associations (through ``refined to``);
3. the classifier: the implementation, its ``extends`` chain, then the type and its chain;
4. for an ``inherit`` property, the value of the containing component;
5. the property's default value (:func:`with_default`).

A feature looks at contained associations, its own (through refinements), then its classifier's
(a data type gives its ``Data_Size`` to the ports it types); a connection at the first of its
declarations along the semantic connection that has a value; modes and flows at their
declaration. ``+=>`` keeps looking further down and the result lists every part
(:class:`Found`); associations ``in binding`` count only when the component is bound to a
matching processor (:mod:`.binding`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

from pyecore.ecore import EObject

from .associations import Associations, ModalValues
from .binding import Binding, binding_applies
from .nodes import ComponentNode, contained_for

__all__ = [
    "Evaluate",
    "Found",
    "combine",
    "component_found",
    "connection_found",
    "default_found",
    "element_found",
    "evaluator",
    "feature_found",
    "with_default",
]


@dataclass
class Found:
    """The winning association(s) for one property on one object.

    ``parts`` runs from the highest precedence down: the first part is the association that set the
    value; when it appends (``+=>``), the following parts are the values it appends to.  Each part is
    ``(association or None, modal values [(expression, in modes)], anchor)``; the anchor is the
    component (node) relative to which ``reference (...)`` paths of that association are resolved.
    """

    parts: list[tuple[EObject | None, ModalValues, Any]]
    complete: bool = True  # False when only appending associations were found (no base value)

    @property
    def association(self) -> EObject | None:
        return self.parts[0][0] if self.parts else None


#: the value of a property (by key) on one element, default value included
Evaluate = Callable[[str], "Found | None"]
_Candidates = Iterator[tuple[EObject, Any]]


def combine(
    assoc: Associations, candidates: _Candidates, base: Callable[[], Found | None] | None
) -> Found | None:
    """The first candidate with a value, with what it appends to (the next candidates, then
    ``base``, the inherited value) while it appends."""
    parts: list[tuple[EObject | None, ModalValues, Any]] = []
    for pa, anchor in candidates:
        values, append, _ = assoc.values(pa)
        if not values:
            continue
        parts.append((pa, values, anchor))
        if not append:
            return Found(parts)
    if base is not None:
        below = base()
        if below is not None:
            parts.extend(below.parts)
            return Found(parts, below.complete)
    if parts:
        return Found(parts, complete=False)
    return None


def _inherited(
    assoc: Associations, container: ComponentNode | None, key: str, binding: Binding | None
) -> Callable[[], Found | None] | None:
    """The value of ``container`` when property ``key`` is ``inherit`` (None otherwise)."""
    prop = assoc.keys.definitions.get(key)
    if container is None or prop is None or not prop.inherit:
        return None
    return lambda: component_found(assoc, container, key, binding)


def component_found(
    assoc: Associations, node: ComponentNode, key: str, binding: Binding | None = None
) -> Found | None:
    """The value of property ``key`` for a component (without the default value)."""
    memo = node.memo
    if key in memo:
        return memo[key]
    memo[key] = None  # a property whose lookup depends on itself finds nothing

    def candidates() -> _Candidates:
        contained = node.own.get(key)
        if contained is not None and binding_applies(assoc, contained[0], node, binding):
            yield contained
        if node.sub is not None:
            for member in assoc.members.refinement_chain(node.sub):
                for pa in assoc.held(member).get(key, ()):
                    if binding_applies(assoc, pa, node, binding):
                        yield pa, node.parent
        if node.classifier is not None:
            for pa in assoc.of_classifier(node.classifier).get(key, ()):
                if binding_applies(assoc, pa, node, binding):
                    yield pa, node

    found = combine(assoc, candidates(), _inherited(assoc, node.parent, key, binding))
    memo[key] = found
    return found


def _declared(
    assoc: Associations,
    node: ComponentNode,
    name: list[tuple[str, int]],
    member: EObject,
    key: str,
    typed: bool = False,
) -> _Candidates:
    """Contained associations reaching ``member`` (a feature, connection, mode or flow of ``node``
    named by the path ``name``), then its own through its refinements, then (``typed``) those of
    its classifier."""
    contained = contained_for(assoc, node, name).get(key)
    if contained is not None:
        yield contained
    members = assoc.members
    for element in members.refinement_chain(member):
        for pa in assoc.held(element).get(key, ()):
            yield pa, node
    if typed:
        classifier = members.member_classifier(member)
        if classifier is not None:
            for pa in assoc.of_classifier(classifier).get(key, ()):
                yield pa, node


def feature_found(
    assoc: Associations,
    node: ComponentNode,
    chain: list[EObject],
    names: list[tuple[str, int]],
    key: str,
    binding: Binding | None = None,
) -> Found | None:
    """The value for a feature of component ``node``; ``chain`` lists the feature declarations
    from the outermost feature group down to the feature, ``names`` their instance names."""
    candidates = _declared(assoc, node, names, chain[-1], key, typed=True)
    return combine(assoc, candidates, _inherited(assoc, node, key, binding))


def connection_found(
    assoc: Associations,
    references: list[tuple[EObject, ComponentNode]],
    owner: ComponentNode | None,
    key: str,
    binding: Binding | None = None,
) -> Found | None:
    """The value for a semantic connection: the first of its declarations (in path order) that
    has one, each looked up with its contained associations and refinements."""
    inherited = _inherited(assoc, owner, key, binding)
    for connection, context in references:
        found = combine(assoc, _declared(assoc, context, [(connection.name or "", 0)], connection, key), None)
        if found is not None:
            return found
    return inherited() if inherited is not None else None


def element_found(
    assoc: Associations, node: ComponentNode, element: EObject, key: str, binding: Binding | None = None
) -> Found | None:
    """The value for a mode, flow specification, flow implementation or end-to-end flow of
    ``node`` (contained associations, the declaration and its refinements, inherit)."""
    candidates = _declared(assoc, node, [(element.name or "", 0)], element, key)
    return combine(assoc, candidates, _inherited(assoc, node, key, binding))


def default_found(assoc: Associations, key: str, anchor: Any = None) -> Found | None:
    """The default value of property ``key`` as a found value (None when it has none)."""
    prop = assoc.keys.definitions.get(key)
    if prop is None or prop.defaultValue is None:
        return None
    return Found([(None, [(prop.defaultValue, [])], anchor)])


def with_default(assoc: Associations, found: Found | None, key: str, anchor: Any = None) -> Found | None:
    """``found`` completed by the default value (when there is no value, or only appends)."""
    if found is not None and found.complete:
        return found
    default = default_found(assoc, key, anchor)
    if found is None:
        return default
    if default is None:
        return found
    return Found(found.parts + default.parts)


def evaluator(assoc: Associations, anchor: Any, found: Callable[[str], Found | None]) -> Evaluate:
    """The value of any property on one element (``found`` gives it without the default value;
    ``anchor`` is the node the default value's references are resolved from)."""

    def evaluate(key: str) -> Found | None:
        return with_default(assoc, found(key), key, anchor)

    return evaluate
