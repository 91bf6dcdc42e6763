"""The library side of a binding: a robot's cores, ports and buses, and the library's nodes.

A robot of the library (``pioneer_3dx::Pioneer_3DX.impl``) is instantiated to find its cores
(processors without processor subcomponents, each with its type and the types it extends), its
ports and its buses (:func:`inspect_robot`, :func:`robot_cores`). A library node type
(``nd_usb_cam::usb_cam_nd``) has ports and one platform-dependent implementation (PDM) per core
type, the one whose ``Reference_Processor`` names it (:class:`Catalogue`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.lookup import PropertyLookup
from rosaadl.transforms.instantiate import instantiate

__all__ = [
    "PORT_CATEGORIES",
    "Catalogue",
    "Core",
    "LibraryNode",
    "Robot",
    "classifier_named",
    "impl_chain",
    "literal",
    "inspect_robot",
    "robot_cores",
    "type_chain",
]

#: The feature categories of the ports a binding connects.
PORT_CATEGORIES = frozenset({"event data port", "data port", "event port"})


@dataclass(frozen=True)
class Core:
    """A core (a processor without processor subcomponents) of a robot."""

    path: str  #: inside the robot: ``OdroidXU4.Exynos_SOC.little_procs_cluster.little_proc1``
    classifier: str  #: ``Exynos_5422::ARM_A7.impl``
    types: tuple[str, ...]  #: its type and the types it extends, lower case (``exynos_5422::arm_a7``)

    @property
    def kind(self) -> str:
        """The core's type as written: ``Exynos_5422::ARM_A7``."""
        return (
            self.classifier.partition(".")[0]
            if "." in self.classifier.rpartition("::")[2]
            else self.classifier
        )


def literal(value: Any) -> str:
    """The text of an enumeration literal (a category, a direction), or of a plain value."""
    return str(getattr(value, "literal", None) or getattr(value, "name", None) or value or "")


def classifier_named(model: EObject, name: str, context: EObject | None = None) -> EObject | None:
    """The classifier of ``model`` named ``name`` (as seen from ``context``), or None."""
    return _model.find_classifier(model, name, context) if name else None


def type_chain(model: EObject, classifier: EObject | None) -> list[EObject]:
    """A classifier's type (for an implementation) and the types it extends, most specific first."""
    chain: list[EObject] = []
    current = classifier
    if current is not None and _model.is_a(current, "ComponentImplementation"):
        type_name = current.type or current.name.partition(".")[0]
        current = classifier_named(model, type_name, current)
    while current is not None and current not in chain:
        chain.append(current)
        current = classifier_named(model, current.extended, current) if current.extended else None
    return chain


def impl_chain(model: EObject, impl: EObject) -> list[EObject]:
    """An implementation and the implementations it extends, most specific first."""
    chain: list[EObject] = []
    current: EObject | None = impl
    while current is not None and current not in chain:
        chain.append(current)
        current = classifier_named(model, current.extended, current) if current.extended else None
    return chain


@dataclass
class Robot:
    """What the binding needs to know of the robot: its cores, its ports and its buses."""

    name: str  # qualified
    cores: list[Core]
    ports: dict[str, EObject]  # lower-case name → feature instance of the robot
    buses: dict[str, str]  # lower-case path → path of a bus or virtual bus inside the robot


def inspect_robot(model: EObject, robot: str) -> Robot:
    """The robot's cores, ports and buses, from an instance of it (removed afterwards)."""
    system = instantiate(model, robot, diagnostics=[])
    try:
        prefix = (system.name or "") + "."
        cores, buses = [], {}
        for obj in _model.component_instances(system):
            category = literal(obj.category)
            path = _model.instance_path(obj).removeprefix(prefix)
            if category in ("bus", "virtual bus"):
                buses[path.lower()] = path
            elif category == "processor" and not any(
                literal(c.category) == "processor" for c in obj.componentInstances
            ):
                classifier = classifier_named(model, obj.classifier or "")
                types = tuple(_model.qualified_name(t).lower() for t in type_chain(model, classifier))
                cores.append(Core(path, obj.classifier or "", types))
        ports = {f.name.lower(): f for f in system.featureInstances if literal(f.category) in PORT_CATEGORIES}
        return Robot(robot, cores, ports, buses)
    finally:
        model.instances.remove(system)


def robot_cores(model: EObject, robot: str) -> list[Core]:
    """The cores of a robot (``Pkg::Robot.impl``, a system implementation of the loaded model),
    in model order; a located :class:`~rosaadl.errors.RosaadlError` when it does not instantiate."""
    return inspect_robot(model, robot).cores


@dataclass
class LibraryNode:
    """What the binding needs to know of one library node type."""

    type: EObject
    qualified: str
    ports: dict[str, EObject]  # lower-case name → port feature of the type chain
    pdms: list[tuple[EObject, str | None]]  # (implementation, its Reference_Processor qualified, lower)


class Catalogue:
    """The library's node types, each read once: its ports and its PDMs."""

    def __init__(self, model: EObject) -> None:
        self.model = model
        self.lookup = PropertyLookup(model)
        self._nodes: dict[str, LibraryNode] = {}

    def reference(self, impl: EObject) -> str | None:
        """The core type an implementation was measured on (its ``Reference_Processor``), lower case."""
        value = self.lookup.value(impl, "Reference_Processor")
        name = getattr(value, "classifier", None) if value is not None else None
        if not name:
            return None
        found = classifier_named(self.model, name, impl)
        return (_model.qualified_name(found) if found is not None else name).lower()

    def node(self, name: str) -> LibraryNode | None:
        """The library node type ``Pkg::Type`` (or the type of ``Pkg::Type.impl``)."""
        found = classifier_named(self.model, name)
        if found is None or literal(found.category) != "process":
            return None
        node_type = (
            type_chain(self.model, found)[0] if _model.is_a(found, "ComponentImplementation") else found
        )
        key = _model.qualified_name(node_type).lower()
        cached = self._nodes.get(key)
        if cached is not None:
            return cached
        ports: dict[str, EObject] = {}
        for classifier in type_chain(self.model, node_type):
            for feature in classifier.features:
                if literal(feature.category) in PORT_CATEGORIES:
                    ports.setdefault(feature.name.lower(), feature)
        package = node_type.eContainer()
        pdms = []
        for impl in package.classifiers:
            if not _model.is_a(impl, "ComponentImplementation") or literal(impl.category) != "process":
                continue
            if (impl.type or impl.name.partition(".")[0]).lower() != node_type.name.lower():
                continue
            reference = self.reference(impl)
            if reference is not None:
                pdms.append((impl, reference))
        entry = LibraryNode(node_type, _model.qualified_name(node_type), ports, pdms)
        self._nodes[key] = entry
        return entry
