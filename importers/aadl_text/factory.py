"""Making the model objects of the AADL reader fast, with :class:`rosaadl.bulk.FastFactory`.

The builder makes every object of the declarative model here: without pyecore's notifications
and per-value checks (the builder passes values typed by construction: enumeration literals,
ints, strs, objects of the right class), with the metamodel's slots looked up once per process.
:func:`make` sets features by name, :func:`maker` gives a function that sets them by position
(for the objects made most often), :func:`add` appends to a list feature, and :func:`literals`
holds the enumeration literals the builder uses.

Every text a feature is set to is interned (:func:`sys.intern`): the same names, property names,
classifier references and units recur all over a model, and one shared string for each saves
about a tenth of a model's memory (its strings are otherwise slices of the source, one per use).
Interned strings are freed with the last model that uses them.
"""

from __future__ import annotations

import functools
import sys
from collections.abc import Callable
from typing import Any

from pyecore.ecore import EObject

from rosaadl import metamodels
from rosaadl.bulk import FastBuilder, FastFactory, FeatureSlot
from rosaadl.errors import ModelError
from rosaadl.importers.aadl_text.tree import CATEGORIES, CONNECTION_NODES, FEATURE_NODES, FLOW_KIND_NODES

__all__ = ["Literals", "add", "literals", "make", "maker", "update"]


@functools.cache
def _class_setters(class_name: str) -> tuple[type, dict[str, tuple[FeatureSlot, Any]]]:
    """The pyecore class of a metamodel class, and each single-valued feature's slot and setter
    (metamodel metadata, looked up once per process)."""
    eclass = metamodels.load().eclass(class_name)
    setters: dict[str, tuple[FeatureSlot, Any]] = {}
    for feature in eclass.eAllStructuralFeatures():
        if not feature.many:
            slot = FeatureSlot(feature)
            setters[feature.name] = (
                slot,
                FastFactory.set_child if slot.containment else FastFactory.set_value,
            )
    return eclass.python_class, setters


@functools.cache
def _list_slot(eclass: Any, name: str) -> FeatureSlot:
    feature = eclass.findEStructuralFeature(name)
    if feature is None or not feature.many:
        raise ModelError(f"{eclass.name} has no list feature {name!r}")
    return FeatureSlot(feature)


_intern = sys.intern


def make(class_name: str, /, **values: Any) -> EObject:
    """A new object with single-valued features set (None: left unset)."""
    cls, setters = _class_setters(class_name)
    obj = FastFactory.new(cls)
    for name, value in values.items():
        if value is not None:
            slot, setter = setters[name]
            setter(obj, slot, _intern(value) if type(value) is str else value)
    return obj


def update(obj: EObject, /, **values: Any) -> None:
    """Set single-valued features of an object made by :func:`make` (None: left as it is)."""
    _, setters = _class_setters(obj.eClass.name)
    for name, value in values.items():
        if value is not None:
            slot, setter = setters[name]
            setter(obj, slot, _intern(value) if type(value) is str else value)


@functools.cache
def maker(class_name: str, *names: str) -> Callable[..., EObject]:
    """``maker("IntegerValue", "value", "line")(3, 12)``: :func:`make` with the features
    given by position, for the objects the builder makes most often."""
    cls, setters = _class_setters(class_name)
    pairs = tuple(setters[name] for name in names)
    new = FastFactory.new

    def make_one(*values: Any) -> EObject:
        obj = new(cls)
        for (slot, setter), value in zip(pairs, values, strict=True):
            if value is not None:
                setter(obj, slot, _intern(value) if type(value) is str else value)
        return obj

    return make_one


def add(owner: EObject, name: str, *items: Any) -> None:
    """Append to a many-valued feature of an object made by :func:`make` (nothing: no change)."""
    if not items:
        return
    slot = _list_slot(owner.eClass, name)
    existing = owner.__dict__.get(name)
    if existing is None:
        FastFactory.set_many(owner, slot, list(items))
    else:
        FastFactory.extend(owner, slot, existing, items)


class Literals:
    """The enumeration literals the builder uses, by their AADL spelling or tree node name."""

    def __init__(self) -> None:
        literal = FastBuilder().literal
        self.categories = {c: literal("ComponentCategory", c) for c in CATEGORIES}
        self.feature_categories = {
            node: literal("FeatureCategory", text) for node, (_, text) in FEATURE_NODES.items()
        }
        self.directions = {d: literal("DirectionType", d) for d in ("in", "out", "in out")}
        self.access = {a: literal("AccessType", a) for a in ("provides", "requires")}
        self.connection_kinds = {n: literal("ConnectionKind", k) for n, k in CONNECTION_NODES.items()}
        self.flow_kinds = {n: literal("FlowKind", k) for n, k in FLOW_KIND_NODES.items()}
        self.visibility = {v: literal("Visibility", v) for v in ("public", "private")}
        self.rename_kinds = {
            k: literal("RenameKind", k) for k in ("classifier", "package", "feature group", "all")
        }


@functools.cache
def literals() -> Literals:
    """The literals, looked up once per process."""
    return Literals()
