"""Fast, read-only navigation of instance models for the generator.

The generator walks large instances many times; these helpers follow the instance containment
directly (``componentInstances``, ``featureInstances``, ``connectionInstances``) with the model
API's walker (:func:`rosaadl.model.component_instances`) and class test
(:func:`rosaadl.model.is_a`), and read property values from a per-object table.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.element_keys import element_key
from rosaadl.properties import EnumLiteral, python_value

__all__ = [
    "enum_name",
    "connections",
    "owner_component",
    "process_of",
    "prop",
    "key",
    "caching",
]


def enum_name(value: object) -> str:
    """The name of an enumeration literal, an :class:`EnumLiteral` or a string."""
    if isinstance(value, EnumLiteral):
        return value.name
    return str(getattr(value, "name", value) or "")


def connections(root: EObject) -> Iterator[EObject]:
    """Every connection instance of ``root`` and of the components below it."""
    for component in model.component_instances(root):
        yield from component.connectionInstances


def owner_component(obj: EObject) -> EObject | None:
    """The component instance a feature instance belongs to (through feature groups)."""
    current = obj.eContainer() if obj is not None else None
    while current is not None and not model.is_a(current, "ComponentInstance"):
        current = current.eContainer()
    return current


def process_of(obj: EObject) -> EObject | None:
    """The process instance that contains ``obj`` (itself for a process), or None."""
    current = obj
    while current is not None:
        if model.is_a(current, "ComponentInstance") and enum_name(current.category) == "process":
            return current
        current = current.eContainer()
    return None


def _table(obj: EObject) -> dict[str, list[tuple[str, EObject]]]:
    table: dict[str, list[tuple[str, EObject]]] = {}
    for assoc in getattr(obj, "ownedPropertyAssociations", None) or ():
        if assoc.appliesTo:
            continue
        written = (assoc.property or "").lower()
        table.setdefault(written.rpartition("::")[2], []).append((written, assoc))
    return table


def _value(assoc: EObject) -> object:
    default = None
    for modal in assoc.ownedValues:
        if not modal.inModes:
            default = modal.value
            break
    if default is None and assoc.ownedValues:
        default = assoc.ownedValues[0].value
    return python_value(default)


_CACHE: ContextVar[dict | None] = ContextVar("rosaadl_rclpy_instance_cache", default=None)


@contextmanager
def caching() -> Iterator[None]:
    """Within the block, property values and element keys are computed once per object (the
    instance must not change meanwhile)."""
    token = _CACHE.set({})
    try:
        yield
    finally:
        _CACHE.reset(token)


def prop(obj: EObject, name: str) -> object:
    """The value of property ``name`` held by an instance object (its resolved value), as
    :func:`rosaadl.properties.property_value` gives it; None when it has none."""
    cache = _CACHE.get()
    wanted = name.lower()
    if cache is not None:
        memo = cache.get((id(obj), wanted), _MISSING)
        if memo is not _MISSING:
            return memo
        table = cache.get(id(obj))
        if table is None:
            table = cache[id(obj)] = _table(obj)
    else:
        table = _table(obj)
    qualified = "::" in wanted
    found = None
    for written, assoc in table.get(wanted.rpartition("::")[2], ()):
        if not qualified or written == wanted or "::" not in written:
            found = assoc
    value = None if found is None else _value(found)
    if cache is not None:
        cache[(id(obj), wanted)] = value
    return value


_MISSING = object()


def key(obj: EObject) -> str:
    """The stable key of ``obj`` (:func:`rosaadl.element_keys.element_key`), remembered for
    the instance's elements within :func:`caching`."""
    cache = _CACHE.get()
    if cache is None:
        return element_key(obj)
    keys = cache.get("keys")
    if keys is None:
        keys = cache["keys"] = {}
    return element_key(obj, keys)
