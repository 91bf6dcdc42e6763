"""What the reader puts in the model: AADL identifiers for Cheddar names, and property values.

The values are made from the metamodel's Python classes directly (looked up once): the reader
makes several per field of every entity, and :func:`rosaadl.model.new` checks each keyword,
which costs more than the assignments themselves.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model

__all__ = [
    "aadl_identifier",
    "int_value",
    "real_value",
    "bool_value",
    "str_value",
    "named_value",
    "range_value",
    "list_value",
    "record_value",
    "reference_value",
    "associate",
]


def aadl_identifier(name: str) -> str:
    """A valid AADL identifier close to ``name`` (``DAG1-Kernel1`` → ``DAG1_Kernel1``)."""
    text = re.sub(r"[^A-Za-z0-9]+", "_", name.strip())
    text = re.sub(r"_+", "_", text).strip("_")
    if not text:
        return "unnamed"
    if not text[0].isalpha():
        text = "n_" + text
    return text


_CLASSES: dict[str, Any] = {}


def _cls(name: str) -> Any:
    cls = _CLASSES.get(name)
    if cls is None:
        cls = _CLASSES[name] = model.eclass_of(name).python_class
    return cls


def _holding(class_name: str, value: Any) -> EObject:
    obj = _cls(class_name)()
    obj.value = value
    return obj


def int_value(value: int, unit: str | None = None) -> EObject:
    obj = _holding("IntegerValue", value)
    if unit:
        obj.unit = unit
    return obj


def real_value(value: float) -> EObject:
    return _holding("RealValue", value)


def bool_value(value: bool) -> EObject:
    return _holding("BooleanValue", value)


def str_value(value: str) -> EObject:
    return _holding("StringValue", value)


def named_value(name: str) -> EObject:
    obj = _cls("NamedValue")()
    obj.name = name
    return obj


def range_value(low: EObject, high: EObject) -> EObject:
    obj = _cls("RangeValue")()
    obj.minimum = low
    obj.maximum = high
    return obj


def list_value(items: Iterable[EObject]) -> EObject:
    obj = _cls("ListValue")()
    obj.ownedItems.extend(items)
    return obj


def record_value(fields: Iterable[tuple[str, EObject]]) -> EObject:
    obj = _cls("RecordValue")()
    for name, value in fields:
        item = _cls("FieldValue")()
        item.name = name
        item.value = value
        obj.ownedFields.append(item)
    return obj


def reference_value(target: EObject | str) -> EObject:
    """A reference to an instance, or (for a name that does not resolve) a path."""
    if isinstance(target, str):
        obj = _cls("ReferenceValue")()
        obj.path = target
        return obj
    obj = _cls("InstanceReferenceValue")()
    obj.referencedInstanceObject = target
    return obj


def associate(owner: EObject, prop: str, value: EObject) -> None:
    """Give ``owner`` the property ``prop`` with ``value`` (no modes, no ``applies to``)."""
    assoc = _cls("PropertyAssociation")()
    assoc.property = prop
    modal = _cls("ModalPropertyValue")()
    modal.value = value
    assoc.ownedValues.append(modal)
    owner.ownedPropertyAssociations.append(assoc)
