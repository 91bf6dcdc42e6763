""":class:`PropertyLookup`: property values of declarative elements and instance objects.

It holds the state of one lookup (the resolver, the property keys, the association tables, the
value builder and its object factory, the diagnostics) and answers :meth:`~PropertyLookup.value`
and :meth:`~PropertyLookup.python_value` for any element. Instantiation drives the steps itself
(component nodes, the lookup order, building values) through the methods that name them.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.errors import Diagnostic, ModelError
from rosaadl.properties import python_value as _python_value
from rosaadl.resolution import Resolver

from . import nodes, order
from .associations import Associations, Contained
from .binding import Binding, fixed_binding
from .declarative import find_declarative
from .factory import Factory
from .instances import find_instance, own_instance_value
from .keys import PropertyKeys
from .nodes import ComponentNode
from .order import Evaluate, Found
from .values import NoValue, Reference, ValueBuilder

__all__ = ["PropertyLookup"]


class PropertyLookup:
    """Property values of declarative elements and instance objects of one ``AadlModel``."""

    def __init__(self, model: EObject, resolver: Resolver | None = None) -> None:
        self.model = model
        self.resolver = resolver if resolver is not None else Resolver(model)
        #: warnings about values (references that do not resolve), located
        self.diagnostics: list[Diagnostic] = []
        #: makes every value (and, for instantiation, every instance object)
        self.factory = Factory()
        self.keys = PropertyKeys(self.resolver)
        self.associations = Associations(model, self.resolver, self.keys)
        self.values = ValueBuilder(self.resolver, self.keys, self.factory, self.diagnostics)

    # ------------------------------------------------------------------ public questions

    def value(
        self,
        element: EObject,
        prop: str | EObject,
        *,
        in_mode: str | None = None,
        in_binding: str | EObject | Iterable[str | EObject] | None = None,
    ) -> EObject | None:
        """The value (a ``PropertyExpression``) of ``prop`` for a declarative element or an instance
        object, following AADL's lookup rules; None when the property has no value there.

        ``in_mode`` selects the value of a modal association; ``in_binding`` names the processor
        classifier(s) the element is bound to, which makes ``in binding`` associations apply.
        Instance objects that carry resolved values (as made by instantiation) answer from them.
        """
        if not isinstance(element, EObject):
            raise ModelError(f"no property lookup for {element!r}: expected a model element")
        instance = _model.is_a(element, "InstanceObject")
        key = self.keys.key(prop, None if instance else element)
        if instance:
            own = own_instance_value(element, key, in_mode)
            if own is not None:
                return own
        binding = fixed_binding(self.resolver, in_binding, element)
        if instance:
            found, evaluate, reference = find_instance(self.associations, element, key, binding)
        else:
            found, evaluate, reference = find_declarative(self.associations, element, key, binding)
        if found is None:
            return None
        try:
            values = self.values.build(
                found, key, evaluate=evaluate, reference=reference, in_mode=in_mode, keep_modes=False
            )
        except NoValue:
            return None
        return values[0][0] if values else None

    def python_value(
        self,
        element: EObject,
        prop: str | EObject,
        default: Any = None,
        *,
        in_mode: str | None = None,
        in_binding: str | EObject | Iterable[str | EObject] | None = None,
    ) -> Any:
        """:meth:`value` decoded by :func:`rosaadl.properties.python_value` (numbers with units)."""
        expr = self.value(element, prop, in_mode=in_mode, in_binding=in_binding)
        if expr is None:
            return default
        return _python_value(expr)

    # ------------------------------------------------------------------ property keys

    def pa_info(self, pa: EObject) -> tuple[str, str, EObject | None]:
        """``(key, display name, Property or None)`` of an association (cached)."""
        return self.keys.pa_info(pa)

    def property_key(self, name: str | EObject, context: EObject | None = None) -> str:
        """The lookup key of a property given by name (``Period``, ``SEI::MIPSBudget``) or element."""
        return self.keys.key(name, context)

    def definition(self, key: str) -> EObject | None:
        return self.keys.definition(key)

    def display_name(self, key: str) -> str:
        return self.keys.display_name(key)

    # ------------------------------------------------------------------ associations by holder

    def holder_associations(self, holder: EObject) -> dict[str, list[EObject]]:
        """Associations without ``applies to`` held by one element, by key, last declared first."""
        return self.associations.held(holder)

    def contained_associations(self, holder: EObject) -> list[Contained]:
        """``(path, association)`` for each ``applies to`` path of a holder, last declared first."""
        return self.associations.contained(holder)

    def classifier_associations(self, classifier: EObject) -> dict[str, list[EObject]]:
        """Associations of a classifier through its chains, by key, in precedence order."""
        return self.associations.of_classifier(classifier)

    def classifier_contained(self, classifier: EObject) -> list[Contained]:
        """The contained associations of a classifier's chains, in precedence order."""
        return self.associations.classifier_contained(classifier)

    def used_properties(self, classifier: EObject | None) -> set[str]:
        """Keys of every property associated anywhere inside a classifier and its chains."""
        return self.associations.used_properties(classifier)

    def model_properties(self) -> set[str]:
        """Keys of every property associated anywhere in the model's units (cached)."""
        return self.associations.model_properties()

    # ------------------------------------------------------------------ nodes and contained PAs

    def root_node(self, classifier: EObject | None, obj: EObject | None = None) -> ComponentNode:
        return nodes.root_node(self.associations, classifier, obj)

    def child_node(
        self,
        parent: ComponentNode,
        sub: EObject | None,
        classifier: EObject | None,
        obj: EObject | None = None,
        index: Iterable[int] = (),
        name: str | None = None,
    ) -> ComponentNode:
        return nodes.child_node(self.associations, parent, sub, classifier, obj, index, name)

    def contained_for(
        self, node: ComponentNode, names: list[tuple[str, int]]
    ) -> dict[str, tuple[EObject, Any]]:
        """Contained associations reaching an element of ``node`` named by the path ``names``."""
        return nodes.contained_for(self.associations, node, names)

    # ------------------------------------------------------------------ lookup order

    def component_found(self, node: ComponentNode, key: str, binding: Binding | None = None) -> Found | None:
        """The value of property ``key`` for a component (without the default value)."""
        return order.component_found(self.associations, node, key, binding)

    def feature_found(
        self,
        node: ComponentNode,
        chain: list[EObject],
        names: list[tuple[str, int]],
        key: str,
        binding: Binding | None = None,
    ) -> Found | None:
        """The value for a feature of component ``node`` (see :func:`.order.feature_found`)."""
        return order.feature_found(self.associations, node, chain, names, key, binding)

    def connection_found(
        self,
        references: list[tuple[EObject, ComponentNode]],
        owner: ComponentNode | None,
        key: str,
        binding: Binding | None = None,
    ) -> Found | None:
        """The value for a semantic connection (see :func:`.order.connection_found`)."""
        return order.connection_found(self.associations, references, owner, key, binding)

    def element_found(
        self, node: ComponentNode, element: EObject, key: str, binding: Binding | None = None
    ) -> Found | None:
        """The value for a mode or flow of ``node`` (see :func:`.order.element_found`)."""
        return order.element_found(self.associations, node, element, key, binding)

    def default_found(self, key: str, anchor: Any = None) -> Found | None:
        return order.default_found(self.associations, key, anchor)

    def with_default(self, found: Found | None, key: str, anchor: Any = None) -> Found | None:
        """``found`` completed by the default value (when there is no value, or only appends)."""
        return order.with_default(self.associations, found, key, anchor)

    # ------------------------------------------------------------------ values

    def build_value(
        self,
        found: Found,
        key: str,
        *,
        evaluate: Evaluate | None = None,
        reference: Reference | None = None,
        in_mode: str | None = None,
        keep_modes: bool = True,
    ) -> list[tuple[EObject, list[str]]]:
        """New value elements for a found value (see :meth:`.values.ValueBuilder.build`)."""
        return self.values.build(
            found, key, evaluate=evaluate, reference=reference, in_mode=in_mode, keep_modes=keep_modes
        )

    def association(
        self,
        obj: EObject,
        key: str,
        found: Found,
        *,
        evaluate: Evaluate | None = None,
        reference: Reference | None = None,
    ) -> EObject | None:
        """A new ``PropertyAssociation`` holding a found value, or None when the value names a
        property that has no value there (see :meth:`.values.ValueBuilder.association`)."""
        return self.values.association(obj, key, found, evaluate=evaluate, reference=reference)
