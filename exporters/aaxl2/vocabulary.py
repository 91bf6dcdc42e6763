"""What the ``.aaxl2`` writer names: OSATE's namespaces, classes and containment lists.

The namespaces a document declares, the era whose layout of OSATE's property sets the writer
follows, where OSATE keeps its own packages, and the ``aadl2`` classes (and so the
``owned<Class>`` containment lists) of declarations per AADL category, feature category and
connection kind. The namespace URIs are the reader's (:mod:`rosaadl.importers.aaxl2.xmi`).
"""

from __future__ import annotations

import re

from rosaadl.importers import osate_eras
from rosaadl.importers.aaxl2.xmi import NS_AADL2, NS_INSTANCE, NS_XMI, NS_XSI

__all__ = [
    "ERA",
    "NAMESPACES",
    "OSATE_PACKAGES",
    "ID_RE",
    "FILE_STEM_RE",
    "CATEGORY_CLASS",
    "FEATURE_CLASS",
    "INSTANCE_FEATURE_CATEGORY",
    "CONNECTION_CLASS",
    "OPERATORS",
    "OWNED_STEP_RE",
    "FRAGMENT_RE",
    "CLASS_OF_STEP",
    "name_fragment",
]

#: The OSATE era whose layout of the predeclared property sets the writer follows.
ERA = osate_eras.CURRENT_ERA
NAMESPACES = (
    ("xmi", NS_XMI),
    ("xsi", NS_XSI),
    ("aadl2", NS_AADL2),
    ("instance", NS_INSTANCE),
)
#: OSATE's own packages (besides the property sets the era tables know) and where it keeps them.
OSATE_PACKAGES = {
    "base_types": "platform:/plugin/org.osate.contribution.sei/resources/packages/Base_Types.aadl",
    "physicalresources": (
        "platform:/plugin/org.osate.contribution.sei/resources/packages/PhysicalResources.aadl"
    ),
}

# an AADL identifier (what instance objects must be named), and an instance file name's stem
ID_RE = re.compile(r"[A-Za-z](?:_?[A-Za-z0-9])*\Z")
FILE_STEM_RE = re.compile(r"[A-Za-z0-9_]+\Z")

# AADL category (our enumeration names) → OSATE class-name stem
CATEGORY_CLASS = {
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
FEATURE_CLASS = {
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
INSTANCE_FEATURE_CATEGORY = {"virtualBusAccess": "busAccess"}
CONNECTION_CLASS = {
    "portConnection": "PortConnection",
    "accessConnection": "AccessConnection",
    "featureConnection": "FeatureConnection",
    "featureGroupConnection": "FeatureGroupConnection",
    "parameterConnection": "ParameterConnection",
}
OPERATORS = {"and": "and", "or": "or", "not": "not", "+": "+", "plus": "+", "-": "-", "minus": "-"}
# the aadl2 classes an opaque positional reference may end in (``…/@ownedDataPort.0`` → DataPort)
OWNED_STEP_RE = re.compile(r"@owned([A-Z][A-Za-z]*?)\.\d+\Z")
FRAGMENT_RE = re.compile(r"(?:/0)?/?(?:/@[A-Za-z]+(?:\.\d+)?)+|/0|/")
CLASS_OF_STEP = frozenset(
    list(FEATURE_CLASS.values())
    + [f"{c}Subcomponent" for c in CATEGORY_CLASS.values()]
    + list(CONNECTION_CLASS.values())
    + ["SubprogramCallSequence", "SubprogramCall", "Mode", "ModeTransition", "FlowSpecification"]
    + ["EndToEndFlow", "FlowImplementation", "Prototype", "Classifier"]
)


def name_fragment(*names: str) -> str:
    """The fragment by which OSATE's hrefs name a package, classifier, property, property type or
    constant: its qualified name with every ``::`` written ``.`` (``functional::Alert`` and
    ``Alert.basic`` → ``functional.Alert.Alert.basic``; ``Timing_Properties.Period``).

    OSATE's rule: the ``.aadl`` resources bind ``Aadl2QualifiedNameFragmentProvider``
    (``org.osate.xtext.aadl2.util``, in ``Aadl2RuntimeModule.bindIFragmentProvider``), whose
    ``getFragment`` is ``Aadl2QualifiedNameProvider.getFullyQualifiedName(obj).toString()``: the
    name ``Pkg::Name`` (``Set::Name`` in a property set) split into segments at ``::`` by
    ``Aadl2QualifiedNameConverter``, and Xtext's ``QualifiedName.toString()`` joins the segments
    with ``.``. Only packages, package sections, classifiers, property sets, properties,
    property types and constants have such a name; every other element (subcomponents,
    features, connections, modes, flows, literals, units) falls back to its EMF path. OSATE
    finds the element by comparing the fragment with each element's, case included, so the
    names are written as declared.
    """
    return ".".join(part.strip() for name in names for part in name.split("::"))
