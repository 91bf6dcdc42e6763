"""AADL name resolution over the declarative model.

The declarative model (``aadl.ecore``) keeps cross references as the names written in the text:
``Feature.classifier = "ros_data::Image.rgb"``, ``Classifier.extended = "ros::node"``,
``PropertyAssociation.property = "Period"``.  A :class:`Resolver` indexes the units of an
``AadlModel`` once (case-insensitively, as AADL names are) and turns those names into model
elements following AADL's visibility rules:

* classifiers: the context's own package, fully qualified names (``P::T``, ``P::T.impl``),
  package aliases and classifier aliases from ``renames`` declarations, and ``renames P::all``;
* properties, property types and constants: ``Set::Name`` qualified, or unqualified through the
  predeclared property sets (``Period`` is ``Timing_Properties::Period``), then through the
  property sets the context names in its ``with`` clauses;
* enumeration and unit literals of a property type.

It also computes the *effective members* of classifiers (features of a type with its ``extends``
chain, ``refined to`` replacing the inherited member in place; subcomponents, connections, flows,
modes and end-to-end flows of an implementation chain) and caches every answer, so that
instantiating large models does not resolve the same name twice.  :meth:`Resolver.check` reports
every reference that does not resolve as a located :class:`~rosaadl.errors.Diagnostic`.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

from pyecore.ecore import EObject

from rosaadl.errors import Diagnostic, Location, NameResolutionError

__all__ = [
    "PREDECLARED_PROPERTY_SETS",
    "Resolver",
    "PathSegment",
    "split_path",
    "split_name",
    "feature_category_word",
]

#: The property sets of SAE AS5506C whose properties may be named without qualification.
PREDECLARED_PROPERTY_SETS: tuple[str, ...] = (
    "Deployment_Properties",
    "Thread_Properties",
    "Timing_Properties",
    "Communication_Properties",
    "Memory_Properties",
    "Programming_Properties",
    "Modeling_Properties",
    "AADL_Project",
)

_INDEX_RE = re.compile(r"\[\s*(\d+)\s*(?:\.\.\s*(\d+)\s*)?\]")


@dataclass(frozen=True)
class PathSegment:
    """One element of a dotted AADL path: ``name`` and the array ``ranges`` written after it.

    ``ranges`` holds one ``(low, high)`` pair per ``[...]`` (``[2]`` is ``(2, 2)``); an empty
    tuple means "every element".
    """

    name: str
    ranges: tuple[tuple[int, int], ...] = ()

    @property
    def key(self) -> str:
        return self.name.lower()

    def matches(self, index: Iterable[int] | int | None) -> bool:
        """Does an element with 1-based ``index`` (list, int or None/0) fall in the ranges?"""
        if not self.ranges:
            return True
        values = list(index) if isinstance(index, Iterable) else ([index] if index else [])
        if len(values) < len(self.ranges):
            return False
        return all(low <= value <= high for (low, high), value in zip(self.ranges, values, strict=False))

    def __str__(self) -> str:
        text = self.name
        for low, high in self.ranges:
            text += f"[{low}]" if low == high else f"[{low} .. {high}]"
        return text


def split_path(text: str) -> list[PathSegment]:
    """``"a.b[2].c"`` → segments ``a``, ``b[2]``, ``c`` (annex elements are kept as one name)."""
    segments: list[PathSegment] = []
    for raw in _split_dots(text or ""):
        raw = raw.strip()
        if not raw:
            continue
        bracket = raw.find("[")
        if bracket < 0:
            segments.append(PathSegment(raw))
            continue
        ranges = tuple(
            (int(m.group(1)), int(m.group(2) or m.group(1))) for m in _INDEX_RE.finditer(raw[bracket:])
        )
        segments.append(PathSegment(raw[:bracket].strip(), ranges))
    return segments


def _split_dots(text: str) -> Iterator[str]:
    depth = 0
    start = 0
    for i, ch in enumerate(text):
        if ch in "[{":
            depth += 1
        elif ch in "]}":
            depth -= 1
        elif ch == "." and depth == 0:
            # "1 .. 3" inside brackets is protected by depth; a bare ".." cannot occur here
            yield text[start:i]
            start = i + 1
    yield text[start:]


def split_name(name: str) -> tuple[str | None, str]:
    """``"a::b::T.impl"`` → ``("a::b", "T.impl")``; ``"T"`` → ``(None, "T")`` (spaces removed)."""
    text = "".join((name or "").split())
    if "::" in text:
        qualifier, _, local = text.rpartition("::")
        return qualifier, local
    return None, text


# metaclass words of "applies to" lists, by feature category name of aadl.ecore
_FEATURE_WORDS = {
    "dataPort": "data port",
    "eventPort": "event port",
    "eventDataPort": "event data port",
    "parameter": "parameter",
    "busAccess": "bus access",
    "dataAccess": "data access",
    "subprogramAccess": "subprogram access",
    "subprogramGroupAccess": "subprogram group access",
    "featureGroup": "feature group",
    "abstractFeature": "abstract feature",
    "virtualBusAccess": "virtual bus access",
}


def feature_category_word(category: object) -> str:
    """The AADL words of a ``FeatureCategory`` value (``data port``, ``feature group``, ...)."""
    name = getattr(category, "name", category)
    return _FEATURE_WORDS.get(str(name), str(name))


def _is(obj: object, *names: str) -> bool:
    """Is ``obj`` an instance of one of the metamodel classes ``names``?"""
    if not isinstance(obj, EObject):
        return False
    return _class_is(obj.eClass, names)


@functools.lru_cache(maxsize=4096)
def _class_is(eclass: object, names: tuple[str, ...]) -> bool:
    """The answer of :func:`_is` for one metaclass (immutable metadata, so cached)."""
    return eclass.name in names or any(sup.name in names for sup in eclass.eAllSuperTypes())


def _lower(name: str | None) -> str:
    return (name or "").lower()


class Resolver:
    """Name resolution and effective members for one ``AadlModel`` (see the module docstring).

    The resolver indexes the model when created; if units are added or renamed afterwards, make a
    new one.  All answers are cached per element, so repeated questions cost a dictionary look-up.
    """

    def __init__(self, model: EObject) -> None:
        self.model = model
        self._units: dict[str, EObject] = {}
        self._duplicate_units: list[EObject] = []
        self._classifiers: dict[int, dict[str, EObject]] = {}
        self._set_members: dict[int, dict[str, dict[str, EObject]]] = {}
        for unit in getattr(model, "units", ()):
            key = _lower(unit.name)
            if not key:
                continue
            if key in self._units:
                self._duplicate_units.append(unit)
                continue
            self._units[key] = unit
            if _is(unit, "AadlPackage"):
                table: dict[str, EObject] = {}
                for classifier in unit.classifiers:
                    table.setdefault(_lower(classifier.name), classifier)
                self._classifiers[id(unit)] = table
            elif _is(unit, "PropertySet"):
                members: dict[str, dict[str, EObject]] = {"property": {}, "type": {}, "constant": {}}
                for prop in unit.ownedProperties:
                    members["property"].setdefault(_lower(prop.name), prop)
                for ptype in unit.ownedPropertyTypes:
                    members["type"].setdefault(_lower(ptype.name), ptype)
                for const in unit.ownedPropertyConstants:
                    members["constant"].setdefault(_lower(const.name), const)
                self._set_members[id(unit)] = members
        self._unit_of: dict[int, EObject | None] = {}
        self._classifier_cache: dict[tuple[int, str], EObject | None] = {}
        self._member_cache: dict[tuple[str, int, str], EObject | None] = {}
        self._chain_cache: dict[int, list[EObject]] = {}
        self._effective: dict[tuple[str, int], list[EObject]] = {}
        self._refines: dict[int, list[EObject]] = {}
        self._pa_property: dict[int, EObject | None] = {}
        self._resolved_types: dict[int, EObject | None] = {}

    # ------------------------------------------------------------------ units and locations

    def unit(self, name: str) -> EObject | None:
        """The package or property set called ``name`` (case-insensitive)."""
        return self._units.get(_lower("".join((name or "").split())))

    def units(self) -> list[EObject]:
        return list(self._units.values())

    def unit_of(self, element: EObject | None) -> EObject | None:
        """The package or property set that contains ``element`` (itself for a unit)."""
        if element is None:
            return None
        key = id(element)
        if key in self._unit_of:
            return self._unit_of[key]
        current = element
        found = None
        while current is not None:
            if _is(current, "ModelUnit"):
                found = current
                break
            current = current.eContainer()
        self._unit_of[key] = found
        return found

    def qualified_name(self, element: EObject) -> str:
        """``Pkg::T.impl`` for a classifier, ``Set::Name`` for a property/type/constant."""
        unit = self.unit_of(element)
        name = getattr(element, "name", None) or ""
        if unit is None or unit is element:
            return name
        owner = element.eContainer()
        if owner is unit:
            return f"{unit.name}::{name}"
        return f"{self.qualified_name(owner)}.{name}" if owner is not None else name

    def location(self, element: EObject | None, path: str | None = None) -> Location:
        """file:line:column of an element (from its unit's ``sourceFile``) and a model path."""
        if element is None:
            return Location(path=path)
        unit = self.unit_of(element)
        file = getattr(unit, "sourceFile", None) if unit is not None else None
        line = _feature(element, "line")
        column = _feature(element, "column")
        return Location(
            file=file or None,
            line=line or None,
            column=column or None,
            path=path if path is not None else self._element_path(element),
        )

    def _element_path(self, element: EObject) -> str:
        parts = []
        current = element
        while current is not None and not _is(current, "ModelUnit", "AadlModel"):
            name = getattr(current, "name", None)
            if name:
                parts.append(name)
            current = current.eContainer()
        unit = current if current is not None and _is(current, "ModelUnit") else None
        text = ".".join(reversed(parts))
        if unit is not None:
            return f"{unit.name}::{text}" if text else str(unit.name)
        return text

    # ------------------------------------------------------------------ classifiers

    def _visible_packages(self, unit: EObject) -> list[str]:
        withs = list(getattr(unit, "withs", ()) or ())
        withs.extend(getattr(unit, "privateWiths", ()) or ())
        return withs

    def _package_alias(self, unit: EObject, qualifier: str) -> EObject | None:
        wanted = qualifier.lower()
        for ren in getattr(unit, "renamings", ()) or ():
            if _enum_name(ren.kind) == "package" and _lower(ren.name) == wanted:
                return self.unit(_strip_all(ren.target))
        return None

    def classifier(self, name: str | None, context: EObject | None = None) -> EObject | None:
        """The classifier ``name`` refers to from ``context`` (an element of a package), or None."""
        if not name:
            return None
        unit = self.unit_of(context) if context is not None else None
        key = (id(unit), "".join(name.split()).lower())
        if key in self._classifier_cache:
            return self._classifier_cache[key]
        found = self._find_classifier(name, unit, set())
        self._classifier_cache[key] = found
        return found

    def _find_classifier(self, name: str, unit: EObject | None, seen: set[tuple[int, str]]) -> EObject | None:
        qualifier, local = split_name(name)
        marker = (id(unit), f"{qualifier}::{local}".lower())
        if marker in seen:  # renames that loop
            return None
        seen.add(marker)
        wanted = local.lower()
        if qualifier is not None:
            target = None
            if unit is not None:
                target = self._package_alias(unit, qualifier)
            if target is None:
                target = self.unit(qualifier)
            if target is None or not _is(target, "AadlPackage"):
                return None
            found = self._classifiers.get(id(target), {}).get(wanted)
            if found is not None and target is not unit and _enum_name(found.visibility) == "private":
                return None
            return found
        if unit is None or not _is(unit, "AadlPackage"):
            return None
        found = self._classifiers.get(id(unit), {}).get(wanted)
        if found is not None:
            return found
        # classifier aliases: "X renames thread P::T;" and "renames thread P::T;"
        type_part, dot, impl_part = wanted.partition(".")
        for ren in getattr(unit, "renamings", ()) or ():
            kind = _enum_name(ren.kind)
            if kind in ("classifier", "featureGroupType"):
                target = ren.target or ""
                alias = _lower(ren.name) or split_name(target)[1].lower()
                if alias == wanted:
                    return self._find_classifier(target, unit, seen)
                if dot and alias == type_part:
                    # an implementation of an aliased type: T.impl where T renames P::T
                    return self._find_classifier(f"{target}.{impl_part}", unit, seen)
        for ren in getattr(unit, "renamings", ()) or ():
            if _enum_name(ren.kind) == "all":
                target_unit = self.unit(_strip_all(ren.target))
                if target_unit is not None and _is(target_unit, "AadlPackage"):
                    found = self._classifiers.get(id(target_unit), {}).get(wanted)
                    if found is not None and _enum_name(found.visibility) != "private":
                        return found
        return None

    def require_classifier(self, name: str, context: EObject | None, what: str = "classifier") -> EObject:
        found = self.classifier(name, context)
        if found is None:
            raise NameResolutionError(f"{what} {name!r} not found", self.location(context))
        return found

    # ------------------------------------------------------------------ property sets

    def _set_member(self, kind: str, name: str | None, context: EObject | None) -> EObject | None:
        if not name:
            return None
        unit = self.unit_of(context) if context is not None else None
        key = (kind, id(unit), "".join(name.split()).lower())
        if key in self._member_cache:
            return self._member_cache[key]
        qualifier, local = split_name(name)
        wanted = local.lower()
        found = None
        if qualifier is not None:
            target = self.unit(qualifier)
            if target is not None and id(target) in self._set_members:
                found = self._set_members[id(target)][kind].get(wanted)
        else:
            candidates: list[EObject] = []
            if unit is not None and id(unit) in self._set_members:
                candidates.append(unit)
            for set_name in PREDECLARED_PROPERTY_SETS:
                target = self.unit(set_name)
                if target is not None and id(target) in self._set_members:
                    candidates.append(target)
            if unit is not None:
                for with_name in self._visible_packages(unit):
                    target = self.unit(with_name)
                    if target is not None and id(target) in self._set_members:
                        candidates.append(target)
            for target in candidates:
                found = self._set_members[id(target)][kind].get(wanted)
                if found is not None:
                    break
        self._member_cache[key] = found
        return found

    def property(self, name: str | None, context: EObject | None = None) -> EObject | None:
        """The ``Property`` definition ``name`` denotes from ``context`` (None when unknown)."""
        return self._set_member("property", name, context)

    def property_type(self, name: str | None, context: EObject | None = None) -> EObject | None:
        return self._set_member("type", name, context)

    def constant(self, name: str | None, context: EObject | None = None) -> EObject | None:
        return self._set_member("constant", name, context)

    def missing_property_set(self, name: str | None) -> str | None:
        """The qualifier of ``name`` when it names a property set that is not loaded, else None."""
        qualifier, _ = split_name(name or "")
        if qualifier is None:
            return None
        target = self.unit(qualifier)
        if target is None:
            return qualifier
        return None

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
        display = self.qualified_name(prop) if prop is not None else "".join((name or "").split())
        return display.lower(), display

    def resolved_type(self, holder: EObject | None) -> EObject | None:
        """The ``PropertyType`` of a property, constant, record field or list element, following
        named types (``AADL_Project::Time``); None when unknown."""
        if holder is None:
            return None
        key = id(holder)
        if key in self._resolved_types:
            return self._resolved_types[key]
        self._resolved_types[key] = None  # guards against cyclic type names
        if _is(holder, "PropertyType"):
            found = holder
        else:
            owned = _feature(holder, "ownedType")
            found = owned if owned is not None else self.property_type(_feature(holder, "type"), holder)
        self._resolved_types[key] = found
        return found

    def element_type(self, ptype: EObject | None) -> EObject | None:
        """The element type of a list type (recursively), else the type itself."""
        seen = 0
        while ptype is not None and _is(ptype, "ListType") and seen < 16:
            inner = ptype.ownedElementType
            ptype = inner if inner is not None else self.property_type(ptype.elementType, ptype)
            seen += 1
        return ptype

    def element_type_once(self, ptype: EObject | None) -> EObject | None:
        """The element type of a list type (one level); any other type unchanged."""
        if ptype is not None and _is(ptype, "ListType"):
            inner = ptype.ownedElementType
            return inner if inner is not None else self.property_type(ptype.elementType, ptype)
        return ptype

    def record_field_type(self, ptype: EObject | None, name: str | None) -> EObject | None:
        """The type of field ``name`` of a record type (lists looked through)."""
        ptype = self.element_type(ptype)
        if ptype is None or not _is(ptype, "RecordType"):
            return None
        wanted = _lower(name)
        for record_field in ptype.ownedFields:
            if _lower(record_field.name) == wanted:
                return self.resolved_type(record_field)
        return None

    def units_type(self, ptype: EObject | None) -> EObject | None:
        """The ``UnitsType`` of a number, range or units type (None when unit-less)."""
        depth = 0
        while ptype is not None and depth < 16:
            depth += 1
            if _is(ptype, "UnitsType"):
                return ptype
            if _is(ptype, "RangeType"):
                inner = ptype.ownedNumberType
                ptype = inner if inner is not None else self.property_type(ptype.numberType, ptype)
                continue
            if _is(ptype, "NumberType"):
                if ptype.ownedUnitsType is not None:
                    return ptype.ownedUnitsType
                if ptype.unitsType:
                    ptype = self.property_type(ptype.unitsType, ptype)
                    continue
                return None
            if _is(ptype, "ListType"):
                ptype = self.element_type(ptype)
                continue
            return None
        return None

    def enumeration_literal(self, ptype: EObject | None, name: str) -> str | None:
        """The declared spelling of enumeration literal ``name`` of ``ptype`` (lists looked through)."""
        ptype = self.element_type(ptype)
        if ptype is None or not _is(ptype, "EnumerationType"):
            return None
        wanted = _lower(name)
        for literal in ptype.ownedLiterals:
            if _lower(literal.name) == wanted:
                return literal.name
        return None

    def unit_literal(self, ptype: EObject | None, name: str) -> str | None:
        """The declared spelling of unit ``name`` in the units of ``ptype``."""
        units = self.units_type(ptype)
        if units is None:
            return None
        wanted = _lower(name)
        for literal in units.ownedLiterals:
            if _lower(literal.name) == wanted:
                return literal.name
        return None

    # ------------------------------------------------------------------ extends chains

    def extends_chain(self, classifier: EObject) -> list[EObject]:
        """``classifier`` then the classifiers it extends, nearest first.

        A cycle raises a located :class:`NameResolutionError`; an ``extends`` name that does not
        resolve ends the chain (:meth:`check` reports it).
        """
        key = id(classifier)
        cached = self._chain_cache.get(key)
        if cached is not None:
            return cached
        chain = [classifier]
        seen = {id(classifier)}
        current = classifier
        while current.extended:
            parent = self.classifier(current.extended, current)
            if parent is None:
                break
            if id(parent) in seen:
                names = " -> ".join(self.qualified_name(c) for c in [*chain, parent])
                raise NameResolutionError(f"extends cycle: {names}", self.location(classifier))
            chain.append(parent)
            seen.add(id(parent))
            current = parent
        self._chain_cache[key] = chain
        return chain

    def implementation_type(self, impl: EObject) -> EObject | None:
        """The component type of an implementation (``T`` of ``T.impl``)."""
        key = ("type", id(impl))
        cached = self._effective.get(key)
        if cached is not None:
            return cached[0] if cached else None
        type_name = impl.type or (impl.name or "").partition(".")[0]
        found = self.classifier(type_name, impl)
        if found is not None and not _is(found, "ComponentType"):
            found = None
        self._effective[key] = [found] if found is not None else []
        return found

    def component_type(self, classifier: EObject | None) -> EObject | None:
        """The type of a component classifier (itself for a type)."""
        if classifier is None:
            return None
        if _is(classifier, "ComponentImplementation"):
            return self.implementation_type(classifier)
        if _is(classifier, "ComponentType"):
            return classifier
        return None

    # ------------------------------------------------------------------ effective members

    def _merge(self, kind: str, classifiers: list[EObject], feature: str) -> list[EObject]:
        """Members of ``feature`` along ``classifiers`` (farthest ancestor first), refinements
        replacing the inherited member of the same name in place."""
        result: list[EObject] = []
        position: dict[str, int] = {}
        for classifier in classifiers:
            for member in getattr(classifier, feature):
                key = _lower(member.name)
                if key and key in position and _feature(member, "refined") is not False:
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

    def _effective_members(self, kind: str, classifier: EObject, feature: str) -> list[EObject]:
        key = (kind, id(classifier))
        cached = self._effective.get(key)
        if cached is not None:
            return cached
        chain = [c for c in self.extends_chain(classifier) if c.eClass.findEStructuralFeature(feature)]
        result = self._merge(kind, list(reversed(chain)), feature)
        self._effective[key] = result
        return result

    def features(self, classifier: EObject | None) -> list[EObject]:
        """All features of a component type, implementation (its type's) or feature group type."""
        if classifier is None:
            return []
        if _is(classifier, "ComponentImplementation"):
            classifier = self.implementation_type(classifier)
            if classifier is None:
                return []
        if not _is(classifier, "ComponentType", "FeatureGroupType"):
            return []
        return self._effective_members("features", classifier, "features")

    def feature_group_features(self, fgt: EObject) -> tuple[list[EObject], bool]:
        """Features of a feature group type and whether their directions are inverted: a type with
        no features of its own that is the ``inverse of`` another takes that type's features."""
        key = ("fgfeatures", id(fgt))
        cached = self._effective.get(key)
        if cached is not None:
            return cached[0], bool(cached[1])
        own = list(fgt.features)
        inverted = False
        base = fgt
        if not own and fgt.inverseOf and not fgt.extended:
            target = self.classifier(fgt.inverseOf, fgt)
            if target is not None and _is(target, "FeatureGroupType"):
                base = target
                inverted = True
        result = self.features(base)
        self._effective[key] = [result, inverted]  # type: ignore[list-item]
        return result, inverted

    def subcomponents(self, impl: EObject | None) -> list[EObject]:
        if impl is None or not _is(impl, "ComponentImplementation"):
            return []
        return self._effective_members("subcomponents", impl, "subcomponents")

    def connections(self, impl: EObject | None) -> list[EObject]:
        if impl is None or not _is(impl, "ComponentImplementation"):
            return []
        return self._effective_members("connections", impl, "connections")

    def flow_implementations(self, impl: EObject | None) -> list[EObject]:
        if impl is None or not _is(impl, "ComponentImplementation"):
            return []
        return self._effective_members("flowImplementations", impl, "flowImplementations")

    def end_to_end_flows(self, impl: EObject | None) -> list[EObject]:
        if impl is None or not _is(impl, "ComponentImplementation"):
            return []
        return self._effective_members("endToEndFlows", impl, "endToEndFlows")

    def flow_specifications(self, classifier: EObject | None) -> list[EObject]:
        ctype = self.component_type(classifier)
        if ctype is None:
            return []
        return self._effective_members("flowSpecifications", ctype, "flowSpecifications")

    def _modal(self, classifier: EObject | None, feature: str) -> list[EObject]:
        if classifier is None or not _is(classifier, "ComponentClassifier"):
            return []
        key = (feature, id(classifier))
        cached = self._effective.get(key)
        if cached is not None:
            return cached
        chains: list[EObject] = []
        if _is(classifier, "ComponentImplementation"):
            ctype = self.implementation_type(classifier)
            if ctype is not None:
                chains.extend(reversed(self.extends_chain(ctype)))
        chains.extend(reversed(self.extends_chain(classifier)))
        result = self._merge(feature, chains, feature)
        self._effective[key] = result
        return result

    def modes(self, classifier: EObject | None) -> list[EObject]:
        """Modes of a component classifier: its type's and its implementation chain's."""
        return self._modal(classifier, "modes")

    def mode_transitions(self, classifier: EObject | None) -> list[EObject]:
        return self._modal(classifier, "modeTransitions")

    def refinement_chain(self, member: EObject) -> list[EObject]:
        """``member`` then the inherited members it refines (``refined to``), nearest first.

        Known once the effective members of the classifier that holds it have been asked for.
        """
        chain = self._refines.get(id(member))
        if chain is None:
            owner = member.eContainer()
            if owner is not None and _is(owner, "Classifier"):
                feature = member.eContainmentFeature().name
                chain_owner = owner
                # compute the members of the owner so that its refinements are known
                if feature in (
                    "features",
                    "subcomponents",
                    "connections",
                    "flowImplementations",
                    "endToEndFlows",
                    "flowSpecifications",
                ):
                    self._effective_members(feature, chain_owner, feature)
                elif feature in ("modes", "modeTransitions"):
                    self._modal(chain_owner, feature)
            chain = self._refines.get(id(member), [member])
        return chain

    def subcomponent_classifier(self, sub: EObject) -> EObject | None:
        """The classifier of a subcomponent, through ``refined to`` (None when it has none)."""
        key = ("subclassifier", id(sub))
        cached = self._effective.get(key)
        if cached is not None:
            return cached[0] if cached else None
        found = None
        for member in self.refinement_chain(sub):
            if member.classifier:
                found = self.classifier(member.classifier, member)
                break
        self._effective[key] = [found] if found is not None else []
        return found

    def subcomponent_classifier_name(self, sub: EObject) -> str | None:
        for member in self.refinement_chain(sub):
            if member.classifier:
                return member.classifier
        return None

    def feature_classifier(self, feature: EObject) -> EObject | None:
        """The classifier of a feature (data type, feature group type, ...), through refinements."""
        key = ("featureclassifier", id(feature))
        cached = self._effective.get(key)
        if cached is not None:
            return cached[0] if cached else None
        found = None
        for member in self.refinement_chain(feature):
            if member.classifier:
                found = self.classifier(member.classifier, member)
                break
        self._effective[key] = [found] if found is not None else []
        return found

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

    # ------------------------------------------------------------------ check

    def check(self) -> list[Diagnostic]:
        """Located diagnostics for every reference that does not resolve.

        Errors: unknown classifiers (extends, implementation types, features, subcomponents,
        feature group inverses, renames, classifier values), unknown properties, extends cycles.
        Warnings: property sets that are not loaded ("values stay untyped"), and packages named
        in ``with`` clauses that are not loaded.  Never raises for a missing property set.
        """
        diagnostics: list[Diagnostic] = []
        seen_sets: set[tuple[int, str]] = set()
        seen_imports: set[tuple[int, str]] = set()

        def error(element: EObject, message: str) -> None:
            diagnostics.append(Diagnostic("error", message, self.location(element)))

        def warning(element: EObject, message: str) -> None:
            diagnostics.append(Diagnostic("warning", message, self.location(element)))

        def property_name(element: EObject, name: str | None, what: str = "property") -> None:
            if not name:
                return
            lookup = self.property if what == "property" else self.constant
            if lookup(name, element) is not None:
                return
            missing = self.missing_property_set(name)
            if missing is not None:
                unit = self.unit_of(element)
                marker = (id(unit), missing.lower())
                if marker not in seen_sets:
                    seen_sets.add(marker)
                    warning(element, f"property set {missing} not found; values stay untyped")
                return
            error(element, f"{what} {name} not found")

        def classifier_name(element: EObject, name: str | None, what: str, *kinds: str) -> None:
            if not name:
                return
            found = self.classifier(name, element)
            if found is None:
                if what in ("subcomponent classifier", "feature classifier") and self._is_prototype(
                    element, name
                ):
                    return
                error(element, f"{what} {name} not found")
            elif kinds and not _is(found, *kinds):
                error(element, f"{what} {name} is a {found.eClass.name}, expected {' or '.join(kinds)}")
            else:
                self._check_imported(element, name, found, warning, seen_imports)

        known_with_targets = {key for key in self._units}
        for unit in self._units.values():
            for with_name in self._visible_packages(unit):
                if "".join(with_name.split()).lower() not in known_with_targets:
                    marker = (id(unit), with_name.lower())
                    if marker not in seen_sets:
                        seen_sets.add(marker)
                        warning(
                            unit, f"package or property set {with_name} named in a with clause is not loaded"
                        )
        for duplicate in self._duplicate_units:
            error(duplicate, f"{duplicate.name} is declared more than once")

        for unit in self._units.values():
            if _is(unit, "AadlPackage"):
                for ren in unit.renamings:
                    kind = _enum_name(ren.kind)
                    if kind in ("package", "all"):
                        if self.unit(_strip_all(ren.target)) is None:
                            error(ren, f"renamed package {_strip_all(ren.target)} not found")
                    else:
                        classifier_name(ren, ren.target, "renamed classifier")
                for classifier in unit.classifiers:
                    self._check_classifier(classifier, error, classifier_name, property_name)
                for pa in unit.ownedPropertyAssociations:
                    self._check_association(pa, property_name, classifier_name)
            elif _is(unit, "PropertySet"):
                self._check_property_set(unit, error, property_name, classifier_name)
        return diagnostics

    def _check_imported(self, element: EObject, name: str, found: EObject, warning, seen: set) -> None:
        """AADL needs a ``with`` clause for a package whose classifiers are named qualified; the
        resolver accepts the name anyway and the check reports the missing clause (once)."""
        qualifier, _ = split_name(name)
        unit = self.unit_of(element)
        target = self.unit_of(found)
        if qualifier is None or unit is None or target is None or target is unit:
            return
        if self._package_alias(unit, qualifier) is not None:
            return
        imported = {"".join(w.split()).lower() for w in self._visible_packages(unit)}
        if _lower(target.name) in imported:
            return
        marker = (id(unit), _lower(target.name))
        if marker not in seen:
            seen.add(marker)
            warning(element, f"package {target.name} is used but not named in a with clause of {unit.name}")

    def _is_prototype(self, element: EObject, name: str) -> bool:
        if "::" in name or "." in name:
            return False
        current = element.eContainer()
        while current is not None and not _is(current, "Classifier"):
            current = current.eContainer()
        if current is None:
            return False
        classifiers = [current]
        if _is(current, "ComponentImplementation"):
            ctype = self.implementation_type(current)
            if ctype is not None:
                classifiers.append(ctype)
        for classifier in classifiers:
            try:
                chain = self.extends_chain(classifier)
            except NameResolutionError:
                chain = [classifier]
            for c in chain:
                for proto in c.prototypes:
                    if _lower(proto.name) == name.lower():
                        return True
        return False

    def _check_classifier(self, classifier, error, classifier_name, property_name) -> None:
        kinds = (classifier.eClass.name,)
        if _is(classifier, "ComponentImplementation"):
            kinds = ("ComponentImplementation",)
        if classifier.extended:
            classifier_name(classifier, classifier.extended, "extended classifier", *kinds)
        try:
            self.extends_chain(classifier)
        except NameResolutionError as exc:
            error(classifier, exc.message)
        if _is(classifier, "ComponentImplementation"):
            type_name = classifier.type or (classifier.name or "").partition(".")[0]
            classifier_name(classifier, type_name, "component type", "ComponentType")
            for sub in classifier.subcomponents:
                classifier_name(sub, sub.classifier, "subcomponent classifier", "ComponentClassifier")
                for pa in sub.ownedPropertyAssociations:
                    self._check_association(pa, property_name, classifier_name)
            for element in (
                *classifier.connections,
                *classifier.flowImplementations,
                *classifier.endToEndFlows,
                *classifier.callSequences,
            ):
                for pa in getattr(element, "ownedPropertyAssociations", ()):
                    self._check_association(pa, property_name, classifier_name)
        if _is(classifier, "ComponentType", "FeatureGroupType"):
            for feature in classifier.features:
                kinds_f: tuple[str, ...] = ()
                if _enum_name(feature.category) == "featureGroup":
                    kinds_f = ("FeatureGroupType",)
                classifier_name(feature, feature.classifier, "feature classifier", *kinds_f)
                for pa in feature.ownedPropertyAssociations:
                    self._check_association(pa, property_name, classifier_name)
        if _is(classifier, "ComponentType"):
            for flow in classifier.flowSpecifications:
                for pa in flow.ownedPropertyAssociations:
                    self._check_association(pa, property_name, classifier_name)
        if _is(classifier, "FeatureGroupType") and classifier.inverseOf:
            classifier_name(
                classifier, classifier.inverseOf, "inverse feature group type", "FeatureGroupType"
            )
        if _is(classifier, "ComponentClassifier"):
            for mode in (*classifier.modes, *classifier.modeTransitions):
                for pa in mode.ownedPropertyAssociations:
                    self._check_association(pa, property_name, classifier_name)
        for pa in classifier.ownedPropertyAssociations:
            self._check_association(pa, property_name, classifier_name)

    def _check_association(self, pa, property_name, classifier_name) -> None:
        property_name(pa, pa.property)
        for binding in pa.inBinding:
            classifier_name(pa, binding, "binding classifier")
        for modal in pa.ownedValues:
            if modal.value is not None:
                self._check_value(pa, modal.value, property_name, classifier_name)

    def _check_value(self, pa, value, property_name, classifier_name) -> None:
        stack = [value]
        while stack:
            expr = stack.pop()
            kind = expr.eClass.name
            if kind == "ClassifierValue":
                classifier_name(pa, expr.classifier, "classifier")
            elif (
                kind == "NamedValue"
                and expr.name
                and "::" in expr.name
                and self.constant(expr.name, pa) is None
                and self.property(expr.name, pa) is None
            ):
                property_name(pa, expr.name, "property constant")
            stack.extend(_children(expr))

    def _check_property_set(self, unit, error, property_name, classifier_name) -> None:
        def type_name(holder: EObject, name: str | None) -> None:
            if name and self.property_type(name, holder) is None:
                missing = self.missing_property_set(name)
                if missing is not None:
                    property_name(holder, name, "property type")
                else:
                    error(holder, f"property type {name} not found")

        for prop in unit.ownedProperties:
            if prop.ownedType is None:
                type_name(prop, prop.type)
            else:
                self._check_type(prop.ownedType, type_name)
            if prop.defaultValue is not None:
                stack = [prop.defaultValue]
                while stack:
                    expr = stack.pop()
                    if (
                        expr.eClass.name == "NamedValue"
                        and expr.name
                        and "::" in expr.name
                        and self.constant(expr.name, prop) is None
                        and self.property(expr.name, prop) is None
                    ):
                        property_name(prop, expr.name, "property constant")
                    stack.extend(_children(expr))
        for const in unit.ownedPropertyConstants:
            if const.ownedType is None:
                type_name(const, const.type)
            else:
                self._check_type(const.ownedType, type_name)
        for ptype in unit.ownedPropertyTypes:
            self._check_type(ptype, type_name)

    def _check_type(self, ptype: EObject, type_name) -> None:
        stack = [ptype]
        while stack:
            current = stack.pop()
            kind = current.eClass.name
            if kind in ("AadlInteger", "AadlReal"):
                if current.ownedUnitsType is None:
                    type_name(current, current.unitsType)
            elif kind == "RangeType":
                if current.ownedNumberType is None:
                    type_name(current, current.numberType)
                else:
                    stack.append(current.ownedNumberType)
            elif kind == "ListType":
                if current.ownedElementType is None:
                    type_name(current, current.elementType)
                else:
                    stack.append(current.ownedElementType)
            elif kind == "RecordType":
                for field in current.ownedFields:
                    if field.ownedType is None:
                        type_name(field, field.type)
                    else:
                        stack.append(field.ownedType)


def _feature(obj: EObject, name: str) -> object:
    if obj.eClass.findEStructuralFeature(name) is None:
        return None
    return getattr(obj, name)


def _enum_name(value: object) -> str:
    return str(getattr(value, "name", value) or "")


def _strip_all(target: str | None) -> str:
    text = "".join((target or "").split())
    if text.lower().endswith("::all"):
        text = text[: -len("::all")]
    return text


def _children(expr: EObject) -> list[EObject]:
    kind = expr.eClass.name
    if kind == "RangeValue":
        return [e for e in (expr.minimum, expr.maximum, expr.delta) if e is not None]
    if kind == "ListValue":
        return list(expr.ownedItems)
    if kind == "RecordValue":
        return [f.value for f in expr.ownedFields if f.value is not None]
    if kind == "OperationValue":
        return list(expr.ownedOperands)
    return []
