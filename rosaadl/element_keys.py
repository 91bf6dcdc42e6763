"""Stable keys of model elements: where an element sits, by containment features and names.

A key is the chain of containment steps from the model's root to the element:
``/units[sw]/classifiers[comp.impl]/subcomponents[timer]``. A named element's step is its
feature and name (``feature[name]``), an unnamed one's its feature and position
(``feature.3``), a single-valued containment's its feature alone. Unlike positional XMI
fragments, a key survives the insertion of siblings, so traces (``transforms/trace.py``),
located diagnostics (``rosaadl.validation``) and the code generator's preservation manifest
(``exporters/rclpy``) name elements by it, and :func:`find_by_key` finds them again in a model
read later.
"""

from __future__ import annotations

from functools import cache

from pyecore.ecore import EClass, EObject

__all__ = ["element_key", "find_by_key"]


@cache
def _named(eclass: EClass) -> bool:
    return eclass.findEStructuralFeature("name") is not None


def _step(obj: EObject, container: EObject) -> str:
    feature = obj.eContainmentFeature()
    name = obj.name if _named(obj.eClass) else None
    if name:
        return f"{feature.name}[{name}]"
    if feature.many:
        return f"{feature.name}.{container.eGet(feature).index(obj)}"
    return feature.name


def element_key(obj: EObject, cache: dict[int, str] | None = None) -> str:
    """The stable key of ``obj`` inside its model (``"/"`` for the root).

    With ``cache`` (a dict kept while the model does not change), the key of each container
    is computed once for all the elements under it, and every key is remembered by ``id``.
    """
    if cache is not None:
        found = cache.get(id(obj))
        if found is None:
            container = obj.eContainer()
            found = (
                "/"
                if container is None
                else f"{element_key(container, cache).rstrip('/')}/{_step(obj, container)}"
            )
            cache[id(obj)] = found
        return found
    steps = []
    current = obj
    container = current.eContainer()
    while container is not None:
        steps.append(_step(current, container))
        current, container = container, container.eContainer()
    return "/" + "/".join(reversed(steps))


def find_by_key(root: EObject, key: str) -> EObject | None:
    """The object with :func:`element_key` ``key`` under ``root`` (None when it is gone)."""
    if key in ("", "/"):
        return root
    current = root
    for step in key.strip("/").split("/"):
        if "[" in step and step.endswith("]"):
            feature_name, _, name = step[:-1].partition("[")
            feature = current.eClass.findEStructuralFeature(feature_name)
            if feature is None:
                return None
            values = current.eGet(feature) if feature.many else [current.eGet(feature)]
            current = next((v for v in values if v is not None and getattr(v, "name", None) == name), None)
        elif "." in step:
            feature_name, _, index = step.partition(".")
            feature = current.eClass.findEStructuralFeature(feature_name)
            if feature is None or not feature.many or not index.isdigit():
                return None
            values = current.eGet(feature)
            position = int(index)
            current = values[position] if position < len(values) else None
        else:
            feature = current.eClass.findEStructuralFeature(step)
            current = current.eGet(feature) if feature is not None else None
        if current is None:
            return None
    return current
