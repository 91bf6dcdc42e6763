"""The hrefs the names in a property value become: properties, units, literals, fields, classifiers.

A property association names its property by qualified name
(``…/Timing_Properties.aadl#Timing_Properties.Period``); units, enumeration literals and record
fields are positional hrefs into the property set that declares their type: in OSATE's layout
of the set for OSATE's own sets (:mod:`.osate_sets`), else into the sidecar written from the
model. References into one of OSATE's sets all follow one era: the current one, unless a value
only exists in an older layout of the set (a property OSATE has since renamed), which then
holds for the whole set (``Writer.set_eras``). A value that cannot be placed raises
:class:`Skip`: its association is left out with a warning.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.importers import osate_eras

from .osate_sets import era_property, era_search, library_property_types, older_eras, osate_set
from .property_types import TypeInfo, unit_of
from .state import Writer
from .vocabulary import ERA, name_fragment

__all__ = [
    "Skip",
    "property_info",
    "literal_href",
    "named_value",
    "eras_of",
    "record_type",
    "classifier_value",
]


class Skip(Exception):
    """A value that cannot be written for OSATE; its association is left out with a warning."""


def property_info(w: Writer, name: str, obj: EObject) -> tuple[str, TypeInfo | None]:
    """(href, type) of the property an association sets."""
    found = w.property_cache.get(name)
    if found is not None:
        return found
    text = name.strip()
    if "#" in text:
        found = (text, None)
    else:
        prop = w.resolver.property(text) if w.resolver is not None else None
        info = None
        if prop is not None:
            unit = unit_of(prop)
            href = f"{w.links.unit_uri(unit)}#{name_fragment(unit.name, prop.name)}"
            info = w.types.of_property(prop) if w.types is not None else None
        else:
            set_name, _, local = text.rpartition("::")
            if not set_name:
                raise w.error(f"property {text!r} is not qualified and not declared in the model", obj)
            href = f"{w.links.uri_for_name(set_name)}#{name_fragment(set_name, local)}"
        if info is None and osate_set(text.rpartition("::")[0]):
            info = library_property_types().get(text.lower()) or era_property(text)
        found = (href, info)
    w.property_cache[name] = found
    return found


def literal_href(w: Writer, info: TypeInfo | None, name: str, kind: str) -> str:
    """Positional href of unit / enumeration literal / record field ``name`` of a type.

    A unit whose type is not known (a property of a set that is not in the model) is looked
    up in OSATE's units types, where unit names are unique. References into one of OSATE's
    sets all follow one era: the current one, unless a value only exists in an older layout
    of the set (a property OSATE has since renamed), which then holds for the whole set."""
    if kind == "unit" and (info is None or info.set_name is None):
        info = era_search("units", (name,), ("AADL_Project",))
    if info is None or info.set_name is None:
        raise Skip(f"the type of {kind} {name!r} is not known")
    key = (id(info), name.lower(), kind)
    cached = w.literal_cache.get(key)
    if cached is not None:
        return cached
    if osate_set(info.set_name):
        href = osate_literal_href(w, info, name, kind)
    else:
        position = info.index(name)
        if position is None:
            raise Skip(f"{name!r} is not a {kind} of {info.set_name}::{info.table_name}")
        unit = w.resolver.unit(info.set_name) if w.resolver is not None else None
        if unit is None or info.fragment is None:
            raise Skip(f"property set {info.set_name} is not in the model")
        step = "@ownedField" if info.kind == "record" else "@ownedLiteral"
        href = f"{w.links.unit_uri(unit)}#{osate_eras.fragment(ERA, f'{info.fragment}/{step}.{position}')}"
    w.literal_cache[key] = href
    return href


def osate_literal_href(w: Writer, info: TypeInfo, name: str, kind: str) -> str:
    set_key = (info.set_name or "").lower()
    pinned = w.set_eras.get(set_key)
    eras = [pinned] if pinned else [ERA, *older_eras(info.set_name or "")]
    for era in eras:
        found, path = info, None
        if info.table_name:  # the type of that name in the era's layout (a type keeps its name)
            path = osate_eras.table(era).literal_path(info.set_name or "", info.table_name, name)
        if path is None:
            # this project's copy of the set may name or place the type differently
            searched = era_search(info.kind, (name,), (info.set_name or "", "AADL_Project"), era)
            if searched is not None and searched.set_name is not None:
                found = searched
                path = osate_eras.table(era).literal_path(searched.set_name, searched.table_name or "", name)
        if path is None:
            continue
        target = (found.set_name or "").lower()
        if era != ERA and not w.set_eras.get(target):
            w.wanted_set_eras[target] = era
        elif w.set_eras.get(target, ERA) != era:
            continue
        uri = osate_eras.predeclared_uri(era, found.set_name or "")
        return f"{uri}#{osate_eras.fragment(era, path)}"
    raise Skip(f"OSATE's {info.set_name} has no {kind} {name!r} in {info.table_name}")


def named_value(w: Writer, expr: EObject, info: TypeInfo | None) -> tuple[str, str]:
    name = (expr.name or "").strip()
    if "#" in name:
        return "aadl2:EnumerationLiteral", name
    base = info.base if info is not None else None
    if base is not None and base.kind == "era" and base.set_name:
        for era in eras_of(w, base.set_name):
            found = era_search("enum", (name,), (base.set_name, "AADL_Project"), era)
            if found is not None:
                base = found
                break
    if base is not None and base.kind == "enum" and base.index(name) is not None:
        return "aadl2:EnumerationLiteral", literal_href(w, base, name, "enumeration literal")
    if w.resolver is not None:
        constant = w.resolver.constant(name)
        if constant is not None:
            unit = unit_of(constant)
            href = f"{w.links.unit_uri(unit)}#{name_fragment(unit.name, constant.name)}"
            return "aadl2:PropertyConstant", href
        prop = w.resolver.property(name)
        if prop is not None:
            unit = unit_of(prop)
            return "aadl2:Property", f"{w.links.unit_uri(unit)}#{name_fragment(unit.name, prop.name)}"
    if base is not None and base.kind == "enum":
        raise Skip(f"{name!r} is not a literal of {base.set_name}::{base.table_name}")
    raise Skip(f"the enumeration literal {name!r} cannot be placed (its type is not known)")


def eras_of(w: Writer, set_name: str) -> list[str]:
    pinned = w.set_eras.get(set_name.lower())
    return [pinned] if pinned else [ERA, *older_eras(set_name)]


def record_type(w: Writer, info: TypeInfo | None, names: list[str]) -> TypeInfo | None:
    """The record type of a record value (found by its field names in OSATE's sets when the
    property is known only from the era tables)."""
    record = info.base if info is not None else None
    if record is not None and record.kind == "era" and record.set_name and names:
        for era in eras_of(w, record.set_name):
            found = era_search("record", tuple(names), (record.set_name,), era)
            if found is not None:
                return found
    return record if record is not None and record.kind == "record" else None


def classifier_value(w: Writer, name: str | None) -> tuple[str, str]:
    element = w.links.classifier(name)
    if element is not None:
        unit = unit_of(element)
        return (
            f"aadl2:{w.links.classifier_class(element)}",
            f"{w.links.unit_uri(unit)}#{name_fragment(unit.name, element.name)}",
        )
    text = (name or "").strip()
    if "#" in text:
        xsi, href = w.links.opaque_href(text)
        return xsi or "aadl2:DataType", href
    package, _, local = text.rpartition("::")
    if not package:
        raise Skip(f"classifier {text!r} is not qualified and not in the model")
    return "aadl2:DataImplementation" if "." in local else "aadl2:DataType", (
        f"{w.links.uri_for_name(package)}#{name_fragment(package, local)}"
    )
