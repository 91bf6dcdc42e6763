"""Instance objects written as OSATE's XMI: components, features, connections, modes, flows.

One function per element of ``instance.ecore``: attributes in the metamodel's feature order
with EMF's default omission (no ``category`` on an abstract component, no ``direction`` for
``in``, no boolean that is false), children in EMF's order (property associations, then the
contained instance objects, then the links into the declarative model: ``subcomponent``,
``index``, ``classifier``), each link's href from the :class:`~.declarations.Declarations`
of the export (a link that cannot be made is left out and counted). Annex instances, kept as
XML text by the reader, are written back at their depth.
"""

from __future__ import annotations

import re
from typing import Any

from lxml import etree
from pyecore.ecore import EObject

from rosaadl.errors import RosaadlError
from rosaadl.fileio import parse_xml_bytes
from rosaadl.model import is_a

from .declarations import find_named
from .emf_text import items_of, java_literal, literal_name, value_of
from .state import Writer
from .values import emit_associations
from .vocabulary import INSTANCE_FEATURE_CATEGORY, NAMESPACES

__all__ = [
    "emit_component",
    "emit_feature",
    "emit_connection",
    "emit_mode",
    "emit_transition",
    "emit_flow_spec",
    "emit_end_to_end",
    "emit_annexes",
]


def emit_annexes(w: Writer, indent: str, obj: EObject) -> None:
    for annex in obj.annexInstances:
        text = annex.text or ""
        if not text.strip():
            continue
        try:
            element = parse_xml_bytes(text.encode("utf-8"), "<annex instance>").getroot()
        except RosaadlError as exc:
            raise w.error(
                f"annex instance {annex.name!r} is not well-formed XML: {exc.message}", obj
            ) from None
        if element.tag != "annexInstance":
            raise w.error(f"annex instance {annex.name!r} holds <{element.tag}>, not an annexInstance", obj)
        for prefix, uri in element.nsmap.items():
            if prefix is None:
                raise w.error(f"annex instance {annex.name!r} declares a default namespace", obj)
            known = dict(NAMESPACES).get(prefix) or w.extra_ns.get(prefix)
            if known is not None and known != uri:
                raise w.error(f"annex instance {annex.name!r} redefines the prefix {prefix!r}", obj)
            if prefix not in dict(NAMESPACES):
                w.extra_ns[prefix] = uri
        etree.indent(element, space="  ", level=len(indent) // 2)  # at the annex's depth
        body = etree.tostring(element, encoding="ascii", with_tail=False).decode("ascii")
        # the document's root declares the namespaces; lxml escapes '>' in attribute values
        head, end, rest = body.partition(">")
        head = re.sub(r'\s+xmlns:[A-Za-z_][\w.-]*="[^"]*"', "", head)
        w.out.append(indent + head + end + rest + "\n")


def emit_component(w: Writer, indent: str, ci: EObject, tag: str, *, root_attrs: str = "") -> None:
    out = w.out
    is_root = ci.eContainer() is None or not is_a(ci.eContainer(), "InstanceObject")
    category = java_literal(value_of(ci, "category"))
    attributes = f' name="{w.text(value_of(ci, "name") or "", ci, "name")}"'
    if category and category != "abstract":
        attributes += f' category="{category}"'
    if len(items_of(ci, "inModes")):
        parent = ci.eContainer()
        modes = []
        for mode_name in items_of(ci, "inModes"):
            mode = (
                find_named(list(items_of(parent, "modeInstances")), mode_name)
                if is_a(parent, "ComponentInstance")
                else None
            )
            if mode is None:
                raise w.error(f"in modes names {mode_name!r}, which is not a mode of the parent", ci)
            modes.append(w.paths[id(mode)])
        attributes += f' inMode="{" ".join(modes)}"'
    start = len(out)
    out.append(f"{indent}<{tag}{root_attrs}{attributes}>\n")
    inner = indent + "  "
    body_start = len(out)
    emit_associations(w, inner, ci)
    emit_annexes(w, inner, ci)
    decls: dict[int, EObject | None] = {}
    for fi in items_of(ci, "featureInstances"):
        emit_feature(w, inner, fi, decls)
    for child in items_of(ci, "componentInstances"):
        emit_component(w, inner, child, "componentInstance")
    for mi in items_of(ci, "modeInstances"):
        emit_mode(w, inner, mi)
    for mti in items_of(ci, "modeTransitionInstances"):
        emit_transition(w, inner, mti)
    for fsi in items_of(ci, "flowSpecifications"):
        emit_flow_spec(w, inner, fsi)
    for flow in items_of(ci, "endToEndFlows"):
        emit_end_to_end(w, inner, flow)
    for conn in items_of(ci, "connectionInstances"):
        emit_connection(w, inner, conn)
    if not is_root:
        sub = w.links.subcomponent_href(ci)
        if sub is not None:
            out.append(f'{inner}<subcomponent xsi:type="{sub[0]}" href="{w.text(sub[1], ci, "href")}"/>\n')
        else:
            w.links.note_missing("subcomponent")
        indexes = [int(i) for i in items_of(ci, "index")] or [0]
        out.extend(f"{inner}<index>{i}</index>\n" for i in indexes)
    else:
        out.extend(f"{inner}<index>{int(i)}</index>\n" for i in items_of(ci, "index"))
    category_value = value_of(ci, "category")
    classifier = w.links.classifier_href(value_of(ci, "classifier"), category_value, implementation=False)
    if classifier is not None:
        out.append(
            f'{inner}<classifier xsi:type="{classifier[0]}" href="{w.text(classifier[1], ci, "href")}"/>\n'
        )
    if is_a(ci, "SystemInstance"):
        soms = list(items_of(ci, "systemOperationModes"))
        for som in soms:
            som_attrs = f' name="{w.text(value_of(som, "name") or "", ci, "name")}"'
            current = items_of(som, "currentModes")
            if len(current):
                som_attrs += f' currentMode="{w.refs(current, ci, "a system operation mode")}"'
            out.append(f"{inner}<systemOperationMode{som_attrs}/>\n")
        if not soms:
            out.append(f'{inner}<systemOperationMode name="No Modes"/>\n')
        impl = w.links.classifier_href(
            value_of(ci, "classifier"), value_of(ci, "category"), implementation=True
        )
        if impl is not None:
            out.append(
                f'{inner}<componentImplementation xsi:type="{impl[0]}" '
                f'href="{w.text(impl[1], ci, "href")}"/>\n'
            )
    if len(out) == body_start:
        out[start] = f"{indent}<{tag}{root_attrs}{attributes}/>\n"
    else:
        out.append(f"{indent}</{tag}>\n")


def emit_feature(w: Writer, indent: str, fi: EObject, decls: dict[int, EObject | None]) -> None:
    out = w.out
    category = literal_name(value_of(fi, "category"))
    category = INSTANCE_FEATURE_CATEGORY.get(category, category)
    attributes = f' name="{w.text(value_of(fi, "name") or "", fi, "name")}"'
    if category and category != "dataPort":
        attributes += f' category="{category}"'
    direction = java_literal(value_of(fi, "direction") or "in")
    if direction != "in":
        attributes += f' direction="{direction}"'
    feature_index = value_of(fi, "index")
    if feature_index:
        attributes += f' index="{int(feature_index)}"'
    if value_of(fi, "type") is not None:
        attributes += f' type="{w.ref(value_of(fi, "type"), fi, "the feature type")}"'
    decl = w.links.feature_decl(fi, decls)
    decls[id(fi)] = decl
    start = len(out)
    out.append(f"{indent}<featureInstance{attributes}>\n")
    inner = indent + "  "
    emit_associations(w, inner, fi)
    for child in items_of(fi, "featureInstances"):
        emit_feature(w, inner, child, decls)
    href = w.links.member_href(decl) if decl is not None else None
    if href is not None:
        out.append(f'{inner}<feature xsi:type="{href[0]}" href="{w.text(href[1], fi, "href")}"/>\n')
    else:
        w.links.note_missing("feature")
    if len(out) == start + 1:
        out[start] = f"{indent}<featureInstance{attributes}/>\n"
    else:
        out.append(f"{indent}</featureInstance>\n")


def emit_connection(w: Writer, indent: str, conn: EObject) -> None:
    out = w.out
    attributes = f' name="{w.text(value_of(conn, "name") or "", conn, "name")}"'
    if len(items_of(conn, "inSystemOperationModes")):
        soms = []
        for name in items_of(conn, "inSystemOperationModes"):
            som = w.som_by_name.get((name or "").lower())
            if som is None:
                raise w.error(
                    f"the connection exists in {name!r}, which is not a system operation mode", conn
                )
            soms.append(w.paths[id(som)])
        attributes += f' inSystemOperationMode="{" ".join(soms)}"'
    if value_of(conn, "complete"):
        attributes += ' complete="true"'
    kind = literal_name(value_of(conn, "kind"))
    if kind and kind != "featureConnection":
        attributes += f' kind="{kind}"'
    attributes += f' destination="{w.ref(value_of(conn, "destination"), conn, "the destination")}"'
    if value_of(conn, "bidirectional"):
        attributes += ' bidirectional="true"'
    attributes += f' source="{w.ref(value_of(conn, "source"), conn, "the source")}"'
    out.append(f"{indent}<connectionInstance{attributes}>\n")
    inner = indent + "  "
    emit_associations(w, inner, conn)
    for ref in items_of(conn, "connectionReferences"):
        context = w.ref(value_of(ref, "context"), conn, "a connection reference context")
        source = w.ref(value_of(ref, "source"), conn, "a connection reference source")
        destination = w.ref(value_of(ref, "destination"), conn, "a connection reference destination")
        ref_attrs = f' context="{context}" source="{source}" destination="{destination}"'
        if value_of(ref, "reverse"):
            ref_attrs += ' reverse="true"'
        href = w.links.connection_href(ref)
        if href is None:
            w.links.note_missing("connection")
            out.append(f"{inner}<connectionReference{ref_attrs}/>\n")
            continue
        type_attr = f' xsi:type="{href[0]}"' if href[0] else ""
        out.append(f"{inner}<connectionReference{ref_attrs}>\n")
        out.append(f'{inner}  <connection{type_attr} href="{w.text(href[1], conn, "href")}"/>\n')
        out.append(f"{inner}</connectionReference>\n")
    out.append(f"{indent}</connectionInstance>\n")


def emit_simple(
    w: Writer, indent: str, obj: EObject, tag: str, attributes: str, link: tuple[str, Any] | None
) -> None:
    """An instance object with associations and one link element to its declaration."""
    out = w.out
    start = len(out)
    out.append(f"{indent}<{tag}{attributes}>\n")
    emit_associations(w, indent + "  ", obj)
    if link is not None and link[1] is not None:
        link_tag, (_xsi, href) = link
        out.append(f'{indent}  <{link_tag} href="{w.text(href, obj, "href")}"/>\n')
    elif link is not None:
        w.links.note_missing(link[0])
    if len(out) == start + 1:
        out[start] = f"{indent}<{tag}{attributes}/>\n"
    else:
        out.append(f"{indent}</{tag}>\n")


def emit_mode(w: Writer, indent: str, mi: EObject) -> None:
    attributes = f' name="{w.text(mi.name or "", mi, "name")}"'
    if mi.initial:
        attributes += ' initial="true"'
    emit_simple(w, indent, mi, "modeInstance", attributes, ("mode", w.links.mode_href(mi)))


def emit_transition(w: Writer, indent: str, mti: EObject) -> None:
    attributes = f' name="{w.text(mti.name or "", mti, "name")}"'
    attributes += f' destination="{w.ref(mti.destination, mti, "the destination mode")}"'
    if len(mti.triggers):
        attributes += f' trigger="{w.refs(mti.triggers, mti, "a trigger")}"'
    attributes += f' source="{w.ref(mti.source, mti, "the source mode")}"'
    emit_simple(
        w, indent, mti, "modeTransitionInstance", attributes, ("modeTransition", w.links.transition_href(mti))
    )


def emit_flow_spec(w: Writer, indent: str, fsi: EObject) -> None:
    attributes = f' name="{w.text(fsi.name or "", fsi, "name")}"'
    if fsi.source is not None:
        attributes += f' source="{w.ref(fsi.source, fsi, "the flow source")}"'
    if fsi.destination is not None:
        attributes += f' destination="{w.ref(fsi.destination, fsi, "the flow destination")}"'
    emit_simple(
        w, indent, fsi, "flowSpecification", attributes, ("flowSpecification", w.links.flow_spec_href(fsi))
    )


def emit_end_to_end(w: Writer, indent: str, flow: EObject) -> None:
    attributes = f' name="{w.text(flow.name or "", flow, "name")}"'
    if len(flow.flowElements):
        attributes += f' flowElement="{w.refs(flow.flowElements, flow, "a flow element")}"'
    emit_simple(w, indent, flow, "endToEndFlow", attributes, ("endToEndFlow", w.links.end_to_end_href(flow)))
