"""The AADL objects the ROSMOD → AADL rules make: packages, classifiers, features,
subcomponents, connections, property associations and their values.

:class:`AadlFactory` makes each with its enumeration literals looked up once, through
:class:`rosaadl.bulk.FastBuilder` (the model API's ``new`` is several times slower, and a large
project makes hundreds of thousands of objects).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from pyecore.ecore import EObject

from rosaadl.bulk import FastBuilder
from rosaadl.transforms.rosmod_to_aadl.vocabulary import SETTINGS

__all__ = ["AadlFactory"]


class AadlFactory:
    """AADL model objects through :class:`FastBuilder` (the model API's ``new`` is ~7x slower)."""

    def __init__(self) -> None:
        self.fb = FastBuilder()
        fb = self.fb
        self._categories = {
            c: fb.literal("ComponentCategory", c)
            for c in (
                "bus",
                "data",
                "process",
                "processor",
                "subprogram",
                "system",
                "thread",
                "thread group",
                "virtual bus",
            )
        }
        self._features = {
            c: fb.literal("FeatureCategory", c)
            for c in ("event data port", "subprogram access", "bus access", "data access", "parameter")
        }
        self._direction = {d: fb.literal("DirectionType", d) for d in ("in", "out")}
        self._access = {a: fb.literal("AccessType", a) for a in ("provides", "requires")}
        self._connections = {
            "port": fb.literal("ConnectionKind", "port"),
            "access": fb.literal("ConnectionKind", "access"),
        }

    # -- units and classifiers
    def package(self, name: str) -> EObject:
        return self.fb.make("AadlPackage", name=name)

    def ctype(self, category: str, name: str, extended: str | None = None) -> EObject:
        return self.fb.make(
            "ComponentType", name=name, category=self._categories[category], extended=extended
        )

    def cimpl(self, category: str, type_name: str, extended: str | None = None) -> EObject:
        return self.fb.make(
            "ComponentImplementation",
            name=f"{type_name}.impl",
            type=type_name,
            category=self._categories[category],
            extended=extended,
        )

    def feature(
        self,
        name: str,
        category: str,
        *,
        direction: str | None = None,
        access: str | None = None,
        classifier: str | None = None,
    ) -> EObject:
        return self.fb.make(
            "Feature",
            name=name,
            category=self._features[category],
            direction=self._direction[direction] if direction else None,
            access=self._access[access] if access else None,
            classifier=classifier,
        )

    def sub(self, name: str, category: str, classifier: str | None) -> EObject:
        return self.fb.make(
            "Subcomponent", name=name, category=self._categories[category], classifier=classifier
        )

    def conn(
        self, name: str, kind: str, source: str, destination: str, category: str | None = None
    ) -> EObject:
        return self.fb.make(
            "Connection",
            name=name,
            kind=self._connections[kind],
            source=source,
            destination=destination,
            accessCategory=self._categories[category] if category else None,
        )

    def add(self, owner: EObject, feature: str, *children: Any) -> None:
        if children:
            self.fb.add(owner, feature, *children)

    # -- values
    def string(self, value: str) -> EObject:
        return self.fb.make("StringValue", value=value)

    def integer(self, value: int, unit: str | None = None) -> EObject:
        return self.fb.make("IntegerValue", value=int(value), unit=unit)

    def named(self, name: str) -> EObject:
        return self.fb.make("NamedValue", name=name)

    def boolean(self, value: bool) -> EObject:
        return self.fb.make("BooleanValue", value=bool(value))

    def reference(self, path: str) -> EObject:
        return self.fb.make("ReferenceValue", path=path)

    def listing(self, items: Iterable[EObject]) -> EObject:
        value = self.fb.make("ListValue")
        self.add(value, "ownedItems", *items)
        return value

    def record(self, fields: Iterable[tuple[str, EObject]]) -> EObject:
        value = self.fb.make("RecordValue")
        self.add(value, "ownedFields", *(self.fb.make("FieldValue", name=n, value=v) for n, v in fields))
        return value

    def pa(self, holder: EObject, prop: str, value: EObject, applies_to: str | None = None) -> EObject:
        assoc = self.fb.make("PropertyAssociation", property=prop)
        self.fb.add(assoc, "ownedValues", self.fb.make("ModalPropertyValue", value=value))
        if applies_to:
            self.fb.add(assoc, "appliesTo", applies_to)
        self.fb.add(holder, "ownedPropertyAssociations", assoc)
        return assoc

    def text(self, holder: EObject, prop: str, value: str | None) -> None:
        if value is not None:
            self.pa(holder, prop, self.string(value))

    def settings(self, holder: EObject, props: Iterable[EObject], prop: str = SETTINGS) -> None:
        items = [
            self.record((("Key", self.string(p.key or "")), ("Value", self.string(p.value or ""))))
            for p in props
        ]
        if items:
            self.pa(holder, prop, self.listing(items))
