"""The :class:`Resolver`: every name question about one ``AadlModel``, answered once.

It brings together the unit index (:mod:`.index`), the visibility rules (:mod:`.visibility`),
the types of property values (:mod:`.property_types`), the effective members of classifiers
(:mod:`.members`) and the reference check (:mod:`.check`), and caches the answers per name and
context, so that instantiating a large model never resolves the same name twice.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.errors import Diagnostic, Location, NameResolutionError

from . import property_types
from .check import check_references
from .index import UnitIndex
from .members import Members
from .names import squeeze
from .visibility import find_classifier, find_set_member, missing_property_set

__all__ = ["Resolver"]


class Resolver:
    """Name resolution and effective members for one ``AadlModel`` (see :mod:`rosaadl.resolution`).

    The resolver indexes the model when created; if units are added or renamed afterwards, make a
    new one. All answers are cached per element, so repeated questions cost a dictionary look-up.
    """

    def __init__(self, model: EObject) -> None:
        self.model = model
        #: the units of the model by name, their members, and where elements stand
        self.index = UnitIndex(model)
        #: extends chains, effective members and refinements
        self.members = Members(self)
        self._classifiers: dict[tuple[int, str], EObject | None] = {}
        self._set_members: dict[tuple[str, int, str], EObject | None] = {}
        self._pa_property: dict[int, EObject | None] = {}
        self._resolved_types: dict[int, EObject | None] = {}

    # ------------------------------------------------------------------ units and locations

    def unit(self, name: str) -> EObject | None:
        """The package or property set called ``name`` (case-insensitive)."""
        return self.index.unit(name)

    def units(self) -> list[EObject]:
        return list(self.index.by_name.values())

    def unit_of(self, element: EObject | None) -> EObject | None:
        """The package or property set that contains ``element`` (itself for a unit)."""
        return self.index.unit_of(element)

    def qualified_name(self, element: EObject) -> str:
        """``Pkg::T.impl`` for a classifier, ``Set::Name`` for a property/type/constant."""
        return self.index.qualified_name(element)

    def location(self, element: EObject | None, path: str | None = None) -> Location:
        """file:line:column of an element (from its unit's ``sourceFile``) and a model path."""
        return self.index.location(element, path)

    # ------------------------------------------------------------------ classifiers

    def classifier(self, name: str | None, context: EObject | None = None) -> EObject | None:
        """The classifier ``name`` refers to from ``context`` (an element of a package), or None."""
        if not name:
            return None
        unit = self.index.unit_of(context) if context is not None else None
        key = (id(unit), "".join(name.split()).lower())
        if key in self._classifiers:
            return self._classifiers[key]
        found = find_classifier(self.index, name, unit)
        self._classifiers[key] = found
        return found

    def require_classifier(self, name: str, context: EObject | None, what: str = "classifier") -> EObject:
        """:meth:`classifier`, or a located :class:`NameResolutionError` when it is unknown."""
        found = self.classifier(name, context)
        if found is None:
            raise NameResolutionError(f"{what} {name!r} not found", self.location(context))
        return found

    # ------------------------------------------------------------------ property sets

    def _set_member(self, kind: str, name: str | None, context: EObject | None) -> EObject | None:
        if not name:
            return None
        unit = self.index.unit_of(context) if context is not None else None
        key = (kind, id(unit), "".join(name.split()).lower())
        if key in self._set_members:
            return self._set_members[key]
        found = find_set_member(self.index, kind, name, unit)
        self._set_members[key] = found
        return found

    def property(self, name: str | None, context: EObject | None = None) -> EObject | None:
        """The ``Property`` definition ``name`` denotes from ``context`` (None when unknown)."""
        return self._set_member("property", name, context)

    def property_type(self, name: str | None, context: EObject | None = None) -> EObject | None:
        """The ``PropertyType`` ``name`` denotes from ``context`` (None when unknown)."""
        return self._set_member("type", name, context)

    def constant(self, name: str | None, context: EObject | None = None) -> EObject | None:
        """The ``PropertyConstant`` ``name`` denotes from ``context`` (None when unknown)."""
        return self._set_member("constant", name, context)

    def missing_property_set(self, name: str | None) -> str | None:
        """The qualifier of ``name`` when it names a property set that is not loaded, else None."""
        return missing_property_set(self.index, name)

    def association_property(self, association: EObject) -> EObject | None:
        """The ``Property`` a ``PropertyAssociation`` sets (cached per association)."""
        key = id(association)
        if key in self._pa_property:
            return self._pa_property[key]
        found = self.property(association.property, association)
        self._pa_property[key] = found
        return found

    def property_key(self, name: str, context: EObject | None = None) -> tuple[str, str]:
        """A canonical ``(lower key, display name)`` for a property name as written.

        Resolved properties give ``Set::Name`` with the declared spelling; unresolved ones keep the
        name as written (a missing property set leaves its values untyped, not lost).
        """
        prop = self.property(name, context)
        display = self.qualified_name(prop) if prop is not None else squeeze(name)
        return display.lower(), display

    # ------------------------------------------------------------------ property types

    def resolved_type(self, holder: EObject | None) -> EObject | None:
        """The ``PropertyType`` of a property, constant, record field or list element, following
        named types (``AADL_Project::Time``); None when unknown."""
        if holder is None:
            return None
        key = id(holder)
        if key in self._resolved_types:
            return self._resolved_types[key]
        self._resolved_types[key] = None  # guards against cyclic type names
        found = property_types.declared_type(self, holder)
        self._resolved_types[key] = found
        return found

    def element_type(self, ptype: EObject | None) -> EObject | None:
        """The element type of a list type (recursively), else the type itself."""
        return property_types.element_type(self, ptype)

    def element_type_once(self, ptype: EObject | None) -> EObject | None:
        """The element type of a list type (one level); any other type unchanged."""
        return property_types.element_type_once(self, ptype)

    def record_field_type(self, ptype: EObject | None, name: str | None) -> EObject | None:
        """The type of field ``name`` of a record type (lists looked through)."""
        return property_types.record_field_type(self, ptype, name)

    def units_type(self, ptype: EObject | None) -> EObject | None:
        """The ``UnitsType`` of a number, range or units type (None when unit-less)."""
        return property_types.units_type(self, ptype)

    def enumeration_literal(self, ptype: EObject | None, name: str) -> str | None:
        """The declared spelling of enumeration literal ``name`` of ``ptype`` (lists looked through)."""
        return property_types.enumeration_literal(self, ptype, name)

    def unit_literal(self, ptype: EObject | None, name: str) -> str | None:
        """The declared spelling of unit ``name`` in the units of ``ptype``."""
        return property_types.unit_literal(self, ptype, name)

    # ------------------------------------------------------------------ effective members

    def extends_chain(self, classifier: EObject) -> list[EObject]:
        """``classifier`` then the classifiers it extends, nearest first (a cycle is a located
        :class:`NameResolutionError`; an ``extends`` that does not resolve ends the chain)."""
        return self.members.extends_chain(classifier)

    def implementation_type(self, impl: EObject) -> EObject | None:
        """The component type of an implementation (``T`` of ``T.impl``)."""
        return self.members.implementation_type(impl)

    def component_type(self, classifier: EObject | None) -> EObject | None:
        """The type of a component classifier (itself for a type)."""
        return self.members.component_type(classifier)

    def features(self, classifier: EObject | None) -> list[EObject]:
        """All features of a component type, implementation (its type's) or feature group type."""
        return self.members.features(classifier)

    def feature_group_features(self, fgt: EObject) -> tuple[list[EObject], bool]:
        """Features of a feature group type and whether their directions are inverted."""
        return self.members.feature_group_features(fgt)

    def subcomponents(self, impl: EObject | None) -> list[EObject]:
        return self.members.implementation_members(impl, "subcomponents")

    def connections(self, impl: EObject | None) -> list[EObject]:
        return self.members.implementation_members(impl, "connections")

    def flow_implementations(self, impl: EObject | None) -> list[EObject]:
        return self.members.implementation_members(impl, "flowImplementations")

    def end_to_end_flows(self, impl: EObject | None) -> list[EObject]:
        return self.members.implementation_members(impl, "endToEndFlows")

    def flow_specifications(self, classifier: EObject | None) -> list[EObject]:
        return self.members.flow_specifications(classifier)

    def modes(self, classifier: EObject | None) -> list[EObject]:
        """Modes of a component classifier: its type's and its implementation chain's."""
        return self.members.modes(classifier)

    def mode_transitions(self, classifier: EObject | None) -> list[EObject]:
        return self.members.mode_transitions(classifier)

    def refinement_chain(self, member: EObject) -> list[EObject]:
        """``member`` then the inherited members it refines (``refined to``), nearest first."""
        return self.members.refinement_chain(member)

    def subcomponent_classifier(self, sub: EObject) -> EObject | None:
        """The classifier of a subcomponent, through ``refined to`` (None when it has none)."""
        return self.members.member_classifier(sub)

    def subcomponent_classifier_name(self, sub: EObject) -> str | None:
        return self.members.subcomponent_classifier_name(sub)

    def feature_classifier(self, feature: EObject) -> EObject | None:
        """The classifier of a feature (data type, feature group type, ...), through refinements."""
        return self.members.member_classifier(feature)

    def effective_attribute(self, member: EObject, attribute: str) -> object:
        """The first set value of ``attribute`` along the refinement chain of ``member``."""
        return self.members.effective_attribute(member, attribute)

    def connection_ends(self, connection: EObject) -> tuple[str, str]:
        """Source and destination paths of a connection, from the connection it refines if needed."""
        return self.members.connection_ends(connection)

    def is_prototype(self, element: EObject, name: str) -> bool:
        """Is ``name`` a prototype of the classifier holding ``element`` (or of its chains)?"""
        return self.members.is_prototype(element, name)

    # ------------------------------------------------------------------ check

    def check(self, *, lenient: bool = False) -> list[Diagnostic]:
        """Located diagnostics for every reference that does not resolve (see :mod:`.check`;
        ``lenient``: a classifier or package that is not found is a warning).

        Never raises for a missing property set.
        """
        return check_references(self, lenient=lenient)
