"""Property values of instance objects.

An instance object made by :mod:`rosaadl.transforms.instantiate` carries its resolved values
(:func:`own_instance_value`). For other instance trees (read from ``.aaxl2`` files, or with their
values removed) the value is computed from the declarative model: :func:`find_instance` rebuilds
the component nodes from the root down to the object (its subcomponent, classifier and array
index), finds the declaration of a feature, connection, mode or flow instance, and follows the
lookup order from there; ``reference (...)`` values resolve against the instance tree
(:func:`resolve_instance_path`).
"""

from __future__ import annotations

from collections.abc import Iterable

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.errors import ModelError
from rosaadl.resolution import split_path
from rosaadl.resolution.names import squeeze

from .associations import Associations
from .binding import Binding
from .nodes import ComponentNode, child_node, root_node
from .order import Evaluate, Found, component_found, connection_found, element_found, evaluator, feature_found
from .values import Reference, select_modal

__all__ = [
    "find_instance",
    "instance_node",
    "instance_reference",
    "own_instance_value",
    "resolve_instance_path",
    "by_name",
]

#: what a lookup needs for one element: its value, how to evaluate other properties on it
#: (``Deadline => Period``), how to resolve its references
Finding = tuple["Found | None", "Evaluate | None", "Reference | None"]


def own_instance_value(obj: EObject, key: str, in_mode: str | None) -> EObject | None:
    """The value an instance object carries for property ``key`` (None when it carries none)."""
    if obj.eClass.findEStructuralFeature("ownedPropertyAssociations") is None:
        return None
    found = None
    for pa in obj.ownedPropertyAssociations:
        if pa.appliesTo:
            continue
        written = squeeze(pa.property).lower()
        if (
            written == key
            or ("::" not in written and written == key.rpartition("::")[2])
            or ("::" not in key and written.rpartition("::")[2] == key)
        ):
            found = pa
    if found is None:
        return None
    values = [(mv.value, list(mv.inModes)) for mv in found.ownedValues if mv.value is not None]
    selected = select_modal(values, in_mode)
    return selected[0][0] if selected else None


def instance_node(assoc: Associations, ci: EObject, cache: dict[int, ComponentNode]) -> ComponentNode:
    """The node of component instance ``ci``, its ancestors' nodes made first (in ``cache``)."""
    node = cache.get(id(ci))
    if node is not None:
        return node
    parent_obj = ci.eContainer()
    resolver = assoc.resolver
    classifier = resolver.classifier(ci.classifier) if ci.classifier else None
    if parent_obj is None or not _model.is_a(parent_obj, "ComponentInstance"):
        node = root_node(assoc, classifier, ci)
    else:
        parent = instance_node(assoc, parent_obj, cache)
        sub = by_name(resolver.subcomponents(parent.impl), ci.subcomponent or ci.name)
        if classifier is None and sub is not None:
            classifier = resolver.subcomponent_classifier(sub)
        node = child_node(assoc, parent, sub, classifier, ci, list(ci.index), ci.name)
    cache[id(ci)] = node
    return node


def find_instance(
    assoc: Associations,
    obj: EObject,
    key: str,
    binding: Binding | None,
    cache: dict[int, ComponentNode] | None = None,
) -> Finding:
    """The value of property ``key`` on instance object ``obj``, computed from the declarative
    model, with its evaluate and reference callbacks; the instances' nodes kept in ``cache``
    (a caller asking of many objects of one instance passes one for them all)."""
    cache = {} if cache is None else cache
    resolver = assoc.resolver
    reference = instance_reference
    if _model.is_a(obj, "ComponentInstance"):
        node = instance_node(assoc, obj, cache)
        evaluate = evaluator(assoc, node, lambda k: component_found(assoc, node, k, binding))
        return evaluate(key), evaluate, reference
    if _model.is_a(obj, "FeatureInstance"):
        path: list[EObject] = []
        current = obj
        while current is not None and _model.is_a(current, "FeatureInstance"):
            path.append(current)
            current = current.eContainer()
        path.reverse()
        if current is None:
            return None, None, reference
        node = instance_node(assoc, current, cache)
        chain: list[EObject] = []
        features = resolver.features(node.classifier)
        for fi in path:
            decl = by_name(features, fi.feature or fi.name)
            if decl is None:
                return None, None, reference
            chain.append(decl)
            fgt = resolver.feature_classifier(decl)
            features = (
                resolver.feature_group_features(fgt)[0]
                if fgt is not None and _model.is_a(fgt, "FeatureGroupType")
                else []
            )
        names = [(fi.name or "", fi.index or 0) for fi in path]
        evaluate = evaluator(assoc, node, lambda k: feature_found(assoc, node, chain, names, k, binding))
        return evaluate(key), evaluate, reference
    if _model.is_a(obj, "ConnectionInstance"):
        owner_obj = obj.eContainer()
        owner = instance_node(assoc, owner_obj, cache) if owner_obj is not None else None
        refs = []
        for ref in obj.connectionReferences:
            if ref.context is None:
                continue
            context = instance_node(assoc, ref.context, cache)
            decl = by_name(resolver.connections(context.impl), ref.connection)
            if decl is not None:
                refs.append((decl, context))
        evaluate = evaluator(assoc, owner, lambda k: connection_found(assoc, refs, owner, k, binding))
        return evaluate(key), evaluate, reference
    if _model.is_a(obj, "ModeInstance", "EndToEndFlowInstance", "FlowSpecificationInstance"):
        node = instance_node(assoc, obj.eContainer(), cache)
        if _model.is_a(obj, "ModeInstance"):
            decl = by_name(resolver.modes(node.classifier), obj.mode or obj.name)
        elif _model.is_a(obj, "EndToEndFlowInstance"):
            decl = by_name(resolver.end_to_end_flows(node.impl), obj.flow or obj.name)
        else:
            decl = by_name(resolver.flow_specifications(node.classifier), obj.name)
        if decl is None:
            return None, None, reference
        evaluate = evaluator(assoc, node, lambda k: element_found(assoc, node, decl, k, binding))
        return evaluate(key), evaluate, reference
    raise ModelError(f"no property lookup for a {obj.eClass.name}")


def instance_reference(anchor: ComponentNode | None, path: str) -> EObject | None:
    """The instance object ``reference (path)`` names from the component of ``anchor``."""
    obj = getattr(anchor, "obj", None)
    if obj is None:
        return None
    return resolve_instance_path(obj, path)


def resolve_instance_path(start: EObject, path: str) -> EObject | None:
    """The instance object a ``reference (a.b[2].c)`` path names, relative to component ``start``."""
    current = start
    for segment in split_path(path):
        wanted = segment.key
        found = None
        for child in _model.instance_children(current):
            if (child.name or "").lower() != wanted:
                continue
            index = getattr(child, "index", None)
            if segment.ranges:
                if segment.matches(
                    list(index) if index is not None and not isinstance(index, int) else index
                ):
                    found = child
                    break
            else:
                found = child
                break
        if found is None:
            return None
        current = found
    return current


def by_name(elements: Iterable[EObject], name: str | None) -> EObject | None:
    wanted = (name or "").lower()
    for element in elements:
        if (element.name or "").lower() == wanted:
            return element
    return None
