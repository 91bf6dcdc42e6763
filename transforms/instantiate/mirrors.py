"""The instance mirrors: what every stage of the instantiation knows about an instance object.

The instance objects themselves (``ComponentInstance``, ``FeatureInstance``, ...) are plain
pyecore objects made in bulk; the stages work on these light records beside them, which keep the
declarative context (the :class:`~rosaadl.lookup.ComponentNode`, the feature declaration, the
category and direction as words), the tree with name indexes, and the connection instances made
so far. Also here: the category words and enumeration spellings the stages share, and the
instance paths of mirrors (for names and messages).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.lookup import ComponentNode

__all__ = [
    "ACCESS",
    "ENDING",
    "PORTS",
    "SHARED",
    "ComponentMirror",
    "ConnectionRecord",
    "FeatureMirror",
    "LazyPath",
    "component_path",
    "end_path",
    "enum_literal",
    "enum_name",
    "literal",
]

#: Categories where a semantic connection ends (OSATE's "final" components).
ENDING = frozenset({"thread", "device", "processor", "virtual processor"})
#: Categories of shared components: a semantic access connection may start at the component itself.
SHARED = frozenset({"data", "bus", "virtual bus", "subprogram", "subprogram group"})
#: FeatureCategory names of ports and of access features.
PORTS = frozenset({"dataPort", "eventPort", "eventDataPort"})
ACCESS = frozenset(
    {"busAccess", "dataAccess", "subprogramAccess", "subprogramGroupAccess", "virtualBusAccess"}
)


def enum_name(value: object) -> str:
    """The name of an enumeration literal (or the text given)."""
    return str(getattr(value, "name", value) or "")


def literal(value: object) -> str:
    """The AADL spelling of an enumeration literal (``thread group``), else its name."""
    return str(getattr(value, "literal", None) or getattr(value, "name", None) or value or "")


@functools.lru_cache(maxsize=256)
def enum_literal(enum_name: str, text: str) -> Any:
    """The literal object of an enumeration of aadl.ecore for a literal name or AADL spelling."""
    from rosaadl import metamodels

    enum = metamodels.load().aadl.getEClassifier(enum_name)
    found = enum.getEEnumLiteral(text)
    return found if found is not None else enum.from_string(text)


@dataclass(eq=False)
class FeatureMirror:
    """A feature instance and what the algorithms need to know about it."""

    obj: EObject
    decl: EObject
    name: str
    key: str  # lower-case name
    index: int  # 1-based element of a feature array, 0 otherwise
    category: str  # FeatureCategory name (dataPort, featureGroup, ...)
    direction: str  # "in", "out", "in out"
    owner: ComponentMirror
    parent: FeatureMirror | None  # the feature group instance holding it
    children: list[FeatureMirror] = field(default_factory=list)
    fgt: EObject | None = None  # the feature group type of a feature group

    @property
    def incoming(self) -> bool:
        return self.direction in ("in", "in out")

    @property
    def outgoing(self) -> bool:
        return self.direction in ("out", "in out")

    def child(self, name: str) -> FeatureMirror | None:
        for fi in self.children:
            if fi.key == name:
                return fi
        return None


@dataclass(eq=False)
class ComponentMirror:
    """A component instance and its declarative context."""

    obj: EObject
    node: ComponentNode
    parent: ComponentMirror | None
    sub: EObject | None
    sub_key: str  # lower-case subcomponent name
    category: str
    index: tuple[int, ...]
    children: list[ComponentMirror] = field(default_factory=list)
    by_sub: dict[str, list[ComponentMirror]] = field(default_factory=dict)
    features: list[FeatureMirror] = field(default_factory=list)
    feature_by_name: dict[str, FeatureMirror] = field(default_factory=dict)
    modes: dict[str, EObject] = field(default_factory=dict)
    mode_list: list[EObject] = field(default_factory=list)
    transitions: list[tuple[EObject, EObject]] = field(default_factory=list)  # (instance, declaration)
    in_modes: list[EObject] = field(default_factory=list)  # parent's mode instances
    # the instance path segment: name and array indices (model.instance_segment's text, made from
    # the mirror's own fields: reading them back from the instance object costs far more)
    segment: str = ""
    connections: list[ConnectionRecord] = field(default_factory=list)
    conn_index: dict[tuple[int, int], list[ConnectionRecord]] = field(default_factory=dict)
    flow_specs: dict[str, EObject] = field(default_factory=dict)

    @property
    def impl(self) -> EObject | None:
        return self.node.impl

    @property
    def classifier(self) -> EObject | None:
        return self.node.classifier

    def child(self, key: str) -> ComponentMirror | None:
        found = self.by_sub.get(key)
        return found[0] if found else None

    def feature(self, key: str) -> FeatureMirror | None:
        return self.feature_by_name.get(key)


@dataclass(eq=False)
class ConnectionRecord:
    """A connection instance made, with its ends and the declarations and contexts of its hops."""

    obj: EObject
    src: Any  # a ComponentMirror or FeatureMirror
    dst: Any
    decls: list[EObject]
    kind: str
    contexts: list[ComponentMirror] = field(default_factory=list)


def component_path(ci: ComponentMirror) -> str:
    """The instance path of a component (root name first)."""
    parts = []
    current: ComponentMirror | None = ci
    while current is not None:
        parts.append(current.segment)
        current = current.parent
    return ".".join(reversed(parts))


def end_path(end: Any) -> str:
    """The instance path of a connection end: a component, a feature or an instance object."""
    if isinstance(end, ComponentMirror):
        return component_path(end)
    if isinstance(end, FeatureMirror):
        parts = []
        current: FeatureMirror | None = end
        while current is not None:
            parts.append(current.name + (f"[{current.index}]" if current.index else ""))
            current = current.parent
        return component_path(end.owner) + "." + ".".join(reversed(parts))
    if isinstance(end, EObject):
        return _model.instance_path(end)
    return ""


class LazyPath:
    """The instance path of a component, computed only when a message needs it."""

    __slots__ = ("_ci",)

    def __init__(self, ci: ComponentMirror) -> None:
        self._ci = ci

    def __str__(self) -> str:
        return component_path(self._ci)

    def __format__(self, spec: str) -> str:
        return format(str(self), spec)
