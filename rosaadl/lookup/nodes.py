"""Contained property associations, carried down a component hierarchy.

An ``applies to a.b.c`` association declared in an implementation (or in the property block of a
subcomponent) reaches the element at the end of that path. A :class:`ComponentNode` stands for
one component of a hierarchy (an instance, or a declarative stand-in); each node holds the
contained associations that still have a path to go below it (``pending``) and those that end on
it (``own``, the outermost first). :func:`root_node` and :func:`child_node` make nodes and move
the paths one segment down; :func:`contained_for` gives those that end on a feature, connection,
mode or flow of a node.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.resolution import PathSegment

from .associations import Associations

if TYPE_CHECKING:
    from .order import Found

__all__ = ["ComponentNode", "child_node", "contained_for", "root_node"]


@dataclass(eq=False)
class ComponentNode:
    """A component in an instance hierarchy (or a declarative stand-in for one).

    ``obj`` is the instance object when there is one; ``sub`` the declaring subcomponent;
    ``classifier`` its component classifier (``impl``/``ctype`` its implementation and type).
    ``pending`` holds the contained associations (``applies to`` paths) that reach this component
    from above and from its own classifier, outermost first.
    """

    obj: EObject | None
    parent: ComponentNode | None
    sub: EObject | None
    classifier: EObject | None
    impl: EObject | None
    ctype: EObject | None
    category: str
    index: tuple[int, ...] = ()
    pending: list[tuple[tuple[PathSegment, ...], EObject, ComponentNode]] = field(default_factory=list)
    own: dict[str, tuple[EObject, ComponentNode]] = field(default_factory=dict)
    memo: dict[str, Found | None] = field(default_factory=dict)
    binding: list[EObject] | None = None

    @property
    def name(self) -> str:
        return (self.sub.name if self.sub is not None else None) or (getattr(self.obj, "name", "") or "")


#: a contained association on its way down: the rest of its path, it, and its anchor (the node
#: relative to which its ``reference (...)`` values are resolved)
_Entry = tuple[tuple[PathSegment, ...], EObject, ComponentNode]


def root_node(assoc: Associations, classifier: EObject | None, obj: EObject | None = None) -> ComponentNode:
    """The node of the root of a hierarchy (``obj`` its instance object, if any)."""
    impl, ctype = _impl_type(assoc, classifier)
    category = _category_word(classifier, None, obj)
    node = ComponentNode(obj, None, None, classifier, impl, ctype, category)
    _add_own_contained(assoc, node, [])
    return node


def child_node(
    assoc: Associations,
    parent: ComponentNode,
    sub: EObject | None,
    classifier: EObject | None,
    obj: EObject | None = None,
    index: Iterable[int] = (),
    name: str | None = None,
) -> ComponentNode:
    """The node of subcomponent ``sub`` (element ``index`` of an array) of ``parent``."""
    impl, ctype = _impl_type(assoc, classifier)
    category = _category_word(classifier, sub, obj)
    node = ComponentNode(obj, parent, sub, classifier, impl, ctype, category, tuple(index))
    wanted = (name or node.name).lower()
    incoming: list[_Entry] = []
    for segments, pa, anchor in parent.pending:
        first = segments[0]
        if first.key == wanted and first.matches(node.index):
            incoming.append((segments[1:], pa, anchor))
    # the subcomponent's own property block: paths relative to this component, declared in
    # the parent's implementation (outer to this component's classifier)
    if sub is not None:
        for member in assoc.members.refinement_chain(sub):
            for segments, pa in assoc.contained(member):
                incoming.append((segments, pa, parent))
    _add_own_contained(assoc, node, incoming)
    return node


def _add_own_contained(assoc: Associations, node: ComponentNode, incoming: list[_Entry]) -> None:
    entries = list(incoming)
    if node.classifier is not None:
        for segments, pa in assoc.classifier_contained(node.classifier):
            entries.append((segments, pa, node))
    pending: list[_Entry] = []
    own = node.own
    pa_info = assoc.keys.pa_info
    for segments, pa, anchor in entries:
        if segments:
            pending.append((segments, pa, anchor))
        else:
            own.setdefault(pa_info(pa)[0], (pa, anchor))
    node.pending = pending


def _impl_type(assoc: Associations, classifier: EObject | None) -> tuple[EObject | None, EObject | None]:
    if classifier is None:
        return None, None
    if _model.is_a(classifier, "ComponentImplementation"):
        return classifier, assoc.resolver.implementation_type(classifier)
    if _model.is_a(classifier, "ComponentType"):
        return None, classifier
    return None, None


def _category_word(classifier: EObject | None, sub: EObject | None, obj: EObject | None) -> str:
    """OSATE's component category: the classifier's unless abstract, then the subcomponent's."""
    for source in (classifier, sub, obj):
        if source is None:
            continue
        category = getattr(source, "category", None)
        if category is None:
            continue
        text = getattr(category, "literal", None) or getattr(category, "name", None) or str(category)
        if text and text != "abstract":
            return text
    return "abstract"


def contained_for(
    assoc: Associations, node: ComponentNode, names: list[tuple[str, int]]
) -> dict[str, tuple[EObject, Any]]:
    """Contained associations reaching an element of ``node`` named by the path ``names``
    (``[(feature group, index), (port, index)]``, a connection, mode or flow name)."""
    result: dict[str, tuple[EObject, Any]] = {}
    depth = len(names)
    pa_info = assoc.keys.pa_info
    for segments, pa, anchor in node.pending:
        if len(segments) != depth:
            continue
        if all(
            seg.key == name.lower() and seg.matches(index)
            for seg, (name, index) in zip(segments, names, strict=True)
        ):
            result.setdefault(pa_info(pa)[0], (pa, anchor))
    return result
