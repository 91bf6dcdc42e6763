"""Feature instances: every feature of a component, feature groups expanded, feature arrays.

What a classifier's features are (declaration, effective category and direction, feature group
type, array size) is planned once per classifier (:func:`feature_plan`), in OSATE's order. A
feature group becomes a feature instance holding one per member of its type, directions swapped
under ``inverse of`` (and an inverse feature group type); feature arrays are expanded where AADL
allows them (components of the categories in :data:`ARRAY_FEATURE_OWNERS`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from pyecore.ecore import EObject

from rosaadl import model as _model

from .arrays import array_sizes
from .mirrors import ACCESS, ComponentMirror, FeatureMirror, component_path, enum_literal, enum_name, literal
from .order import FEATURE_ORDER, in_osate_order

if TYPE_CHECKING:
    from .instantiator import Instantiator

__all__ = ["ARRAY_FEATURE_OWNERS", "feature_plan", "instantiate_features"]

#: The categories whose features may be arrays.
ARRAY_FEATURE_OWNERS = frozenset({"abstract", "device", "memory", "processor", "system", "thread"})

_Plan = list[tuple[EObject, str, str, EObject | None, int]]


def feature_plan(st: Instantiator, classifier: EObject) -> _Plan:
    """(declaration, category, direction, feature group type, array size) per feature."""
    key = id(classifier)
    plan = st.feature_plans.get(key)
    if plan is not None:
        return plan
    resolver = st.resolver
    ctype = resolver.component_type(classifier) if not _model.is_a(classifier, "FeatureGroupType") else None
    owner_category = literal(ctype.category) if ctype is not None else ""
    plan = []
    for feature in resolver.features(classifier):
        category = enum_name(resolver.effective_attribute(feature, "category") or feature.category)
        direction = _direction(st, feature, category)
        fgt = None
        if category == "featureGroup":
            fgt = _feature_group_type(st, feature)
        size = 0
        dims = list(resolver.effective_attribute(feature, "arrayDimensions") or [])
        if dims and owner_category in ARRAY_FEATURE_OWNERS:
            size = array_sizes(st, dims[:1], feature, resolver.qualified_name(feature))[0] or 0
        plan.append((feature, category, direction, fgt, size))
    if ctype is not None:
        plan = in_osate_order(
            resolver, ctype, plan, lambda entry: entry[0], lambda entry: entry[1], FEATURE_ORDER
        )
    st.feature_plans[key] = plan
    return plan


def _feature_group_type(st: Instantiator, feature: EObject) -> EObject | None:
    fgt = st.resolver.feature_classifier(feature)
    return fgt if fgt is not None and _model.is_a(fgt, "FeatureGroupType") else None


def _direction(st: Instantiator, feature: EObject, category: str) -> str:
    if category in ACCESS:
        return "in out"
    for element in st.resolver.refinement_chain(feature):
        if element.eIsSet("direction"):
            return literal(element.direction)
    if category in ("featureGroup", "abstractFeature"):
        return "in out"
    return literal(feature.direction)


def instantiate_features(st: Instantiator, ci: ComponentMirror) -> None:
    """The feature instances of a component's classifier."""
    classifier = ci.node.classifier
    if classifier is None:
        return
    for feature, category, direction, fgt, size in feature_plan(st, classifier):
        for index in range(1, size + 1) if size else (0,):
            fi = _new_feature(st, ci, None, feature, category, direction, fgt, index, False, [])
            ci.features.append(fi)
            ci.feature_by_name.setdefault(fi.key, fi)
    st.factory.extend(ci.obj, "featureInstances", [fi.obj for fi in ci.features])


def _new_feature(
    st: Instantiator,
    ci: ComponentMirror,
    parent: FeatureMirror | None,
    feature: EObject,
    category: str,
    direction: str,
    fgt: EObject | None,
    index: int,
    inverse: bool,
    seen: list[EObject],
) -> FeatureMirror:
    resolver = st.resolver
    if inverse and direction in ("in", "out"):
        direction = "out" if direction == "in" else "in"
    factory = st.factory
    fclassifier = fgt if fgt is not None else resolver.feature_classifier(feature)
    obj = factory.new(
        "FeatureInstance",
        name=feature.name,
        feature=feature.name,
        index=index or None,
        category=enum_literal("FeatureCategory", category),
        direction=enum_literal("DirectionType", direction),
        access=resolver.effective_attribute(feature, "access") if category in ACCESS else None,
        classifier=resolver.qualified_name(fclassifier) if fclassifier is not None else None,
    )
    if fclassifier is None:
        name = resolver.effective_attribute(feature, "classifier")
        if name and category != "featureGroup" and not resolver.is_prototype(feature, name):
            st.warn(f"classifier {name} of feature {feature.name} not found", component_path(ci), feature)
    fi = FeatureMirror(
        obj,
        feature,
        feature.name or "",
        (feature.name or "").lower(),
        index,
        category,
        direction,
        ci,
        parent,
    )
    fi.fgt = fgt
    if category == "featureGroup":
        name = resolver.effective_attribute(feature, "classifier")
        if fgt is None and name and not resolver.is_prototype(feature, name):
            message = f"feature group type {name} of feature group {feature.name} not found"
            if st.strict:
                st.error(message, component_path(ci), feature)
            else:
                st.warn(message, component_path(ci), feature)
        elif fgt is not None:
            if any(f is feature for f in seen):
                st.error(f"feature group {feature.name} contains itself", component_path(ci), feature)
                return fi
            members, inverted = resolver.feature_group_features(fgt)
            inner_inverse = inverse ^ bool(resolver.effective_attribute(feature, "inverse")) ^ inverted
            for member in members:
                mcat = enum_name(member.category)
                mdir = _direction(st, member, mcat)
                mfgt = _feature_group_type(st, member) if mcat == "featureGroup" else None
                child = _new_feature(st, ci, fi, member, mcat, mdir, mfgt, 0, inner_inverse, [*seen, feature])
                fi.children.append(child)
            factory.extend(obj, "featureInstances", [child.obj for child in fi.children])
    return fi
