"""Read OSATE ``.aaxl2`` files: instance models (and declarative packages / property sets).

:func:`read_aaxl2` turns an OSATE instance file into our instance model (see
``docs/instance-model.md``): an ``AadlModel`` whose ``instances`` hold the ``SystemInstance``
roots, with component, feature, connection, flow and mode instances and the property values
OSATE resolved onto them. Declarative ``.aaxl2`` files (root ``aadl2:Package`` or
``aadl2:PropertySet``) become an ``AadlPackage`` / ``PropertySet`` in ``AadlModel.units``.

What the file format gives, and how it is decoded:

* Intra-file references: ``//@componentInstance.4/@featureInstance.0`` (``/`` is the root,
  ``/1/@…`` the second root of an ``xmi:XMI`` file), space-separated lists, or ``xmi:id``
  UUIDs in 2014 files. All must resolve; a dangling one is a located error.
* References into the declarative model are ``href`` child elements: classifiers and
  properties by qualified name (``../P.aadl#P.L.i`` → ``P::L.i``,
  ``…#Timing_Properties.Period`` → ``Timing_Properties::Period``); subcomponents, features,
  modes and flows by position, whose names are those of the instance elements. Declared
  connections are only known by position: ``ConnectionReference.connection`` keeps the href
  (``uri#fragment``) until the ``.aadl`` sidecars are read.
* Units, enumeration literals and record fields are positional hrefs into the property set
  that declares them. For OSATE's predeclared sets they are decoded with the per-era tables
  of :mod:`rosaadl.importers.osate_eras`; the era is chosen from the URI forms and checked
  against every such href (see :func:`osate_eras.choose_era`) and recorded on the result.
  Hrefs into other property sets keep their ``uri#fragment`` text and are reported once
  per property set.
* EMF omits default values: a component without ``category`` is abstract, a feature without
  one a data port, no ``direction`` is ``in``, no ``kind`` a feature connection, booleans false.
* Annex instances (EMV2) are kept opaque: an ``AnnexInstance`` with the element's XML text.

Speed: pyecore's normal object construction costs about 25 µs per object (feature lookups,
value checks, notifications to listeners a new object cannot have yet). The reader builds
objects through :class:`FastFactory`, which writes the state pyecore would (attribute value
holders, container and containment feature; ``_isset``, which saving reads, and inverse
references are made on first read from those) directly, in about a tenth of that time, and
pauses the cyclic garbage collector while it builds (:func:`gc_paused`). The file is parsed
without its indentation (half the nodes), and the parsed document is freed last
(:meth:`_Reader.release`), so that glibc does not merge its freed nodes within the call.
"""

from __future__ import annotations

import logging
import os
from dataclasses import dataclass, field
from functools import cache, cached_property
from pathlib import Path
from typing import Any

from lxml import etree
from pyecore.ecore import EClass, EEnum, EObject

from rosaadl import metamodels, model
from rosaadl.bulk import FastFactory, FeatureSlot, gc_paused
from rosaadl.errors import Diagnostic, ImportFormatError, Location, RosaadlError
from rosaadl.fileio import parse_xml_bytes
from rosaadl.importers import osate_eras

__all__ = [
    "ImportResult",
    "read_aaxl2",
    "loads_aaxl2",
    "DEFAULT_MAX_BYTES",
]

log = logging.getLogger(__name__)

#: Files larger than this are refused before parsing (override with ``max_bytes``).
DEFAULT_MAX_BYTES = 512 * 1024 * 1024

NS_XMI = "http://www.omg.org/XMI"
NS_XSI = "http://www.w3.org/2001/XMLSchema-instance"
NS_AADL2 = "http://aadl.info/AADL/2.0"
NS_INSTANCE = "http://aadl.info/AADL/2.0/instance"

_XSI_TYPE = f"{{{NS_XSI}}}type"
# the same key as bytes: lxml reads an attribute by it without encoding the key each time
_XSI_TYPE_KEY = _XSI_TYPE.encode()
_XMI_ID = f"{{{NS_XMI}}}id"
_XMI_ID_KEY = _XMI_ID.encode()
_ROOT_SYSTEM = f"{{{NS_INSTANCE}}}SystemInstance"
_ROOT_COMPONENT = f"{{{NS_INSTANCE}}}ComponentInstance"
_ROOT_XMI = f"{{{NS_XMI}}}XMI"
_ROOT_PACKAGE = f"{{{NS_AADL2}}}Package"
_ROOT_PROPERTY_SET = f"{{{NS_AADL2}}}PropertySet"


# =========================================================================== result


@dataclass
class ImportResult:
    """What :func:`read_aaxl2` produced.

    ``model`` is an ``AadlModel``: ``instances`` (SystemInstance roots), ``componentInstances``
    (further ``ComponentInstance`` roots of an ``xmi:XMI`` file, such as the data-type
    instances ``FeatureInstance.type`` refers to) and ``units`` (for declarative files).
    ``era`` is the OSATE era whose predeclared property sets the file refers to (None when it
    refers to none); ``property_set_eras`` names the sets decoded with another era's table
    (see :class:`osate_eras.EraChoice`); ``warnings`` also holds ``info`` diagnostics;
    ``sidecars`` maps each declarative ``.aadl`` URI the file refers to
    (other than predeclared sets) to its resolved path and whether that file is present
    (looked up on first use: an import itself touches no file).
    """

    model: EObject
    source: str
    kind: str  # "instance" | "package" | "property set"
    era: str | None = None
    property_set_eras: dict[str, str] = field(default_factory=dict)
    warnings: list[Diagnostic] = field(default_factory=list)
    # the declarative URIs, and the directory relative ones resolve against (None: kept as URIs;
    # not normalised, the paths in ``sidecars`` are)
    sidecar_uris: tuple[str, ...] = ()
    base_dir: str | None = None

    @cached_property
    def sidecars(self) -> dict[str, tuple[str, bool]]:
        out = {}
        for uri in self.sidecar_uris:
            if self.base_dir is None or ":" in uri.split("/")[0]:
                out[uri] = (uri, False)
                continue
            resolved = os.path.normpath(os.path.join(self.base_dir, uri))
            out[uri] = (resolved, os.path.isfile(resolved))
        return out

    @property
    def instances(self) -> list[EObject]:
        return list(self.model.instances)

    @property
    def root(self) -> EObject | None:
        """The first system instance (None for declarative files)."""
        return self.model.instances[0] if self.model.instances else None


# =========================================================================== hrefs


def _qualified_name(fragment: str) -> str:
    """Xtext qualified name ``P.L.i`` / ``a::b.L.i`` / ``Set.Prop`` → ``P::L.i`` / ``a::b::L.i``."""
    head, sep, local = fragment.partition(".")
    if not sep:
        return fragment
    return f"{head}::{local}"


def _name_of(uri: str, fragment: str) -> str:
    """A link as we keep it: ``P::L.i`` for a fragment by qualified name, else ``uri#fragment``."""
    if not fragment or _is_positional(fragment):
        return f"{uri}#{fragment}"
    return _qualified_name(fragment)


def _is_positional(fragment: str) -> bool:
    return fragment.startswith("/") or fragment.startswith("@")


def _split_ref_attribute(text: str) -> tuple[str | None, str, str]:
    """Attribute-form reference ``aadl2:DataType ../X.aadl#X.T`` → (type, uri, fragment)."""
    xsi_type = None
    value = text.strip()
    if " " in value:
        xsi_type, _, value = value.partition(" ")
    uri, _, frag = value.partition("#")
    return xsi_type, uri, frag


# =========================================================================== reader


# xsi:type local names that may appear on declarative link elements (checked, never guessed).
_FEATURE_TYPES = frozenset(
    {
        "DataPort",
        "EventPort",
        "EventDataPort",
        "Parameter",
        "BusAccess",
        "DataAccess",
        "SubprogramAccess",
        "SubprogramGroupAccess",
        "VirtualBusAccess",
        "FeatureGroup",
        "AbstractFeature",
        "FeaturePrototype",
    }
)
_CATEGORIES = (
    "Abstract",
    "Bus",
    "Data",
    "Device",
    "Memory",
    "Process",
    "Processor",
    "Subprogram",
    "SubprogramGroup",
    "System",
    "Thread",
    "ThreadGroup",
    "VirtualBus",
    "VirtualProcessor",
)
_SUBCOMPONENT_TYPES = frozenset(f"{c}Subcomponent" for c in _CATEGORIES)
_CLASSIFIER_TYPES = frozenset(
    [f"{c}Type" for c in _CATEGORIES] + [f"{c}Implementation" for c in _CATEGORIES] + ["FeatureGroupType"]
)
_CONNECTION_TYPES = frozenset(
    {
        "PortConnection",
        "AccessConnection",
        "FeatureConnection",
        "FeatureGroupConnection",
        "ParameterConnection",
    }
)

# instance element tag → feature of our metamodel holding the objects made from it; the
# per-tag position of a child in its parent is what ``@tag.N`` in a reference means.
_TAG_FEATURE = {
    "componentInstance": "componentInstances",
    "featureInstance": "featureInstances",
    "connectionInstance": "connectionInstances",
    "flowSpecification": "flowSpecifications",
    "endToEndFlow": "endToEndFlows",
    "modeInstance": "modeInstances",
    "modeTransitionInstance": "modeTransitionInstances",
    "systemOperationMode": "systemOperationModes",
    "connectionReference": "connectionReferences",
    "ownedPropertyAssociation": "ownedPropertyAssociations",
    "annexInstance": "annexInstances",
}

_PA_IGNORED = frozenset({"property", "propertyAssociation", "appliesTo", "inBinding"})

# elements that only link an instance object to its declarative element, whose name the
# instance object already carries (kept by position in the file, not needed here).
_DECLARATIVE_LINKS = frozenset(
    {
        "feature",
        "subcomponent",
        "flowSpecification",
        "endToEndFlow",
        "mode",
        "modeTransition",
        "propertyAssociation",
    }
)


@dataclass(frozen=True)
class _MetamodelFacts:
    """What the reader needs from aadl.ecore, looked up once per process (immutable metadata)."""

    eclasses: dict[str, EClass]
    enums: dict[str, EEnum]
    classes: dict[str, type]
    slots: dict[str, FeatureSlot]
    enum_literals: dict[tuple[str, str], Any]
    # the attributes every _Reader starts with (read-only to it)
    reader_constants: dict[str, Any]


@cache
def _metamodel_facts() -> _MetamodelFacts:
    mm = metamodels.load().aadl
    eclasses = {c.name: c for c in mm.eClassifiers if isinstance(c, EClass)}
    enums = {c.name: c for c in mm.eClassifiers if isinstance(c, EEnum)}
    classes = {name: ec.python_class for name, ec in eclasses.items()}
    for name, cls in classes.items():
        if not eclasses[name].abstract:
            FastFactory.prepare(cls)  # the reader makes their objects with object.__new__
    factory = FastFactory()
    f = {}
    wanted = {
        "AadlModel": ("name", "instances", "componentInstances", "units"),
        "ComponentInstance": (
            "name",
            "category",
            "classifier",
            "subcomponent",
            "index",
            "componentInstances",
            "featureInstances",
            "connectionInstances",
            "modeInstances",
            "modeTransitionInstances",
            "flowSpecifications",
            "endToEndFlows",
            "inModes",
            "annexInstances",
            "ownedPropertyAssociations",
        ),
        "SystemInstance": ("systemOperationModes",),
        "FeatureInstance": (
            "name",
            "category",
            "direction",
            "feature",
            "index",
            "featureInstances",
            "type",
            "ownedPropertyAssociations",
        ),
        "ConnectionInstance": (
            "name",
            "kind",
            "bidirectional",
            "complete",
            "source",
            "destination",
            "connectionReferences",
            "inSystemOperationModes",
            "ownedPropertyAssociations",
        ),
        "ConnectionReference": ("connection", "context", "source", "destination"),
        "ModeInstance": ("name", "initial", "mode", "ownedPropertyAssociations"),
        "ModeTransitionInstance": (
            "name",
            "source",
            "destination",
            "triggers",
            "ownedPropertyAssociations",
        ),
        "FlowSpecificationInstance": (
            "name",
            "kind",
            "source",
            "destination",
            "ownedPropertyAssociations",
        ),
        "EndToEndFlowInstance": ("name", "flow", "flowElements", "ownedPropertyAssociations"),
        "SystemOperationMode": ("name", "currentModes"),
        "AnnexInstance": ("name", "text"),
        "PropertyAssociation": ("property", "append", "constant", "ownedValues"),
        "ModalPropertyValue": ("value", "inModes"),
        "IntegerValue": ("value", "unit"),
        "RealValue": ("value", "unit"),
        "RangeValue": ("minimum", "maximum", "delta"),
        "BooleanValue": ("value",),
        "StringValue": ("value",),
        "NamedValue": ("name",),
        "ReferenceValue": ("path",),
        "ClassifierValue": ("classifier",),
        "ListValue": ("ownedItems",),
        "RecordValue": ("ownedFields",),
        "FieldValue": ("name", "value"),
        "ComputedValue": ("function",),
        "OperationValue": ("operator", "ownedOperands"),
        "InstanceReferenceValue": ("referencedInstanceObject",),
    }
    for cname, names in wanted.items():
        ec = eclasses[cname]
        for name in names:
            try:
                f[f"{cname}.{name}"] = factory.slot(ec, name)
            except KeyError:
                raise RosaadlError(f"metamodel class {cname} lacks feature {name}") from None
    literals = {}
    for enum in enums.values():
        for literal in enum.eLiterals:
            for text in (literal.name, literal.literal):
                if text:
                    literals[(enum.name, text)] = literal
    constants = {
        "fast": factory,
        # the classes are prepared (above): FastFactory.new without its check
        "new": object.__new__,
        "ec": eclasses,
        "enums": enums,
        "cls": classes,
        "f": f,
        "c_pa": classes["PropertyAssociation"],
        "c_modal": classes["ModalPropertyValue"],
        "c_int": classes["IntegerValue"],
        "c_real": classes["RealValue"],
        "s_pa_property": f["PropertyAssociation.property"],
        "s_pa_values": f["PropertyAssociation.ownedValues"],
        "s_modal_value": f["ModalPropertyValue.value"],
        "s_int_value": f["IntegerValue.value"],
        "s_int_unit": f["IntegerValue.unit"],
        "s_real_value": f["RealValue.value"],
        "s_real_unit": f["RealValue.unit"],
        "s_named_name": f["NamedValue.name"],
        "s_reference_ends": tuple(
            (end, f[f"ConnectionReference.{end}"]) for end in ("context", "source", "destination")
        ),
        "s_connection_ends": tuple(
            (end, f[f"ConnectionInstance.{end}"]) for end in ("source", "destination")
        ),
    }
    return _MetamodelFacts(eclasses, enums, classes, f, literals, constants)


def _directory_of(filename: str) -> str | None:
    """The directory a file's relative sidecar URIs resolve against (None for ``<...>`` names)."""
    if not filename or filename.startswith("<"):
        return None
    directory = os.path.dirname(filename)
    return directory if os.path.isabs(filename) else os.path.join(os.getcwd(), directory)


class _Reader:
    """One read of one file (no state survives it)."""

    def __init__(self, filename: str, tree: etree._ElementTree, *, strict: bool) -> None:
        meta = _metamodel_facts()
        # what is the same for every read (metamodel classes, feature slots), in one step
        self.__dict__.update(meta.reader_constants)
        self.filename = filename
        self.tree = tree
        self.strict = strict
        # sidecar paths are normalised when they are looked up (ImportResult.sidecars)
        self.base_dir = _directory_of(filename)
        self.warnings: list[Diagnostic] = []
        self.enum_cache: dict[tuple[str, str], Any] = dict(meta.enum_literals)
        self.ids: dict[str, EObject] = {}
        self.roots: list[EObject] = []
        # reference attributes to resolve once every object exists:
        # (object, slot, text, element, attribute, many, names_of)
        self.pending: list[tuple] = []
        # positional literal hrefs into property sets, decoded once the era is known:
        # (uri, fragment, role, property, field href) → [(object, feature name)]
        self.literal_uses: dict[tuple, list[tuple[EObject, str]]] = {}
        self.href_cache: dict[str, tuple[str, str]] = {}
        self.link_names: dict[str, str] = {}
        # a unit's (href, property, field href) → (the unit kept until decoded, its literal_uses list)
        self.unit_uses: dict[tuple, tuple[str, list]] = {}
        self.xsi_cache: dict[tuple[str, str], tuple[str, str]] = {}
        self.unknown_tags: dict[tuple[str, str], int] = {}
        self.declarative_uris: set[str] = set()
        self.seen_uris: set[str] = set()
        # the root's namespace prefixes (lxml makes a new dict at each read of nsmap)
        self.nsmap: dict[str | None, str] = tree.getroot().nsmap
        self.has_ids = True
        self.nsmap_is_global = True
        self.property_cache: dict[str, tuple[str, bool]] = {}
        self.handler_cache: dict[str, Any] = {}
        self.link_types_ok: set[tuple[str | None, frozenset[str]]] = set()
        self.path_cache: dict[str, EObject] = {}
        # a record field's (uri, fragment) → (the name kept for it, whether it is positional)
        self.field_names: dict[tuple[str, str], tuple[str, bool]] = {}
        # a named value's (uri, fragment) → (its name, whether it is positional)
        self.named_values: dict[tuple[str, str], tuple[str, bool]] = {}

    def release(self) -> None:
        """Free the reader's tables before the parsed document (which goes with the caller's
        last reference to it, at the end of the call).

        In that order, nothing large is freed or allocated after the document within the call:
        glibc keeps the document's ~10^5 small freed nodes in its fast bins, and the next large
        request merges them all at once (about 40 ms for a 10 MB file, cold in the cache). Freed
        last, they are reused chunk for chunk by the next parse instead, as by a bare parse.
        """
        tree = self.tree
        self.__dict__.clear()
        del tree

    # ------------------------------------------------------------------ helpers

    def location(self, element: etree._Element | None, attribute: str | None = None) -> Location:
        if element is None:
            return Location(file=self.filename)
        try:
            path = self.tree.getpath(element)
        except ValueError:
            path = None
        if path and attribute:
            path = f"{path}/@{attribute}"
        return Location(file=self.filename, line=element.sourceline, path=path)

    def error(self, message: str, element: etree._Element | None = None, attribute: str | None = None):
        return ImportFormatError(message, self.location(element, attribute))

    def warn(self, message: str, element: etree._Element | None = None) -> None:
        self.warnings.append(Diagnostic("warning", message, self.location(element)))

    def unknown(self, element: etree._Element, parent: str) -> None:
        tag = element.tag
        if not isinstance(tag, str):  # comments, processing instructions
            return
        if self.strict:
            raise self.error(f"unexpected element <{tag}> in {parent}", element)
        key = (parent, tag)
        if key not in self.unknown_tags:
            self.warn(f"skipped unknown element <{tag}> in {parent} (and any further ones there)", element)
        self.unknown_tags[key] = self.unknown_tags.get(key, 0) + 1

    def xsi_type(self, element: etree._Element, required: bool = True) -> tuple[str, str] | None:
        """(namespace URI, local name) of the element's ``xsi:type``."""
        text = element.get(_XSI_TYPE)
        if text is None:
            if required:
                raise self.error(f"<{element.tag}> has no xsi:type; expected one naming its class", element)
            return None
        key = (text, "")
        found = self.xsi_cache.get(key)
        if found is None:
            prefix, sep, local = text.rpartition(":")
            ns = self.nsmap.get(prefix if sep else None)
            if ns is None:
                ns = element.nsmap.get(prefix if sep else None)
            if ns is None:
                raise self.error(
                    f"xsi:type {text!r} uses an undeclared namespace prefix", element, "xsi:type"
                )
            found = (ns, local)
            if self.nsmap_is_global:
                self.xsi_cache[key] = found
        return found

    def enum(self, enum_name: str, text: str, element: etree._Element, attribute: str):
        key = (enum_name, text)
        literal = self.enum_cache.get(key)
        if literal is None:
            try:
                literal = self.enums[enum_name].from_string(text)
            except RosaadlError as exc:
                raise self.error(exc.message, element, attribute) from None
            self.enum_cache[key] = literal
        return literal

    def int_text(self, text: str | None, element: etree._Element, attribute: str) -> int:
        if text is None:
            return 0
        try:
            return int(text.strip())
        except ValueError:
            raise self.error(f"{attribute} {text!r} is not an integer", element, attribute) from None

    def href(self, element: etree._Element) -> tuple[str, str]:
        """(uri, fragment) of a link element's ``href``."""
        text = element.get("href")
        if text is None:
            raise self.error(f"<{element.tag}> has no href", element)
        found = self.href_cache.get(text)
        if found is None:
            uri, _, frag = text.partition("#")
            found = (uri, frag)
            self.href_cache[text] = found
            self.note_uri(uri)
        return found

    def link_checked(self, element: etree._Element) -> None:
        """A link element whose target the instance object already names (a subcomponent's, a
        feature's): only its href's presence and file are noted (see :attr:`ImportResult.sidecars`)."""
        text = element.get("href")
        if text is None:
            raise self.error(f"<{element.tag}> has no href", element)
        self.note_uri(text.partition("#")[0])

    def note_uri(self, uri: str) -> None:
        if uri and uri not in self.seen_uris:
            self.seen_uris.add(uri)
            if osate_eras.classify_uri(uri) is None:
                self.declarative_uris.add(uri)

    def check_link_type(self, element: etree._Element, allowed: frozenset[str]) -> None:
        key = (element.get(_XSI_TYPE_KEY), allowed)
        if key in self.link_types_ok:
            return
        ns, local = self.xsi_type(element)
        if ns == NS_AADL2 and local in allowed:
            if self.nsmap_is_global:
                self.link_types_ok.add(key)
            return
        raise self.error(
            f"<{element.tag}> has unknown xsi:type {element.get(_XSI_TYPE)!r} "
            f"(expected aadl2: one of {', '.join(sorted(allowed))})",
            element,
            "xsi:type",
        )

    def link_name(self, element: etree._Element) -> str:
        """The name a link element's ``href`` is kept as (see :func:`_name_of`), one string per href."""
        text = element.get("href")
        name = self.link_names.get(text)
        if name is None:
            name = self.link_names[text] = _name_of(*self.href(element))
        return name

    def link(self, el: etree._Element, tag: str, owner: str) -> tuple[str, str] | None:
        """(uri, fragment) of the link ``tag`` of ``el``: a child element, or else the attribute
        form EMF also writes; None when there is neither."""
        target = None
        for child in el:
            if child.tag == tag:
                target = self.href(child)
            else:
                self.unknown(child, owner)
        if target is None and el.get(tag) is not None:
            _type, uri, frag = _split_ref_attribute(el.get(tag))
            target = (uri, frag)
        return target

    def ref_later(self, obj, feature, element, attribute, *, many=False, names_of: str | None = None) -> None:
        """Resolve reference ``attribute`` into ``feature`` once every object exists.

        ``names_of``: the feature holds the *names* of the referenced objects, which must be of
        that class (modes in which a component or a value exists).
        """
        text = element.get(attribute)
        if text is not None and text.strip():
            self.pending.append((obj, feature, text, element.sourceline, attribute, many, names_of))

    def ends_later(
        self, obj: EObject, el: etree._Element, ends: tuple, what: str, name: str | None = None
    ) -> None:
        """Resolve later each of ``ends`` (``(attribute, slot)`` pairs of single-valued
        references), which ``el`` must have (a connection's, a connection reference's).
        ``what`` and ``name`` say what ``el`` is, in the error when one is missing."""
        line = el.sourceline
        append = self.pending.append
        for attribute, slot in ends:
            text = el.get(attribute)
            if text is None:
                named = what if name is None else f"{what} {name!r}"
                raise self.error(f"{named} has no {attribute}", el)
            if text.strip():
                append((obj, slot, text, line, attribute, False, None))

    def register_id(self, obj: EObject, element: etree._Element) -> None:
        """Index ``obj`` by its element's ``xmi:id`` (callers check :attr:`has_ids` first)."""
        xid = element.get(_XMI_ID_KEY)
        if xid is not None:
            self.ids[xid] = obj

    # ------------------------------------------------------------------ instance files

    def read_instance_roots(self, root_el: etree._Element) -> EObject:
        f, fast = self.f, self.fast
        if root_el.tag == _ROOT_XMI:
            root_elements = [child for child in root_el if isinstance(child.tag, str)]
            if not root_elements:
                raise self.error("the xmi:XMI document holds no instance root", root_el)
        else:
            root_elements = [root_el]
        systems, components = [], []
        for element in root_elements:
            if element.tag == _ROOT_SYSTEM:
                obj = self.component(element, self.cls["SystemInstance"], is_system=True)
                systems.append(obj)
            elif element.tag == _ROOT_COMPONENT:
                obj = self.component(element, self.cls["ComponentInstance"], is_system=False)
                components.append(obj)
            else:
                raise self.error(
                    f"unexpected root <{element.tag}>; expected instance:SystemInstance or "
                    "instance:ComponentInstance",
                    element,
                )
            self.roots.append(obj)
        if not systems:
            raise self.error("the file holds no instance:SystemInstance root", root_el)
        aadl_model = self.new(self.cls["AadlModel"])
        fast.set_many(aadl_model, f["AadlModel.instances"], systems)
        if components:
            fast.set_many(aadl_model, f["AadlModel.componentInstances"], components)
        return aadl_model

    def component(self, el: etree._Element, cls: type, *, is_system: bool = False) -> EObject:
        f, fast = self.f, self.fast
        set_value = fast.set_value
        obj = self.new(cls)
        if self.has_ids:
            self.register_id(obj, el)
        name = el.get("name")
        if name is None:
            raise self.error("a component instance has no name", el)
        set_value(obj, f["ComponentInstance.name"], name)
        category = el.get("category")
        set_value(
            obj,
            f["ComponentInstance.category"],
            self.enum("ComponentCategory", category or "abstract", el, "category"),
        )
        if el.get("inMode") is not None:
            self.ref_later(
                obj, f["ComponentInstance.inModes"], el, "inMode", many=True, names_of="ModeInstance"
            )
        lists: dict[str, list] = {}
        index: list[int] = []
        classifier = None
        for child in el:
            tag = child.tag
            if tag == "ownedPropertyAssociation":
                lists.setdefault(tag, []).append(self.property_association(child))
            elif tag == "featureInstance":
                lists.setdefault(tag, []).append(self.feature_instance(child))
            elif tag == "componentInstance":
                lists.setdefault(tag, []).append(self.component(child, self.cls["ComponentInstance"]))
            elif tag == "connectionInstance":
                lists.setdefault(tag, []).append(self.connection_instance(child))
            elif tag == "subcomponent":
                self.check_link_type(child, _SUBCOMPONENT_TYPES)
                self.link_checked(child)
            elif tag == "index":
                index.append(self.int_text(child.text, child, "index"))
            elif tag == "classifier" or (
                is_system and tag in ("componentImplementation", "systemImplementation")
            ):
                if child.get(_XSI_TYPE_KEY) is not None:  # 2014's systemImplementation has none
                    self.check_link_type(child, _CLASSIFIER_TYPES)
                if classifier is None or tag != "classifier":
                    classifier = self.link_name(child)
            elif tag == "flowSpecification":
                lists.setdefault(tag, []).append(self.flow_specification(child))
            elif tag == "endToEndFlow":
                lists.setdefault(tag, []).append(self.end_to_end_flow(child))
            elif tag == "modeInstance":
                lists.setdefault(tag, []).append(self.mode_instance(child))
            elif tag == "modeTransitionInstance":
                lists.setdefault(tag, []).append(self.mode_transition(child))
            elif tag == "systemOperationMode" and is_system:
                lists.setdefault(tag, []).append(self.system_operation_mode(child))
            elif tag == "annexInstance":
                lists.setdefault(tag, []).append(self.annex_instance(child))
            else:
                self.unknown(child, "componentInstance")
        if classifier is not None:
            set_value(obj, f["ComponentInstance.classifier"], classifier)
        if not is_system and el.tag == "componentInstance":
            set_value(obj, f["ComponentInstance.subcomponent"], name)
        if any(index):
            fast.set_many(obj, f["ComponentInstance.index"], index)
        for tag, items in lists.items():
            feature = f["SystemInstance.systemOperationModes"] if tag == "systemOperationMode" else None
            if feature is None:
                feature = f[f"ComponentInstance.{_TAG_FEATURE[tag]}"]
            fast.set_many(obj, feature, items)
        return obj

    def feature_instance(self, el: etree._Element) -> EObject:
        f, fast = self.f, self.fast
        set_value = fast.set_value
        obj = self.new(self.cls["FeatureInstance"])
        if self.has_ids:
            self.register_id(obj, el)
        get = el.get
        name = get("name")
        if name is None:
            raise self.error("a feature instance has no name", el)
        set_value(obj, f["FeatureInstance.name"], name)
        set_value(obj, f["FeatureInstance.feature"], name)
        enum_cache = self.enum_cache
        category = get("category") or "dataPort"
        literal = enum_cache.get(("FeatureCategory", category))
        if literal is None:
            literal = self.enum("FeatureCategory", category, el, "category")
        set_value(obj, f["FeatureInstance.category"], literal)
        direction = get("direction") or "in"
        literal = enum_cache.get(("DirectionType", direction))
        if literal is None:
            literal = self.enum("DirectionType", direction, el, "direction")
        set_value(obj, f["FeatureInstance.direction"], literal)
        index_text = get("index")
        index = self.int_text(index_text, el, "index") if index_text is not None else 0
        if get("type") is not None:
            self.ref_later(obj, f["FeatureInstance.type"], el, "type")
        pas, subs = [], []
        ok_types = self.link_types_ok
        for child in el:
            tag = child.tag
            if tag == "ownedPropertyAssociation":
                pas.append(self.property_association(child))
            elif tag == "feature":
                if (child.get(_XSI_TYPE_KEY), _FEATURE_TYPES) not in ok_types:
                    self.check_link_type(child, _FEATURE_TYPES)
                self.link_checked(child)
            elif tag == "featureInstance":
                subs.append(self.feature_instance(child))
            elif tag == "index":
                index = self.int_text(child.text, child, "index")
            else:
                self.unknown(child, "featureInstance")
        if index:
            set_value(obj, f["FeatureInstance.index"], index)
        if pas:
            fast.set_many(obj, f["FeatureInstance.ownedPropertyAssociations"], pas)
        if subs:
            fast.set_many(obj, f["FeatureInstance.featureInstances"], subs)
        return obj

    def connection_instance(self, el: etree._Element) -> EObject:
        f, fast = self.f, self.fast
        set_value = fast.set_value
        obj = self.new(self.cls["ConnectionInstance"])
        if self.has_ids:
            self.register_id(obj, el)
        name = el.get("name")
        if name is None:
            raise self.error("a connection instance has no name", el)
        set_value(obj, f["ConnectionInstance.name"], name)
        set_value(
            obj,
            f["ConnectionInstance.kind"],
            self.enum("ConnectionKind", el.get("kind") or "featureConnection", el, "kind"),
        )
        if el.get("complete") == "true":
            set_value(obj, f["ConnectionInstance.complete"], True)
        if el.get("bidirectional") == "true":
            set_value(obj, f["ConnectionInstance.bidirectional"], True)
        self.ends_later(obj, el, self.s_connection_ends, "connection instance", name)
        if el.get("inSystemOperationMode") is not None:
            self.ref_later(
                obj,
                f["ConnectionInstance.inSystemOperationModes"],
                el,
                "inSystemOperationMode",
                many=True,
                names_of="SystemOperationMode",
            )
        pas, refs = [], []
        for child in el:
            tag = child.tag
            if tag == "connectionReference":
                refs.append(self.connection_reference(child))
            elif tag == "ownedPropertyAssociation":
                pas.append(self.property_association(child))
            else:
                self.unknown(child, "connectionInstance")
        if refs:
            fast.set_many(obj, f["ConnectionInstance.connectionReferences"], refs)
        if pas:
            fast.set_many(obj, f["ConnectionInstance.ownedPropertyAssociations"], pas)
        return obj

    def connection_reference(self, el: etree._Element) -> EObject:
        f, fast = self.f, self.fast
        obj = self.new(self.cls["ConnectionReference"])
        if self.has_ids:
            self.register_id(obj, el)
        self.ends_later(obj, el, self.s_reference_ends, "a connection reference")
        ok_types = self.link_types_ok
        for child in el:
            if child.tag == "connection":
                if (child.get(_XSI_TYPE_KEY), _CONNECTION_TYPES) not in ok_types:
                    self.check_link_type(child, _CONNECTION_TYPES)
                fast.set_value(obj, f["ConnectionReference.connection"], self.link_name(child))
            else:
                self.unknown(child, "connectionReference")
        return obj

    def flow_specification(self, el: etree._Element) -> EObject:
        f, fast = self.f, self.fast
        obj = self.new(self.cls["FlowSpecificationInstance"])
        if self.has_ids:
            self.register_id(obj, el)
        name = el.get("name") or ""
        fast.set_value(obj, f["FlowSpecificationInstance.name"], name)
        has_source, has_destination = el.get("source") is not None, el.get("destination") is not None
        kind = "path" if has_source and has_destination else "sink" if has_source else "source"
        fast.set_value(obj, f["FlowSpecificationInstance.kind"], self.enum("FlowKind", kind, el, "kind"))
        self.ref_later(obj, f["FlowSpecificationInstance.source"], el, "source")
        self.ref_later(obj, f["FlowSpecificationInstance.destination"], el, "destination")
        self._owned_pas_and_links(obj, el, "FlowSpecificationInstance", "flowSpecification")
        return obj

    def end_to_end_flow(self, el: etree._Element) -> EObject:
        f, fast = self.f, self.fast
        obj = self.new(self.cls["EndToEndFlowInstance"])
        if self.has_ids:
            self.register_id(obj, el)
        name = el.get("name") or ""
        fast.set_value(obj, f["EndToEndFlowInstance.name"], name)
        fast.set_value(obj, f["EndToEndFlowInstance.flow"], name)
        self.ref_later(obj, f["EndToEndFlowInstance.flowElements"], el, "flowElement", many=True)
        self._owned_pas_and_links(obj, el, "EndToEndFlowInstance", "endToEndFlow")
        return obj

    def mode_instance(self, el: etree._Element) -> EObject:
        f, fast = self.f, self.fast
        obj = self.new(self.cls["ModeInstance"])
        if self.has_ids:
            self.register_id(obj, el)
        name = el.get("name") or ""
        fast.set_value(obj, f["ModeInstance.name"], name)
        fast.set_value(obj, f["ModeInstance.mode"], name)
        if el.get("initial") == "true":
            fast.set_value(obj, f["ModeInstance.initial"], True)
        self._owned_pas_and_links(obj, el, "ModeInstance", "modeInstance")
        return obj

    def mode_transition(self, el: etree._Element) -> EObject:
        f, fast = self.f, self.fast
        obj = self.new(self.cls["ModeTransitionInstance"])
        if self.has_ids:
            self.register_id(obj, el)
        fast.set_value(obj, f["ModeTransitionInstance.name"], el.get("name") or "")
        self.ref_later(obj, f["ModeTransitionInstance.source"], el, "source")
        self.ref_later(obj, f["ModeTransitionInstance.destination"], el, "destination")
        self.ref_later(obj, f["ModeTransitionInstance.triggers"], el, "trigger", many=True)
        self._owned_pas_and_links(obj, el, "ModeTransitionInstance", "modeTransitionInstance")
        return obj

    def system_operation_mode(self, el: etree._Element) -> EObject:
        f, fast = self.f, self.fast
        obj = self.new(self.cls["SystemOperationMode"])
        if self.has_ids:
            self.register_id(obj, el)
        fast.set_value(obj, f["SystemOperationMode.name"], el.get("name") or "")
        self.ref_later(obj, f["SystemOperationMode.currentModes"], el, "currentMode", many=True)
        for child in el:
            self.unknown(child, "systemOperationMode")
        return obj

    def annex_instance(self, el: etree._Element) -> EObject:
        f, fast = self.f, self.fast
        obj = self.new(self.cls["AnnexInstance"])
        if self.has_ids:
            self.register_id(obj, el)
        fast.set_value(obj, f["AnnexInstance.name"], el.get("name") or "")
        # the file's indentation is not kept (see _load): the text is indented on its own
        text = etree.tostring(el, encoding="unicode", with_tail=False, pretty_print=True).rstrip("\n")
        fast.set_value(obj, f["AnnexInstance.text"], text)
        return obj

    def _owned_pas_and_links(self, obj: EObject, el: etree._Element, cname: str, where: str) -> None:
        pas = []
        for child in el:
            tag = child.tag
            if tag == "ownedPropertyAssociation":
                pas.append(self.property_association(child))
            elif tag in _DECLARATIVE_LINKS:
                self.link_checked(child)
            else:
                self.unknown(child, where)
        if pas:
            self.fast.set_many(obj, self.f[f"{cname}.ownedPropertyAssociations"], pas)

    # ------------------------------------------------------------------ property values

    def property_association(self, el: etree._Element) -> EObject:
        f, fast = self.f, self.fast
        obj = self.new(self.c_pa)
        if self.has_ids:
            self.register_id(obj, el)
        prop = None
        value_elements = []
        for child in el:
            tag = child.tag
            if tag == "ownedValue":
                value_elements.append(child)
            elif tag == "property":
                href = child.get("href")
                found = self.property_cache.get(href)
                if found is not None and not found[1]:  # by name, seen before
                    prop = found[0]
                    fast.set_value(obj, self.s_pa_property, prop)
                else:
                    prop = self.property_name(href, obj, child)
            elif tag in _PA_IGNORED or not isinstance(tag, str):
                continue
            else:
                self.unknown(child, "ownedPropertyAssociation")
        if prop is None:
            text = el.get("property")
            if text is None:
                raise self.error("a property association names no property", el)
            _type, uri, frag = _split_ref_attribute(text)
            prop = self.property_name(f"{uri}#{frag}", obj, el)
        if value_elements:
            modal_value = self.modal_value
            fast.set_many(obj, self.s_pa_values, [modal_value(v, prop) for v in value_elements])
        if el.get("append") == "true":
            fast.set_value(obj, f["PropertyAssociation.append"], True)
        if el.get("constant") == "true":
            fast.set_value(obj, f["PropertyAssociation.constant"], True)
        return obj

    def property_name(self, href: str | None, obj: EObject, el: etree._Element) -> str:
        """The qualified property name; positional references are decoded once the era is known."""
        if href is None:
            raise self.error(f"<{el.tag}> has no href", el)
        found = self.property_cache.get(href)
        if found is None:
            uri, _, frag = href.partition("#")
            self.note_uri(uri)
            positional = not frag or _is_positional(frag)
            found = (href if positional else _qualified_name(frag), positional)
            self.property_cache[href] = found
        name, positional = found
        if positional:
            uri, _, frag = href.partition("#")
            self.literal_use((uri, frag, "property", None, None), obj, "property")
        self.fast.set_value(obj, self.f["PropertyAssociation.property"], name)
        return name

    def literal_use(self, key: tuple, obj: EObject, feature_name: str) -> None:
        self.literal_uses.setdefault(key, []).append((obj, feature_name))

    def modal_value(self, el: etree._Element, prop: str | None) -> EObject:
        fast = self.fast
        obj = self.new(self.c_modal)
        if self.has_ids:
            self.register_id(obj, el)
        value = None
        for child in el:
            if child.tag == "ownedValue":
                value = self.value(child, prop, None)
            else:
                self.unknown(child, "ownedValue")
        if value is None:
            raise self.error("a property value holds no ownedValue", el)
        fast.set_child(obj, self.s_modal_value, value)
        if el.get("inMode"):
            self.ref_later(
                obj,
                self.f["ModalPropertyValue.inModes"],
                el,
                "inMode",
                many=True,
                names_of="SystemOperationMode",
            )
        return obj

    def value(self, el: etree._Element, prop: str | None, field_href: tuple[str, str] | None) -> EObject:
        handler = self.handler_cache.get(el.get(_XSI_TYPE_KEY))
        if handler is None:
            handler = _VALUE_HANDLERS.get(self.xsi_type(el))
            if handler is None:
                raise self.error(
                    f"unknown property value type xsi:type={el.get(_XSI_TYPE)!r}", el, "xsi:type"
                )
            if el.get(_XSI_TYPE) is not None and self.nsmap_is_global:
                self.handler_cache[el.get(_XSI_TYPE)] = handler
        obj = handler(self, el, prop, field_href)
        if self.has_ids:
            self.register_id(obj, el)
        return obj

    def _number(self, el, prop, field_href, cls: type, value_slot, unit_slot, convert) -> EObject:
        fast = self.fast
        obj = self.new(cls)
        text = el.get("value")
        if text is None:
            number = convert("0")
        else:
            try:
                number = convert(text)  # int() and float() ignore surrounding whitespace
            except ValueError:
                raise self.error(f"value {text!r} is not a number", el, "value") from None
        fast.set_value(obj, value_slot, number)
        # a number has one child at most, its unit
        count = len(el)
        unit_el = None
        if count == 1:
            unit_el = el[0]
            if unit_el.tag != "unit":
                self.unknown(unit_el, el.tag)
                unit_el = None
        elif count:
            for child in el:
                if child.tag == "unit":
                    unit_el = child
                else:
                    self.unknown(child, el.tag)
        if unit_el is not None:
            href = unit_el.get("href")
            key = (href, prop, field_href)
            found = self.unit_uses.get(key)
            if found is None:
                uri, frag = self.href(unit_el)
                uses = self.literal_uses.setdefault((uri, frag, "unit", prop, field_href), [])
                found = self.unit_uses[key] = (f"{uri}#{frag}", uses)
        else:
            unit_attr = el.get("unit")
            if unit_attr is None:
                return obj
            _type, uri, frag = _split_ref_attribute(unit_attr)
            self.note_uri(uri)
            found = (f"{uri}#{frag}", self.literal_uses.setdefault((uri, frag, "unit", prop, field_href), []))
        fast.set_value(obj, unit_slot, found[0])
        found[1].append((obj, "unit"))
        return obj

    def _integer(self, el, prop, field_href) -> EObject:
        return self._number(el, prop, field_href, self.c_int, self.s_int_value, self.s_int_unit, int)

    def _real(self, el, prop, field_href) -> EObject:
        return self._number(el, prop, field_href, self.c_real, self.s_real_value, self.s_real_unit, float)

    def _string(self, el, prop, field_href) -> EObject:
        obj = self.new(self.cls["StringValue"])
        self.fast.set_value(obj, self.f["StringValue.value"], el.get("value") or "")
        return obj

    def _boolean(self, el, prop, field_href) -> EObject:
        obj = self.new(self.cls["BooleanValue"])
        text = el.get("value")
        if text not in (None, "true", "false"):
            raise self.error(f"value {text!r} is not a boolean (true or false)", el, "value")
        self.fast.set_value(obj, self.f["BooleanValue.value"], text == "true")
        return obj

    def _named(self, el, prop, field_href) -> EObject:
        obj = self.new(self.cls["NamedValue"])
        target = self.link(el, "namedValue", "NamedValue")
        if target is None:
            raise self.error("a named value names nothing (expected a namedValue reference)", el)
        found = self.named_values.get(target)
        if found is None:
            uri, frag = target
            found = self.named_values[target] = (_name_of(uri, frag), not frag or _is_positional(frag))
        if found[1]:
            self.literal_use((*target, "enum", prop, field_href), obj, "name")
        self.fast.set_value(obj, self.s_named_name, found[0])
        return obj

    def _range(self, el, prop, field_href) -> EObject:
        f, fast = self.f, self.fast
        obj = self.new(self.cls["RangeValue"])
        for child in el:
            tag = child.tag
            if tag in ("minimum", "maximum", "delta"):
                fast.set_child(obj, f[f"RangeValue.{tag}"], self.value(child, prop, field_href))
            else:
                self.unknown(child, "RangeValue")
        return obj

    def _list(self, el, prop, field_href) -> EObject:
        obj = self.new(self.cls["ListValue"])
        items = []
        for child in el:
            if child.tag == "ownedListElement":
                items.append(self.value(child, prop, field_href))
            else:
                self.unknown(child, "ListValue")
        if items:
            self.fast.set_many(obj, self.f["ListValue.ownedItems"], items)
        return obj

    def _record(self, el, prop, field_href) -> EObject:
        f, fast = self.f, self.fast
        new, set_value, set_child = self.new, fast.set_value, fast.set_child
        c_field, s_name, s_value = self.cls["FieldValue"], f["FieldValue.name"], f["FieldValue.value"]
        field_names, value = self.field_names, self.value
        obj = new(self.cls["RecordValue"])
        fields = []
        for child in el:
            if child.tag != "ownedFieldValue":
                self.unknown(child, "RecordValue")
                continue
            field_obj = new(c_field)
            if self.has_ids:
                self.register_id(field_obj, child)
            target = None
            value_el = None
            for part in child:
                tag = part.tag
                if tag == "property":
                    target = self.href(part)
                elif tag == "ownedValue":
                    value_el = part
                else:
                    self.unknown(part, "ownedFieldValue")
            if target is None and child.get("property") is not None:
                _type, uri, frag = _split_ref_attribute(child.get("property"))
                target = (uri, frag)
            if target is None or value_el is None:
                raise self.error("a record field needs a property and an ownedValue", child)
            name = field_names.get(target)
            if name is None:
                uri, frag = target
                positional = not frag or _is_positional(frag)
                name = field_names[target] = (
                    f"{uri}#{frag}" if positional else _qualified_name(frag).rpartition("::")[2],
                    positional,
                )
            set_value(field_obj, s_name, name[0])
            if name[1]:
                self.literal_use((*target, "field", prop, field_href), field_obj, "name")
            set_child(field_obj, s_value, value(value_el, prop, target))
            fields.append(field_obj)
        if fields:
            fast.set_many(obj, f["RecordValue.ownedFields"], fields)
        return obj

    def _classifier(self, el, prop, field_href) -> EObject:
        obj = self.new(self.cls["ClassifierValue"])
        target = self.link(el, "classifier", "ClassifierValue")
        if target is None:
            raise self.error("a classifier value names no classifier", el)
        name = _name_of(*target)
        self.fast.set_value(obj, self.f["ClassifierValue.classifier"], name)
        return obj

    def _reference(self, el, prop, field_href) -> EObject:
        obj = self.new(self.cls["ReferenceValue"])
        steps = []
        current = el
        while current is not None:
            nxt = None
            for child in current:
                if child.tag == "containmentPathElement" or child.tag == "path":
                    nxt = child
                elif child.tag == "namedElement":
                    uri, frag = self.href(child)
                    named = _name_of(uri, frag)
                    steps.append(named if named.startswith(f"{uri}#") else named.rpartition("::")[2])
                elif child.tag == "arrayRange":
                    continue
                else:
                    self.unknown(child, "ReferenceValue")
            current = nxt
        path = ".".join(steps)
        self.fast.set_value(obj, self.f["ReferenceValue.path"], path)
        self.warn(f"reference value ({path}) kept as a declarative path, not resolved to an instance", el)
        return obj

    def _instance_reference(self, el, prop, field_href) -> EObject:
        obj = self.new(self.cls["InstanceReferenceValue"])
        if el.get("referencedInstanceObject") is None:
            raise self.error("an instance reference value refers to nothing", el)
        self.ref_later(
            obj, self.f["InstanceReferenceValue.referencedInstanceObject"], el, "referencedInstanceObject"
        )
        return obj

    def _computed(self, el, prop, field_href) -> EObject:
        obj = self.new(self.cls["ComputedValue"])
        self.fast.set_value(obj, self.f["ComputedValue.function"], el.get("function") or "")
        return obj

    def _operation(self, el, prop, field_href) -> EObject:
        obj = self.new(self.cls["OperationValue"])
        self.fast.set_value(obj, self.f["OperationValue.operator"], el.get("op") or "and")
        operands = [
            self.value(child, prop, field_href) for child in el if child.tag == "ownedPropertyExpression"
        ]
        if operands:
            self.fast.set_many(obj, self.f["OperationValue.ownedOperands"], operands)
        return obj

    # ------------------------------------------------------------------ references

    def resolve_pending(self) -> None:
        set_many, set_value = FastFactory.set_many, FastFactory.set_value
        cache: dict[str, EObject] = {}
        lists: dict[tuple, list] = {}
        resolve = self.resolve
        # a pending reference keeps its element's line, not the element: holding tens of
        # thousands of lxml element proxies costs more to free than the references to resolve
        for obj, slot, text, line, attribute, many, names_of in self.pending:
            if not many:
                # most references (a connection's ends) take this path: one token, looked up in
                # `cache` alone (going through `lists` as well costs 1-3 ms on 50 000 objects)
                token = text.strip()
                target = cache.get(token)
                if target is None:
                    target = cache[token] = resolve(token, line, attribute, text)
                expected = slot.target if names_of is None else self.cls[names_of]
                if not isinstance(target, expected):
                    raise self._wrong_target(attribute, target, expected, line, text)
                set_value(obj, slot, target if names_of is None else _name_held(target))
                continue
            # the same list is often written again and again (the modes a connection or a
            # value is in): each text is resolved and checked once per expected class
            expected = slot.target if names_of is None else self.cls[names_of]
            key = (text, expected, names_of is None)
            checked = lists.get(key)
            if checked is None:
                targets = []
                for token in text.split():
                    target = cache.get(token)
                    if target is None:
                        target = cache[token] = resolve(token, line, attribute, text)
                    targets.append(target)
                for target in targets:
                    if not isinstance(target, expected):
                        raise self._wrong_target(attribute, target, expected, line, text)
                if names_of is not None:
                    targets = [_name_held(target) for target in targets]
                checked = lists[key] = targets
            set_many(obj, slot, checked[:])  # set_many keeps the list it is given

    def _wrong_target(
        self, attribute: str, target: EObject, expected: type, line: int | None, text: str
    ) -> ImportFormatError:
        return self.error_at(
            f"{attribute} refers to a {target.eClass.name}, expected a {expected.eClass.name}",
            line,
            attribute,
            text,
        )

    def error_at(self, message: str, line: int | None, attribute: str, text: str) -> ImportFormatError:
        """An error located at the element of ``line`` whose ``attribute`` is ``text``."""
        for element in self.tree.getroot().iter():
            if element.sourceline == line and element.get(attribute) == text:
                return self.error(message, element, attribute)
        return ImportFormatError(message, Location(file=self.filename, line=line))

    def resolve(self, token: str, line: int | None, attribute: str, text_of_attribute: str) -> EObject:
        text = token[1:] if token.startswith("#") else token
        if not text.startswith("/"):
            if not self.has_ids:
                raise _IdsNeeded
            found = self.ids.get(text)
            if found is None:
                raise self.error_at(
                    f"{attribute} refers to {token!r}, which no element of the file has as xmi:id",
                    line,
                    attribute,
                    text_of_attribute,
                )
            return found
        found = self.path_at(text)
        if found is None:
            raise self.error_at(
                f"{attribute} refers to {token!r}, which is not an element of this file",
                line,
                attribute,
                text_of_attribute,
            )
        return found

    def path_at(self, text: str) -> EObject | None:
        """The object at an EMF fragment path (``/``, ``/1``, ``//@a.2/@b.0``), or None; memoised."""
        found = self.path_cache.get(text)
        if found is not None:
            return found
        head, _, last = text.rpartition("/")
        if not last.startswith("@"):
            # the root: "/" or "" (first root), or "/<n>"
            if head or not (last == "" or last.isdigit()):
                return None
            position = int(last) if last else 0
            found = self.roots[position] if position < len(self.roots) else None
        else:
            parent = self.path_at(head or "/")
            tag, _, number = last[1:].partition(".")
            # only instance objects' containment features are named in _TAG_FEATURE, and only the
            # features the reader filled are in an object's dict
            feature_name = _TAG_FEATURE.get(tag)
            if parent is None or feature_name is None or not number.isdigit():
                return None
            items = parent.__dict__.get(feature_name)
            position = int(number)
            if items is None:
                return None
            items = FastFactory.items(items)
            if position >= len(items):
                return None
            found = items[position]
        self.path_cache[text] = found
        return found

    # ------------------------------------------------------------------ era and literals

    def decode_literals(self) -> osate_eras.EraChoice:
        uses = [
            osate_eras.HrefUse(uri, frag, role, prop, fh) for (uri, frag, role, prop, fh) in self.literal_uses
        ]
        choice = osate_eras.choose_era(uses, uris=sorted(self.seen_uris))
        problems = {(u.uri, u.fragment, u.role, u.property, u.field_href): why for u, why in choice.problems}
        opaque: dict[str, int] = {}
        undecoded: dict[str, tuple[int, str]] = {}
        for key, targets in self.literal_uses.items():
            uri, frag, role, _prop, _fh = key
            pre = osate_eras.classify_uri(uri)
            decoded = None
            era = choice.era_of(pre.property_set) if pre is not None else None
            if pre is not None and era is not None and key not in problems:
                era_table = osate_eras.table(era)
                path = osate_eras.normalize_fragment(frag)
                if role == "property":
                    decoded = era_table.property_name(pre.property_set, int(path.rpartition(".")[2]))
                else:
                    literal = era_table.literal(pre.property_set, path)
                    decoded = literal.name if literal is not None else None
            if decoded is None:
                if pre is not None:
                    count, _why = undecoded.get(f"{uri}#{frag}", (0, ""))
                    undecoded[f"{uri}#{frag}"] = (count + len(targets), problems.get(key, "unknown position"))
                else:
                    opaque[uri] = opaque.get(uri, 0) + len(targets)
                continue
            for obj, feature_name in targets:
                obj.__dict__[feature_name]._value = decoded
        for href, (count, why) in sorted(undecoded.items()):
            self.warn(
                f"{count} reference(s) to {href} do not decode consistently in any known OSATE era ({why}); "
                "kept as written"
            )
        for uri, count in sorted(opaque.items()):
            self.warn(
                f"{count} positional reference(s) into {uri} (not a predeclared property set) kept as "
                "uri#fragment until its .aadl source is read"
            )
        for set_name, era in sorted(choice.set_eras.items()):
            self.warnings.append(
                Diagnostic(
                    "info",
                    f"references into {set_name} decode with the {era} table (the file is {choice.era})",
                    Location(file=self.filename),
                )
            )
        return choice


_VALUE_HANDLERS = {
    (NS_AADL2, "IntegerLiteral"): _Reader._integer,
    (NS_AADL2, "RealLiteral"): _Reader._real,
    (NS_AADL2, "StringLiteral"): _Reader._string,
    (NS_AADL2, "BooleanLiteral"): _Reader._boolean,
    (NS_AADL2, "NamedValue"): _Reader._named,
    (NS_AADL2, "RangeValue"): _Reader._range,
    (NS_AADL2, "ListValue"): _Reader._list,
    (NS_AADL2, "RecordValue"): _Reader._record,
    (NS_AADL2, "ClassifierValue"): _Reader._classifier,
    (NS_AADL2, "ReferenceValue"): _Reader._reference,
    (NS_AADL2, "ComputedValue"): _Reader._computed,
    (NS_AADL2, "Operation"): _Reader._operation,
    (NS_INSTANCE, "InstanceReferenceValue"): _Reader._instance_reference,
}


# =========================================================================== declarative files

_FEATURE_TAGS = {
    "ownedDataPort": "dataPort",
    "ownedEventPort": "eventPort",
    "ownedEventDataPort": "eventDataPort",
    "ownedParameter": "parameter",
    "ownedBusAccess": "busAccess",
    "ownedDataAccess": "dataAccess",
    "ownedSubprogramAccess": "subprogramAccess",
    "ownedSubprogramGroupAccess": "subprogramGroupAccess",
    "ownedVirtualBusAccess": "virtualBusAccess",
    "ownedFeatureGroup": "featureGroup",
    "ownedAbstractFeature": "abstractFeature",
}
_CONNECTION_TAGS = {
    "ownedPortConnection": "portConnection",
    "ownedAccessConnection": "accessConnection",
    "ownedFeatureConnection": "featureConnection",
    "ownedFeatureGroupConnection": "featureGroupConnection",
    "ownedParameterConnection": "parameterConnection",
}
_CATEGORY_OF = {c.lower(): c[0].lower() + c[1:] for c in _CATEGORIES}


class _DeclarativeReader:
    """Reads an ``aadl2:Package`` or ``aadl2:PropertySet`` root into our declarative model.

    Classifiers (types, implementations, feature group types) with their features,
    subcomponents, connections, modes, flows, property associations and annex subclauses
    (kept as text); property sets with their property types, properties and constants.
    Intra-file references (``#//@ownedPublicSection/@ownedClassifier.0`` or ``#<xmi:id>``)
    are resolved on the document; references into other files keep qualified names.
    """

    def __init__(self, reader: _Reader, root_el: etree._Element) -> None:
        self.r = reader
        self.root = root_el
        self.unit_name = root_el.get("name") or ""
        self.by_id = {el.get(_XMI_ID): el for el in root_el.iter() if el.get(_XMI_ID) is not None}

    def read(self) -> tuple[EObject, str]:
        if self.root.tag == _ROOT_PACKAGE:
            unit, kind = self.package(), "package"
        else:
            unit, kind = self.property_set(), "property set"
        aadl_model = model.new("AadlModel")
        aadl_model.units.append(unit)
        return aadl_model, kind

    # ------------------------------------------------------------------ references

    def located(self, build, element: etree._Element):
        """``build(element)``, with a model error (a bad enumeration literal, say) located there."""
        try:
            return build(element)
        except ImportFormatError:
            raise
        except RosaadlError as exc:
            raise self.r.error(exc.message, element) from None

    def literal(self, enum_name: str, text: str, element: etree._Element, attribute: str):
        """An enumeration literal of our metamodel from its name or AADL spelling (located error)."""
        return self.r.enum(enum_name, text, element, attribute)

    def element_at(self, fragment: str) -> etree._Element | None:
        """The element an intra-file fragment (``//@a/@b.1``, ``/``, or an xmi:id) designates."""
        if not fragment.startswith("/"):
            return self.by_id.get(fragment)
        current = self.root
        for segment in fragment.split("/")[2:]:
            if not segment:
                continue
            if not segment.startswith("@"):
                return None
            tag, _, number = segment[1:].partition(".")
            matches = [child for child in current if child.tag == tag]
            position = int(number) if number.isdigit() else 0
            if position >= len(matches):
                return None
            current = matches[position]
        return current

    def ref_name(self, element: etree._Element, attribute: str, *, qualify: bool) -> str | None:
        text = element.get(attribute)
        if text is None:
            return None
        _type, uri, frag = _split_ref_attribute(text)
        if uri:
            if frag and not _is_positional(frag):
                name = _qualified_name(frag)
                return name if qualify else name.rpartition("::")[2]
            return f"{uri}#{frag}"
        target = self.element_at(frag)
        if target is None:
            raise self.r.error(
                f"{attribute} refers to {text!r}, which is not an element of this file", element, attribute
            )
        name = target.get("name") or ""
        return f"{self.unit_name}::{name}" if qualify else name

    # ------------------------------------------------------------------ packages

    def package(self) -> EObject:
        pkg = model.new("AadlPackage", name=self.unit_name, sourceFile=self.r.filename)
        for section_tag, visibility, withs_feature in (
            ("ownedPublicSection", "public", "withs"),
            ("ownedPrivateSection", "private", "privateWiths"),
        ):
            for section in (c for c in self.root if c.tag == section_tag):
                getattr(pkg, withs_feature).extend(self.imported_units(section))
                for child in section:
                    if child.tag == "ownedClassifier":
                        classifier = self.located(self.classifier, child)
                        if classifier is not None:
                            classifier.visibility = self.literal(
                                "Visibility", visibility, child, "visibility"
                            )
                            pkg.classifiers.append(classifier)
                    elif child.tag == "ownedAnnexLibrary":
                        pkg.annexLibraries.append(
                            model.new(
                                "AnnexLibrary",
                                name=child.get("name") or "",
                                text=child.get("sourceText") or "",
                            )
                        )
                    elif child.tag in ("importedUnit", "ownedComment"):
                        continue
                    else:
                        self.r.unknown(child, section_tag)
        for child in self.root:
            if child.tag == "ownedPropertyAssociation":
                pkg.ownedPropertyAssociations.append(self.r.property_association(child))
        return pkg

    def imported_units(self, section: etree._Element) -> list[str]:
        names = []
        text = section.get("importedUnit")
        tokens = text.split() if text else []
        refs = [
            tokens[i + 1] if i + 1 < len(tokens) and ":" in tokens[i] else tokens[i]
            for i in range(0, len(tokens), 2)
        ]
        refs += [child.get("href") for child in section if child.tag == "importedUnit" and child.get("href")]
        for ref in refs:
            uri, _, frag = ref.partition("#")
            if frag and not _is_positional(frag):
                names.append(frag)
            else:
                names.append(Path(uri).name.rsplit(".", 1)[0])
        return names

    def classifier(self, el: etree._Element) -> EObject | None:
        ns, local = self.r.xsi_type(el)
        if ns != NS_AADL2 or local not in _CLASSIFIER_TYPES:
            raise self.r.error(f"unknown classifier type xsi:type={el.get(_XSI_TYPE)!r}", el, "xsi:type")
        name = el.get("name") or ""
        if local == "FeatureGroupType":
            obj = model.new("FeatureGroupType", name=name)
        elif local.endswith("Implementation"):
            category = _CATEGORY_OF[local[: -len("Implementation")].lower()]
            obj = model.new("ComponentImplementation", name=name, category=category)
        else:
            category = _CATEGORY_OF[local[: -len("Type")].lower()]
            obj = model.new("ComponentType", name=name, category=category)
        for child in el:
            tag = child.tag
            if tag in _FEATURE_TAGS and obj.eClass.findEStructuralFeature("features") is not None:
                obj.features.append(self.feature(child, _FEATURE_TAGS[tag]))
            elif (
                tag.endswith("Subcomponent") and tag.startswith("owned") and local.endswith("Implementation")
            ):
                obj.subcomponents.append(self.subcomponent(child, tag[len("owned") : -len("Subcomponent")]))
            elif tag in _CONNECTION_TAGS and local.endswith("Implementation"):
                obj.connections.append(self.connection(child, _CONNECTION_TAGS[tag]))
            elif tag == "ownedPropertyAssociation":
                obj.ownedPropertyAssociations.append(self.r.property_association(child))
            elif tag == "ownedRealization" and local.endswith("Implementation"):
                obj.type = self.ref_name(child, "implemented", qualify=True)
            elif tag == "ownedExtension":
                obj.extended = self.ref_name(child, "extended", qualify=True)
            elif tag == "ownedAnnexSubclause":
                obj.annexSubclauses.append(
                    model.new(
                        "AnnexSubclause", name=child.get("name") or "", text=child.get("sourceText") or ""
                    )
                )
            elif tag == "ownedMode" and obj.eClass.findEStructuralFeature("modes") is not None:
                obj.modes.append(
                    model.new("Mode", name=child.get("name") or "", initial=child.get("initial") == "true")
                )
            elif tag == "ownedFlowSpecification" and local.endswith("Type"):
                obj.flowSpecifications.append(
                    model.new(
                        "FlowSpecification", name=child.get("name") or "", kind=child.get("kind") or "source"
                    )
                )
            elif tag == "ownedEndToEndFlow" and local.endswith("Implementation"):
                obj.endToEndFlows.append(model.new("EndToEndFlow", name=child.get("name") or ""))
            elif tag in (
                "ownedComment",
                "ownedModeTransition",
                "ownedFlowImplementation",
                "ownedPrototype",
                "ownedPrototypeBinding",
                "ownedSubprogramCallSequence",
            ):
                continue
            else:
                self.r.unknown(child, "ownedClassifier")
        return obj

    def feature(self, el: etree._Element, category: str) -> EObject:
        obj = model.new("Feature", name=el.get("name") or "", category=category)
        if category.endswith("Access"):
            obj.access = self.literal("AccessType", el.get("kind") or "provides", el, "kind")
        else:
            obj.direction = self.literal("DirectionType", el.get("direction") or "in", el, "direction")
        for attribute in el.attrib:
            if attribute.endswith("FeatureClassifier") or attribute == "featureType":
                obj.classifier = self.ref_name(el, attribute, qualify=True)
        if el.get("inverse") == "true":
            obj.inverse = True
        for child in el:
            if child.tag == "ownedPropertyAssociation":
                obj.ownedPropertyAssociations.append(self.r.property_association(child))
            elif child.tag == "arrayDimension":
                obj.arrayDimensions.append(self.array_size(child))
        return obj

    def array_size(self, el: etree._Element) -> str:
        for child in el:
            if child.tag == "size":
                return child.get("size") or ""
        return ""

    def subcomponent(self, el: etree._Element, category: str) -> EObject:
        obj = model.new("Subcomponent", name=el.get("name") or "", category=_CATEGORY_OF[category.lower()])
        for attribute in el.attrib:
            if attribute.endswith("SubcomponentType"):
                obj.classifier = self.ref_name(el, attribute, qualify=True)
        for child in el:
            if child.tag == "ownedPropertyAssociation":
                obj.ownedPropertyAssociations.append(self.r.property_association(child))
            elif child.tag == "arrayDimension":
                obj.arrayDimensions.append(self.array_size(child))
        return obj

    def connection(self, el: etree._Element, kind: str) -> EObject:
        obj = model.new(
            "Connection",
            name=el.get("name") or "",
            kind=kind,
            bidirectional=el.get("bidirectional") == "true",
        )
        for child in el:
            if child.tag in ("source", "destination"):
                parts = []
                current = child
                while current is not None:
                    context = self.ref_name(current, "context", qualify=False)
                    end = self.ref_name(current, "connectionEnd", qualify=False)
                    parts.extend(p for p in (context, end) if p)
                    current = next((c for c in current if c.tag == "next"), None)
                setattr(obj, child.tag, ".".join(parts))
            elif child.tag == "ownedPropertyAssociation":
                obj.ownedPropertyAssociations.append(self.r.property_association(child))
        return obj

    # ------------------------------------------------------------------ property sets

    def property_set(self) -> EObject:
        pset = model.new("PropertySet", name=self.unit_name, sourceFile=self.r.filename)
        for child in self.root:
            tag = child.tag
            if tag == "ownedPropertyType":
                pset.ownedPropertyTypes.append(self.located(self.property_type, child))
            elif tag == "ownedProperty":
                pset.ownedProperties.append(self.located(self.property, child))
            elif tag == "ownedPropertyConstant":
                pset.ownedPropertyConstants.append(self.located(self.constant, child))
            elif tag == "importedUnit":
                pset.withs.append(Path(child.get("href", "")).name.partition(".")[0])
            elif tag in ("ownedComment", "ownedAnnexSubclause"):
                continue
            else:
                self.r.unknown(child, "aadl2:PropertySet")
        return pset

    def property_type(self, el: etree._Element) -> EObject:
        ns, local = self.r.xsi_type(el)
        name = el.get("name")
        if ns != NS_AADL2:
            raise self.r.error(f"unknown property type xsi:type={el.get(_XSI_TYPE)!r}", el, "xsi:type")
        if local in ("AadlBoolean", "AadlString"):
            return model.new(local, name=name)
        if local in ("AadlInteger", "AadlReal"):
            obj = model.new(local, name=name)
            obj.unitsType = self.ref_name(el, "referencedUnitsType", qualify=True)
            for child in el:
                if child.tag == "ownedUnitsType":
                    obj.ownedUnitsType = self.units_type(child)
            return obj
        if local == "UnitsType":
            return self.units_type(el)
        if local == "EnumerationType":
            obj = model.new("EnumerationType", name=name)
            obj.ownedLiterals.extend(
                model.new("EnumerationLiteral", name=c.get("name")) for c in el if c.tag == "ownedLiteral"
            )
            return obj
        if local == "RangeType":
            obj = model.new(
                "RangeType", name=name, numberType=self.ref_name(el, "referencedNumberType", qualify=True)
            )
            for child in el:
                if child.tag == "ownedNumberType":
                    obj.ownedNumberType = self.property_type(child)
            return obj
        if local == "ListType":
            obj = model.new(
                "ListType", name=name, elementType=self.ref_name(el, "referencedElementType", qualify=True)
            )
            for child in el:
                if child.tag == "ownedElementType":
                    obj.ownedElementType = self.property_type(child)
            return obj
        if local == "RecordType":
            obj = model.new("RecordType", name=name)
            for child in el:
                if child.tag == "ownedField":
                    fld = model.new(
                        "RecordField",
                        name=child.get("name"),
                        type=self.ref_name(child, "referencedPropertyType", qualify=True),
                    )
                    for part in child:
                        if part.tag == "ownedPropertyType":
                            fld.ownedType = self.property_type(part)
                    obj.ownedFields.append(fld)
            return obj
        if local in ("ClassifierType", "ReferenceType"):
            obj = model.new(local, name=name)
            for child in el:
                obj.categories.extend(m.text.strip() for m in child if m.tag == "metaclassName" and m.text)
            return obj
        raise self.r.error(f"unknown property type xsi:type={el.get(_XSI_TYPE)!r}", el, "xsi:type")

    def units_type(self, el: etree._Element) -> EObject:
        obj = model.new("UnitsType", name=el.get("name"))
        for child in el:
            if child.tag != "ownedLiteral":
                continue
            literal = model.new("UnitLiteral", name=child.get("name"))
            if child.get("baseUnit"):
                literal.baseUnit = self.ref_name(child, "baseUnit", qualify=False)
            for part in child:
                if part.tag == "factor":
                    literal.factor = self.r.value(part, None, None)
            obj.ownedLiterals.append(literal)
        return obj

    def property(self, el: etree._Element) -> EObject:
        obj = model.new(
            "Property",
            name=el.get("name"),
            inherit=el.get("inherit") == "true",
            type=self.ref_name(el, "referencedPropertyType", qualify=True),
        )
        for child in el:
            if child.tag == "ownedPropertyType":
                obj.ownedType = self.property_type(child)
            elif child.tag == "appliesTo":
                obj.appliesTo.extend(m.text.strip() for m in child if m.tag == "metaclassName" and m.text)
            elif child.tag == "defaultValue":
                obj.defaultValue = self.r.value(child, None, None)
        return obj

    def constant(self, el: etree._Element) -> EObject:
        obj = model.new(
            "PropertyConstant",
            name=el.get("name"),
            type=self.ref_name(el, "referencedPropertyType", qualify=True),
        )
        for child in el:
            if child.tag == "ownedPropertyType":
                obj.ownedType = self.property_type(child)
            elif child.tag == "constantValue":
                obj.value = self.r.value(child, None, None)
        return obj


# =========================================================================== entry points


def read_aaxl2(
    path: str | os.PathLike[str], *, strict: bool = False, max_bytes: int = DEFAULT_MAX_BYTES
) -> ImportResult:
    """Read an OSATE ``.aaxl2`` file; every problem is a located :class:`ImportFormatError`.

    ``strict`` turns unknown elements (otherwise skipped with a warning) into errors;
    ``max_bytes`` refuses larger files before reading them.
    """
    source = Path(path)
    filename = str(path)
    try:
        size = source.stat().st_size
    except OSError as exc:
        raise ImportFormatError(f"cannot read the file: {exc.strerror}", file=filename) from None
    if size > max_bytes:
        raise ImportFormatError(
            f"the file is {size} bytes, more than the {max_bytes}-byte limit for .aaxl2 files", file=filename
        )
    try:
        data = source.read_bytes()
    except OSError as exc:
        raise ImportFormatError(f"cannot read the file: {exc.strerror}", file=filename) from None
    return loads_aaxl2(data, filename, strict=strict, max_bytes=max_bytes)


def loads_aaxl2(
    data: bytes, filename: str = "<aaxl2>", *, strict: bool = False, max_bytes: int = DEFAULT_MAX_BYTES
) -> ImportResult:
    """Read ``.aaxl2`` content from bytes (``filename`` is used in messages and for sidecars)."""
    if len(data) > max_bytes:
        raise ImportFormatError(
            f"the document is {len(data)} bytes, more than the {max_bytes}-byte limit for .aaxl2 files",
            file=filename,
        )
    try:
        return _load(data, filename, strict=strict, with_ids=False)
    except _IdsNeeded:
        return _load(data, filename, strict=strict, with_ids=True)


def _name_held(obj: EObject) -> str:
    """``obj.name or ""`` for an object the reader made, read from its value holder."""
    holder = obj.__dict__.get("name")
    return (holder._value if holder is not None else None) or ""


class _IdsNeeded(Exception):
    """A reference names an ``xmi:id`` but the reader did not index them: read again with ids."""


def _carries_id(root_el: etree._Element) -> bool:
    element = root_el
    for _depth in range(3):
        if element.get(_XMI_ID_KEY) is not None:
            return True
        for child in element:
            if isinstance(child.tag, str):
                element = child
                break
        else:
            return False
    return False


def _load(data: bytes, filename: str, *, strict: bool, with_ids: bool) -> ImportResult:
    with gc_paused():
        # indentation is never read (annex text is re-indented): half the nodes to build and free
        tree = parse_xml_bytes(data, filename, remove_blank_text=True)
        root_el = tree.getroot()
        reader = _Reader(filename, tree, strict=strict)
        # cheap facts about the text that let the reader skip work: no ids to index, and no
        # namespace prefix declared below the root (so xsi:type prefixes mean the same everywhere).
        # EMF writes an xmi:id on every object of a resource that uses them, so the root and its
        # first child tell; a file that refers to an id only deeper down is read again with ids
        reader.has_ids = with_ids or _carries_id(root_el)
        reader.nsmap_is_global = data.count(b"xmlns") <= len(reader.nsmap)
        tag = root_el.tag
        if tag in (_ROOT_SYSTEM, _ROOT_XMI):
            aadl_model = reader.read_instance_roots(root_el)
            kind = "instance"
        elif tag in (_ROOT_PACKAGE, _ROOT_PROPERTY_SET):
            aadl_model, kind = _DeclarativeReader(reader, root_el).read()
        else:
            raise ImportFormatError(
                f"unexpected root element <{tag}>; expected instance:SystemInstance, xmi:XMI, aadl2:Package "
                "or aadl2:PropertySet (an OSATE .aaxl2 file)",
                Location(file=filename, line=root_el.sourceline, path=tree.getpath(root_el)),
            )
        reader.resolve_pending()
        choice = reader.decode_literals()
    model_name = os.path.basename(filename).rsplit(".", 1)[0] if not filename.startswith("<") else "aaxl2"
    reader.fast.set_value(aadl_model, reader.f["AadlModel.name"], model_name)
    result = ImportResult(
        model=aadl_model,
        source=filename,
        kind=kind,
        era=choice.era,
        property_set_eras=dict(choice.set_eras),
        warnings=reader.warnings,
        sidecar_uris=tuple(sorted(reader.declarative_uris)),
        base_dir=reader.base_dir,
    )
    log.debug("read %s: %s, era %s, %d warning(s)", filename, kind, choice.era, len(reader.warnings))
    # the document goes last: see _Reader.release
    reader.release()
    return result
