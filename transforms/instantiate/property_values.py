"""Property values on instances: the resolved value of every property on every instance object.

The properties given to instance objects are those the model associates somewhere, each where
it applies (``applies to``, by the object's metaclass in the OSATE followed) and has a value,
default values included. OSATE caches fewer: only the properties associated in the classifiers
the instance uses (``InstantiateModel.getAllUsedPropertyDefinitions``) and no default value
(``PropertyImpl.evaluate``); here every loaded unit counts and defaults are kept, so that an
instance's value of a property does not depend on which classifiers it happens to use and the
analyses find every value on the instance. The values are found by
:class:`~rosaadl.lookup.PropertyLookup` (AADL's lookup order, ``in binding`` through the
processor bindings); ``reference (...)`` values become references to instance objects.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.lookup import ComponentNode, Found, NoValue, accepts
from rosaadl.resolution import feature_category_word, split_path

from .mirrors import ComponentMirror, ConnectionRecord, FeatureMirror

if TYPE_CHECKING:
    from .instantiator import Instantiator

__all__ = ["property_values"]

#: The ``applies to`` word of each connection kind.
_CONNECTION_WORDS = {
    "portConnection": "port connection",
    "accessConnection": "access connection",
    "featureGroupConnection": "feature group connection",
    "featureConnection": "feature connection",
    "parameterConnection": "parameter connection",
    "modeTransitionConnection": "mode transition connection",
}


def property_values(st: Instantiator) -> None:
    """Give every component, feature, mode, flow and connection instance its property values."""
    _PropertyValues(st).run()


class _PropertyValues:
    """One pass over the instance: the properties to look at, the processor bindings (for
    ``in binding`` values) and the ``applies to`` answers, computed once."""

    def __init__(self, st: Instantiator) -> None:
        self.st = st
        self.lookup = st.lookup
        self.keys = sorted(set(st.lookup.model_properties()))
        self.mirror = {id(ci.obj): ci for ci in st.components}
        self.binding_key = st.lookup.property_key("Deployment_Properties::Actual_Processor_Binding")
        self.accept_cache: dict[tuple[str, str, str], bool] = {}

    def accepts(self, key: str, kind: str, word: str) -> bool:
        """Whether property ``key`` applies to an object of ``kind`` described by ``word``, with
        the metaclass hierarchy of the OSATE the instantiation follows (:func:`accepts`)."""
        marker = (key, kind, word)
        cached = self.accept_cache.get(marker)
        if cached is None:
            cached = accepts(self.lookup.definition(key), kind, word, osate_2_0=self.st.legacy)
            self.accept_cache[marker] = cached
        return cached

    def reference(self, anchor: Any, path: str) -> EObject | None:
        """The instance object named by a ``reference (path)`` value seen from ``anchor``."""
        start = self.mirror.get(id(getattr(anchor, "obj", None))) if anchor is not None else None
        return _resolve_reference(start or self.st.root, path)

    def binding(self, node: ComponentNode | None) -> list[EObject] | None:
        """The classifiers of the processors a component is bound to (``in binding``)."""
        if node is None:
            return None
        if node.binding is not None:
            return node.binding
        lookup = self.lookup
        binding_key = self.binding_key
        node.binding = []
        found = lookup.with_default(lookup.component_found(node, binding_key, None), binding_key, node)
        result: list[EObject] = []
        values = []
        if found is not None:
            try:
                values = lookup.build_value(found, binding_key, reference=self.reference)
            except NoValue:
                values = []
        if values:
            for expr, _modes in values:
                for target in _referenced(expr):
                    ci = self.mirror.get(id(target))
                    if ci is not None and ci.node.classifier is not None:
                        result.append(ci.node.classifier)
        node.binding = result
        return result

    def associate(
        self, obj: EObject, key: str, found: Found, evaluate: Callable[[str], Found | None]
    ) -> None:
        """Give ``obj`` its association of property ``key`` (the value ``found``)."""
        association = self.lookup.association(obj, key, found, evaluate=evaluate, reference=self.reference)
        if association is not None:
            self.st.factory.extend(obj, "ownedPropertyAssociations", [association])

    def run(self) -> None:
        st = self.st
        lookup = self.lookup
        resolver = st.resolver
        binding = self.binding
        for ci in st.components:
            node = ci.node

            def evaluate(k: str, node: ComponentNode = node) -> Found | None:
                return lookup.with_default(lookup.component_found(node, k, binding), k, node)

            for key in self.keys:
                if not self.accepts(key, "component", ci.category):
                    continue
                found = lookup.with_default(lookup.component_found(node, key, binding), key, node)
                if found is not None:
                    self.associate(ci.obj, key, found, evaluate)
            self.features(ci)
            for mi, decl in (
                (ci.modes.get((m.name or "").lower()), m) for m in resolver.modes(node.classifier)
            ):
                if mi is None:
                    continue
                self.element(ci, mi, decl, "mode", "mode")
            for spec in resolver.flow_specifications(node.classifier):
                fsi = ci.flow_specs.get((spec.name or "").lower())
                if fsi is not None:
                    self.element(ci, fsi, spec, "flow", "flow specification")
            for flow_obj in ci.obj.endToEndFlows:
                decl = next(
                    (f for f in resolver.end_to_end_flows(node.impl) if (f.name or "") == flow_obj.flow), None
                )
                if decl is not None:
                    self.element(ci, flow_obj, decl, "end to end flow", "end to end flow")
        for container in st.components:
            for record in container.connections:
                self.connection(container, record)

    def features(self, ci: ComponentMirror) -> None:
        """The feature instances of a component (feature group members included)."""
        lookup = self.lookup
        binding = self.binding
        node = ci.node
        stack: list[tuple[FeatureMirror, list[EObject], list[tuple[str, int]]]] = [
            (fi, [fi.decl], [(fi.name, fi.index)]) for fi in ci.features
        ]
        while stack:
            fi, chain, names = stack.pop()
            # by the feature's metaclass: OSATE 2.0's made a bus access a bus (an inherited Period
            # reaches it, the bus classifier's Transmission_Time too), today's a feature only
            word = feature_category_word(fi.category)
            for key in self.keys:
                if not self.accepts(key, "feature", word):
                    continue
                found = lookup.with_default(lookup.feature_found(node, chain, names, key, binding), key, node)
                if found is not None:

                    def evaluate(k: str, chain=chain, names=names) -> Found | None:
                        return lookup.with_default(
                            lookup.feature_found(node, chain, names, k, binding), k, node
                        )

                    self.associate(fi.obj, key, found, evaluate)
            for child in fi.children:
                stack.append((child, [*chain, child.decl], [*names, (child.name, child.index)]))

    def element(self, ci: ComponentMirror, obj: EObject, decl: EObject, kind: str, word: str) -> None:
        """A mode, flow specification or end-to-end flow instance of a component."""
        lookup = self.lookup
        binding = self.binding
        node = ci.node
        for key in self.keys:
            if not self.accepts(key, kind, word):
                continue
            found = lookup.with_default(lookup.element_found(node, decl, key, binding), key, node)
            if found is not None:

                def evaluate(k: str) -> Found | None:
                    return lookup.with_default(lookup.element_found(node, decl, k, binding), k, node)

                self.associate(obj, key, found, evaluate)

    def connection(self, container: ComponentMirror, record: ConnectionRecord) -> None:
        """A connection instance (its declarations, hop by hop)."""
        lookup = self.lookup
        binding = self.binding
        word = _CONNECTION_WORDS.get(record.kind, "connection")
        refs = [(decl, context.node) for decl, context in zip(record.decls, record.contexts, strict=False)]
        owner = container.node
        for key in self.keys:
            if not self.accepts(key, "connection", word):
                continue
            found = lookup.with_default(lookup.connection_found(refs, owner, key, binding), key, owner)
            if found is not None:

                def evaluate(k: str) -> Found | None:
                    return lookup.with_default(lookup.connection_found(refs, owner, k, binding), k, owner)

                self.associate(record.obj, key, found, evaluate)


def _resolve_reference(start: ComponentMirror, path: str) -> EObject | None:
    """The instance object at ``path`` below component ``start`` (a component, feature, mode or
    connection instance), or None."""
    current: Any = start
    for segment in split_path(path):
        key = segment.key
        found: Any = None
        if isinstance(current, ComponentMirror):
            for child in current.by_sub.get(key, []):
                if segment.matches(list(child.index)):
                    found = child
                    break
            if found is None:
                for fi in current.features:
                    if fi.key == key and segment.matches(fi.index):
                        found = fi
                        break
            if found is None:
                mode = current.modes.get(key)
                if mode is not None:
                    found = mode
            if found is None:
                for record in current.connections:
                    for ref in record.obj.connectionReferences:
                        if (ref.connection or "").lower() == key and ref.context is current.obj:
                            found = record.obj
                            break
                    if found is not None:
                        break
        elif isinstance(current, FeatureMirror):
            found = current.child(key)
        if found is None:
            return None
        current = found
    if isinstance(current, (ComponentMirror, FeatureMirror)):
        return current.obj
    return current


def _referenced(expr: EObject) -> list[EObject]:
    """The instance objects a value refers to (in a list too)."""
    if _model.is_a(expr, "InstanceReferenceValue"):
        return [expr.referencedInstanceObject] if expr.referencedInstanceObject is not None else []
    if _model.is_a(expr, "ListValue"):
        result = []
        for item in expr.ownedItems:
            result.extend(_referenced(item))
        return result
    return []
