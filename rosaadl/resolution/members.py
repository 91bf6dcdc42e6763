"""Effective members of classifiers: what a classifier has through its ``extends`` chain.

AADL classifiers inherit the members of the classifiers they extend; a member declared
``refined to`` replaces the inherited member of the same name, in its place. :class:`Members`
computes, once per classifier:

* the ``extends`` chain (a cycle is a located error) and the type of an implementation;
* features of a type or feature group type (a feature group type that is only the ``inverse of``
  another takes that type's features, inverted), subcomponents, connections, flow
  implementations and end-to-end flows of an implementation chain, flow specifications of a type,
  modes and mode transitions of a type and its implementations;
* the refinement chain of each member, and what it says through its refinements: the classifier
  of a subcomponent or feature, any attribute, the ends of a connection;
* whether a name is a prototype of the classifier that holds an element.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from pyecore.ecore import EObject

from rosaadl.errors import NameResolutionError
from rosaadl.model import is_a

from .index import feature_value
from .names import lower

if TYPE_CHECKING:
    from .resolver import Resolver

__all__ = ["Members"]

# the containment features whose members a classifier chain merges by name
_CHAIN_FEATURES = (
    "features",
    "subcomponents",
    "connections",
    "flowImplementations",
    "endToEndFlows",
    "flowSpecifications",
)
# the members a component classifier takes from its type's chain and then its own
_MODAL_FEATURES = ("modes", "modeTransitions")
# not yet in a cache
_UNKNOWN = object()


class Members:
    """Extends chains, effective members and refinements, cached per classifier and member.

    ``resolver`` gives the classifier a name denotes, qualified names and locations.
    """

    def __init__(self, resolver: Resolver) -> None:
        self.resolver = resolver
        self._chains: dict[int, list[EObject]] = {}
        # by (what, id(element)): member lists, or a one-item list for a single answer
        self._effective: dict[tuple[str, int], list] = {}
        # by id(member): the member, then the inherited members it refines (nearest first)
        self._refines: dict[int, list[EObject]] = {}
        # by id(subcomponent or feature): its classifier
        self._classifier_of: dict[int, EObject | None] = {}

    # ------------------------------------------------------------------ chains

    def extends_chain(self, classifier: EObject) -> list[EObject]:
        """``classifier`` then the classifiers it extends, nearest first.

        A cycle raises a located :class:`NameResolutionError`; an ``extends`` name that does not
        resolve ends the chain (the reference check reports it).
        """
        key = id(classifier)
        cached = self._chains.get(key)
        if cached is not None:
            return cached
        resolver = self.resolver
        chain = [classifier]
        seen = {id(classifier)}
        current = classifier
        while current.extended:
            parent = resolver.classifier(current.extended, current)
            if parent is None:
                break
            if id(parent) in seen:
                names = " -> ".join(resolver.qualified_name(c) for c in [*chain, parent])
                raise NameResolutionError(f"extends cycle: {names}", resolver.location(classifier))
            chain.append(parent)
            seen.add(id(parent))
            current = parent
        self._chains[key] = chain
        return chain

    def implementation_type(self, impl: EObject) -> EObject | None:
        """The component type of an implementation (``T`` of ``T.impl``)."""
        key = ("type", id(impl))
        cached = self._effective.get(key)
        if cached is not None:
            return cached[0] if cached else None
        type_name = impl.type or (impl.name or "").partition(".")[0]
        found = self.resolver.classifier(type_name, impl)
        if found is not None and not is_a(found, "ComponentType"):
            found = None
        self._effective[key] = [found] if found is not None else []
        return found

    def component_type(self, classifier: EObject | None) -> EObject | None:
        """The type of a component classifier (itself for a type)."""
        if classifier is None:
            return None
        if is_a(classifier, "ComponentImplementation"):
            return self.implementation_type(classifier)
        if is_a(classifier, "ComponentType"):
            return classifier
        return None

    # ------------------------------------------------------------------ effective members

    def _merge(self, classifiers: list[EObject], feature: str) -> list[EObject]:
        """Members of ``feature`` along ``classifiers`` (farthest ancestor first), refinements
        replacing the inherited member of the same name in place."""
        result: list[EObject] = []
        position: dict[str, int] = {}
        for classifier in classifiers:
            for member in getattr(classifier, feature):
                key = lower(member.name)
                if key and key in position and feature_value(member, "refined") is not False:
                    index = position[key]
                    previous = result[index]
                    self._refines[id(member)] = [member, *self._refines.get(id(previous), [previous])]
                    result[index] = member
                    continue
                if key:
                    position[key] = len(result)
                self._refines.setdefault(id(member), [member])
                result.append(member)
        return result

    def _chain_members(self, classifier: EObject, feature: str) -> list[EObject]:
        """The members of ``feature`` through the extends chain of ``classifier``."""
        key = (feature, id(classifier))
        cached = self._effective.get(key)
        if cached is not None:
            return cached
        chain = [c for c in self.extends_chain(classifier) if c.eClass.findEStructuralFeature(feature)]
        result = self._merge(list(reversed(chain)), feature)
        self._effective[key] = result
        return result

    def _modal_members(self, classifier: EObject | None, feature: str) -> list[EObject]:
        """Modes or mode transitions: the type's chain, then the implementation's."""
        if classifier is None or not is_a(classifier, "ComponentClassifier"):
            return []
        key = (feature, id(classifier))
        cached = self._effective.get(key)
        if cached is not None:
            return cached
        chains: list[EObject] = []
        if is_a(classifier, "ComponentImplementation"):
            ctype = self.implementation_type(classifier)
            if ctype is not None:
                chains.extend(reversed(self.extends_chain(ctype)))
        chains.extend(reversed(self.extends_chain(classifier)))
        result = self._merge(chains, feature)
        self._effective[key] = result
        return result

    def features(self, classifier: EObject | None) -> list[EObject]:
        """All features of a component type, implementation (its type's) or feature group type."""
        if classifier is None:
            return []
        if is_a(classifier, "ComponentImplementation"):
            classifier = self.implementation_type(classifier)
            if classifier is None:
                return []
        if not is_a(classifier, "ComponentType", "FeatureGroupType"):
            return []
        return self._chain_members(classifier, "features")

    def feature_group_features(self, fgt: EObject) -> tuple[list[EObject], bool]:
        """Features of a feature group type and whether their directions are inverted: a type with
        no features of its own that is the ``inverse of`` another takes that type's features."""
        key = ("fgfeatures", id(fgt))
        cached = self._effective.get(key)
        if cached is not None:
            return cached[0], bool(cached[1])
        inverted = False
        base = fgt
        if not list(fgt.features) and fgt.inverseOf and not fgt.extended:
            target = self.resolver.classifier(fgt.inverseOf, fgt)
            if target is not None and is_a(target, "FeatureGroupType"):
                base = target
                inverted = True
        result = self.features(base)
        self._effective[key] = [result, inverted]
        return result, inverted

    def implementation_members(self, impl: EObject | None, feature: str) -> list[EObject]:
        """The ``subcomponents``, ``connections``, ``flowImplementations`` or ``endToEndFlows``
        (``feature``) of an implementation chain."""
        if impl is None or not is_a(impl, "ComponentImplementation"):
            return []
        return self._chain_members(impl, feature)

    def flow_specifications(self, classifier: EObject | None) -> list[EObject]:
        """The flow specifications of a component classifier's type chain."""
        ctype = self.component_type(classifier)
        if ctype is None:
            return []
        return self._chain_members(ctype, "flowSpecifications")

    def modes(self, classifier: EObject | None) -> list[EObject]:
        """Modes of a component classifier: its type's and its implementation chain's."""
        return self._modal_members(classifier, "modes")

    def mode_transitions(self, classifier: EObject | None) -> list[EObject]:
        """Mode transitions of a component classifier, as :meth:`modes`."""
        return self._modal_members(classifier, "modeTransitions")

    # ------------------------------------------------------------------ refinements

    def refinement_chain(self, member: EObject) -> list[EObject]:
        """``member`` then the inherited members it refines (``refined to``), nearest first."""
        chain = self._refines.get(id(member))
        if chain is None:
            owner = member.eContainer()
            if owner is not None and is_a(owner, "Classifier"):
                # compute the members of the owner so that its refinements are known
                feature = member.eContainmentFeature().name
                if feature in _CHAIN_FEATURES:
                    self._chain_members(owner, feature)
                elif feature in _MODAL_FEATURES:
                    self._modal_members(owner, feature)
            chain = self._refines.get(id(member), [member])
        return chain

    def member_classifier(self, member: EObject) -> EObject | None:
        """The classifier of a subcomponent or feature, through ``refined to`` (None when it has
        none)."""
        key = id(member)
        found = self._classifier_of.get(key, _UNKNOWN)
        if found is _UNKNOWN:
            name, holder = self._refined_classifier_name(member)
            found = self.resolver.classifier(name, holder) if name else None
            self._classifier_of[key] = found
        return found

    subcomponent_classifier = member_classifier
    feature_classifier = member_classifier

    def _refined_classifier_name(self, member: EObject) -> tuple[str | None, EObject | None]:
        """The first classifier name along the refinement chain, and the member that names it."""
        for element in self.refinement_chain(member):
            if element.classifier:
                return element.classifier, element
        return None, None

    def subcomponent_classifier_name(self, sub: EObject) -> str | None:
        """The classifier name of a subcomponent as written, through ``refined to``."""
        return self._refined_classifier_name(sub)[0]

    def effective_attribute(self, member: EObject, attribute: str) -> object:
        """The first set value of ``attribute`` along the refinement chain of ``member``."""
        for element in self.refinement_chain(member):
            value = getattr(element, attribute, None)
            if value:
                return value
        return getattr(member, attribute, None)

    def connection_ends(self, connection: EObject) -> tuple[str, str]:
        """Source and destination paths of a connection, from the connection it refines if needed."""
        for element in self.refinement_chain(connection):
            if element.source or element.destination:
                return element.source or "", element.destination or ""
        return connection.source or "", connection.destination or ""

    # ------------------------------------------------------------------ prototypes

    def is_prototype(self, element: EObject, name: str) -> bool:
        """Is ``name`` (unqualified) a prototype of the classifier holding ``element``, of its
        type or of a classifier they extend?"""
        if "::" in name or "." in name:
            return False
        current = element.eContainer()
        while current is not None and not is_a(current, "Classifier"):
            current = current.eContainer()
        if current is None:
            return False
        classifiers = [current]
        if is_a(current, "ComponentImplementation"):
            ctype = self.implementation_type(current)
            if ctype is not None:
                classifiers.append(ctype)
        wanted = name.lower()
        for classifier in classifiers:
            try:
                chain = self.extends_chain(classifier)
            except NameResolutionError:
                chain = [classifier]
            for c in chain:
                for proto in c.prototypes:
                    if lower(proto.name) == wanted:
                        return True
        return False
