"""The readers of property associations and values (``aadl2:*Literal``, ``NamedValue``, ...).

:func:`property_association` reads an ``ownedPropertyAssociation`` with its modal values;
:func:`read_value` dispatches on a value's ``xsi:type`` (:data:`VALUE_HANDLERS`, looked up
once per ``xsi:type`` text) to one function per value class. Positional references into
property sets (a property, a unit, an enumeration literal, a record field) are kept as
``uri#fragment`` on the object and recorded on the reader (``literal_uses``), to be decoded
once the era of the file is known (:mod:`.literals`).
"""

from __future__ import annotations

from lxml import etree
from pyecore.ecore import EObject

from .document import Reader
from .xmi import (
    NS_AADL2,
    NS_INSTANCE,
    PA_IGNORED,
    XSI_TYPE,
    XSI_TYPE_KEY,
    is_positional,
    link_class,
    name_of,
    qualified_name,
    split_ref_attribute,
)

__all__ = ["property_association", "property_name", "modal_value", "read_value", "VALUE_HANDLERS"]


def property_association(r: Reader, el: etree._Element) -> EObject:
    f, fast = r.f, r.fast
    obj = r.new(r.c_pa)
    if r.has_ids:
        r.register_id(obj, el)
    prop = None
    value_elements = []
    for child in el:
        tag = child.tag
        if tag == "ownedValue":
            value_elements.append(child)
        elif tag == "property":
            href = child.get("href")
            found = r.property_cache.get(href)
            if found is not None and not found[1]:  # by name, seen before
                prop = found[0]
                fast.set_value(obj, r.s_pa_property, prop)
            else:
                prop = property_name(r, href, obj, child)
        elif tag in PA_IGNORED or not isinstance(tag, str):
            continue
        else:
            r.unknown(child, "ownedPropertyAssociation")
    if prop is None:
        text = el.get("property")
        if text is None:
            raise r.error("a property association names no property", el)
        _type, uri, frag = split_ref_attribute(text)
        prop = property_name(r, f"{uri}#{frag}", obj, el)
    if value_elements:
        fast.set_many(obj, r.s_pa_values, [modal_value(r, v, prop) for v in value_elements])
    if el.get("append") == "true":
        fast.set_value(obj, f["PropertyAssociation.append"], True)
    if el.get("constant") == "true":
        fast.set_value(obj, f["PropertyAssociation.constant"], True)
    return obj


def property_name(r: Reader, href: str | None, obj: EObject, el: etree._Element) -> str:
    """The qualified property name; positional references are decoded once the era is known."""
    if href is None:
        raise r.error(f"<{el.tag}> has no href", el)
    found = r.property_cache.get(href)
    if found is None:
        uri, _, frag = href.partition("#")
        r.check_fragment(frag, el, "href" if el.get("href") is not None else "property")
        r.note_uri(uri)
        positional = not frag or is_positional(frag)
        found = (href if positional else qualified_name(frag, "Property"), positional)
        r.property_cache[href] = found
    name, positional = found
    if positional:
        uri, _, frag = href.partition("#")
        r.literal_use((uri, frag, "property", None, None), obj, "property")
    r.fast.set_value(obj, r.f["PropertyAssociation.property"], name)
    return name


def modal_value(r: Reader, el: etree._Element, prop: str | None) -> EObject:
    fast = r.fast
    obj = r.new(r.c_modal)
    if r.has_ids:
        r.register_id(obj, el)
    value = None
    for child in el:
        if child.tag == "ownedValue":
            value = read_value(r, child, prop, None)
        else:
            r.unknown(child, "ownedValue")
    if value is None:
        raise r.error("a property value holds no ownedValue", el)
    fast.set_child(obj, r.s_modal_value, value)
    if el.get("inMode"):
        r.ref_later(
            obj,
            r.f["ModalPropertyValue.inModes"],
            el,
            "inMode",
            many=True,
            names_of="SystemOperationMode",
        )
    return obj


def read_value(
    r: Reader, el: etree._Element, prop: str | None, field_href: tuple[str, str] | None
) -> EObject:
    handler = r.handler_cache.get(el.get(XSI_TYPE_KEY))
    if handler is None:
        handler = VALUE_HANDLERS.get(r.xsi_type(el))
        if handler is None:
            raise r.error(f"unknown property value type xsi:type={el.get(XSI_TYPE)!r}", el, "xsi:type")
        if el.get(XSI_TYPE) is not None and r.nsmap_is_global:
            r.handler_cache[el.get(XSI_TYPE)] = handler
    obj = handler(r, el, prop, field_href)
    if r.has_ids:
        r.register_id(obj, el)
    return obj


def _number(r: Reader, el, prop, field_href, cls: type, value_slot, unit_slot, convert) -> EObject:
    fast = r.fast
    obj = r.new(cls)
    text = el.get("value")
    if text is None:
        number = convert("0")
    else:
        try:
            number = convert(text)  # int() and float() ignore surrounding whitespace
        except ValueError:
            raise r.error(f"value {text!r} is not a number", el, "value") from None
    fast.set_value(obj, value_slot, number)
    # a number has one child at most, its unit
    count = len(el)
    unit_el = None
    if count == 1:
        unit_el = el[0]
        if unit_el.tag != "unit":
            r.unknown(unit_el, el.tag)
            unit_el = None
    elif count:
        for child in el:
            if child.tag == "unit":
                unit_el = child
            else:
                r.unknown(child, el.tag)
    if unit_el is not None:
        href = unit_el.get("href")
        key = (href, prop, field_href)
        found = r.unit_uses.get(key)
        if found is None:
            uri, frag = r.href(unit_el)
            uses = r.literal_uses.setdefault((uri, frag, "unit", prop, field_href), [])
            found = r.unit_uses[key] = (f"{uri}#{frag}", uses)
    else:
        unit_attr = el.get("unit")
        if unit_attr is None:
            return obj
        _type, uri, frag = split_ref_attribute(unit_attr)
        r.check_fragment(frag, el, "unit")
        r.note_uri(uri)
        found = (f"{uri}#{frag}", r.literal_uses.setdefault((uri, frag, "unit", prop, field_href), []))
    fast.set_value(obj, unit_slot, found[0])
    found[1].append((obj, "unit"))
    return obj


def _integer(r: Reader, el, prop, field_href) -> EObject:
    return _number(r, el, prop, field_href, r.c_int, r.s_int_value, r.s_int_unit, int)


def _real(r: Reader, el, prop, field_href) -> EObject:
    return _number(r, el, prop, field_href, r.c_real, r.s_real_value, r.s_real_unit, float)


def _string(r: Reader, el, prop, field_href) -> EObject:
    obj = r.new(r.cls["StringValue"])
    r.fast.set_value(obj, r.f["StringValue.value"], el.get("value") or "")
    return obj


def _boolean(r: Reader, el, prop, field_href) -> EObject:
    obj = r.new(r.cls["BooleanValue"])
    text = el.get("value")
    if text not in (None, "true", "false"):
        raise r.error(f"value {text!r} is not a boolean (true or false)", el, "value")
    r.fast.set_value(obj, r.f["BooleanValue.value"], text == "true")
    return obj


def _named(r: Reader, el, prop, field_href) -> EObject:
    obj = r.new(r.cls["NamedValue"])
    target = r.link(el, "namedValue", "NamedValue")
    if target is None:
        raise r.error("a named value names nothing (expected a namedValue reference)", el)
    found = r.named_values.get(target)
    if found is None:
        uri, frag = target
        found = r.named_values[target] = (name_of(uri, frag), not frag or is_positional(frag))
    if found[1]:
        r.literal_use((*target, "enum", prop, field_href), obj, "name")
    r.fast.set_value(obj, r.s_named_name, found[0])
    return obj


def _range(r: Reader, el, prop, field_href) -> EObject:
    f, fast = r.f, r.fast
    obj = r.new(r.cls["RangeValue"])
    for child in el:
        tag = child.tag
        if tag in ("minimum", "maximum", "delta"):
            fast.set_child(obj, f[f"RangeValue.{tag}"], read_value(r, child, prop, field_href))
        else:
            r.unknown(child, "RangeValue")
    return obj


def _list(r: Reader, el, prop, field_href) -> EObject:
    obj = r.new(r.cls["ListValue"])
    items = []
    for child in el:
        if child.tag == "ownedListElement":
            items.append(read_value(r, child, prop, field_href))
        else:
            r.unknown(child, "ListValue")
    if items:
        r.fast.set_many(obj, r.f["ListValue.ownedItems"], items)
    return obj


def _record(r: Reader, el, prop, field_href) -> EObject:
    f, fast = r.f, r.fast
    new, set_value, set_child = r.new, fast.set_value, fast.set_child
    c_field, s_name, s_value = r.cls["FieldValue"], f["FieldValue.name"], f["FieldValue.value"]
    field_names = r.field_names
    obj = new(r.cls["RecordValue"])
    fields = []
    for child in el:
        if child.tag != "ownedFieldValue":
            r.unknown(child, "RecordValue")
            continue
        field_obj = new(c_field)
        if r.has_ids:
            r.register_id(field_obj, child)
        target = None
        value_el = None
        for part in child:
            tag = part.tag
            if tag == "property":
                target = r.href(part)
            elif tag == "ownedValue":
                value_el = part
            else:
                r.unknown(part, "ownedFieldValue")
        if target is None and child.get("property") is not None:
            _type, uri, frag = split_ref_attribute(child.get("property"))
            r.check_fragment(frag, child, "property")
            target = (uri, frag)
        if target is None or value_el is None:
            raise r.error("a record field needs a property and an ownedValue", child)
        name = field_names.get(target)
        if name is None:
            uri, frag = target
            positional = not frag or is_positional(frag)
            name = field_names[target] = (
                f"{uri}#{frag}" if positional else qualified_name(frag).rpartition("::")[2],
                positional,
            )
        set_value(field_obj, s_name, name[0])
        if name[1]:
            r.literal_use((*target, "field", prop, field_href), field_obj, "name")
        set_child(field_obj, s_value, read_value(r, value_el, prop, target))
        fields.append(field_obj)
    if fields:
        fast.set_many(obj, f["RecordValue.ownedFields"], fields)
    return obj


def _classifier(r: Reader, el, prop, field_href) -> EObject:
    obj = r.new(r.cls["ClassifierValue"])
    target = r.typed_link(el, "classifier", "ClassifierValue")
    if target is None:
        raise r.error("a classifier value names no classifier", el)
    kind, uri, frag = target
    name = name_of(uri, frag, kind)
    r.fast.set_value(obj, r.f["ClassifierValue.classifier"], name)
    return obj


def _reference(r: Reader, el, prop, field_href) -> EObject:
    obj = r.new(r.cls["ReferenceValue"])
    steps = []
    current = el
    while current is not None:
        nxt = None
        for child in current:
            if child.tag == "containmentPathElement" or child.tag == "path":
                nxt = child
            elif child.tag == "namedElement":
                uri, frag = r.href(child)
                named = name_of(uri, frag, link_class(child.get(XSI_TYPE_KEY)))
                steps.append(named if named.startswith(f"{uri}#") else named.rpartition("::")[2])
            elif child.tag == "arrayRange":
                continue
            else:
                r.unknown(child, "ReferenceValue")
        current = nxt
    path = ".".join(steps)
    r.fast.set_value(obj, r.f["ReferenceValue.path"], path)
    r.warn(f"reference value ({path}) kept as a declarative path, not resolved to an instance", el)
    return obj


def _instance_reference(r: Reader, el, prop, field_href) -> EObject:
    obj = r.new(r.cls["InstanceReferenceValue"])
    if el.get("referencedInstanceObject") is None:
        raise r.error("an instance reference value refers to nothing", el)
    r.ref_later(obj, r.f["InstanceReferenceValue.referencedInstanceObject"], el, "referencedInstanceObject")
    return obj


def _computed(r: Reader, el, prop, field_href) -> EObject:
    obj = r.new(r.cls["ComputedValue"])
    r.fast.set_value(obj, r.f["ComputedValue.function"], el.get("function") or "")
    return obj


def _operation(r: Reader, el, prop, field_href) -> EObject:
    obj = r.new(r.cls["OperationValue"])
    r.fast.set_value(obj, r.f["OperationValue.operator"], el.get("op") or "and")
    operands = [
        read_value(r, child, prop, field_href) for child in el if child.tag == "ownedPropertyExpression"
    ]
    if operands:
        r.fast.set_many(obj, r.f["OperationValue.ownedOperands"], operands)
    return obj


VALUE_HANDLERS = {
    (NS_AADL2, "IntegerLiteral"): _integer,
    (NS_AADL2, "RealLiteral"): _real,
    (NS_AADL2, "StringLiteral"): _string,
    (NS_AADL2, "BooleanLiteral"): _boolean,
    (NS_AADL2, "NamedValue"): _named,
    (NS_AADL2, "RangeValue"): _range,
    (NS_AADL2, "ListValue"): _list,
    (NS_AADL2, "RecordValue"): _record,
    (NS_AADL2, "ClassifierValue"): _classifier,
    (NS_AADL2, "ReferenceValue"): _reference,
    (NS_AADL2, "ComputedValue"): _computed,
    (NS_AADL2, "Operation"): _operation,
    (NS_INSTANCE, "InstanceReferenceValue"): _instance_reference,
}
