"""The vocabulary of OSATE's ``.aaxl2`` files, and how the text of a reference is split.

Namespaces and root tags; the ``xsi:type`` class names a link into the declarative model may
carry (checked, never guessed); which containment list of our metamodel each instance element
tag fills (what ``@tag.N`` in an EMF path counts, for the reader and the writer alike); and the
pure functions that turn a reference's text (``../P.aadl#P.L.i``, ``aadl2:DataType uri#frag``)
into the names the model keeps.
"""

from __future__ import annotations

import re

__all__ = [
    "NS_XMI",
    "NS_XSI",
    "NS_AADL2",
    "NS_INSTANCE",
    "XSI_TYPE",
    "XSI_TYPE_KEY",
    "XMI_ID",
    "XMI_ID_KEY",
    "ROOT_SYSTEM",
    "ROOT_COMPONENT",
    "ROOT_XMI",
    "ROOT_PACKAGE",
    "ROOT_PROPERTY_SET",
    "FEATURE_TYPES",
    "CATEGORIES",
    "SUBCOMPONENT_TYPES",
    "CLASSIFIER_TYPES",
    "CONNECTION_TYPES",
    "TAG_FEATURE",
    "PA_IGNORED",
    "DECLARATIVE_LINKS",
    "UNIT_CLASSES",
    "qualified_name",
    "link_class",
    "name_of",
    "is_positional",
    "fragment_index_problem",
    "split_ref_attribute",
]

NS_XMI = "http://www.omg.org/XMI"
NS_XSI = "http://www.w3.org/2001/XMLSchema-instance"
NS_AADL2 = "http://aadl.info/AADL/2.0"
NS_INSTANCE = "http://aadl.info/AADL/2.0/instance"

XSI_TYPE = f"{{{NS_XSI}}}type"
# the same key as bytes: lxml reads an attribute by it without encoding the key each time
XSI_TYPE_KEY = XSI_TYPE.encode()
XMI_ID = f"{{{NS_XMI}}}id"
XMI_ID_KEY = XMI_ID.encode()
ROOT_SYSTEM = f"{{{NS_INSTANCE}}}SystemInstance"
ROOT_COMPONENT = f"{{{NS_INSTANCE}}}ComponentInstance"
ROOT_XMI = f"{{{NS_XMI}}}XMI"
ROOT_PACKAGE = f"{{{NS_AADL2}}}Package"
ROOT_PROPERTY_SET = f"{{{NS_AADL2}}}PropertySet"

# xsi:type local names that may appear on declarative link elements (checked, never guessed).
FEATURE_TYPES = frozenset(
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
CATEGORIES = (
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
SUBCOMPONENT_TYPES = frozenset(f"{c}Subcomponent" for c in CATEGORIES)
CLASSIFIER_TYPES = frozenset(
    [f"{c}Type" for c in CATEGORIES] + [f"{c}Implementation" for c in CATEGORIES] + ["FeatureGroupType"]
)
CONNECTION_TYPES = frozenset(
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
TAG_FEATURE = {
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

# children of a property association that the instance model does not keep
PA_IGNORED = frozenset({"property", "propertyAssociation", "appliesTo", "inBinding"})

# elements that only link an instance object to its declarative element, whose name the
# instance object already carries (kept by position in the file, not needed here).
DECLARATIVE_LINKS = frozenset(
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


# the classes whose whole qualified name is a unit's name (no trailing member name)
UNIT_CLASSES = frozenset({"AadlPackage", "Package", "PropertySet", "ModelUnit"})


def qualified_name(fragment: str, kind: str | None = None) -> str:
    """The AADL name an Xtext fragment by name designates: ``P.T.i`` → ``P::T.i``,
    ``functional.Alert.Alert.basic`` → ``functional::Alert::Alert.basic``, ``Set.Prop`` → ``Set::Prop``.

    OSATE names a package, classifier, property, property type or constant by its qualified
    name with every ``::`` written ``.`` (``Aadl2QualifiedNameFragmentProvider``: the segments of
    ``Aadl2QualifiedNameProvider``'s ``Pkg::Name`` joined by Xtext's ``QualifiedName.toString()``;
    see :func:`rosaadl.exporters.aaxl2.vocabulary.name_fragment`). The dots of a package name
    with several segments and the dot of an implementation name read alike, so ``kind``, the
    ``aadl2`` class of the element (its link's ``xsi:type``), tells how many trailing segments
    are the element's own name: none for a package or property set (``functional.Alert`` →
    ``functional::Alert``), two for an implementation (``…Implementation``), one for any other
    class (a type, property, property type or constant). Without a class, and for a fragment
    that already holds ``::`` (as earlier versions of this project wrote them), the first dot
    ends the owner's name, which holds for every property set (one identifier) and every
    package of one segment.
    """
    if kind is not None and "::" not in fragment:
        segments = fragment.split(".")
        if kind in UNIT_CLASSES:
            return "::".join(segments)
        own = 2 if kind.endswith("Implementation") else 1
        if len(segments) > own:
            return "::".join(segments[:-own]) + "::" + ".".join(segments[-own:])
    head, sep, local = fragment.partition(".")
    if not sep:
        return fragment
    return f"{head}::{local}"


def name_of(uri: str, fragment: str, kind: str | None = None) -> str:
    """A link as we keep it: ``P::L.i`` for a fragment by qualified name (:func:`qualified_name`,
    ``kind`` the class of the element it names), else ``uri#fragment``."""
    if not fragment or is_positional(fragment):
        return f"{uri}#{fragment}"
    return qualified_name(fragment, kind)


def is_positional(fragment: str) -> bool:
    return fragment.startswith("/") or fragment.startswith("@")


_POSITION = re.compile(r"[0-9]+")


def fragment_index_problem(fragment: str) -> str | None:
    """Why the positions of an EMF fragment path are malformed (``@ownedPropertyType.-1``,
    ``@x.1_0``, ``/+0``), or None when they are well formed or the fragment is not a path.

    EMF reads a segment ``@feature.k`` by ``Integer.parseInt`` of what follows the last dot and
    takes the ``k``-th item of the feature's list (``EObjectImpl.eObjectForURIFragmentSegment``),
    and a root segment ``/k`` as the ``k``-th root (``ResourceImpl.getEObject``): a negative
    position fails there (``IndexOutOfBoundsException``), as does a number Java cannot parse
    (``1_0``, an empty one). A position is ASCII digits, nothing else (OSATE never writes a
    sign, so ``+2``, which Java would read as 2, is refused too). A keyed segment
    (``@feature[name='a.b']``) holds no position.
    """
    if not is_positional(fragment):
        return None
    for number, segment in enumerate(fragment.split("/")):
        if segment.startswith("@"):
            if "[" in segment:
                continue
            _feature, dot, position = segment.rpartition(".")
            if dot and not _POSITION.fullmatch(position):
                return f"position {position!r} of {segment!r} is not a list index (digits 0-9)"
        elif segment and (number != 1 or not _POSITION.fullmatch(segment)):
            return f"segment {segment!r} is neither @feature.index nor the index of a root"
    return None


def split_ref_attribute(text: str) -> tuple[str | None, str, str]:
    """Attribute-form reference ``aadl2:DataType ../X.aadl#X.T`` → (type, uri, fragment)."""
    xsi_type = None
    value = text.strip()
    if " " in value:
        xsi_type, _, value = value.partition(" ")
    uri, _, frag = value.partition("#")
    return xsi_type, uri, frag


def link_class(xsi_type: str | None, tag: str = "") -> str | None:
    """The ``aadl2`` class a link names, for :func:`qualified_name`: its ``xsi:type``'s local
    name, else ``ComponentImplementation`` for the links that only hold implementations (2014's
    ``systemImplementation``, ``componentImplementation``), else None."""
    if xsi_type:
        return xsi_type.rpartition(":")[2]
    return "ComponentImplementation" if tag.endswith("Implementation") else None
