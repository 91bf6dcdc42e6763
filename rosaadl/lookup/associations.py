"""The property associations of the declarative model, filed by holder and property key.

:class:`Associations` is the shared state of one property lookup: the resolver, the property
keys, and tables computed once per element:

* the associations an element holds without ``applies to``, by key, last declared first
  (:meth:`~Associations.held`), and those of a classifier through its chains, in precedence order
  (the implementation chain, then the type chain; :meth:`~Associations.of_classifier`);
* the contained associations (``applies to`` paths, split into segments) of an element and of a
  classifier's chains (:meth:`~Associations.contained`,
  :meth:`~Associations.classifier_contained`);
* the values of each association with its ``+=>`` flag and ``in binding`` classifiers;
* the properties used anywhere in a classifier or in the model.
"""

from __future__ import annotations

from collections.abc import Iterable

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.resolution import PathSegment, Resolver, split_path

from .keys import PropertyKeys

__all__ = ["Associations", "Contained", "ModalValues"]

#: ``(path segments, association)`` of one ``applies to`` path
Contained = tuple[tuple[PathSegment, ...], EObject]
#: the values of an association: ``[(expression, in modes)]``
ModalValues = list[tuple[EObject, list[str]]]


class Associations:
    """Associations by holder and key, for one resolver (see the module docstring)."""

    def __init__(self, model: EObject, resolver: Resolver, keys: PropertyKeys) -> None:
        self.model = model
        self.resolver = resolver
        #: the resolver's effective members and refinements (asked on every lookup)
        self.members = resolver.members
        self.keys = keys
        self._held: dict[int, dict[str, list[EObject]]] = {}
        self._contained: dict[int, list[Contained]] = {}
        self._classifier: dict[int, dict[str, list[EObject]]] = {}
        self._classifier_contained: dict[int, list[Contained]] = {}
        self._values: dict[int, tuple[ModalValues, bool, tuple[str, ...]]] = {}
        self._used: dict[int, set[str]] = {}
        self._model_used: set[str] | None = None

    def held(self, holder: EObject) -> dict[str, list[EObject]]:
        """Associations without ``applies to`` held by one element, by key, last declared first."""
        key = id(holder)
        table = self._held.get(key)
        if table is None:
            table = {}
            pa_info = self.keys.pa_info
            for pa in reversed(list(_owned(holder))):
                if pa.appliesTo:
                    continue
                table.setdefault(pa_info(pa)[0], []).append(pa)
            self._held[key] = table
        return table

    def contained(self, holder: EObject) -> list[Contained]:
        """``(path, association)`` for each ``applies to`` path of a holder, last declared first."""
        key = id(holder)
        table = self._contained.get(key)
        if table is None:
            table = []
            for pa in reversed(list(_owned(holder))):
                for path in reversed(list(pa.appliesTo)):
                    segments = tuple(split_path(path))
                    if segments:
                        self.keys.pa_info(pa)
                        table.append((segments, pa))
            self._contained[key] = table
        return table

    def chain_holders(self, classifier: EObject) -> list[EObject]:
        """The classifiers whose associations a component classifier sees: the implementation chain
        then the type chain (nearest first); for other classifiers their extends chain."""
        resolver = self.resolver
        holders = list(resolver.extends_chain(classifier))
        if _model.is_a(classifier, "ComponentImplementation"):
            ctype = resolver.implementation_type(classifier)
            if ctype is not None:
                holders.extend(resolver.extends_chain(ctype))
        return holders

    def of_classifier(self, classifier: EObject) -> dict[str, list[EObject]]:
        """Associations of a classifier through its chains, by key, in precedence order."""
        key = id(classifier)
        table = self._classifier.get(key)
        if table is None:
            table = {}
            for holder in self.chain_holders(classifier):
                for pkey, pas in self.held(holder).items():
                    table.setdefault(pkey, []).extend(pas)
            self._classifier[key] = table
        return table

    def classifier_contained(self, classifier: EObject) -> list[Contained]:
        """The contained associations of a classifier's chains, in precedence order."""
        key = id(classifier)
        table = self._classifier_contained.get(key)
        if table is None:
            table = []
            for holder in self.chain_holders(classifier):
                table.extend(self.contained(holder))
            self._classifier_contained[key] = table
        return table

    def values(self, pa: EObject) -> tuple[ModalValues, bool, tuple[str, ...]]:
        """``([(value, in modes)], appends, in binding classifier names)`` of an association."""
        key = id(pa)
        data = self._values.get(key)
        if data is None:
            values = [(mv.value, list(mv.inModes)) for mv in pa.ownedValues if mv.value is not None]
            data = (values, bool(pa.append), tuple(pa.inBinding))
            self._values[key] = data
        return data

    def used_properties(self, classifier: EObject | None) -> set[str]:
        """Keys of every property associated anywhere inside a classifier and its chains
        (what OSATE calls the used property definitions)."""
        if classifier is None:
            return set()
        key = id(classifier)
        used = self._used.get(key)
        if used is None:
            used = self._keys_inside(self.chain_holders(classifier))
            self._used[key] = used
        return used

    def model_properties(self) -> set[str]:
        """Keys of every property associated anywhere in the model's units (cached)."""
        if self._model_used is None:
            self._model_used = self._keys_inside(self.model.units)
        return self._model_used

    def _keys_inside(self, roots: Iterable[EObject]) -> set[str]:
        used: set[str] = set()
        for root in roots:
            for obj in _model.walk(root):
                if _model.is_a(obj, "PropertyAssociation"):
                    used.add(self.keys.pa_info(obj)[0])
        return used


def _owned(holder: EObject) -> Iterable[EObject]:
    if holder.eClass.findEStructuralFeature("ownedPropertyAssociations") is None:
        return ()
    return holder.ownedPropertyAssociations
