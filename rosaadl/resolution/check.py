"""The reference check: a located diagnostic for every name of a model that does not resolve.

Errors: unknown classifiers (extends, implementation types, features, subcomponents, feature
group inverses, renames, classifier values, ``in binding``), unknown properties, property types
and constants, extends cycles, property constants whose values name each other in a cycle
(:func:`~.constants.constant_cycles`), units declared twice. Warnings: property sets that are not loaded
("values stay untyped", once per unit and set), packages named in ``with`` clauses that are not
loaded, and packages whose classifiers are named without a ``with`` clause (once per unit).

Lenient (``lenient=True``), a classifier or renamed package that is not found is a warning, as
OSATE keeps going past a reference it cannot resolve: Xtext leaves an unresolved proxy (an
error marker in the editor, no stop), and the instantiator instantiates a subcomponent whose
classifier is such a proxy without a classifier. The component type an implementation names is
not forgiven (it is declared in the same package, so no missing file explains it), nor a
classifier of the wrong kind, an unknown property or an extends cycle.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from pyecore.ecore import EObject

from rosaadl.bulk import stored_value
from rosaadl.errors import Diagnostic, NameResolutionError
from rosaadl.model import is_a

from .constants import VALUE_OPERANDS, constant_cycles
from .index import visible_packages
from .names import enum_name, lower, split_name, squeeze, strip_all
from .visibility import package_alias

if TYPE_CHECKING:
    from .resolver import Resolver

__all__ = ["check_references"]


def check_references(resolver: Resolver, *, lenient: bool = False) -> list[Diagnostic]:
    """Located diagnostics for every reference of the resolver's model that does not resolve
    (with ``lenient``, a classifier or package that is not found is a warning).

    Never raises for a missing property set or an extends cycle: both are reported.
    """
    return _ReferenceCheck(resolver, lenient=lenient).run()


class _ReferenceCheck:
    """One run of the check: the diagnostics so far and what was reported once already."""

    def __init__(self, resolver: Resolver, *, lenient: bool = False) -> None:
        self.resolver = resolver
        self.lenient = lenient
        self.diagnostics: list[Diagnostic] = []
        # (id(unit), lower-case name): missing sets and with clauses reported, packages imported
        self.reported_sets: set[tuple[int, str]] = set()
        self.reported_imports: set[tuple[int, str]] = set()

    def error(self, element: EObject, message: str) -> None:
        self.diagnostics.append(Diagnostic("error", message, self.resolver.location(element)))

    def warning(self, element: EObject, message: str) -> None:
        self.diagnostics.append(Diagnostic("warning", message, self.resolver.location(element)))

    def unresolved(self, element: EObject, message: str) -> None:
        """A classifier or package that is not found: an error, a warning when lenient."""
        (self.warning if self.lenient else self.error)(element, message)

    def run(self) -> list[Diagnostic]:
        resolver = self.resolver
        units = resolver.index.by_name
        for unit in units.values():
            for with_name in visible_packages(unit):
                if squeeze(with_name).lower() not in units:
                    marker = (id(unit), with_name.lower())
                    if marker not in self.reported_sets:
                        self.reported_sets.add(marker)
                        self.warning(
                            unit, f"package or property set {with_name} named in a with clause is not loaded"
                        )
        for cycle in constant_cycles(resolver):
            links = "; ".join(
                f"{resolver.qualified_name(link.constant)} => "
                + ", ".join(resolver.qualified_name(named) for named in link.names)
                for link in cycle
            )
            self.error(cycle[0].constant, f"property constants defined in a cycle: {links}")
        for duplicate in resolver.index.duplicates:
            self.error(duplicate, f"{duplicate.name} is declared more than once")
        for unit in units.values():
            if is_a(unit, "AadlPackage"):
                for ren in unit.renamings:
                    if enum_name(ren.kind) in ("package", "all"):
                        if resolver.unit(strip_all(ren.target)) is None:
                            self.unresolved(ren, f"renamed package {strip_all(ren.target)} not found")
                    else:
                        self.classifier_name(ren, ren.target, "renamed classifier")
                for classifier in unit.classifiers:
                    self.classifier(classifier)
                for pa in unit.ownedPropertyAssociations:
                    self.association(pa)
            elif is_a(unit, "PropertySet"):
                self.property_set(unit)
        return self.diagnostics

    # ------------------------------------------------------------------ names

    def property_name(self, element: EObject, name: str | None, what: str = "property") -> None:
        """A property (or property constant, property type) name; a missing set is a warning."""
        if not name:
            return
        resolver = self.resolver
        lookup = resolver.property if what == "property" else resolver.constant
        if lookup(name, element) is not None:
            return
        missing = resolver.missing_property_set(name)
        if missing is not None:
            marker = (id(resolver.unit_of(element)), missing.lower())
            if marker not in self.reported_sets:
                self.reported_sets.add(marker)
                self.warning(element, f"property set {missing} not found; values stay untyped")
            return
        self.error(element, f"{what} {name} not found")

    def classifier_name(self, element: EObject, name: str | None, what: str, *kinds: str) -> None:
        """A classifier name, which must denote one of ``kinds`` (any classifier when none)."""
        if not name:
            return
        found = self.resolver.classifier(name, element)
        if found is None:
            if what in ("subcomponent classifier", "feature classifier") and self.resolver.is_prototype(
                element, name
            ):
                return
            if what == "component type":
                self.error(element, f"{what} {name} not found")
            else:
                self.unresolved(element, f"{what} {name} not found")
        elif kinds and not is_a(found, *kinds):
            self.error(element, f"{what} {name} is a {found.eClass.name}, expected {' or '.join(kinds)}")
        else:
            self.imported(element, name, found)

    def imported(self, element: EObject, name: str, found: EObject) -> None:
        """AADL needs a ``with`` clause for a package whose classifiers are named qualified; the
        resolver accepts the name anyway and the check reports the missing clause (once)."""
        resolver = self.resolver
        qualifier, _ = split_name(name)
        unit = resolver.unit_of(element)
        target = resolver.unit_of(found)
        if qualifier is None or unit is None or target is None or target is unit:
            return
        if package_alias(resolver.index, unit, qualifier) is not None:
            return
        if lower(target.name) in {squeeze(w).lower() for w in visible_packages(unit)}:
            return
        marker = (id(unit), lower(target.name))
        if marker not in self.reported_imports:
            self.reported_imports.add(marker)
            self.warning(
                element, f"package {target.name} is used but not named in a with clause of {unit.name}"
            )

    # ------------------------------------------------------------------ packages

    def classifier(self, classifier: EObject) -> None:
        """A classifier: what it extends, its type, members, and every association inside it."""
        kinds = (classifier.eClass.name,)  # the exact class: a type extends a type
        if is_a(classifier, "ComponentImplementation"):
            kinds = ("ComponentImplementation",)
        if classifier.extended:
            self.classifier_name(classifier, classifier.extended, "extended classifier", *kinds)
        try:
            self.resolver.extends_chain(classifier)
        except NameResolutionError as exc:
            self.error(classifier, exc.message)
        if is_a(classifier, "ComponentImplementation"):
            type_name = classifier.type or (classifier.name or "").partition(".")[0]
            self.classifier_name(classifier, type_name, "component type", "ComponentType")
            for sub in _items(classifier, "subcomponents"):
                self.classifier_name(sub, sub.classifier, "subcomponent classifier", "ComponentClassifier")
                self.associations(sub)
            self.associations(
                *_items(classifier, "connections"),
                *_items(classifier, "flowImplementations"),
                *_items(classifier, "endToEndFlows"),
                *_items(classifier, "callSequences"),
            )
        if is_a(classifier, "ComponentType", "FeatureGroupType"):
            for feature in _items(classifier, "features"):
                kinds_f = ("FeatureGroupType",) if enum_name(feature.category) == "featureGroup" else ()
                self.classifier_name(feature, feature.classifier, "feature classifier", *kinds_f)
                self.associations(feature)
        if is_a(classifier, "ComponentType"):
            self.associations(*_items(classifier, "flowSpecifications"))
        if is_a(classifier, "FeatureGroupType") and classifier.inverseOf:
            self.classifier_name(
                classifier, classifier.inverseOf, "inverse feature group type", "FeatureGroupType"
            )
        if is_a(classifier, "ComponentClassifier"):
            self.associations(*_items(classifier, "modes"), *_items(classifier, "modeTransitions"))
        self.associations(classifier)

    def associations(self, *holders: EObject) -> None:
        """The property associations the elements ``holders`` own, in order."""
        for holder in holders:
            for pa in _items(holder, "ownedPropertyAssociations"):
                self.association(pa)

    def association(self, pa: EObject) -> None:
        self.property_name(pa, pa.property)
        for binding in _items(pa, "inBinding"):
            self.classifier_name(pa, binding, "binding classifier")
        for modal in pa.ownedValues:
            if modal.value is not None:
                self.value(pa, modal.value, classifiers=True)

    def value(self, holder: EObject, value: EObject, *, classifiers: bool) -> None:
        """The qualified constants a value names, and its classifiers when ``classifiers`` (not
        in default values); ``holder`` locates them."""
        resolver = self.resolver
        stack = [value]
        while stack:
            expr = stack.pop()
            kind = expr.eClass.name  # a dispatch on the value classes (leaves of the metamodel)
            if kind == "ClassifierValue":
                if classifiers:
                    self.classifier_name(holder, expr.classifier, "classifier")
            elif (
                kind == "NamedValue"
                and expr.name
                and "::" in expr.name
                and resolver.constant(expr.name, holder) is None
                and resolver.property(expr.name, holder) is None
            ):
                self.property_name(holder, expr.name, "property constant")
            operands = VALUE_OPERANDS.get(kind)
            if operands is not None:
                stack.extend(operands(expr))

    # ------------------------------------------------------------------ property sets

    def property_set(self, unit: EObject) -> None:
        for prop in unit.ownedProperties:
            if prop.ownedType is None:
                self.type_name(prop, prop.type)
            else:
                self.property_type(prop.ownedType)
            if prop.defaultValue is not None:
                self.value(prop, prop.defaultValue, classifiers=False)
        for const in unit.ownedPropertyConstants:
            if const.ownedType is None:
                self.type_name(const, const.type)
            else:
                self.property_type(const.ownedType)
        for ptype in unit.ownedPropertyTypes:
            self.property_type(ptype)

    def type_name(self, holder: EObject, name: str | None) -> None:
        if name and self.resolver.property_type(name, holder) is None:
            if self.resolver.missing_property_set(name) is not None:
                self.property_name(holder, name, "property type")
            else:
                self.error(holder, f"property type {name} not found")

    def property_type(self, ptype: EObject) -> None:
        """The named types inside a type (units of numbers, ranges, list elements, fields)."""
        stack = [ptype]
        while stack:
            current = stack.pop()
            kind = current.eClass.name  # a dispatch on the type classes (leaves of the metamodel)
            if kind in ("AadlInteger", "AadlReal"):
                if current.ownedUnitsType is None:
                    self.type_name(current, current.unitsType)
            elif kind == "RangeType":
                if current.ownedNumberType is None:
                    self.type_name(current, current.numberType)
                else:
                    stack.append(current.ownedNumberType)
            elif kind == "ListType":
                if current.ownedElementType is None:
                    self.type_name(current, current.elementType)
                else:
                    stack.append(current.ownedElementType)
            elif kind == "RecordType":
                for field in current.ownedFields:
                    if field.ownedType is None:
                        self.type_name(field, field.type)
                    else:
                        stack.append(field.ownedType)


def _items(obj: EObject, name: str):
    """The items of the list feature ``name`` of ``obj`` (empty when never set, or when its class
    has none), read without pyecore's getter, which would keep an empty list on every object
    checked (most elements own no property association, no modes, ...)."""
    return stored_value(obj, name, ())
