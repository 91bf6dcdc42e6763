"""The object factory of bulk producers: property values, instance objects.

:class:`Factory` makes model objects by class and feature name on
:class:`rosaadl.bulk.FastBuilder` and counts them; the property lookup makes its values with it,
and instantiation its instance objects (through the lookup's :attr:`factory`).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from pyecore.ecore import EObject

from rosaadl.bulk import FastBuilder, FastFactory
from rosaadl.errors import ModelError

__all__ = ["Factory"]


class Factory:
    """Makes model objects for bulk producers such as instantiation, by class and feature name,
    on :class:`rosaadl.bulk.FastBuilder` (no per-assignment checks or notifications; the objects
    behave like ordinary ones).  Counts what it made, by class (:attr:`made`)."""

    def __init__(self) -> None:
        self.builder = FastBuilder()
        #: how many objects of each class this factory made
        self.made: dict[str, int] = {}

    def new(self, class_name: str, /, **values: Any) -> EObject:
        """A new object of class ``class_name`` with single-valued features set (None skipped)."""
        made = self.made
        made[class_name] = made.get(class_name, 0) + 1
        return self.builder.make(class_name, **values)

    def set(self, obj: EObject, name: str, value: Any) -> None:
        """Set a single-valued feature of an object made by this factory."""
        slot = self.builder.slot(obj.eClass, name)
        if slot.many:
            raise ModelError(f"{obj.eClass.name}.{name} is many-valued; use extend")
        if slot.containment:
            FastFactory.set_child(obj, slot, value)
        else:
            FastFactory.set_value(obj, slot, value)

    def extend(self, obj: EObject, name: str, values: Iterable[Any]) -> None:
        """Append to a many-valued feature of an object made by this factory (nothing when empty,
        so that an empty list is never recorded as set)."""
        values = list(values)
        if values:
            self.builder.add(obj, name, *values)
