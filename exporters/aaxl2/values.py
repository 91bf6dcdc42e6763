"""Property associations and values written as OSATE's XMI (``instance:PropertyAssociationInstance``).

:func:`emit_associations` writes the associations of an instance object, each with its modal
values (``inMode``: the system operation modes their mode names stand for); :func:`emit_value`
writes one value by its class, with the hrefs of :mod:`.value_hrefs`. An association whose
value cannot be written for OSATE (:class:`~.value_hrefs.Skip`) is taken back out of the
document and reported.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.model import instance_path, is_a

from .declarations import find_named
from .emf_text import attr_text, items_of, java_double, value_of
from .property_types import TypeInfo
from .state import Writer
from .value_hrefs import Skip, classifier_value, literal_href, named_value, property_info, record_type
from .vocabulary import FRAGMENT_RE, OPERATORS

__all__ = ["emit_associations", "emit_value", "modal_in_modes", "opaque_steps"]


def emit_associations(w: Writer, indent: str, obj: EObject) -> None:
    for association in items_of(obj, "ownedPropertyAssociations"):
        mark = len(w.out)
        try:
            emit_association(w, indent, association, obj)
        except Skip as exc:
            del w.out[mark:]
            w.skipped.append(f"{instance_path(obj)}: {value_of(association, 'property')}: {exc}")


def emit_association(w: Writer, indent: str, association: EObject, obj: EObject) -> None:
    out = w.out
    name = value_of(association, "property") or ""
    href, info = property_info(w, name, obj)
    attributes = ""
    if value_of(association, "append"):
        attributes += ' append="true"'
    if value_of(association, "constant"):
        attributes += ' constant="true"'
    out.append(
        f'{indent}<ownedPropertyAssociation xsi:type="instance:PropertyAssociationInstance"{attributes}>\n'
    )
    out.append(f'{indent}  <property href="{w.text(href, obj, "property")}"/>\n')
    for modal in items_of(association, "ownedValues"):
        if value_of(modal, "value") is None:
            continue
        in_mode = ""
        if len(items_of(modal, "inModes")):
            paths = modal_in_modes(w, list(items_of(modal, "inModes")), obj)
            if paths is None:
                raise Skip(
                    f"in modes ({', '.join(items_of(modal, 'inModes'))}) name no system operation mode"
                )
            in_mode = f' inMode="{paths}"'
        out.append(f"{indent}  <ownedValue{in_mode}>\n")
        emit_value(w, indent + "    ", "ownedValue", value_of(modal, "value"), info, obj)
        out.append(f"{indent}  </ownedValue>\n")
    out.append(f"{indent}</ownedPropertyAssociation>\n")


def modal_in_modes(w: Writer, names: list[str], owner: EObject) -> str | None:
    """``inMode`` of a modal value: the system operation modes its mode names stand for."""
    targets: list[EObject] = []
    for name in names:
        key = (name or "").split("=>")[0].strip().lower()
        som = w.som_by_name.get(key)
        if som is not None:
            targets.append(som)
            continue
        component = owner
        while component is not None and not is_a(component, "ComponentInstance"):
            component = component.eContainer()
        mode = None
        while component is not None and mode is None:
            mode = find_named(list(component.modeInstances), key)
            component = component.eContainer() if mode is None else component
            if component is not None and not is_a(component, "ComponentInstance"):
                component = None
        if mode is None:
            return None
        targets.extend(s for s in w.system.systemOperationModes if any(m is mode for m in s.currentModes))
    return " ".join(w.paths[id(t)] for t in targets)


def emit_value(
    w: Writer, indent: str, tag: str, expr: EObject, info: TypeInfo | None, owner: EObject
) -> None:
    out = w.out
    kind = expr.eClass.name  # each value class is written as its own aadl2 class
    if kind in ("IntegerValue", "RealValue"):
        value = value_of(expr, "value") or 0
        if kind == "IntegerValue":
            xsi, shown = "aadl2:IntegerLiteral", (str(int(value)) if value else "")
        else:
            xsi, shown = "aadl2:RealLiteral", (java_double(float(value)) if value else "")
        attributes = f' value="{shown}"' if shown else ""
        unit = (value_of(expr, "unit") or "").strip()
        if not unit:
            out.append(f'{indent}<{tag} xsi:type="{xsi}"{attributes}/>\n')
            return
        if "#" in unit:
            href = unit
        else:
            href = literal_href(w, info.units if info is not None else None, unit, "unit")
        out.append(f'{indent}<{tag} xsi:type="{xsi}"{attributes}>\n')
        out.append(f'{indent}  <unit href="{w.text(href, owner, "unit")}"/>\n')
        out.append(f"{indent}</{tag}>\n")
    elif kind == "StringValue":
        value = value_of(expr, "value")
        attributes = f' value="{w.text(value, owner, "string")}"' if value is not None else ""
        out.append(f'{indent}<{tag} xsi:type="aadl2:StringLiteral"{attributes}/>\n')
    elif kind == "BooleanValue":
        attributes = ' value="true"' if value_of(expr, "value") else ""
        out.append(f'{indent}<{tag} xsi:type="aadl2:BooleanLiteral"{attributes}/>\n')
    elif kind == "NamedValue":
        xsi, href = named_value(w, expr, info)
        out.append(f'{indent}<{tag} xsi:type="aadl2:NamedValue">\n')
        out.append(f'{indent}  <namedValue xsi:type="{xsi}" href="{w.text(href, owner, "value")}"/>\n')
        out.append(f"{indent}</{tag}>\n")
    elif kind == "RangeValue":
        number = info.inner if info is not None and info.kind == "range" else info
        out.append(f'{indent}<{tag} xsi:type="aadl2:RangeValue">\n')
        for part in ("minimum", "maximum", "delta"):
            bound = getattr(expr, part)
            if bound is not None:
                emit_value(w, indent + "  ", part, bound, number, owner)
        out.append(f"{indent}</{tag}>\n")
    elif kind == "ListValue":
        items = list(items_of(expr, "ownedItems"))
        if not items:
            out.append(f'{indent}<{tag} xsi:type="aadl2:ListValue"/>\n')
            return
        element = info.element if info is not None else None
        out.append(f'{indent}<{tag} xsi:type="aadl2:ListValue">\n')
        for item in items:
            emit_value(w, indent + "  ", "ownedListElement", item, element, owner)
        out.append(f"{indent}</{tag}>\n")
    elif kind == "RecordValue":
        fields = list(items_of(expr, "ownedFields"))
        record = record_type(w, info, [(f.name or "").strip() for f in fields if "#" not in (f.name or "")])
        out.append(f'{indent}<{tag} xsi:type="aadl2:RecordValue"' + (">\n" if fields else "/>\n"))
        for item in fields:
            name = (value_of(item, "name") or "").strip()
            field_info = None
            if "#" in name:
                href = name
            else:
                if record is None:
                    raise Skip(f"record field {name!r} cannot be placed (the record type is not known)")
                href = literal_href(w, record, name, "record field")
                position = record.index(name)
                if position is not None and position < len(record.fields):
                    field_info = record.fields[position]
            out.append(f"{indent}  <ownedFieldValue>\n")
            out.append(f'{indent}    <property href="{w.text(href, owner, "field")}"/>\n')
            if value_of(item, "value") is not None:
                emit_value(w, indent + "    ", "ownedValue", value_of(item, "value"), field_info, owner)
            out.append(f"{indent}  </ownedFieldValue>\n")
        if fields:
            out.append(f"{indent}</{tag}>\n")
    elif kind == "InstanceReferenceValue":
        target = w.ref(value_of(expr, "referencedInstanceObject"), owner, "a reference value")
        out.append(
            f'{indent}<{tag} xsi:type="instance:InstanceReferenceValue" '
            f'referencedInstanceObject="{target}"/>\n'
        )
    elif kind == "ClassifierValue":
        found = classifier_value(w, value_of(expr, "classifier"))
        out.append(f'{indent}<{tag} xsi:type="aadl2:ClassifierValue">\n')
        out.append(
            f'{indent}  <classifier xsi:type="{found[0]}" href="{w.text(found[1], owner, "classifier")}"/>\n'
        )
        out.append(f"{indent}</{tag}>\n")
    elif kind == "ReferenceValue":
        steps = (
            [s for s in (value_of(expr, "path") or "").split(".") if s]
            if "#" not in (value_of(expr, "path") or "")
            else []
        )
        if "#" in (value_of(expr, "path") or ""):
            steps = opaque_steps(value_of(expr, "path"))
        if not steps or not all("#" in s for s in steps):
            raise Skip(f"the reference ({value_of(expr, 'path')}) does not resolve to an instance object")
        out.append(f'{indent}<{tag} xsi:type="aadl2:ReferenceValue">\n')
        depth = indent + "  "
        for step in steps:
            xsi, href = w.links.opaque_href(step)
            type_attr = f' xsi:type="{xsi}"' if xsi else ""
            out.append(f"{depth}<path>\n")
            out.append(f'{depth}  <namedElement{type_attr} href="{w.text(href, owner, "reference")}"/>\n')
            depth += "  "
        for _ in steps:
            depth = depth[:-2]
            out.append(f"{depth}</path>\n")
        out.append(f"{indent}</{tag}>\n")
    elif kind == "ComputedValue":
        function = value_of(expr, "function")
        attributes = f' function="{w.text(function, owner, "function")}"' if function else ""
        out.append(f'{indent}<{tag} xsi:type="aadl2:ComputedValue"{attributes}/>\n')
    elif kind == "OperationValue":
        operator = OPERATORS.get((value_of(expr, "operator") or "and").strip().lower())
        if operator is None:
            raise Skip(f"operator {value_of(expr, 'operator')!r} is not an AADL operator")
        attributes = f' op="{attr_text(operator)}"' if operator != "and" else ""
        operands = list(items_of(expr, "ownedOperands"))
        out.append(f'{indent}<{tag} xsi:type="aadl2:Operation"{attributes}' + (">\n" if operands else "/>\n"))
        for operand in operands:
            emit_value(w, indent + "  ", "ownedPropertyExpression", operand, info, owner)
        if operands:
            out.append(f"{indent}</{tag}>\n")
    else:
        raise Skip(f"a {kind} has no OSATE form")


def opaque_steps(path: str) -> list[str]:
    """Split ``uri#frag.uri#frag`` (a reference path the reader kept, its steps joined by
    dots) into its steps; a fragment is an EMF path (``//@a.1/@b.0``) or a qualified name."""
    steps: list[str] = []
    position = 0
    while position < len(path):
        hash_at = path.find("#", position)
        if hash_at < 0:
            return []
        match = FRAGMENT_RE.match(path, hash_at + 1)
        if match is None:
            return []
        steps.append(path[position : match.end()])
        position = match.end()
        if position < len(path):
            if path[position] != ".":
                return []
            position += 1
    return steps
