"""Write OSATE ``.aaxl2`` instance files, with the ``.aadl`` sidecars their references point into.

:func:`write_aaxl2` takes a ``SystemInstance`` (or an ``AadlModel`` holding one, or a declarative
``AadlModel`` and the root implementation to instantiate) and writes what OSATE itself would
write: ``instances/<Pkg>_<Type>_<impl>_Instance.aaxl2`` and, beside the ``instances`` folder, the
packages and property sets the instance refers to, written by :mod:`rosaadl.exporters.aadl_text`.
:func:`dumps_aaxl2` gives the ``.aaxl2`` bytes alone and :func:`export_aaxl2` everything in
memory (bytes, sidecar texts, warnings).

The file follows OSATE's serialisation (EMF's XMI writer on ``aadl2.ecore``/``instance.ecore``):

* ``encoding="ASCII"``: every other character is written as a character reference
  (``&#xE9;``), as are line feeds, carriage returns and tabs in attribute values;
* elements and attributes in the metamodel's feature order (attributes: ``name``,
  ``category``, ``direction``, ...; children: property associations, feature instances,
  component instances, modes, flows, connection instances, then the links into the
  declarative model: ``subcomponent``, ``index``, ``classifier``);
* EMF's default omission: no ``category`` on an abstract component or a data port, no
  ``direction`` for ``in``, no ``kind`` for a feature connection, no boolean that is false,
  no number that is zero; Java enumeration literals (``in out``, ``thread group``);
  ``<index>0</index>`` children for components that are not array elements;
* intra-file references as EMF paths (``//@componentInstance.4/@featureInstance.0``, the root
  ``/``; ``/0/@…`` and ``/1`` when an ``xmi:XMI`` document holds several roots);
* references into the declarative model as ``href`` children: classifiers and properties by
  qualified name (``../P.aadl#P.T.impl``, ``…/Timing_Properties.aadl#Timing_Properties.Period``),
  subcomponents, features, connections, modes and flows by position, counted the way OSATE's
  Xtext model holds them (``#/0/@ownedPublicSection/@ownedClassifier.10/@ownedAbstractSubcomponent.0``:
  classifiers per package section, members per containment list of their class);
* units and enumeration literals of OSATE's own property sets as positional references of the
  current OSATE era (:mod:`rosaadl.importers.osate_eras`), under
  ``platform:/plugin/org.osate.aadl2.contrib/…`` (``org.osate.contribution.sei`` for ``SEI``,
  ``Data_Model``, ``Base_Types``, …); those of other property sets point into the sidecars.

Instances read from an ``.aaxl2`` file have no declarative model: references that the reader
kept as written (``uri#fragment``) are written back as they were, classifiers and properties by
qualified name, and links the reader did not keep (a feature instance's declaration) are left
out, with one warning that says how many.
"""

from __future__ import annotations

import functools
import logging
import math
import os
import re
from dataclasses import dataclass, field
from decimal import Decimal
from pathlib import Path
from types import MappingProxyType
from typing import Any

from lxml import etree
from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.errors import Diagnostic, ExportError, Location, RosaadlError
from rosaadl.fileio import atomic_write_bytes, atomic_write_text, parse_xml_bytes, safe_join
from rosaadl.importers import osate_eras

__all__ = [
    "Aaxl2Export",
    "export_aaxl2",
    "dumps_aaxl2",
    "write_aaxl2",
    "instance_file_name",
    "java_double",
    "INSTANCES_FOLDER",
]

log = logging.getLogger(__name__)

#: The folder, under the output directory, that holds the ``.aaxl2`` file (as in OSATE projects).
INSTANCES_FOLDER = "instances"

_ERA = osate_eras.CURRENT_ERA
_NS = (
    ("xmi", "http://www.omg.org/XMI"),
    ("xsi", "http://www.w3.org/2001/XMLSchema-instance"),
    ("aadl2", "http://aadl.info/AADL/2.0"),
    ("instance", "http://aadl.info/AADL/2.0/instance"),
)
#: OSATE's own packages (besides the property sets the era tables know) and where it keeps them.
_OSATE_PACKAGES = {
    "base_types": "platform:/plugin/org.osate.contribution.sei/resources/packages/Base_Types.aadl",
}

_ID_RE = re.compile(r"[A-Za-z](?:_?[A-Za-z0-9])*\Z")
_FILE_STEM_RE = re.compile(r"[A-Za-z0-9_]+\Z")

# AADL category (our enumeration names) → OSATE class-name stem
_CATEGORY_CLASS = {
    "abstract": "Abstract",
    "bus": "Bus",
    "data": "Data",
    "device": "Device",
    "memory": "Memory",
    "process": "Process",
    "processor": "Processor",
    "subprogram": "Subprogram",
    "subprogramGroup": "SubprogramGroup",
    "system": "System",
    "thread": "Thread",
    "threadGroup": "ThreadGroup",
    "virtualBus": "VirtualBus",
    "virtualProcessor": "VirtualProcessor",
}
# feature category → the aadl2 class of the declaration (its containment list is owned<Class>);
# a virtual bus access is a BusAccess in aadl2 (``virtual`` set) and an instance's busAccess
_FEATURE_CLASS = {
    "dataPort": "DataPort",
    "eventPort": "EventPort",
    "eventDataPort": "EventDataPort",
    "parameter": "Parameter",
    "busAccess": "BusAccess",
    "virtualBusAccess": "BusAccess",
    "dataAccess": "DataAccess",
    "subprogramAccess": "SubprogramAccess",
    "subprogramGroupAccess": "SubprogramGroupAccess",
    "featureGroup": "FeatureGroup",
    "abstractFeature": "AbstractFeature",
}
_INSTANCE_FEATURE_CATEGORY = {"virtualBusAccess": "busAccess"}
_CONNECTION_CLASS = {
    "portConnection": "PortConnection",
    "accessConnection": "AccessConnection",
    "featureConnection": "FeatureConnection",
    "featureGroupConnection": "FeatureGroupConnection",
    "parameterConnection": "ParameterConnection",
}
_OPERATORS = {"and": "and", "or": "or", "not": "not", "+": "+", "plus": "+", "-": "-", "minus": "-"}
# the aadl2 classes an opaque positional reference may end in (``…/@ownedDataPort.0`` → DataPort)
_OWNED_STEP_RE = re.compile(r"@owned([A-Z][A-Za-z]*?)\.\d+\Z")
_FRAGMENT_RE = re.compile(r"(?:/0)?/?(?:/@[A-Za-z]+(?:\.\d+)?)+|/0|/")
_CLASS_OF_STEP = frozenset(
    list(_FEATURE_CLASS.values())
    + [f"{c}Subcomponent" for c in _CATEGORY_CLASS.values()]
    + list(_CONNECTION_CLASS.values())
    + ["SubprogramCallSequence", "SubprogramCall", "Mode", "ModeTransition", "FlowSpecification"]
    + ["EndToEndFlow", "FlowImplementation", "Prototype", "Classifier"]
)


# =========================================================================== text helpers


def java_double(value: float) -> str:
    """``Double.toString`` as Java writes it: ``100.0``, ``0.5``, ``1.0E7``, ``1.5E-4``."""
    if math.isnan(value):
        return "NaN"
    if math.isinf(value):
        return "Infinity" if value > 0 else "-Infinity"
    if value == 0:
        return "-0.0" if math.copysign(1.0, value) < 0 else "0.0"
    sign, digits, exponent = Decimal(repr(float(value))).as_tuple()
    text = "".join(str(d) for d in digits).rstrip("0") or "0"
    point = len(digits) + int(exponent)  # digits before the decimal point
    prefix = "-" if sign else ""
    if 1e-3 <= abs(value) < 1e7:
        if point <= 0:
            return f"{prefix}0.{'0' * -point}{text}"
        whole = text[:point].ljust(point, "0")
        fraction = text[point:] or "0"
        return f"{prefix}{whole}.{fraction}"
    return f"{prefix}{text[0]}.{text[1:] or '0'}E{point - 1}"


_ESCAPES = {"&": "&amp;", "<": "&lt;", '"': "&quot;", "\n": "&#xA;", "\r": "&#xD;", "\t": "&#x9;"}
_NEEDS_ESCAPE = re.compile(r'[&<"\n\r\t]|[^\x20-\x7e]')
_INVALID_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")


def _char_ref(match: re.Match[str]) -> str:
    char = match.group(0)
    return _ESCAPES.get(char) or f"&#x{ord(char):X};"


class _Invalid(Exception):
    """A string holds a character that XML 1.0 cannot carry, even as a reference."""


def _attr(text: str) -> str:
    """An attribute value as EMF writes it in an ASCII document."""
    if _NEEDS_ESCAPE.search(text) is None:
        return text
    if _INVALID_XML.search(text) is not None:
        raise _Invalid(text)
    return _NEEDS_ESCAPE.sub(_char_ref, text)


def _name(value: Any) -> str:
    return str(getattr(value, "name", value) or "")


def _java_literal(value: Any) -> str:
    return str(getattr(value, "literal", None) or getattr(value, "name", None) or value or "")


def _get(obj: EObject, name: str) -> Any:
    """A feature's value without pyecore's descriptor (which also creates an empty holder for a
    feature never set); None when unset. Many-valued features give their collection."""
    holder = obj.__dict__.get(name)
    if holder is None:
        return None
    try:
        return holder._get()
    except AttributeError:
        return holder


def _items(obj: EObject, name: str) -> Any:
    """The items of a many-valued feature (an empty tuple when it was never touched)."""
    holder = obj.__dict__.get(name)
    return holder if holder is not None else ()


_CHECKED_NAMES = frozenset(
    {
        "ComponentInstance",
        "FeatureInstance",
        "ModeInstance",
        "FlowSpecificationInstance",
        "EndToEndFlowInstance",
    }
)


@functools.cache
def _class_names(eclass: Any) -> frozenset[str]:
    """The names of a metamodel class and of all its superclasses (metadata, looked up once)."""
    return frozenset([eclass.name, *(c.name for c in eclass.eAllSuperTypes())])


def _is(obj: Any, *names: str) -> bool:
    """``isinstance`` against metamodel classes named in ``names``."""
    if not isinstance(obj, EObject):
        return False
    known = _class_names(obj.eClass)
    return any(name in known for name in names)


def instance_file_name(instance: EObject) -> str:
    """OSATE's file name for an instance: ``Pkg_Type_impl_Instance.aaxl2`` (``::`` and ``.`` → ``_``)."""
    classifier = (instance.classifier or "").strip()
    if classifier and "#" not in classifier and "/" not in classifier:
        stem = classifier.replace("::", "_").replace(".", "_") + "_Instance"
    else:
        stem = instance.name or ""
    if not _FILE_STEM_RE.match(stem):
        raise ExportError(
            f"cannot name the instance file after {stem!r}: expected letters, digits and underscores",
            Location(path=instance.name or None),
        )
    return f"{stem}.aaxl2"


# =========================================================================== property types


@dataclass(frozen=True)
class _TypeInfo:
    """What writing a value needs to know of its property type (from any declarative model).

    ``kind``: ``units``, ``enum``, ``record``, ``list``, ``range``, ``number`` or ``other``.
    For units, enumeration and record types: ``set_name`` (the property set declaring it),
    ``table_name`` (its name as the era tables know it: the type's name, or the property's for
    an anonymous type, ``Record.Field`` for a field's type), ``fragment`` (its era-neutral path
    in the set) and ``names`` (literals or fields, in order). ``inner``: the element type of a
    list, the number type of a range, the units of a number; ``fields``: the field types.
    """

    kind: str
    set_name: str | None = None
    table_name: str | None = None
    fragment: str | None = None
    names: tuple[str, ...] = ()
    inner: _TypeInfo | None = None
    fields: tuple[_TypeInfo | None, ...] = ()
    era: str = osate_eras.CURRENT_ERA

    def index(self, name: str) -> int | None:
        wanted = name.lower()
        for position, item in enumerate(self.names):
            if item.lower() == wanted:
                return position
        return None

    @property
    def units(self) -> _TypeInfo | None:
        info: _TypeInfo | None = self
        for _ in range(8):
            if info is None or info.kind == "units":
                return info
            info = info.inner
        return None

    @property
    def element(self) -> _TypeInfo | None:
        """The type of a list's elements (itself for anything else)."""
        return self.inner if self.kind == "list" else self

    @property
    def base(self) -> _TypeInfo | None:
        """The innermost non-list type (what a named value or record is checked against)."""
        info: _TypeInfo | None = self
        for _ in range(8):
            if info is None or info.kind != "list":
                return info
            info = info.inner
        return None


def _unit_of(element: EObject | None) -> EObject | None:
    while element is not None and not _is(element, "ModelUnit"):
        element = element.eContainer()
    return element


def _type_fragment(ptype: EObject) -> str | None:
    """The era-neutral path of a property type in its property set (``@ownedPropertyType.3``,
    ``@ownedProperty.4/@ownedPropertyType/@ownedField.1/@ownedPropertyType``)."""
    owner = ptype.eContainer()
    if owner is None:
        return None
    feature = ptype.eContainmentFeature().name
    if _is(owner, "PropertySet"):
        lists = {
            "ownedPropertyTypes": "@ownedPropertyType",
            "ownedProperties": "@ownedProperty",
            "ownedPropertyConstants": "@ownedPropertyConstant",
        }
        step = lists.get(feature)
        if step is None:
            return None
        items = getattr(owner, feature)
        position = next(i for i, item in enumerate(items) if item is ptype)
        return f"{step}.{position}"
    head = _type_fragment(owner)
    if head is None:
        return None
    if feature == "ownedFields":
        position = next(i for i, item in enumerate(owner.ownedFields) if item is ptype)
        return f"{head}/@ownedField.{position}"
    step = {
        "ownedType": "@ownedPropertyType",
        "ownedUnitsType": "@ownedUnitsType",
        "ownedNumberType": "@ownedNumberType",
        "ownedElementType": "@ownedElementType",
    }.get(feature)
    return f"{head}/{step}" if step else None


def _table_name(ptype: EObject) -> str | None:
    """The name the era tables give a type: its own, its property's, or ``Record.Field``."""
    owner = ptype.eContainer()
    if owner is None:
        return None
    if _is(owner, "PropertySet"):
        return ptype.name
    if _is(owner, "Property", "PropertyConstant"):
        return owner.name
    if _is(owner, "RecordField"):
        record = owner.eContainer()
        head = _table_name(record) if record is not None else None
        return f"{head}.{owner.name}" if head else None
    return _table_name(owner)


class _TypeBuilder:
    """Turns property types of a declarative model into :class:`_TypeInfo` (cached per type)."""

    def __init__(self, resolver: Any) -> None:
        self.resolver = resolver
        self.cache: dict[int, _TypeInfo | None] = {}

    def of_property(self, prop: EObject | None) -> _TypeInfo | None:
        if prop is None:
            return None
        return self.of_type(self.resolver.resolved_type(prop), 0)

    def of_type(self, ptype: EObject | None, depth: int) -> _TypeInfo | None:
        if ptype is None or depth > 12:
            return None
        key = id(ptype)
        if key in self.cache:
            return self.cache[key]
        self.cache[key] = None  # cyclic type names end here
        info = self._build(ptype, depth)
        self.cache[key] = info
        return info

    def _named(self, ptype: EObject, kind: str, names: tuple[str, ...], fields=()) -> _TypeInfo:
        unit = _unit_of(ptype)
        return _TypeInfo(
            kind,
            set_name=unit.name if unit is not None else None,
            table_name=_table_name(ptype),
            fragment=_type_fragment(ptype),
            names=names,
            fields=fields,
        )

    def _build(self, ptype: EObject, depth: int) -> _TypeInfo | None:
        resolver = self.resolver
        kind = ptype.eClass.name
        if kind == "UnitsType":
            return self._named(ptype, "units", tuple(lit.name or "" for lit in ptype.ownedLiterals))
        if kind == "EnumerationType":
            return self._named(ptype, "enum", tuple(lit.name or "" for lit in ptype.ownedLiterals))
        if kind == "RecordType":
            names = tuple(f.name or "" for f in ptype.ownedFields)
            fields = tuple(self.of_type(resolver.resolved_type(f), depth + 1) for f in ptype.ownedFields)
            return self._named(ptype, "record", names, fields)
        if kind == "ListType":
            inner = ptype.ownedElementType
            if inner is None:
                inner = resolver.property_type(ptype.elementType, ptype)
            return _TypeInfo("list", inner=self.of_type(inner, depth + 1))
        if kind == "RangeType":
            inner = ptype.ownedNumberType
            if inner is None:
                inner = resolver.property_type(ptype.numberType, ptype)
            return _TypeInfo("range", inner=self.of_type(inner, depth + 1))
        if kind in ("AadlInteger", "AadlReal"):
            units = ptype.ownedUnitsType
            if units is None and ptype.unitsType:
                units = resolver.property_type(ptype.unitsType, ptype)
            return _TypeInfo("number", inner=self.of_type(units, depth + 1))
        return _TypeInfo("other")


def _osate_set(name: str | None) -> bool:
    """Is ``name`` one of the property sets OSATE ships (written as platform references)?"""
    return bool(name) and osate_eras.table(_ERA).has_set(name or "")


def _osate_unit(name: str | None) -> bool:
    return _osate_set(name) or (name or "").lower() in _OSATE_PACKAGES


@functools.cache
def _library_property_types() -> MappingProxyType:
    """Qualified property name (lower case) → :class:`_TypeInfo`, for OSATE's property sets as
    this project's library declares them (used when a model does not hold them, as after
    reading an ``.aaxl2`` file). Built once from the library's files; immutable."""
    from rosaadl.importers.aadl_text import library_files, read_files
    from rosaadl.resolution import Resolver

    files = [p for p in library_files() if _osate_set(p.stem)]
    try:
        library = read_files(files, include_library=False, warnings=[])
    except RosaadlError as exc:  # the era tables still answer for OSATE's sets
        log.warning("the library's property sets do not read (%s); using the OSATE era tables only", exc)
        return MappingProxyType({})
    builder = _TypeBuilder(Resolver(library))
    table: dict[str, _TypeInfo | None] = {}
    for unit in library.units:
        if not _is(unit, "PropertySet"):
            continue
        for prop in unit.ownedProperties:
            table[f"{unit.name}::{prop.name}".lower()] = builder.of_property(prop)
    return MappingProxyType(table)


def _probe_container(tab: Any, set_name: str, path: str) -> _TypeInfo | None:
    """The enumeration, units or record type at ``path`` of an OSATE property set, per the era table."""
    first = tab.literal(set_name, f"{path}/@ownedLiteral.0") or tab.literal(set_name, f"{path}/@ownedField.0")
    if first is None:
        return None
    step = "@ownedField" if first.kind == "field" else "@ownedLiteral"
    names: list[str] = []
    while (entry := tab.literal(set_name, f"{path}/{step}.{len(names)}")) is not None:
        names.append(entry.name)
    kind = {"field": "record", "enum": "enum", "units": "units"}[first.kind]
    table_name = first.type_name.rpartition("::")[2]
    return _TypeInfo(
        kind, set_name=first.property_set, table_name=table_name, fragment=path, names=tuple(names)
    )


@functools.cache
def _era_catalogue(era: str = osate_eras.CURRENT_ERA) -> MappingProxyType:
    """Property set name (lower case) → the enumeration, units and record types of OSATE's copy of
    it in ``era``, read off the era tables (immutable, built once). Record types carry their
    fields' types where the tables know them: an anonymous field type, the units of its numbers,
    or an ``era`` marker for a named type (whose literals are then looked up by name)."""
    tab = osate_eras.table(era)
    catalogue: dict[str, tuple[_TypeInfo, ...]] = {}
    nested = ("/@ownedElementType", "/@ownedUnitsType", "/@ownedNumberType")
    for set_name in tab.property_sets():
        count = 0
        while tab.property_name(set_name, count) is not None:
            count += 1
        bases = [f"@ownedPropertyType.{n}" for n in range(128)]
        bases += [f"@ownedProperty.{n}/@ownedPropertyType" for n in range(count)]
        bases += [f"@ownedPropertyConstant.{n}/@ownedPropertyType" for n in range(32)]
        queue = bases + [base + step for base in bases for step in nested]
        queue += [base + step + "/@ownedUnitsType" for base in bases for step in nested[::2]]
        found: list[_TypeInfo] = []
        while queue:
            path = queue.pop()
            info = _probe_container(tab, set_name, path)
            if info is not None:
                found.append(info)
                if info.kind == "record":
                    queue += [f"{path}/@ownedField.{k}/@ownedPropertyType" for k in range(len(info.names))]
        found.sort(key=lambda i: i.fragment or "")
        by_name = {(i.table_name or "").lower(): i for i in found}
        linked = []
        for info in found:
            if info.kind == "record":
                fields: list[_TypeInfo | None] = []
                for position, name in enumerate(info.names):
                    inner = by_name.get(f"{info.table_name}.{name}".lower())
                    if inner is None:
                        entry = tab.literal(set_name, f"{info.fragment}/@ownedField.{position}")
                        units = entry.units if entry is not None else None
                        if units:
                            inner = _TypeInfo("number", inner=_era_units(units, era))
                        else:  # a named type: its literals are looked up by name in the set
                            inner = _TypeInfo("era", set_name=info.set_name, table_name=name, era=era)
                    fields.append(inner)
                info = _TypeInfo(
                    "record",
                    info.set_name,
                    info.table_name,
                    info.fragment,
                    info.names,
                    fields=tuple(fields),
                    era=era,
                )
            linked.append(info)
        catalogue[set_name.lower()] = tuple(linked)
    return MappingProxyType(catalogue)


@functools.cache
def _era_units(qualified: str | None, era: str = osate_eras.CURRENT_ERA) -> _TypeInfo | None:
    """The units type ``Set::Name`` of OSATE's property sets in ``era``, as a :class:`_TypeInfo`."""
    if not qualified:
        return None
    set_name, _, local = qualified.rpartition("::")
    tab = osate_eras.table(era)
    for path in [f"@ownedPropertyType.{n}" for n in range(128)]:
        info = _probe_container(tab, set_name, path)
        if info is not None and info.kind == "units" and (info.table_name or "").lower() == local.lower():
            return info
    return None


def _older_eras(set_name: str) -> list[str]:
    """Older eras whose copy of ``set_name`` OSATE finds under the same URI as today's (the
    SEI-contributed sets), newest first: a value of a property OSATE has since renamed can
    still be written in the layout of the set that had it."""
    current = osate_eras.predeclared_uri(osate_eras.CURRENT_ERA, set_name)
    out = []
    for era in reversed(osate_eras.ERAS[:-1]):
        if osate_eras.table(era).has_set(set_name) and osate_eras.predeclared_uri(era, set_name) == current:
            out.append(era)
    return out


def _era_search(
    kind: str, names: tuple[str, ...], sets: tuple[str, ...], era: str = osate_eras.CURRENT_ERA
) -> _TypeInfo | None:
    """The one ``kind`` type (enum, units, record) of OSATE's sets holding every literal or field
    of ``names``, looking in ``sets`` in order (each set, then all sets); None when none or
    several do."""
    catalogue = _era_catalogue(era)
    wanted = {n.lower() for n in names}
    for group in [(s,) for s in sets] + [tuple(catalogue)]:
        hits = [
            info
            for set_name in group
            for info in catalogue.get(set_name.lower(), ())
            if info.kind == kind and wanted <= {n.lower() for n in info.names}
        ]
        if len(hits) == 1:
            return hits[0]
        if len(hits) > 1:
            return None
    return None


def _era_property(qualified: str) -> _TypeInfo | None:
    """What the era tables tell of the type of a property of OSATE's sets not declared anywhere:
    its anonymous type when it has one, else the units of its numbers, else an ``era`` marker
    (enumeration literals and record fields are then found by name in the set's types)."""
    set_name, _, local = qualified.rpartition("::")
    if not _osate_set(set_name):
        return None
    for info in _era_catalogue().get(set_name.lower(), ()):
        if (info.table_name or "").lower() == local.lower():
            return info
    units = _era_units(osate_eras.table(_ERA).property_units(qualified))
    if units is not None:
        return _TypeInfo("number", inner=units)
    return _TypeInfo("era", set_name=set_name, table_name=local)


# =========================================================================== the export


@dataclass
class Aaxl2Export:
    """An instance file and its sidecars, in memory.

    ``file_name`` is relative to the output directory (``instances/X_Instance.aaxl2``);
    ``sidecars`` maps ``.aadl`` file names (relative to the output directory) to their text.
    """

    file_name: str
    data: bytes
    sidecars: dict[str, str] = field(default_factory=dict)
    warnings: list[Diagnostic] = field(default_factory=list)
    instance: EObject | None = None


class _Skip(Exception):
    """A value that cannot be written for OSATE; its association is left out with a warning."""


def _select(
    subject: EObject, root: str | None, diagnostics: list[Diagnostic]
) -> tuple[EObject, EObject | None]:
    """(the SystemInstance to write, the AadlModel holding its declarative model, or None)."""
    if not isinstance(subject, EObject):
        raise ExportError(f"expected an AadlModel or a SystemInstance, got {type(subject).__name__}")
    kind = subject.eClass.name
    if kind == "SystemInstance":
        container = subject.eContainer()
        aadl_model = container if container is not None and _is(container, "AadlModel") else None
        if root and not _root_matches(subject, root):
            raise ExportError(
                f"root {root!r} does not match the instance given ({subject.classifier or subject.name})",
                Location(path=subject.name or None),
            )
        return subject, aadl_model
    if kind != "AadlModel":
        raise ExportError(f"expected an AadlModel or a SystemInstance, got a {kind}")
    instances = list(subject.instances)
    if root:
        matches = [i for i in instances if _root_matches(i, root)]
        if matches:
            return matches[-1], subject
        if not subject.units:
            known = ", ".join(i.classifier or i.name or "?" for i in instances) or "none"
            raise ExportError(
                f"root {root!r} is not an instance of the model (instances: {known}) and the model has "
                "no declarative units to instantiate it from",
                Location(path=root),
            )
        from rosaadl.transforms.instantiate import Instantiator

        instantiator = Instantiator(subject)
        system = instantiator.run(root)
        diagnostics.extend(instantiator.diagnostics)
        return system, subject
    if len(instances) == 1:
        return instances[0], subject
    if not instances:
        raise ExportError(
            "the model holds no system instance; name the root implementation to instantiate "
            "(root='Pkg::System.impl')"
        )
    names = ", ".join(i.classifier or i.name or "?" for i in instances)
    raise ExportError(f"the model holds {len(instances)} system instances ({names}); name the one to write")


def _root_matches(instance: EObject, root: str) -> bool:
    wanted = "".join(root.split()).lower()
    return wanted in ((instance.classifier or "").replace(" ", "").lower(), (instance.name or "").lower())


class _Writer:
    """One export (no state survives it)."""

    def __init__(self, system: EObject, aadl_model: EObject | None, diagnostics: list[Diagnostic]) -> None:
        self.system = system
        self.model = aadl_model
        self.warnings = diagnostics
        self.resolver = None
        if aadl_model is not None and len(aadl_model.units):
            from rosaadl.resolution import Resolver

            self.resolver = Resolver(aadl_model)
        self.types = _TypeBuilder(self.resolver) if self.resolver is not None else None
        self.paths: dict[int, str] = {}
        self.roots: list[EObject] = []
        self.used_units: dict[int, EObject] = {}
        self.guessed_units: dict[str, str] = {}
        self.missing: dict[str, int] = {}
        self.skipped: list[str] = []
        self.out: list[str] = []
        self.extra_ns: dict[str, str] = {}
        # caches
        self.classifier_cache: dict[str, EObject | None] = {}
        self.classifier_frag: dict[int, str] = {}
        self.member_frag: dict[int, str] = {}
        self.href_cache: dict[tuple, tuple[str, str] | None] = {}
        self.property_cache: dict[str, tuple[str, _TypeInfo | None]] = {}
        self.literal_cache: dict[tuple, str] = {}
        self.set_eras: dict[str, str] = {}
        self.wanted_set_eras: dict[str, str] = {}
        self.som_by_name: dict[str, EObject] = {}

    # ------------------------------------------------------------------ diagnostics

    def warn(self, message: str, obj: EObject | None = None) -> None:
        path = _model.instance_path(obj) if obj is not None and _is(obj, "InstanceObject") else None
        diagnostic = Diagnostic("warning", message, Location(path=path))
        self.warnings.append(diagnostic)
        log.warning("%s", diagnostic)

    def error(self, message: str, obj: EObject | None = None) -> ExportError:
        path = _model.instance_path(obj) if obj is not None and _is(obj, "InstanceObject") else None
        return ExportError(message, Location(path=path or (obj.name if obj is not None else None)))

    def text(self, value: str, obj: EObject | None, what: str) -> str:
        try:
            return _attr(value)
        except _Invalid:
            bad = next(c for c in value if _INVALID_XML.match(c))
            raise self.error(
                f"{what} {value!r} holds the character U+{ord(bad):04X}, which an XML 1.0 file cannot carry",
                obj,
            ) from None

    # ------------------------------------------------------------------ checks and paths

    def extra_roots(self) -> list[EObject]:
        """Further ComponentInstance roots of the model that feature instances refer to (``type``)."""
        if self.model is None or not len(self.model.componentInstances):
            return []
        available = {id(r) for r in self.model.componentInstances}
        wanted: dict[int, EObject] = {}
        pending = [self.system]
        while pending:
            for obj in _model.walk(pending.pop()):
                target = obj.type if obj.eClass.name == "FeatureInstance" else None
                if target is None:
                    continue
                while target.eContainer() is not None and _is(target.eContainer(), "InstanceObject"):
                    target = target.eContainer()
                if id(target) in available and id(target) not in wanted:
                    wanted[id(target)] = target
                    pending.append(target)
        return [r for r in self.model.componentInstances if id(r) in wanted]

    def assign_paths(self) -> None:
        """EMF paths of every instance object: ``/`` and ``//@a.1/@b.0`` (``/0``, ``/0/@a.1`` with
        several roots); component, feature, mode and flow instances must be named by AADL
        identifiers (a located :class:`ExportError` otherwise)."""
        system_name = _get(self.system, "name") or ""
        if not _FILE_STEM_RE.match(system_name):
            raise ExportError(
                f"the system instance is named {system_name!r}: expected letters, digits and underscores "
                "(OSATE names it Type_impl_Instance)",
                Location(path=system_name or None),
            )
        multi = len(self.roots) > 1
        for number, root in enumerate(self.roots):
            head = f"/{number}" if multi else "/"
            self.paths[id(root)] = head
            stack = [(root, head)]
            while stack:
                obj, path = stack.pop()
                for tag, items in self.containments(obj):
                    for position, child in enumerate(items):
                        child_path = f"{path}/@{tag}.{position}"
                        self.paths[id(child)] = child_path
                        kind = child.eClass.name
                        if kind in _CHECKED_NAMES:
                            name = _get(child, "name") or ""
                            if not _ID_RE.match(name):
                                shown = repr(name) if name else "no name"
                                raise ExportError(
                                    f"a {kind} has {shown}: an AADL identifier is letters, digits and "
                                    "single underscores, starting with a letter",
                                    Location(path=f"{_model.instance_path(obj)}.{name}"),
                                )
                        stack.append((child, child_path))
        for som in _items(self.system, "systemOperationModes"):
            self.som_by_name.setdefault((_get(som, "name") or "").lower(), som)

    @staticmethod
    def containments(obj: EObject) -> list[tuple[str, Any]]:
        kind = obj.eClass.name
        if kind in ("ComponentInstance", "SystemInstance"):
            out = [
                ("featureInstance", _items(obj, "featureInstances")),
                ("componentInstance", _items(obj, "componentInstances")),
                ("modeInstance", _items(obj, "modeInstances")),
                ("modeTransitionInstance", _items(obj, "modeTransitionInstances")),
                ("flowSpecification", _items(obj, "flowSpecifications")),
                ("endToEndFlow", _items(obj, "endToEndFlows")),
                ("connectionInstance", _items(obj, "connectionInstances")),
            ]
            if kind == "SystemInstance":
                out.append(("systemOperationMode", _items(obj, "systemOperationModes")))
            return out
        if kind == "FeatureInstance":
            return [("featureInstance", _items(obj, "featureInstances"))]
        return []

    def ref(self, target: EObject | None, owner: EObject, what: str) -> str:
        if target is None:
            raise self.error(f"{what} refers to nothing", owner)
        path = self.paths.get(id(target))
        if path is None:
            shown = _model.instance_path(target) if _is(target, "InstanceObject") else target.name
            raise self.error(f"{what} refers to {shown!r}, which is not part of the exported instance", owner)
        return path

    def refs(self, targets: Any, owner: EObject, what: str) -> str:
        return " ".join(self.ref(t, owner, what) for t in targets)

    # ------------------------------------------------------------------ declarative model

    def note_missing(self, what: str) -> None:
        self.missing[what] = self.missing.get(what, 0) + 1

    def unit_uri(self, unit: EObject) -> str:
        name = unit.name or ""
        if _osate_set(name):
            return osate_eras.predeclared_uri(_ERA, name)
        package = _OSATE_PACKAGES.get(name.lower())
        if package is not None:
            return package
        from rosaadl.exporters.aadl_text import unit_file_name

        self.used_units.setdefault(id(unit), unit)
        return f"../{unit_file_name(unit)}"

    def uri_for_name(self, unit_name: str) -> str:
        """The URI of a unit known only by name (no declarative model): OSATE's, or ``../X.aadl``."""
        if _osate_set(unit_name):
            return osate_eras.predeclared_uri(_ERA, unit_name)
        package = _OSATE_PACKAGES.get(unit_name.lower())
        if package is not None:
            return package
        self.guessed_units.setdefault(unit_name.lower(), unit_name)
        return "../" + "-".join(part.strip() for part in unit_name.split("::")) + ".aadl"

    def classifier(self, name: str | None) -> EObject | None:
        if not name or self.resolver is None or "#" in name:
            return None
        key = name.lower()
        if key not in self.classifier_cache:
            self.classifier_cache[key] = self.resolver.classifier(name)
        return self.classifier_cache[key]

    def classifier_fragment(self, classifier: EObject) -> str | None:
        found = self.classifier_frag.get(id(classifier))
        if found is not None:
            return found
        package = classifier.eContainer()
        if package is None or not _is(package, "AadlPackage"):
            return None
        counts = {"public": 0, "private": 0}
        for item in package.classifiers:
            section = "private" if _name(item.visibility) == "private" else "public"
            step = "ownedPrivateSection" if section == "private" else "ownedPublicSection"
            self.classifier_frag[id(item)] = f"@{step}/@ownedClassifier.{counts[section]}"
            counts[section] += 1
        return self.classifier_frag.get(id(classifier))

    @staticmethod
    def classifier_class(classifier: EObject) -> str:
        kind = classifier.eClass.name
        if kind == "FeatureGroupType":
            return "FeatureGroupType"
        stem = _CATEGORY_CLASS.get(_name(classifier.category), "Abstract")
        return stem + ("Implementation" if kind == "ComponentImplementation" else "Type")

    def classifier_href(self, name: str | None, category: Any, *, implementation: bool = False):
        """(xsi:type, href) of a classifier named ``name`` (None when there is none)."""
        if not name:
            return None
        key = ("classifier", name, _name(category), implementation)
        if key in self.href_cache:
            return self.href_cache[key]
        element = self.classifier(name)
        if element is not None:
            unit = _unit_of(element)
            href = f"{self.unit_uri(unit)}#{unit.name}.{element.name}"
            found = (f"aadl2:{self.classifier_class(element)}", href)
        elif "#" in name:
            # kept as written by the reader: a positional reference names no kind of classifier
            stem = _CATEGORY_CLASS.get(_name(category), "Abstract")
            found = (f"aadl2:{stem}Implementation" if implementation else f"aadl2:{stem}Type", name)
        else:
            package, _, local = name.rpartition("::")
            if not package:
                self.note_missing("classifier without a package")
                found = None
            else:
                stem = _CATEGORY_CLASS.get(_name(category), "Abstract")
                suffix = "Implementation" if "." in local or implementation else "Type"
                found = (f"aadl2:{stem}{suffix}", f"{self.uri_for_name(package)}#{package}.{local}")
        self.href_cache[key] = found
        return found

    def member_fragment(self, element: EObject) -> str | None:
        """Path of a feature, subcomponent, connection, mode, transition or flow in its unit."""
        found = self.member_frag.get(id(element))
        if found is not None:
            return found
        owner = element.eContainer()
        if owner is None or not _is(owner, "Classifier"):
            return None
        head = self.classifier_fragment(owner)
        if head is None:
            return None
        feature = element.eContainmentFeature().name
        counts: dict[str, int] = {}
        for item in getattr(owner, feature):
            cls = self.member_class(item)
            if cls is None:
                continue
            position = counts.get(cls, 0)
            counts[cls] = position + 1
            self.member_frag[id(item)] = f"{head}/@owned{cls}.{position}"
        return self.member_frag.get(id(element))

    @staticmethod
    def member_class(element: EObject) -> str | None:
        kind = element.eClass.name
        if kind == "Feature":
            return _FEATURE_CLASS.get(_name(element.category))
        if kind == "Subcomponent":
            stem = _CATEGORY_CLASS.get(_name(element.category))
            return f"{stem}Subcomponent" if stem else None
        if kind == "Connection":
            return _CONNECTION_CLASS.get(_name(element.kind))
        if kind in ("Mode", "ModeTransition", "FlowSpecification", "EndToEndFlow"):
            return kind
        return None

    def member_href(self, element: EObject | None) -> tuple[str, str] | None:
        if element is None:
            return None
        fragment = self.member_fragment(element)
        cls = self.member_class(element)
        unit = _unit_of(element)
        if fragment is None or cls is None or unit is None:
            return None
        return f"aadl2:{cls}", f"{self.unit_uri(unit)}#{osate_eras.fragment(_ERA, fragment)}"

    @staticmethod
    def opaque_href(text: str) -> tuple[str | None, str]:
        """A reference the reader kept as ``uri#fragment``, with the class its last step names."""
        _uri, _, fragment = text.partition("#")
        match = _OWNED_STEP_RE.search(fragment)
        cls = match.group(1) if match and match.group(1) in _CLASS_OF_STEP else None
        return (f"aadl2:{cls}" if cls else None), text

    @staticmethod
    def find(items: list[EObject], name: str | None) -> EObject | None:
        wanted = (name or "").lower()
        for item in items:
            if (item.name or "").lower() == wanted:
                return item
        return None

    def component_classifier(self, ci: EObject | None) -> EObject | None:
        return self.classifier(ci.classifier) if ci is not None else None

    def subcomponent_href(self, ci: EObject) -> tuple[str, str] | None:
        parent = ci.eContainer()
        impl = self.component_classifier(parent) if parent is not None else None
        key = ("sub", id(impl), (ci.subcomponent or ci.name or "").lower())
        if key in self.href_cache:
            return self.href_cache[key]
        found = None
        if impl is not None and _is(impl, "ComponentImplementation"):
            found = self.member_href(self.find(self.resolver.subcomponents(impl), ci.subcomponent or ci.name))
        self.href_cache[key] = found
        return found

    def feature_decl(self, fi: EObject, decls: dict[int, EObject | None]) -> EObject | None:
        """The declaration of a feature instance (the most refined one), or None."""
        parent = fi.eContainer()
        if parent is None or self.resolver is None:
            return None
        if parent.eClass.name == "FeatureInstance":
            group = decls.get(id(parent))
            if group is None:
                return None
            fgt = self.resolver.feature_classifier(group)
            if fgt is None or not _is(fgt, "FeatureGroupType"):
                return None
            members, _inverted = self.resolver.feature_group_features(fgt)
            return self.find(members, fi.feature or fi.name)
        classifier = self.component_classifier(parent)
        if classifier is None:
            return None
        key = ("features", id(classifier))
        members = self.href_cache.get(key)
        if members is None:
            members = self.resolver.features(classifier)
            self.href_cache[key] = members  # type: ignore[assignment]
        return self.find(members, fi.feature or fi.name)  # type: ignore[arg-type]

    def connection_href(self, ref: EObject) -> tuple[str | None, str] | None:
        text = (ref.connection or "").strip()
        if not text:
            return None
        if "#" in text:
            return self.opaque_href(text)
        context = ref.context
        impl = self.component_classifier(context)
        key = ("conn", id(impl), text.lower())
        if key in self.href_cache:
            return self.href_cache[key]
        found = None
        if impl is not None and _is(impl, "ComponentImplementation"):
            found = self.member_href(self.find(self.resolver.connections(impl), text.rpartition("::")[2]))
        self.href_cache[key] = found
        return found

    def mode_href(self, mi: EObject) -> tuple[str, str] | None:
        owner = mi.eContainer()
        classifier = self.component_classifier(owner)
        if classifier is None:
            return None
        return self.member_href(self.find(self.resolver.modes(classifier), mi.mode or mi.name))

    def transition_href(self, mti: EObject) -> tuple[str, str] | None:
        owner = mti.eContainer()
        classifier = self.component_classifier(owner)
        if classifier is None:
            return None
        transitions = self.resolver.mode_transitions(classifier)
        found = self.find(transitions, mti.name)
        if found is None and mti.source is not None and mti.destination is not None:
            src, dst = (mti.source.name or "").lower(), (mti.destination.name or "").lower()
            candidates = [
                t
                for t in transitions
                if (t.source or "").lower() == src and (t.destination or "").lower() == dst
            ]
            found = candidates[0] if len(candidates) == 1 else None
        return self.member_href(found)

    def flow_spec_href(self, fsi: EObject) -> tuple[str, str] | None:
        classifier = self.component_classifier(fsi.eContainer())
        if classifier is None:
            return None
        return self.member_href(self.find(self.resolver.flow_specifications(classifier), fsi.name))

    def end_to_end_href(self, flow: EObject) -> tuple[str, str] | None:
        impl = self.component_classifier(flow.eContainer())
        if impl is None:
            return None
        return self.member_href(self.find(self.resolver.end_to_end_flows(impl), flow.flow or flow.name))

    # ------------------------------------------------------------------ properties and values

    def property_info(self, name: str, obj: EObject) -> tuple[str, _TypeInfo | None]:
        """(href, type) of the property an association sets."""
        found = self.property_cache.get(name)
        if found is not None:
            return found
        text = name.strip()
        if "#" in text:
            found = (text, None)
        else:
            prop = self.resolver.property(text) if self.resolver is not None else None
            info = None
            if prop is not None:
                unit = _unit_of(prop)
                href = f"{self.unit_uri(unit)}#{unit.name}.{prop.name}"
                info = self.types.of_property(prop) if self.types is not None else None
            else:
                set_name, _, local = text.rpartition("::")
                if not set_name:
                    raise self.error(f"property {text!r} is not qualified and not declared in the model", obj)
                href = f"{self.uri_for_name(set_name)}#{set_name}.{local}"
            if info is None and _osate_set(text.rpartition("::")[0]):
                info = _library_property_types().get(text.lower()) or _era_property(text)
            found = (href, info)
        self.property_cache[name] = found
        return found

    def literal_href(self, info: _TypeInfo | None, name: str, kind: str) -> str:
        """Positional href of unit / enumeration literal / record field ``name`` of a type.

        A unit whose type is not known (a property of a set that is not in the model) is looked
        up in OSATE's units types, where unit names are unique. References into one of OSATE's
        sets all follow one era: the current one, unless a value only exists in an older layout
        of the set (a property OSATE has since renamed), which then holds for the whole set."""
        if kind == "unit" and (info is None or info.set_name is None):
            info = _era_search("units", (name,), ("AADL_Project",))
        if info is None or info.set_name is None:
            raise _Skip(f"the type of {kind} {name!r} is not known")
        key = (id(info), name.lower(), kind)
        cached = self.literal_cache.get(key)
        if cached is not None:
            return cached
        if _osate_set(info.set_name):
            href = self.osate_literal_href(info, name, kind)
        else:
            position = info.index(name)
            if position is None:
                raise _Skip(f"{name!r} is not a {kind} of {info.set_name}::{info.table_name}")
            unit = self.resolver.unit(info.set_name) if self.resolver is not None else None
            if unit is None or info.fragment is None:
                raise _Skip(f"property set {info.set_name} is not in the model")
            step = "@ownedField" if info.kind == "record" else "@ownedLiteral"
            href = f"{self.unit_uri(unit)}#{osate_eras.fragment(_ERA, f'{info.fragment}/{step}.{position}')}"
        self.literal_cache[key] = href
        return href

    def osate_literal_href(self, info: _TypeInfo, name: str, kind: str) -> str:
        set_key = (info.set_name or "").lower()
        pinned = self.set_eras.get(set_key)
        eras = [pinned] if pinned else [_ERA, *_older_eras(info.set_name or "")]
        for era in eras:
            found, path = info, None
            if info.era == era:
                path = osate_eras.table(era).literal_path(info.set_name or "", info.table_name or "", name)
            if path is None:
                # this project's copy of the set may name or place the type differently
                searched = _era_search(info.kind, (name,), (info.set_name or "", "AADL_Project"), era)
                if searched is not None and searched.set_name is not None:
                    found = searched
                    path = osate_eras.table(era).literal_path(
                        searched.set_name, searched.table_name or "", name
                    )
            if path is None:
                continue
            target = (found.set_name or "").lower()
            if era != _ERA and not self.set_eras.get(target):
                self.wanted_set_eras[target] = era
            elif self.set_eras.get(target, _ERA) != era:
                continue
            uri = osate_eras.predeclared_uri(era, found.set_name or "")
            return f"{uri}#{osate_eras.fragment(era, path)}"
        raise _Skip(f"OSATE's {info.set_name} has no {kind} {name!r} in {info.table_name}")

    def named_value(self, expr: EObject, info: _TypeInfo | None) -> tuple[str, str]:
        name = (expr.name or "").strip()
        if "#" in name:
            return "aadl2:EnumerationLiteral", name
        base = info.base if info is not None else None
        if base is not None and base.kind == "era" and base.set_name:
            for era in self.eras_of(base.set_name):
                found = _era_search("enum", (name,), (base.set_name, "AADL_Project"), era)
                if found is not None:
                    base = found
                    break
        if base is not None and base.kind == "enum" and base.index(name) is not None:
            return "aadl2:EnumerationLiteral", self.literal_href(base, name, "enumeration literal")
        if self.resolver is not None:
            constant = self.resolver.constant(name)
            if constant is not None:
                unit = _unit_of(constant)
                return "aadl2:PropertyConstant", f"{self.unit_uri(unit)}#{unit.name}.{constant.name}"
            prop = self.resolver.property(name)
            if prop is not None:
                unit = _unit_of(prop)
                return "aadl2:Property", f"{self.unit_uri(unit)}#{unit.name}.{prop.name}"
        if base is not None and base.kind == "enum":
            raise _Skip(f"{name!r} is not a literal of {base.set_name}::{base.table_name}")
        raise _Skip(f"the enumeration literal {name!r} cannot be placed (its type is not known)")

    def eras_of(self, set_name: str) -> list[str]:
        pinned = self.set_eras.get(set_name.lower())
        return [pinned] if pinned else [_ERA, *_older_eras(set_name)]

    def record_type(self, info: _TypeInfo | None, names: list[str]) -> _TypeInfo | None:
        """The record type of a record value (found by its field names in OSATE's sets when the
        property is known only from the era tables)."""
        record = info.base if info is not None else None
        if record is not None and record.kind == "era" and record.set_name and names:
            for era in self.eras_of(record.set_name):
                found = _era_search("record", tuple(names), (record.set_name,), era)
                if found is not None:
                    return found
        return record if record is not None and record.kind == "record" else None

    def emit_value(
        self, indent: str, tag: str, expr: EObject, info: _TypeInfo | None, owner: EObject
    ) -> None:
        out = self.out
        kind = expr.eClass.name
        if kind in ("IntegerValue", "RealValue"):
            value = _get(expr, "value") or 0
            if kind == "IntegerValue":
                xsi, shown = "aadl2:IntegerLiteral", (str(int(value)) if value else "")
            else:
                xsi, shown = "aadl2:RealLiteral", (java_double(float(value)) if value else "")
            attributes = f' value="{shown}"' if shown else ""
            unit = (_get(expr, "unit") or "").strip()
            if not unit:
                out.append(f'{indent}<{tag} xsi:type="{xsi}"{attributes}/>\n')
                return
            if "#" in unit:
                href = unit
            else:
                href = self.literal_href(info.units if info is not None else None, unit, "unit")
            out.append(f'{indent}<{tag} xsi:type="{xsi}"{attributes}>\n')
            out.append(f'{indent}  <unit href="{self.text(href, owner, "unit")}"/>\n')
            out.append(f"{indent}</{tag}>\n")
        elif kind == "StringValue":
            value = _get(expr, "value")
            attributes = f' value="{self.text(value, owner, "string")}"' if value is not None else ""
            out.append(f'{indent}<{tag} xsi:type="aadl2:StringLiteral"{attributes}/>\n')
        elif kind == "BooleanValue":
            attributes = ' value="true"' if _get(expr, "value") else ""
            out.append(f'{indent}<{tag} xsi:type="aadl2:BooleanLiteral"{attributes}/>\n')
        elif kind == "NamedValue":
            xsi, href = self.named_value(expr, info)
            out.append(f'{indent}<{tag} xsi:type="aadl2:NamedValue">\n')
            out.append(f'{indent}  <namedValue xsi:type="{xsi}" href="{self.text(href, owner, "value")}"/>\n')
            out.append(f"{indent}</{tag}>\n")
        elif kind == "RangeValue":
            number = info.inner if info is not None and info.kind == "range" else info
            out.append(f'{indent}<{tag} xsi:type="aadl2:RangeValue">\n')
            for part in ("minimum", "maximum", "delta"):
                bound = getattr(expr, part)
                if bound is not None:
                    self.emit_value(indent + "  ", part, bound, number, owner)
            out.append(f"{indent}</{tag}>\n")
        elif kind == "ListValue":
            items = list(_items(expr, "ownedItems"))
            if not items:
                out.append(f'{indent}<{tag} xsi:type="aadl2:ListValue"/>\n')
                return
            element = info.element if info is not None else None
            out.append(f'{indent}<{tag} xsi:type="aadl2:ListValue">\n')
            for item in items:
                self.emit_value(indent + "  ", "ownedListElement", item, element, owner)
            out.append(f"{indent}</{tag}>\n")
        elif kind == "RecordValue":
            fields = list(_items(expr, "ownedFields"))
            record = self.record_type(
                info, [(f.name or "").strip() for f in fields if "#" not in (f.name or "")]
            )
            out.append(f'{indent}<{tag} xsi:type="aadl2:RecordValue"' + (">\n" if fields else "/>\n"))
            for item in fields:
                name = (_get(item, "name") or "").strip()
                field_info = None
                if "#" in name:
                    href = name
                else:
                    if record is None:
                        raise _Skip(f"record field {name!r} cannot be placed (the record type is not known)")
                    href = self.literal_href(record, name, "record field")
                    position = record.index(name)
                    if position is not None and position < len(record.fields):
                        field_info = record.fields[position]
                out.append(f"{indent}  <ownedFieldValue>\n")
                out.append(f'{indent}    <property href="{self.text(href, owner, "field")}"/>\n')
                if _get(item, "value") is not None:
                    self.emit_value(indent + "    ", "ownedValue", _get(item, "value"), field_info, owner)
                out.append(f"{indent}  </ownedFieldValue>\n")
            if fields:
                out.append(f"{indent}</{tag}>\n")
        elif kind == "InstanceReferenceValue":
            target = self.ref(_get(expr, "referencedInstanceObject"), owner, "a reference value")
            out.append(
                f'{indent}<{tag} xsi:type="instance:InstanceReferenceValue" '
                f'referencedInstanceObject="{target}"/>\n'
            )
        elif kind == "ClassifierValue":
            found = self.classifier_value(_get(expr, "classifier"))
            out.append(f'{indent}<{tag} xsi:type="aadl2:ClassifierValue">\n')
            out.append(
                f'{indent}  <classifier xsi:type="{found[0]}" '
                f'href="{self.text(found[1], owner, "classifier")}"/>\n'
            )
            out.append(f"{indent}</{tag}>\n")
        elif kind == "ReferenceValue":
            steps = (
                [s for s in (_get(expr, "path") or "").split(".") if s]
                if "#" not in (_get(expr, "path") or "")
                else []
            )
            if "#" in (_get(expr, "path") or ""):
                steps = self.opaque_steps(_get(expr, "path"))
            if not steps or not all("#" in s for s in steps):
                raise _Skip(f"the reference ({_get(expr, 'path')}) does not resolve to an instance object")
            out.append(f'{indent}<{tag} xsi:type="aadl2:ReferenceValue">\n')
            depth = indent + "  "
            for step in steps:
                xsi, href = self.opaque_href(step)
                type_attr = f' xsi:type="{xsi}"' if xsi else ""
                out.append(f"{depth}<path>\n")
                out.append(
                    f'{depth}  <namedElement{type_attr} href="{self.text(href, owner, "reference")}"/>\n'
                )
                depth += "  "
            for _ in steps:
                depth = depth[:-2]
                out.append(f"{depth}</path>\n")
            out.append(f"{indent}</{tag}>\n")
        elif kind == "ComputedValue":
            function = _get(expr, "function")
            attributes = f' function="{self.text(function, owner, "function")}"' if function else ""
            out.append(f'{indent}<{tag} xsi:type="aadl2:ComputedValue"{attributes}/>\n')
        elif kind == "OperationValue":
            operator = _OPERATORS.get((_get(expr, "operator") or "and").strip().lower())
            if operator is None:
                raise _Skip(f"operator {_get(expr, 'operator')!r} is not an AADL operator")
            attributes = f' op="{_attr(operator)}"' if operator != "and" else ""
            operands = list(_items(expr, "ownedOperands"))
            out.append(
                f'{indent}<{tag} xsi:type="aadl2:Operation"{attributes}' + (">\n" if operands else "/>\n")
            )
            for operand in operands:
                self.emit_value(indent + "  ", "ownedPropertyExpression", operand, info, owner)
            if operands:
                out.append(f"{indent}</{tag}>\n")
        else:
            raise _Skip(f"a {kind} has no OSATE form")

    @staticmethod
    def opaque_steps(path: str) -> list[str]:
        """Split ``uri#frag.uri#frag`` (a reference path the reader kept, its steps joined by
        dots) into its steps; a fragment is an EMF path (``//@a.1/@b.0``) or a qualified name."""
        steps: list[str] = []
        position = 0
        while position < len(path):
            hash_at = path.find("#", position)
            if hash_at < 0:
                return []
            match = _FRAGMENT_RE.match(path, hash_at + 1)
            if match is None:
                return []
            steps.append(path[position : match.end()])
            position = match.end()
            if position < len(path):
                if path[position] != ".":
                    return []
                position += 1
        return steps

    def classifier_value(self, name: str | None) -> tuple[str, str]:
        element = self.classifier(name)
        if element is not None:
            unit = _unit_of(element)
            return (
                f"aadl2:{self.classifier_class(element)}",
                f"{self.unit_uri(unit)}#{unit.name}.{element.name}",
            )
        text = (name or "").strip()
        if "#" in text:
            xsi, href = self.opaque_href(text)
            return xsi or "aadl2:DataType", href
        package, _, local = text.rpartition("::")
        if not package:
            raise _Skip(f"classifier {text!r} is not qualified and not in the model")
        return "aadl2:DataImplementation" if "." in local else "aadl2:DataType", (
            f"{self.uri_for_name(package)}#{package}.{local}"
        )

    def modal_in_modes(self, names: list[str], owner: EObject) -> str | None:
        """``inMode`` of a modal value: the system operation modes its mode names stand for."""
        targets: list[EObject] = []
        for name in names:
            key = (name or "").split("=>")[0].strip().lower()
            som = self.som_by_name.get(key)
            if som is not None:
                targets.append(som)
                continue
            component = owner
            while component is not None and component.eClass.name not in (
                "ComponentInstance",
                "SystemInstance",
            ):
                component = component.eContainer()
            mode = None
            while component is not None and mode is None:
                mode = self.find(list(component.modeInstances), key)
                component = component.eContainer() if mode is None else component
                if component is not None and not _is(component, "ComponentInstance"):
                    component = None
            if mode is None:
                return None
            targets.extend(
                s for s in self.system.systemOperationModes if any(m is mode for m in s.currentModes)
            )
        return " ".join(self.paths[id(t)] for t in targets)

    def emit_associations(self, indent: str, obj: EObject) -> None:
        for association in _items(obj, "ownedPropertyAssociations"):
            mark = len(self.out)
            try:
                self.emit_association(indent, association, obj)
            except _Skip as exc:
                del self.out[mark:]
                self.skipped.append(f"{_model.instance_path(obj)}: {_get(association, 'property')}: {exc}")

    def emit_association(self, indent: str, association: EObject, obj: EObject) -> None:
        out = self.out
        name = _get(association, "property") or ""
        href, info = self.property_info(name, obj)
        attributes = ""
        if _get(association, "append"):
            attributes += ' append="true"'
        if _get(association, "constant"):
            attributes += ' constant="true"'
        out.append(
            f'{indent}<ownedPropertyAssociation xsi:type="instance:PropertyAssociationInstance"'
            f"{attributes}>\n"
        )
        out.append(f'{indent}  <property href="{self.text(href, obj, "property")}"/>\n')
        for modal in _items(association, "ownedValues"):
            if _get(modal, "value") is None:
                continue
            in_mode = ""
            if len(_items(modal, "inModes")):
                paths = self.modal_in_modes(list(_items(modal, "inModes")), obj)
                if paths is None:
                    raise _Skip(
                        f"in modes ({', '.join(_items(modal, 'inModes'))}) name no system operation mode"
                    )
                in_mode = f' inMode="{paths}"'
            out.append(f"{indent}  <ownedValue{in_mode}>\n")
            self.emit_value(indent + "    ", "ownedValue", _get(modal, "value"), info, obj)
            out.append(f"{indent}  </ownedValue>\n")
        out.append(f"{indent}</ownedPropertyAssociation>\n")

    # ------------------------------------------------------------------ instance objects

    def emit_annexes(self, indent: str, obj: EObject) -> None:
        for annex in obj.annexInstances:
            text = annex.text or ""
            if not text.strip():
                continue
            try:
                element = parse_xml_bytes(text.encode("utf-8"), "<annex instance>").getroot()
            except RosaadlError as exc:
                raise self.error(
                    f"annex instance {annex.name!r} is not well-formed XML: {exc.message}", obj
                ) from None
            if element.tag != "annexInstance":
                raise self.error(
                    f"annex instance {annex.name!r} holds <{element.tag}>, not an annexInstance", obj
                )
            for prefix, uri in element.nsmap.items():
                if prefix is None:
                    raise self.error(f"annex instance {annex.name!r} declares a default namespace", obj)
                known = dict(_NS).get(prefix) or self.extra_ns.get(prefix)
                if known is not None and known != uri:
                    raise self.error(f"annex instance {annex.name!r} redefines the prefix {prefix!r}", obj)
                if prefix not in dict(_NS):
                    self.extra_ns[prefix] = uri
            etree.indent(element, space="  ", level=len(indent) // 2)  # at the annex's depth
            body = etree.tostring(element, encoding="ascii", with_tail=False).decode("ascii")
            # the document's root declares the namespaces; lxml escapes '>' in attribute values
            head, end, rest = body.partition(">")
            head = re.sub(r'\s+xmlns:[A-Za-z_][\w.-]*="[^"]*"', "", head)
            self.out.append(indent + head + end + rest + "\n")

    def emit_component(self, indent: str, ci: EObject, tag: str, *, root_attrs: str = "") -> None:
        out = self.out
        is_root = ci.eContainer() is None or not _is(ci.eContainer(), "InstanceObject")
        category = _java_literal(_get(ci, "category"))
        attributes = f' name="{self.text(_get(ci, "name") or "", ci, "name")}"'
        if category and category != "abstract":
            attributes += f' category="{category}"'
        if len(_items(ci, "inModes")):
            parent = ci.eContainer()
            modes = []
            for mode_name in _items(ci, "inModes"):
                mode = (
                    self.find(list(_items(parent, "modeInstances")), mode_name)
                    if _is(parent, "ComponentInstance")
                    else None
                )
                if mode is None:
                    raise self.error(f"in modes names {mode_name!r}, which is not a mode of the parent", ci)
                modes.append(self.paths[id(mode)])
            attributes += f' inMode="{" ".join(modes)}"'
        start = len(out)
        out.append(f"{indent}<{tag}{root_attrs}{attributes}>\n")
        inner = indent + "  "
        body_start = len(out)
        self.emit_associations(inner, ci)
        self.emit_annexes(inner, ci)
        decls: dict[int, EObject | None] = {}
        for fi in _items(ci, "featureInstances"):
            self.emit_feature(inner, fi, decls)
        for child in _items(ci, "componentInstances"):
            self.emit_component(inner, child, "componentInstance")
        for mi in _items(ci, "modeInstances"):
            self.emit_mode(inner, mi)
        for mti in _items(ci, "modeTransitionInstances"):
            self.emit_transition(inner, mti)
        for fsi in _items(ci, "flowSpecifications"):
            self.emit_flow_spec(inner, fsi)
        for flow in _items(ci, "endToEndFlows"):
            self.emit_end_to_end(inner, flow)
        for conn in _items(ci, "connectionInstances"):
            self.emit_connection(inner, conn)
        if not is_root:
            sub = self.subcomponent_href(ci)
            if sub is not None:
                out.append(
                    f'{inner}<subcomponent xsi:type="{sub[0]}" href="{self.text(sub[1], ci, "href")}"/>\n'
                )
            else:
                self.note_missing("subcomponent")
            indexes = [int(i) for i in _items(ci, "index")] or [0]
            out.extend(f"{inner}<index>{i}</index>\n" for i in indexes)
        else:
            out.extend(f"{inner}<index>{int(i)}</index>\n" for i in _items(ci, "index"))
        category_value = _get(ci, "category")
        classifier = self.classifier_href(_get(ci, "classifier"), category_value, implementation=False)
        if classifier is not None:
            out.append(
                f'{inner}<classifier xsi:type="{classifier[0]}" '
                f'href="{self.text(classifier[1], ci, "href")}"/>\n'
            )
        if ci.eClass.name == "SystemInstance":
            soms = list(_items(ci, "systemOperationModes"))
            for som in soms:
                som_attrs = f' name="{self.text(_get(som, "name") or "", ci, "name")}"'
                current = _items(som, "currentModes")
                if len(current):
                    som_attrs += f' currentMode="{self.refs(current, ci, "a system operation mode")}"'
                out.append(f"{inner}<systemOperationMode{som_attrs}/>\n")
            if not soms:
                out.append(f'{inner}<systemOperationMode name="No Modes"/>\n')
            impl = self.classifier_href(_get(ci, "classifier"), _get(ci, "category"), implementation=True)
            if impl is not None:
                out.append(
                    f'{inner}<componentImplementation xsi:type="{impl[0]}" '
                    f'href="{self.text(impl[1], ci, "href")}"/>\n'
                )
        if len(out) == body_start:
            out[start] = f"{indent}<{tag}{root_attrs}{attributes}/>\n"
        else:
            out.append(f"{indent}</{tag}>\n")

    def emit_feature(self, indent: str, fi: EObject, decls: dict[int, EObject | None]) -> None:
        out = self.out
        category = _name(_get(fi, "category"))
        category = _INSTANCE_FEATURE_CATEGORY.get(category, category)
        attributes = f' name="{self.text(_get(fi, "name") or "", fi, "name")}"'
        if category and category != "dataPort":
            attributes += f' category="{category}"'
        direction = _java_literal(_get(fi, "direction") or "in")
        if direction != "in":
            attributes += f' direction="{direction}"'
        feature_index = _get(fi, "index")
        if feature_index:
            attributes += f' index="{int(feature_index)}"'
        if _get(fi, "type") is not None:
            attributes += f' type="{self.ref(_get(fi, "type"), fi, "the feature type")}"'
        decl = self.feature_decl(fi, decls)
        decls[id(fi)] = decl
        start = len(out)
        out.append(f"{indent}<featureInstance{attributes}>\n")
        inner = indent + "  "
        self.emit_associations(inner, fi)
        for child in _items(fi, "featureInstances"):
            self.emit_feature(inner, child, decls)
        href = self.member_href(decl) if decl is not None else None
        if href is not None:
            out.append(f'{inner}<feature xsi:type="{href[0]}" href="{self.text(href[1], fi, "href")}"/>\n')
        else:
            self.note_missing("feature")
        if len(out) == start + 1:
            out[start] = f"{indent}<featureInstance{attributes}/>\n"
        else:
            out.append(f"{indent}</featureInstance>\n")

    def emit_connection(self, indent: str, conn: EObject) -> None:
        out = self.out
        attributes = f' name="{self.text(_get(conn, "name") or "", conn, "name")}"'
        if len(_items(conn, "inSystemOperationModes")):
            soms = []
            for name in _items(conn, "inSystemOperationModes"):
                som = self.som_by_name.get((name or "").lower())
                if som is None:
                    raise self.error(
                        f"the connection exists in {name!r}, which is not a system operation mode", conn
                    )
                soms.append(self.paths[id(som)])
            attributes += f' inSystemOperationMode="{" ".join(soms)}"'
        if _get(conn, "complete"):
            attributes += ' complete="true"'
        kind = _name(_get(conn, "kind"))
        if kind and kind != "featureConnection":
            attributes += f' kind="{kind}"'
        attributes += f' destination="{self.ref(_get(conn, "destination"), conn, "the destination")}"'
        if _get(conn, "bidirectional"):
            attributes += ' bidirectional="true"'
        attributes += f' source="{self.ref(_get(conn, "source"), conn, "the source")}"'
        out.append(f"{indent}<connectionInstance{attributes}>\n")
        inner = indent + "  "
        self.emit_associations(inner, conn)
        for ref in _items(conn, "connectionReferences"):
            context = self.ref(_get(ref, "context"), conn, "a connection reference context")
            source = self.ref(_get(ref, "source"), conn, "a connection reference source")
            destination = self.ref(_get(ref, "destination"), conn, "a connection reference destination")
            ref_attrs = f' context="{context}" source="{source}" destination="{destination}"'
            if _get(ref, "reverse"):
                ref_attrs += ' reverse="true"'
            href = self.connection_href(ref)
            if href is None:
                self.note_missing("connection")
                out.append(f"{inner}<connectionReference{ref_attrs}/>\n")
                continue
            type_attr = f' xsi:type="{href[0]}"' if href[0] else ""
            out.append(f"{inner}<connectionReference{ref_attrs}>\n")
            out.append(f'{inner}  <connection{type_attr} href="{self.text(href[1], conn, "href")}"/>\n')
            out.append(f"{inner}</connectionReference>\n")
        out.append(f"{indent}</connectionInstance>\n")

    def emit_simple(
        self, indent: str, obj: EObject, tag: str, attributes: str, link: tuple[str, Any] | None
    ) -> None:
        """An instance object with associations and one link element to its declaration."""
        out = self.out
        start = len(out)
        out.append(f"{indent}<{tag}{attributes}>\n")
        self.emit_associations(indent + "  ", obj)
        if link is not None and link[1] is not None:
            link_tag, (_xsi, href) = link
            out.append(f'{indent}  <{link_tag} href="{self.text(href, obj, "href")}"/>\n')
        elif link is not None:
            self.note_missing(link[0])
        if len(out) == start + 1:
            out[start] = f"{indent}<{tag}{attributes}/>\n"
        else:
            out.append(f"{indent}</{tag}>\n")

    def emit_mode(self, indent: str, mi: EObject) -> None:
        attributes = f' name="{self.text(mi.name or "", mi, "name")}"'
        if mi.initial:
            attributes += ' initial="true"'
        self.emit_simple(indent, mi, "modeInstance", attributes, ("mode", self.mode_href(mi)))

    def emit_transition(self, indent: str, mti: EObject) -> None:
        attributes = f' name="{self.text(mti.name or "", mti, "name")}"'
        attributes += f' destination="{self.ref(mti.destination, mti, "the destination mode")}"'
        if len(mti.triggers):
            attributes += f' trigger="{self.refs(mti.triggers, mti, "a trigger")}"'
        attributes += f' source="{self.ref(mti.source, mti, "the source mode")}"'
        self.emit_simple(
            indent, mti, "modeTransitionInstance", attributes, ("modeTransition", self.transition_href(mti))
        )

    def emit_flow_spec(self, indent: str, fsi: EObject) -> None:
        attributes = f' name="{self.text(fsi.name or "", fsi, "name")}"'
        if fsi.source is not None:
            attributes += f' source="{self.ref(fsi.source, fsi, "the flow source")}"'
        if fsi.destination is not None:
            attributes += f' destination="{self.ref(fsi.destination, fsi, "the flow destination")}"'
        self.emit_simple(
            indent, fsi, "flowSpecification", attributes, ("flowSpecification", self.flow_spec_href(fsi))
        )

    def emit_end_to_end(self, indent: str, flow: EObject) -> None:
        attributes = f' name="{self.text(flow.name or "", flow, "name")}"'
        if len(flow.flowElements):
            attributes += f' flowElement="{self.refs(flow.flowElements, flow, "a flow element")}"'
        self.emit_simple(
            indent, flow, "endToEndFlow", attributes, ("endToEndFlow", self.end_to_end_href(flow))
        )

    # ------------------------------------------------------------------ document

    def run(self) -> bytes:
        self.roots = [self.system, *self.extra_roots()]
        self.assign_paths()
        for _attempt in range(4):
            text = self.document()
            if not self.wanted_set_eras:
                break
            # a value exists only in an older layout of one of OSATE's sets: write every
            # reference into that set in that layout, and start again
            self.set_eras.update(self.wanted_set_eras)
        self.report()
        return text.encode("ascii")

    def document(self) -> str:
        self.out = body = []
        self.used_units.clear()
        self.guessed_units.clear()
        self.missing.clear()
        self.skipped.clear()
        self.literal_cache.clear()
        self.extra_ns.clear()
        self.wanted_set_eras = {}
        multi = len(self.roots) > 1
        if multi:
            for number, root in enumerate(self.roots):
                tag = "instance:SystemInstance" if number == 0 else "instance:ComponentInstance"
                self.emit_component("  ", root, tag)
        else:
            self.emit_component("", self.system, "instance:SystemInstance", root_attrs="\x00")
        namespaces = dict(_NS)
        for prefix, uri in self.extra_ns.items():
            namespaces.setdefault(prefix, uri)
        ordered = [("xmi", namespaces.pop("xmi")), ("xsi", namespaces.pop("xsi"))]
        ordered += sorted(namespaces.items())
        declaration = ' xmi:version="2.0"' + "".join(f' xmlns:{p}="{u}"' for p, u in ordered)
        head = '<?xml version="1.0" encoding="ASCII"?>\n'
        if multi:
            return head + f"<xmi:XMI{declaration}>\n" + "".join(body) + "</xmi:XMI>\n"
        body[0] = body[0].replace("\x00", declaration, 1)
        return head + "".join(body)

    def report(self) -> None:
        for set_name, era in sorted(self.set_eras.items()):
            spelled = next(
                (n for n in osate_eras.table(era).property_sets() if n.lower() == set_name), set_name
            )
            self.warn(
                f"references into OSATE's {spelled} follow its {era} layout: a value "
                "exists only there (OSATE has since renamed it, and today's OSATE does not resolve it)"
            )
        for what, count in sorted(self.missing.items()):
            self.warn(
                f"{count} {what} link(s) left out: the declarative element is not in the model "
                "(OSATE re-instantiates from the .aadl sources)"
            )
        if self.guessed_units:
            names = ", ".join(sorted(self.guessed_units.values(), key=str.lower))
            self.warn(f"units not in the model, referred to as ../<name>.aadl: {names}")
        for line in self.skipped[:20]:
            self.warn(f"property association left out: {line}")
        if len(self.skipped) > 20:
            self.warn(f"... and {len(self.skipped) - 20} more property association(s) left out")

    # ------------------------------------------------------------------ sidecars

    def sidecars(self) -> dict[str, str]:
        """The ``.aadl`` texts of the units the file refers to and the units they name in ``with``."""
        from rosaadl.exporters.aadl_text import unit_file_name, write_unit

        if self.resolver is None:
            return {}
        order: list[EObject] = []
        seen: set[int] = set()
        pending = list(self.used_units.values())
        missing: set[str] = set()
        while pending:
            unit = pending.pop(0)
            if id(unit) in seen or _osate_unit(unit.name):
                continue
            seen.add(id(unit))
            order.append(unit)
            for name in list(unit.withs) + list(getattr(unit, "privateWiths", []) or []):
                target = self.resolver.unit(name)
                if target is None:
                    if not _osate_unit(name):
                        missing.add(name)
                    continue
                pending.append(target)
        if missing:
            self.warn(
                f"units named in with clauses are not in the model, not written: {', '.join(sorted(missing))}"
            )
        texts: dict[str, str] = {}
        lowered: dict[str, str] = {}
        for unit in sorted(order, key=lambda u: (u.name or "").lower()):
            name = unit_file_name(unit)
            if name.lower() in lowered:
                raise ExportError(
                    f"units {lowered[name.lower()]!r} and {unit.name!r} would both be written to {name!r}",
                    Location(path=unit.name),
                )
            lowered[name.lower()] = unit.name
            texts[name] = write_unit(unit)
        return texts


# =========================================================================== public API


def export_aaxl2(subject: EObject, *, root: str | None = None) -> Aaxl2Export:
    """An instance as an OSATE ``.aaxl2`` document and its ``.aadl`` sidecars, in memory.

    ``subject`` is a ``SystemInstance`` or an ``AadlModel``; ``root`` (``Pkg::Sys.impl``) picks
    the instance of the model to write, or the implementation to instantiate when the model holds
    no such instance. Problems are :class:`ExportError` naming the instance path.
    """
    diagnostics: list[Diagnostic] = []
    system, aadl_model = _select(subject, root, diagnostics)
    writer = _Writer(system, aadl_model, diagnostics)
    data = writer.run()
    sidecars = writer.sidecars()
    file_name = f"{INSTANCES_FOLDER}/{instance_file_name(system)}"
    return Aaxl2Export(file_name, data, sidecars, diagnostics, system)


def dumps_aaxl2(
    subject: EObject, *, root: str | None = None, warnings: list[Diagnostic] | None = None
) -> bytes:
    """The ``.aaxl2`` bytes of an instance (see :func:`export_aaxl2`); warnings are logged and
    appended to ``warnings`` when given."""
    result = export_aaxl2(subject, root=root)
    if warnings is not None:
        warnings.extend(result.warnings)
    return result.data


def write_aaxl2(
    subject: EObject,
    out_dir: str | os.PathLike[str],
    *,
    root: str | None = None,
    warnings: list[Diagnostic] | None = None,
) -> Path:
    """Write ``instances/<Name>_Instance.aaxl2`` and its ``.aadl`` sidecars into ``out_dir``.

    Everything is made in memory first, so an error leaves no output; each file is written
    atomically and no path lands outside ``out_dir``. Returns the path of the ``.aaxl2`` file;
    warnings are logged and appended to ``warnings`` when given.
    """
    result = export_aaxl2(subject, root=root)
    targets = [(safe_join(out_dir, name), text) for name, text in result.sidecars.items()]
    instance_path = safe_join(out_dir, *result.file_name.split("/"))
    for target, text in targets:
        atomic_write_text(target, text)
    atomic_write_bytes(instance_path, result.data)
    if warnings is not None:
        warnings.extend(result.warnings)
    return instance_path
