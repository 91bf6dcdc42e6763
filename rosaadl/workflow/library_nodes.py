"""The measured nodes in the model: which node, thread and core a measurement names.

:class:`NodeFinder` resolves the ``node``, ``thread`` and ``processor`` cells of a
:class:`~rosaadl.workflow.library_measurements.Measurement` against a model read with the library:
a node is a process type with a platform-independent implementation (PIM) ``T.impl``, named by
its package, its type, both, or its ROS node name; its PIM is instantiated once so that the
threads' values (Period, Data_Size of their ports) are those analyses see. What does not match
is an error located at the row and the column (``errors``); what is only odd, a warning.

:func:`instance_value`, :func:`ns_of` and :func:`bytes_of` read those values back exactly.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass
from decimal import Decimal
from typing import Any

from pyecore.ecore import EObject

from rosaadl.errors import Diagnostic, ModelError, RosaadlError
from rosaadl.exporters.aadl_text.lexical import literal
from rosaadl.lookup import PropertyLookup
from rosaadl.model import find_instance, is_a
from rosaadl.properties import property_value
from rosaadl.resolution import Resolver
from rosaadl.transforms.instantiate import instantiate
from rosaadl.units import Quantity
from rosaadl.workflow.library_measurements import Measurement

__all__ = [
    "MeasuredNode",
    "MeasuredThread",
    "NodeFinder",
    "instance_value",
    "ns_of",
    "bytes_of",
    "us_text",
]


@dataclass
class MeasuredNode:
    """A node of the model: its process type, package and PIM (``T.impl``), and the PIM's threads
    as instantiated (values as analyses see them)."""

    ctype: EObject
    package: EObject
    pim: EObject
    threads: dict[str, EObject]  # lower-case path -> thread subcomponent (see :attr:`paths`)
    instances: dict[str, EObject]  # lower-case path -> thread instance
    #: lower-case path -> the thread's path in the PIM: its subcomponent's name, or the names of
    #: the thread groups it is in and its own, dotted (``Client.client_timer``, as ROSMOD
    #: components become thread groups)
    paths: dict[str, str]


@dataclass
class MeasuredThread:
    """A measurement matched to the thread of a node's PIM it measures."""

    m: Measurement
    node: MeasuredNode
    sub: EObject
    thread_classifier: EObject  # what the PIM subcomponent is (an implementation or a type)
    thread_type: EObject
    path: str  # the thread's path in the PIM (:attr:`MeasuredNode.paths`)
    port: str | None = None  # the data port data_size_bytes belongs to

    @property
    def key(self) -> str:
        """The lower-case path: the key of the thread in its node's maps."""
        return self.path.lower()

    @property
    def nested(self) -> bool:
        """The thread is in a thread group of the PIM, not a subcomponent of the process."""
        return "." in self.path


class NodeFinder:
    """Finds the nodes, threads and reference processors that measurements name in ``workspace``;
    the problems go to ``errors`` and ``warnings``, shared with whoever builds from the rows."""

    def __init__(self, workspace: EObject) -> None:
        self.model = workspace
        self.resolver = Resolver(workspace)
        self.lookup = PropertyLookup(workspace, self.resolver)
        self.errors: list[RosaadlError] = []
        self.warnings: list[Diagnostic] = []
        self._nodes: dict[int, MeasuredNode | None] = {}
        self._named: dict[str, tuple[list[EObject], str]] = {}
        self._node_failures: dict[int, str] = {}
        self._processes = [
            c
            for u in workspace.units
            if is_a(u, "AadlPackage")
            for c in u.classifiers
            if is_a(c, "ComponentType") and literal(c.category) == "process"
        ]

    # ------------------------------------------------------------------ nodes and threads

    def process_types(self, value: str) -> tuple[list[EObject], str]:
        """Process types ``value`` may name, and how it named them (cached)."""
        known = self._named.get(value)
        if known is None:
            known = self._named[value] = self._find_process_types(value)
        return known

    def _find_process_types(self, value: str) -> tuple[list[EObject], str]:
        resolver = self.resolver
        if "::" in value:
            found = resolver.classifier(value)
            if found is not None and is_a(found, "ComponentType") and literal(found.category) == "process":
                return [found], "classifier"
            return [], "classifier"
        unit = resolver.unit(value)
        if unit is not None and is_a(unit, "AadlPackage"):
            types = [c for c in self._processes if resolver.unit_of(c) is unit]
            with_pim = [c for c in types if self._pim(c) is not None]
            return (with_pim or types), "package"
        wanted = value.lower()
        named = [c for c in self._processes if (c.name or "").lower() == wanted]
        if named:
            return named, "process type"
        by_ros_name = []
        for ctype in self._processes:
            ros_name = self.lookup.python_value(ctype, "ROS_Properties::Node_Name")
            if isinstance(ros_name, str) and ros_name == value:
                by_ros_name.append(ctype)
        return by_ros_name, "ROS node name"

    def _pim(self, ctype: EObject) -> EObject | None:
        found = self.resolver.classifier(f"{ctype.name}.impl", ctype)
        return found if found is not None and is_a(found, "ComponentImplementation") else None

    def node(self, m: Measurement) -> MeasuredNode | None:
        """The node a row measures, its PIM instantiated once (an error when there is none)."""
        types, how = self.process_types(m.node)
        if not types:
            names = sorted(
                {self.resolver.qualified_name(c) for c in self._processes if self._pim(c) is not None},
                key=str.lower,
            )
            close = difflib.get_close_matches(m.node.lower(), [n.lower() for n in names], n=5, cutoff=0.5)
            shown = [n for n in names if n.lower() in close]
            shown += [n for n in names if n not in shown][: max(0, 12 - len(shown))]
            self.errors.append(
                m.error(
                    "node",
                    f"unknown node {m.node!r}: not a node of the library or of the inputs "
                    f"(nodes: {', '.join(shown)}{', ...' if len(shown) < len(names) else ''}); "
                    "a node of a model of your own: give its AADL files or folders after the "
                    "measurements",
                )
            )
            return None
        if len(types) > 1:
            names = sorted(self.resolver.qualified_name(c) for c in types)
            self.errors.append(
                m.error(
                    "node",
                    f"{m.node!r} ({how}) names several nodes: {', '.join(names)}; "
                    "write the node as Pkg::process_type",
                )
            )
            return None
        ctype = types[0]
        key = id(ctype)
        if key in self._nodes:
            known = self._nodes[key]
            if known is None:
                self.errors.append(m.error("node", self._node_failures[key]))
            return known
        pim = self._pim(ctype)
        qualified = self.resolver.qualified_name(ctype)
        if pim is None:
            message = (
                f"node {qualified} has no platform-independent implementation {ctype.name}.impl "
                "for a PDM to extend"
            )
            return self._node_failed(key, m, message)
        try:
            node = self._instantiate_pim(ctype, pim)
        except RosaadlError as exc:
            return self._node_failed(
                key, m, f"the PIM {self.resolver.qualified_name(pim)} does not instantiate: {exc}"
            )
        self._nodes[key] = node
        return node

    def _node_failed(self, key: int, m: Measurement, message: str) -> None:
        self._nodes[key] = None
        self._node_failures[key] = message
        self.errors.append(m.error("node", message))
        return None

    def _pim_threads(self, pim: EObject) -> dict[str, tuple[str, EObject]]:
        """Lower-case path -> ``(path, subcomponent)`` of every thread of ``pim``, in its thread
        groups too (an implementation that contains itself is not entered again)."""
        found: dict[str, tuple[str, EObject]] = {}

        def walk(impl: EObject, prefix: str, entered: frozenset[int]) -> None:
            for sub in self.resolver.subcomponents(impl):
                path = f"{prefix}{sub.name or ''}"
                category = literal(sub.category)
                if category == "thread":
                    found.setdefault(path.lower(), (path, sub))
                elif category == "thread group":
                    inner = self.resolver.subcomponent_classifier(sub)
                    if is_a(inner, "ComponentImplementation") and id(inner) not in entered:
                        walk(inner, f"{path}.", entered | {id(inner)})

        walk(pim, "", frozenset({id(pim)}))
        return found

    def _instantiate_pim(self, ctype: EObject, pim: EObject) -> MeasuredNode:
        found = self._pim_threads(pim)
        threads = {key: sub for key, (_path, sub) in found.items()}
        notes: list[Diagnostic] = []
        instance = instantiate(
            self.model, self.resolver.qualified_name(pim), resolver=self.resolver, diagnostics=notes
        )
        instances: dict[str, EObject] = {}
        try:
            for key, (path, _sub) in found.items():
                try:
                    instances[key] = find_instance(instance, path)
                except ModelError:
                    continue  # not instantiated (in a mode, say): no values to compare with
        finally:
            self.model.instances.remove(instance)
        unit = self.resolver.unit_of(ctype)
        paths = {key: path for key, (path, _sub) in found.items()}
        return MeasuredNode(ctype, unit, pim, threads, instances, paths)

    def thread(self, m: Measurement, node: MeasuredNode) -> MeasuredThread | None:
        """The thread of the node's PIM a row measures, by subcomponent or thread type name."""
        resolver = self.resolver
        wanted = m.thread.lower()
        key = wanted if wanted in node.threads else None
        if key is None:  # a thread in a thread group, named by its own name alone
            named = [k for k in node.threads if "." in k and k.rpartition(".")[2] == wanted]
            key = named[0] if len(named) == 1 else None
        if key is None:
            matches = []
            for candidate, sub in node.threads.items():
                classifier = resolver.subcomponent_classifier(sub)
                ctype = resolver.component_type(classifier)
                if ctype is not None and (ctype.name or "").lower() == wanted:
                    matches.append(candidate)
            if len(matches) > 1:
                names = ", ".join(node.paths[k] for k in matches)
                self.errors.append(
                    m.error(
                        "thread",
                        f"{m.thread!r} is the type of several threads of "
                        f"{resolver.qualified_name(node.pim)} ({names}); name the thread",
                    )
                )
                return None
            key = matches[0] if matches else None
        if key is None:
            names = ", ".join(node.paths.values()) or "none"
            self.errors.append(
                m.error(
                    "thread",
                    f"unknown thread {m.thread!r}: {resolver.qualified_name(node.pim)} "
                    f"has the threads {names}",
                )
            )
            return None
        sub = node.threads[key]
        classifier = resolver.subcomponent_classifier(sub)
        ctype = resolver.component_type(classifier)
        if classifier is None or ctype is None:
            self.errors.append(
                m.error(
                    "thread",
                    f"thread {node.paths[key]} of {resolver.qualified_name(node.pim)} has no "
                    "thread classifier that a PDM could extend",
                )
            )
            return None
        return MeasuredThread(m, node, sub, classifier, ctype, node.paths[key])

    # ------------------------------------------------------------------ reference processors

    def reference_processor(self, m: Measurement) -> EObject | None:
        """The processor classifier a ``processor`` cell names (an error when it names none)."""
        found = self.resolver.classifier(m.processor)
        processor = is_a(found, "ComponentClassifier") and literal(found.category) in (
            "processor",
            "virtual processor",
        )
        if not processor:
            what = (
                "not found"
                if found is None
                else f"a {literal(getattr(found, 'category', ''))}, not a processor"
            )
            self.errors.append(m.error("processor", f"{m.processor}: {what} in the library or the inputs"))
            return None
        return found

    def known_reference_processor(self, pdm: str) -> tuple[EObject | None, list[str]]:
        """The Reference_Processor the model's process PDMs named ``*.<pdm>`` agree on."""
        found: dict[str, EObject] = {}
        suffix = "." + pdm.lower()
        for unit in self.model.units:
            if not is_a(unit, "AadlPackage"):
                continue
            for impl in unit.classifiers:
                if not is_a(impl, "ComponentImplementation") or literal(impl.category) != "process":
                    continue
                if not (impl.name or "").lower().endswith(suffix):
                    continue
                for pa in impl.ownedPropertyAssociations:
                    prop = self.resolver.association_property(pa)
                    if prop is None or (prop.name or "").lower() != "reference_processor" or pa.appliesTo:
                        continue
                    for mv in pa.ownedValues:
                        value = mv.value
                        if is_a(value, "ClassifierValue"):
                            target = self.resolver.classifier(value.classifier, impl)
                            if target is not None:
                                found.setdefault(self.resolver.qualified_name(target), target)
        if len(found) == 1:
            return next(iter(found.values())), []
        return None, sorted(found)


def instance_value(obj: EObject | None, name: str) -> Any:
    """The value of property ``name`` of an instance object (``None`` without an object)."""
    return property_value(obj, name) if obj is not None else None


def _whole(value: Any, unit: str) -> int | None:
    """A quantity as a whole number of ``unit``; ``None`` when it is not one."""
    if not isinstance(value, Quantity):
        return None
    try:
        converted = value.to(unit)
    except ModelError:
        return None
    return int(converted) if float(converted).is_integer() else None


def ns_of(value: Any) -> int | None:
    """A time as a whole number of nanoseconds, or ``None``."""
    return _whole(value, "ns")


def bytes_of(value: Any) -> int | None:
    """A size as a whole number of bytes, or ``None``."""
    return _whole(value, "Bytes")


def us_text(ns: int) -> str:
    """A time in nanoseconds as microseconds, for messages (``2319 us``, ``2319.5 us``)."""
    return f"{ns // 1000} us" if ns % 1000 == 0 else f"{Decimal(ns) / 1000} us"
