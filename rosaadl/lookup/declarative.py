"""Property values of declarative elements: classifiers and the members they declare.

A classifier is looked up as the root of a hierarchy (its own chains and contained
associations; a feature group type through its chain only); a subcomponent, feature,
connection, mode or flow as a member of the classifier that declares it, that classifier
standing for the enclosing component.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.errors import ModelError

from .associations import Associations
from .binding import Binding
from .instances import Finding
from .nodes import child_node, root_node
from .order import (
    combine,
    component_found,
    connection_found,
    element_found,
    evaluator,
    feature_found,
    with_default,
)

__all__ = ["find_declarative"]

# the members looked up by their declaration (contained associations, refinements, inherit)
_DECLARED = ("Mode", "ModeTransition", "FlowSpecification", "FlowImplementation", "EndToEndFlow")


def find_declarative(assoc: Associations, element: EObject, key: str, binding: Binding | None) -> Finding:
    """The value of property ``key`` on a declarative element, with its evaluate callback (no
    reference callback: declarative references stay paths)."""
    if _model.is_a(element, "Classifier"):
        if _model.is_a(element, "FeatureGroupType"):
            pas = assoc.of_classifier(element).get(key, ())
            found = combine(assoc, ((pa, None) for pa in pas), None)
            return with_default(assoc, found, key), None, None
        node = root_node(assoc, element)
        evaluate = evaluator(assoc, node, lambda k: component_found(assoc, node, k, binding))
        return evaluate(key), evaluate, None
    owner = element.eContainer()
    if owner is None or not _model.is_a(owner, "Classifier"):
        raise ModelError(f"no property lookup for a {element.eClass.name}")
    owner_node = root_node(assoc, owner)
    if _model.is_a(element, "Subcomponent"):
        node = child_node(assoc, owner_node, element, assoc.resolver.subcomponent_classifier(element))
        evaluate = evaluator(assoc, node, lambda k: component_found(assoc, node, k, binding))
    elif _model.is_a(element, "Feature"):
        chain = [element]
        names = [(element.name or "", 0)]
        evaluate = evaluator(
            assoc, owner_node, lambda k: feature_found(assoc, owner_node, chain, names, k, binding)
        )
    elif _model.is_a(element, "Connection"):
        refs = [(element, owner_node)]
        evaluate = evaluator(
            assoc, owner_node, lambda k: connection_found(assoc, refs, owner_node, k, binding)
        )
    elif _model.is_a(element, *_DECLARED):
        evaluate = evaluator(
            assoc, owner_node, lambda k: element_found(assoc, owner_node, element, k, binding)
        )
    else:
        raise ModelError(f"no property lookup for a {element.eClass.name}")
    return evaluate(key), evaluate, None
