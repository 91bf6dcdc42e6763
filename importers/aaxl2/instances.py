"""The readers of instance elements: one function per element of ``instance.ecore``.

Each takes the :class:`~.document.Reader` of the read and an lxml element, and returns the
object of our instance model it makes (component, feature, connection, connection reference,
flow, mode, transition, system operation mode and annex instances). Children are read
depth first into plain lists and handed to the object's containment features in one step;
references between instance objects are queued on the reader (``ref_later``/``ends_later``)
and resolved once every object exists (:mod:`.references`). Links into the declarative model
whose target the instance object already names (its subcomponent, feature, mode, flow) are
only checked for their ``xsi:type`` and noted for the sidecars.

These are the reader's hot loops: slots and methods are bound to locals once per element, and
the element's attributes are read once.
"""

from __future__ import annotations

from lxml import etree
from pyecore.ecore import EObject

from .document import Reader
from .values import property_association
from .xmi import (
    CLASSIFIER_TYPES,
    CONNECTION_TYPES,
    DECLARATIVE_LINKS,
    FEATURE_TYPES,
    ROOT_COMPONENT,
    ROOT_SYSTEM,
    ROOT_XMI,
    SUBCOMPONENT_TYPES,
    TAG_FEATURE,
    XSI_TYPE_KEY,
)

__all__ = [
    "read_instance_roots",
    "component",
    "feature_instance",
    "connection_instance",
    "connection_reference",
    "flow_specification",
    "end_to_end_flow",
    "mode_instance",
    "mode_transition",
    "system_operation_mode",
    "annex_instance",
]


def read_instance_roots(r: Reader, root_el: etree._Element) -> EObject:
    f, fast = r.f, r.fast
    if root_el.tag == ROOT_XMI:
        root_elements = [child for child in root_el if isinstance(child.tag, str)]
        if not root_elements:
            raise r.error("the xmi:XMI document holds no instance root", root_el)
    else:
        root_elements = [root_el]
    systems, components = [], []
    for element in root_elements:
        if element.tag == ROOT_SYSTEM:
            obj = component(r, element, r.cls["SystemInstance"], is_system=True)
            systems.append(obj)
        elif element.tag == ROOT_COMPONENT:
            obj = component(r, element, r.cls["ComponentInstance"], is_system=False)
            components.append(obj)
        else:
            raise r.error(
                f"unexpected root <{element.tag}>; expected instance:SystemInstance or "
                "instance:ComponentInstance",
                element,
            )
        r.roots.append(obj)
    if not systems:
        raise r.error("the file holds no instance:SystemInstance root", root_el)
    aadl_model = r.new(r.cls["AadlModel"])
    fast.set_many(aadl_model, f["AadlModel.instances"], systems)
    if components:
        fast.set_many(aadl_model, f["AadlModel.componentInstances"], components)
    return aadl_model


def component(r: Reader, el: etree._Element, cls: type, *, is_system: bool = False) -> EObject:
    f, fast = r.f, r.fast
    set_value = fast.set_value
    obj = r.new(cls)
    if r.has_ids:
        r.register_id(obj, el)
    name = el.get("name")
    if name is None:
        raise r.error("a component instance has no name", el)
    set_value(obj, f["ComponentInstance.name"], name)
    category = el.get("category")
    set_value(
        obj,
        f["ComponentInstance.category"],
        r.enum("ComponentCategory", category or "abstract", el, "category"),
    )
    if el.get("inMode") is not None:
        r.ref_later(obj, f["ComponentInstance.inModes"], el, "inMode", many=True, names_of="ModeInstance")
    lists: dict[str, list] = {}
    index: list[int] = []
    classifier = None
    for child in el:
        tag = child.tag
        if tag == "ownedPropertyAssociation":
            lists.setdefault(tag, []).append(property_association(r, child))
        elif tag == "featureInstance":
            lists.setdefault(tag, []).append(feature_instance(r, child))
        elif tag == "componentInstance":
            lists.setdefault(tag, []).append(component(r, child, r.cls["ComponentInstance"]))
        elif tag == "connectionInstance":
            lists.setdefault(tag, []).append(connection_instance(r, child))
        elif tag == "subcomponent":
            r.check_link_type(child, SUBCOMPONENT_TYPES)
            r.link_checked(child)
        elif tag == "index":
            index.append(r.int_text(child.text, child, "index"))
        elif tag == "classifier" or (
            is_system and tag in ("componentImplementation", "systemImplementation")
        ):
            if child.get(XSI_TYPE_KEY) is not None:  # 2014's systemImplementation has none
                r.check_link_type(child, CLASSIFIER_TYPES)
            if classifier is None or tag != "classifier":
                classifier = r.link_name(child)
        elif tag == "flowSpecification":
            lists.setdefault(tag, []).append(flow_specification(r, child))
        elif tag == "endToEndFlow":
            lists.setdefault(tag, []).append(end_to_end_flow(r, child))
        elif tag == "modeInstance":
            lists.setdefault(tag, []).append(mode_instance(r, child))
        elif tag == "modeTransitionInstance":
            lists.setdefault(tag, []).append(mode_transition(r, child))
        elif tag == "systemOperationMode" and is_system:
            lists.setdefault(tag, []).append(system_operation_mode(r, child))
        elif tag == "annexInstance":
            lists.setdefault(tag, []).append(annex_instance(r, child))
        else:
            r.unknown(child, "componentInstance")
    if classifier is not None:
        set_value(obj, f["ComponentInstance.classifier"], classifier)
    if not is_system and el.tag == "componentInstance":
        set_value(obj, f["ComponentInstance.subcomponent"], name)
    if any(index):
        fast.set_many(obj, f["ComponentInstance.index"], index)
    for tag, items in lists.items():
        feature = f["SystemInstance.systemOperationModes"] if tag == "systemOperationMode" else None
        if feature is None:
            feature = f[f"ComponentInstance.{TAG_FEATURE[tag]}"]
        fast.set_many(obj, feature, items)
    return obj


def feature_instance(r: Reader, el: etree._Element) -> EObject:
    f, fast = r.f, r.fast
    set_value = fast.set_value
    obj = r.new(r.cls["FeatureInstance"])
    if r.has_ids:
        r.register_id(obj, el)
    get = el.get
    name = get("name")
    if name is None:
        raise r.error("a feature instance has no name", el)
    set_value(obj, f["FeatureInstance.name"], name)
    set_value(obj, f["FeatureInstance.feature"], name)
    enum_cache = r.enum_cache
    category = get("category") or "dataPort"
    literal = enum_cache.get(("FeatureCategory", category))
    if literal is None:
        literal = r.enum("FeatureCategory", category, el, "category")
    set_value(obj, f["FeatureInstance.category"], literal)
    direction = get("direction") or "in"
    literal = enum_cache.get(("DirectionType", direction))
    if literal is None:
        literal = r.enum("DirectionType", direction, el, "direction")
    set_value(obj, f["FeatureInstance.direction"], literal)
    index_text = get("index")
    index = r.int_text(index_text, el, "index") if index_text is not None else 0
    if get("type") is not None:
        r.ref_later(obj, f["FeatureInstance.type"], el, "type")
    pas, subs = [], []
    ok_types = r.link_types_ok
    for child in el:
        tag = child.tag
        if tag == "ownedPropertyAssociation":
            pas.append(property_association(r, child))
        elif tag == "feature":
            if (child.get(XSI_TYPE_KEY), FEATURE_TYPES) not in ok_types:
                r.check_link_type(child, FEATURE_TYPES)
            r.link_checked(child)
        elif tag == "featureInstance":
            subs.append(feature_instance(r, child))
        elif tag == "index":
            index = r.int_text(child.text, child, "index")
        else:
            r.unknown(child, "featureInstance")
    if index:
        set_value(obj, f["FeatureInstance.index"], index)
    if pas:
        fast.set_many(obj, f["FeatureInstance.ownedPropertyAssociations"], pas)
    if subs:
        fast.set_many(obj, f["FeatureInstance.featureInstances"], subs)
    return obj


def connection_instance(r: Reader, el: etree._Element) -> EObject:
    f, fast = r.f, r.fast
    set_value = fast.set_value
    obj = r.new(r.cls["ConnectionInstance"])
    if r.has_ids:
        r.register_id(obj, el)
    name = el.get("name")
    if name is None:
        raise r.error("a connection instance has no name", el)
    set_value(obj, f["ConnectionInstance.name"], name)
    set_value(
        obj,
        f["ConnectionInstance.kind"],
        r.enum("ConnectionKind", el.get("kind") or "featureConnection", el, "kind"),
    )
    if el.get("complete") == "true":
        set_value(obj, f["ConnectionInstance.complete"], True)
    if el.get("bidirectional") == "true":
        set_value(obj, f["ConnectionInstance.bidirectional"], True)
    r.ends_later(obj, el, r.s_connection_ends, "connection instance", name)
    if el.get("inSystemOperationMode") is not None:
        r.ref_later(
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
            refs.append(connection_reference(r, child))
        elif tag == "ownedPropertyAssociation":
            pas.append(property_association(r, child))
        else:
            r.unknown(child, "connectionInstance")
    if refs:
        fast.set_many(obj, f["ConnectionInstance.connectionReferences"], refs)
    if pas:
        fast.set_many(obj, f["ConnectionInstance.ownedPropertyAssociations"], pas)
    return obj


def connection_reference(r: Reader, el: etree._Element) -> EObject:
    f, fast = r.f, r.fast
    obj = r.new(r.cls["ConnectionReference"])
    if r.has_ids:
        r.register_id(obj, el)
    r.ends_later(obj, el, r.s_reference_ends, "a connection reference")
    ok_types = r.link_types_ok
    for child in el:
        if child.tag == "connection":
            if (child.get(XSI_TYPE_KEY), CONNECTION_TYPES) not in ok_types:
                r.check_link_type(child, CONNECTION_TYPES)
            fast.set_value(obj, f["ConnectionReference.connection"], r.link_name(child))
        else:
            r.unknown(child, "connectionReference")
    return obj


def flow_specification(r: Reader, el: etree._Element) -> EObject:
    f, fast = r.f, r.fast
    obj = _named_object(r, el, "FlowSpecificationInstance")
    has_source, has_destination = el.get("source") is not None, el.get("destination") is not None
    kind = "path" if has_source and has_destination else "sink" if has_source else "source"
    fast.set_value(obj, f["FlowSpecificationInstance.kind"], r.enum("FlowKind", kind, el, "kind"))
    r.ref_later(obj, f["FlowSpecificationInstance.source"], el, "source")
    r.ref_later(obj, f["FlowSpecificationInstance.destination"], el, "destination")
    _owned_pas_and_links(r, obj, el, "FlowSpecificationInstance", "flowSpecification")
    return obj


def end_to_end_flow(r: Reader, el: etree._Element) -> EObject:
    f, fast = r.f, r.fast
    obj = _named_object(r, el, "EndToEndFlowInstance")
    fast.set_value(obj, f["EndToEndFlowInstance.flow"], el.get("name") or "")
    r.ref_later(obj, f["EndToEndFlowInstance.flowElements"], el, "flowElement", many=True)
    _owned_pas_and_links(r, obj, el, "EndToEndFlowInstance", "endToEndFlow")
    return obj


def mode_instance(r: Reader, el: etree._Element) -> EObject:
    f, fast = r.f, r.fast
    obj = _named_object(r, el, "ModeInstance")
    fast.set_value(obj, f["ModeInstance.mode"], el.get("name") or "")
    if el.get("initial") == "true":
        fast.set_value(obj, f["ModeInstance.initial"], True)
    _owned_pas_and_links(r, obj, el, "ModeInstance", "modeInstance")
    return obj


def mode_transition(r: Reader, el: etree._Element) -> EObject:
    f = r.f
    obj = _named_object(r, el, "ModeTransitionInstance")
    r.ref_later(obj, f["ModeTransitionInstance.source"], el, "source")
    r.ref_later(obj, f["ModeTransitionInstance.destination"], el, "destination")
    r.ref_later(obj, f["ModeTransitionInstance.triggers"], el, "trigger", many=True)
    _owned_pas_and_links(r, obj, el, "ModeTransitionInstance", "modeTransitionInstance")
    return obj


def system_operation_mode(r: Reader, el: etree._Element) -> EObject:
    obj = _named_object(r, el, "SystemOperationMode")
    r.ref_later(obj, r.f["SystemOperationMode.currentModes"], el, "currentMode", many=True)
    for child in el:
        r.unknown(child, "systemOperationMode")
    return obj


def annex_instance(r: Reader, el: etree._Element) -> EObject:
    obj = _named_object(r, el, "AnnexInstance")
    # the file's indentation is not kept (see load.load_document): the text is indented on its own
    text = etree.tostring(el, encoding="unicode", with_tail=False, pretty_print=True).rstrip("\n")
    r.fast.set_value(obj, r.f["AnnexInstance.text"], text)
    return obj


def _named_object(r: Reader, el: etree._Element, cname: str) -> EObject:
    """A new object of class ``cname`` for ``el`` (indexed by its ``xmi:id``), named as ``el``;
    for the elements a file holds few of (flows, modes, annexes)."""
    obj = r.new(r.cls[cname])
    if r.has_ids:
        r.register_id(obj, el)
    r.fast.set_value(obj, r.f[f"{cname}.name"], el.get("name") or "")
    return obj


def _owned_pas_and_links(r: Reader, obj: EObject, el: etree._Element, cname: str, where: str) -> None:
    """The property associations of ``el`` into ``obj``; its links into the declarative model are
    only noted (``where`` names ``el`` in warnings)."""
    pas = []
    for child in el:
        tag = child.tag
        if tag == "ownedPropertyAssociation":
            pas.append(property_association(r, child))
        elif tag in DECLARATIVE_LINKS:
            r.link_checked(child)
        else:
            r.unknown(child, where)
    if pas:
        r.fast.set_many(obj, r.f[f"{cname}.ownedPropertyAssociations"], pas)
