"""Instantiate a root system implementation of a declarative AADL model, as OSATE does.

:func:`instantiate` builds a ``SystemInstance`` (conventions: ``docs/instance-model.md``):

* the component hierarchy, arrays expanded (one instance per element, 1-based ``index``);
* feature instances of every component (feature groups expanded with ``inverse of``, feature
  arrays expanded where AADL allows them);
* mode instances, mode transition instances and the system operation modes;
* semantic connection instances from ultimate source to ultimate destination, found with OSATE's
  algorithm (each declared connection is a hop; a connection instance starts at a thread, device,
  processor or shared data/bus, or at a feature nothing inside continues, goes up, across once and
  down), with one connection reference per hop, bidirectional access connections merged, modal
  connections limited to the system operation modes they exist in, and connections between
  component arrays replicated according to ``Connection_Pattern``;
* end-to-end flow instances;
* the resolved property values of every instance object (see :mod:`rosaadl.lookup`), with
  ``reference (...)`` values turned into references to instance objects.

Everything that depends only on a classifier (effective members, resolved connection ends,
property associations) is computed once per classifier, so large models instantiate quickly.
"""

from __future__ import annotations

import functools
import itertools
import logging
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.bulk import gc_paused
from rosaadl.errors import Diagnostic, Location, ModelError, NameResolutionError, UsageError
from rosaadl.lookup import ComponentNode, Found, NoValue, PropertyLookup, accepts
from rosaadl.resolution import Resolver, feature_category_word, split_path

__all__ = [
    "instantiate",
    "Instantiator",
    "COMPATIBILITY_MODES",
    "MAX_COMPONENT_INSTANCES",
    "MAX_SYSTEM_OPERATION_MODES",
]

log = logging.getLogger(__name__)

#: Upper bound on component instances, so that a mistyped array size fails instead of hanging.
MAX_COMPONENT_INSTANCES = 2_000_000
#: Accepted values of ``compatibility``: current OSATE, or the rules of OSATE 2.0.
COMPATIBILITY_MODES = ("current", "osate-2.0")
#: OSATE's default limit on the number of system operation modes.
MAX_SYSTEM_OPERATION_MODES = 1000

# The order in which OSATE's Xtext model lists an implementation's subcomponents: its
# ownedSubcomponent union concatenates one list per category, in aadl2.ecore's order for the
# implementation's class (ComponentImplementation's abstract list first).
_SUBCOMPONENT_ORDER: dict[str, list[str]] = {
    category: ["abstract", *members.split(",")]
    for category, members in {
        "abstract": "bus,data,device,memory,process,processor,system,subprogram,subprogram group,"
        "thread,thread group,virtual bus,virtual processor",
        "bus": "virtual bus",
        "data": "data,subprogram",
        "device": "bus,data,virtual bus",
        "memory": "bus,memory,virtual bus",
        "process": "data,subprogram,subprogram group,thread,thread group",
        "processor": "bus,memory,virtual bus,virtual processor",
        "subprogram": "data,subprogram",
        "subprogram group": "subprogram,subprogram group,data",
        "system": "bus,data,device,memory,process,processor,subprogram,subprogram group,system,"
        "virtual bus,virtual processor",
        "thread": "subprogram group,subprogram,data",
        "thread group": "data,thread,thread group,subprogram,subprogram group",
        "virtual bus": "virtual bus",
        "virtual processor": "virtual bus,virtual processor",
    }.items()
}
# The same for a component type's features: ComponentType's feature group and abstract feature
# lists first, then the lists of the type's class, in aadl2.ecore's order.
_FEATURE_ORDER: dict[str, list[str]] = {
    category: ["featureGroup", "abstractFeature", *members.split()]
    for category, members in {
        "abstract": "busAccess dataAccess subprogramAccess dataPort eventPort eventDataPort "
        "subprogramGroupAccess",
        "bus": "busAccess dataPort eventDataPort eventPort",
        "data": "subprogramAccess dataAccess subprogramGroupAccess",
        "device": "dataPort eventDataPort eventPort busAccess subprogramAccess subprogramGroupAccess",
        "memory": "busAccess dataPort eventDataPort eventPort",
        "subprogram": "eventDataPort eventPort parameter dataAccess subprogramAccess subprogramGroupAccess",
        "subprogram group": "subprogramAccess subprogramGroupAccess",
        "system": "busAccess dataAccess dataPort subprogramGroupAccess subprogramAccess eventPort "
        "eventDataPort",
        "processor": "dataPort eventDataPort eventPort busAccess subprogramAccess subprogramGroupAccess",
        "process": "dataPort eventDataPort eventPort dataAccess subprogramAccess subprogramGroupAccess",
        "thread": "dataPort eventDataPort eventPort dataAccess subprogramAccess subprogramGroupAccess",
        "thread group": "dataPort eventDataPort eventPort dataAccess subprogramAccess subprogramGroupAccess",
        "virtual bus": "dataPort eventDataPort eventPort busAccess",
        "virtual processor": "dataPort eventDataPort eventPort subprogramAccess subprogramGroupAccess "
        "busAccess",
    }.items()
}
_ENDING = frozenset({"thread", "device", "processor", "virtual processor"})
_SHARED = frozenset({"data", "bus", "virtual bus", "subprogram", "subprogram group"})
_ARRAY_FEATURE_OWNERS = frozenset({"abstract", "device", "memory", "processor", "system", "thread"})
_PORTS = frozenset({"dataPort", "eventPort", "eventDataPort"})
_ACCESS = frozenset(
    {"busAccess", "dataAccess", "subprogramAccess", "subprogramGroupAccess", "virtualBusAccess"}
)


def _enum(value: object) -> str:
    return str(getattr(value, "name", value) or "")


def _lit(value: object) -> str:
    return str(getattr(value, "literal", None) or getattr(value, "name", None) or value or "")


# ---------------------------------------------------------------------- instance mirrors


@dataclass(eq=False)
class _FI:
    """A feature instance and what the algorithms need to know about it."""

    obj: EObject
    decl: EObject
    name: str
    key: str
    index: int
    category: str  # FeatureCategory name (dataPort, featureGroup, ...)
    direction: str  # "in", "out", "in out"
    owner: _CI
    parent: _FI | None
    children: list[_FI] = field(default_factory=list)
    fgt: EObject | None = None

    @property
    def incoming(self) -> bool:
        return self.direction in ("in", "in out")

    @property
    def outgoing(self) -> bool:
        return self.direction in ("out", "in out")

    def child(self, name: str) -> _FI | None:
        for fi in self.children:
            if fi.key == name:
                return fi
        return None


@dataclass(eq=False)
class _CI:
    """A component instance and its declarative context."""

    obj: EObject
    node: ComponentNode
    parent: _CI | None
    sub: EObject | None
    sub_key: str
    category: str
    index: tuple[int, ...]
    children: list[_CI] = field(default_factory=list)
    by_sub: dict[str, list[_CI]] = field(default_factory=dict)
    features: list[_FI] = field(default_factory=list)
    feature_by_name: dict[str, _FI] = field(default_factory=dict)
    modes: dict[str, EObject] = field(default_factory=dict)
    mode_list: list[EObject] = field(default_factory=list)
    transitions: list[tuple[EObject, EObject]] = field(default_factory=list)  # (instance, declaration)
    in_modes: list[EObject] = field(default_factory=list)  # parent's mode instances
    segment: str = ""  # the instance path segment: name and array indices
    connections: list[_ConnRecord] = field(default_factory=list)
    conn_index: dict[tuple[int, int], list[_ConnRecord]] = field(default_factory=dict)
    flow_specs: dict[str, EObject] = field(default_factory=dict)

    @property
    def impl(self) -> EObject | None:
        return self.node.impl

    @property
    def classifier(self) -> EObject | None:
        return self.node.classifier

    def child(self, key: str) -> _CI | None:
        found = self.by_sub.get(key)
        return found[0] if found else None

    def feature(self, key: str) -> _FI | None:
        return self.feature_by_name.get(key)


@dataclass(eq=False)
class _ConnRecord:
    obj: EObject
    src: Any
    dst: Any
    decls: list[EObject]
    kind: str
    contexts: list[_CI] = field(default_factory=list)


@dataclass(eq=False)
class _End:
    """One end of a declared connection, resolved against its implementation."""

    ctx_kind: str | None  # None, "sub" or "fg"
    ctx: str  # lower-case context name
    end_kind: str  # "feature", "sub" or "internal"
    end: str  # lower-case end name
    next: tuple[str, ...] = ()
    feature: EObject | None = None
    category: str = ""  # feature category name of the end feature
    sub_category: str = ""  # declared category of the end (or context) subcomponent
    ctx_category: str = ""
    owner_is_subprogram_type: bool = False


@dataclass(eq=False)
class _Conn:
    decl: EObject
    name: str
    kind: str
    bidir: bool
    src: _End
    dst: _End
    modes: tuple[str, ...]
    same_fg: bool = False

    @property
    def across(self) -> bool:
        return (self.src.ctx_kind == "sub" or self.src.end_kind == "sub") and (
            self.dst.ctx_kind == "sub" or self.dst.end_kind == "sub"
        )


class _Info:
    """A connection instance under construction (OSATE's ConnectionInfo)."""

    __slots__ = (
        "connections",
        "opposites",
        "contexts",
        "sources",
        "destinations",
        "src",
        "bidirectional",
        "complete",
        "across",
        "src_to_match",
        "dst_to_match",
        "container",
        "mode_transition",
    )

    def __init__(self, src: Any) -> None:
        self.connections: list[_Conn] = []
        self.opposites: list[bool] = []
        self.contexts: list[_CI] = []
        self.sources: list[Any] = []
        self.destinations: list[Any] = []
        self.src = src
        self.bidirectional = True
        self.complete = False
        self.across = False
        self.src_to_match: tuple[str, ...] = ()
        self.dst_to_match: tuple[str, ...] = ()
        self.container: _CI | None = None
        self.mode_transition = False

    def clone(self) -> _Info:
        other = _Info(self.src)
        other.connections = list(self.connections)
        other.opposites = list(self.opposites)
        other.contexts = list(self.contexts)
        other.sources = list(self.sources)
        other.destinations = list(self.destinations)
        other.bidirectional = self.bidirectional
        other.complete = self.complete
        other.across = self.across
        other.src_to_match = self.src_to_match
        other.dst_to_match = self.dst_to_match
        other.container = self.container
        other.mode_transition = self.mode_transition
        return other

    def add_segment(
        self, conn: _Conn, from_end: Any, to_end: Any, ci: _CI, opposite: bool
    ) -> tuple[bool, bool]:
        src_ref = conn.dst if opposite else conn.src
        dst_ref = conn.src if opposite else conn.dst
        going_up = dst_ref.ctx_kind != "sub" and (src_ref.end_kind == "sub" or src_ref.ctx_kind == "sub")
        going_down = src_ref.ctx_kind != "sub" and (dst_ref.end_kind == "sub" or dst_ref.ctx_kind == "sub")
        keep = True
        valid = True
        if from_end is not None:
            self.sources.append(from_end)
            if isinstance(from_end, _FI):
                direction = from_end.direction
                self.bidirectional &= direction == "in out"
                if going_up or not going_down:
                    valid &= direction in ("out", "in out")
                else:
                    valid &= direction in ("in", "in out")
        self.bidirectional &= conn.bidir
        if to_end is not None:
            self.destinations.append(to_end)
            if isinstance(to_end, _FI):
                direction = to_end.direction
                self.bidirectional &= direction == "in out"
                if going_up:
                    valid &= direction in ("out", "in out")
                else:
                    valid &= direction in ("in", "in out")
        if valid:
            if conn.across:
                i = len(self.connections)
                to_match = conn.dst.next if opposite else conn.src.next
                while keep and i > 0 and to_match:
                    i -= 1
                    previous = self.connections[i]
                    if not previous.same_fg:
                        end = previous.src.end if self.opposites[i] else previous.dst.end
                        keep = to_match[0] == end
                        to_match = to_match[1:]
                self.src_to_match = to_match
                self.across = True
                self.dst_to_match = conn.src.next if opposite else conn.dst.next
                self.container = ci
            elif self.across and self.dst_to_match and not conn.same_fg:
                end = conn.dst.end if opposite else conn.src.end
                keep = self.dst_to_match[0] == end
                self.dst_to_match = self.dst_to_match[1:]
        self.connections.append(conn)
        self.opposites.append(opposite)
        self.contexts.append(ci)
        return keep, valid


# ---------------------------------------------------------------------- public API


def instantiate(
    model: EObject,
    root: str,
    *,
    resolver: Resolver | None = None,
    diagnostics: list[Diagnostic] | None = None,
    strict: bool = True,
    compatibility: str = "current",
) -> EObject:
    """Instantiate the implementation ``root`` (``Pkg::Sys.impl``) of an ``AadlModel``.

    Returns the ``SystemInstance``, which is also appended to ``model.instances``.  Warnings
    (connections that cannot continue, references that do not resolve, ...) are logged and
    appended to ``diagnostics`` when given.  An unknown root, a root that is not an
    implementation, a classifier that does not resolve or a containment cycle raise a located
    :class:`~rosaadl.errors.NameResolutionError` / :class:`~rosaadl.errors.ModelError`.

    With ``strict=False`` a subcomponent or feature group whose classifier does not resolve is
    instantiated without it (a warning), as OSATE does for a model with unresolved references.
    ``compatibility="osate-2.0"`` reproduces two connection rules of OSATE 2.0 (the version that
    wrote instance files with a ``systemImplementation`` root reference): a connection that goes up
    to a feature of a component that nothing continues ends there as an incomplete connection
    instance (current OSATE, the default, drops it with a warning), and a bidirectional access
    connection found from both ends keeps its ``->`` name (current OSATE renames it ``<->``).
    """
    instantiator = Instantiator(model, resolver=resolver, strict=strict, compatibility=compatibility)
    system = instantiator.run(root)
    if diagnostics is not None:
        diagnostics.extend(instantiator.diagnostics)
    model.instances.append(system)
    return system


class Instantiator:
    """One instantiation (use :func:`instantiate`); keeps the caches and the diagnostics."""

    def __init__(
        self,
        model: EObject,
        *,
        resolver: Resolver | None = None,
        strict: bool = True,
        compatibility: str = "current",
    ) -> None:
        if compatibility not in COMPATIBILITY_MODES:
            raise UsageError(
                f"unknown compatibility {compatibility!r} (expected one of: {', '.join(COMPATIBILITY_MODES)})"
            )
        self.model = model
        self.strict = strict
        self.legacy = compatibility == "osate-2.0"
        self.resolver = resolver if resolver is not None else Resolver(model)
        self.lookup = PropertyLookup(model, self.resolver)
        self.factory = self.lookup.factory
        self.diagnostics: list[Diagnostic] = []
        self._errors: list[Diagnostic] = []
        self._conn_cache: dict[int, list[_Conn]] = {}
        self._outgoing_cache: dict[int, dict[str, list[_Conn]]] = {}
        self._feature_cache: dict[int, list[tuple[EObject, str, str, EObject | None, int]]] = {}
        self._count = 0
        self._up: list[_FI] = []
        self._down: list[_FI] = []
        self._root: _CI | None = None
        self._all: list[_CI] = []
        self._soms: list[tuple[EObject, frozenset[int]]] = []
        self._accept_cache: dict[tuple[str, str, str], bool] = {}

    # ------------------------------------------------------------------ diagnostics

    def _warn(
        self, message: str, path: str | None = None, element: EObject | None = None, severity: str = "warning"
    ) -> None:
        location = self.resolver.location(element, path=path) if element is not None else Location(path=path)
        diagnostic = Diagnostic(severity, message, location)
        self.diagnostics.append(diagnostic)
        log.log(logging.WARNING if severity == "warning" else logging.INFO, "%s", diagnostic)

    def _error(self, message: str, path: str | None = None, element: EObject | None = None) -> None:
        location = self.resolver.location(element, path=path) if element is not None else Location(path=path)
        self._errors.append(Diagnostic("error", message, location))

    def _raise_errors(self) -> None:
        if not self._errors:
            return
        first = self._errors[0]
        message = first.message
        if len(self._errors) > 1:
            message += (
                f" (and {len(self._errors) - 1} more error(s): "
                + "; ".join(str(e) for e in self._errors[1:6])
                + ("; ..." if len(self._errors) > 6 else "")
                + ")"
            )
        raise NameResolutionError(message, first.location, errors=self._errors)

    # ------------------------------------------------------------------ run

    def run(self, root: str) -> EObject:
        """Instantiate ``root`` and return the ``SystemInstance`` (not added to the model)."""
        # The instance model is built from many small objects that are never garbage; Python's
        # cyclic collector would rescan the growing heap again and again (half the time of a large
        # model), so it is paused while the instance is built (rosaadl.bulk.gc_paused).
        with gc_paused():
            return self._run(root)

    def _run(self, root: str) -> EObject:
        resolver = self.resolver
        impl = resolver.classifier(root)
        if impl is None and root and "::" not in root:
            # an unqualified root is accepted when exactly one package declares it
            matches = [c for unit in resolver.units() if (c := resolver.classifier(f"{unit.name}::{root}"))]
            if len(matches) == 1:
                impl = matches[0]
        if impl is None:
            known = sorted(
                resolver.qualified_name(c)
                for unit in resolver.units()
                if _is(unit, "AadlPackage")
                for c in unit.classifiers
                if _is(c, "ComponentImplementation")
            )
            hint = f"; implementations in the model: {', '.join(known[:8])}" + (
                " ..." if len(known) > 8 else ""
            )
            raise NameResolutionError(
                f"root implementation {root!r} not found"
                + (hint if known else "; the model has no implementations"),
                Location(path=root),
            )
        if not _is(impl, "ComponentImplementation"):
            impls = [
                resolver.qualified_name(c)
                for c in resolver.unit_of(impl).classifiers
                if _is(c, "ComponentImplementation") and resolver.implementation_type(c) is impl
            ]
            raise NameResolutionError(
                f"root {root!r} is a {impl.eClass.name}, not a component implementation"
                + (f"; instantiate one of: {', '.join(impls)}" if impls else ""),
                resolver.location(impl),
            )
        ctype = resolver.implementation_type(impl)
        if ctype is None:
            raise NameResolutionError(
                f"the component type of {resolver.qualified_name(impl)} is not found", resolver.location(impl)
            )
        resolver.extends_chain(impl)
        type_name, _, impl_name = (impl.name or "").partition(".")
        system = _model.eclass_of("SystemInstance").python_class(
            name=f"{type_name}_{impl_name}_Instance",
            classifier=resolver.qualified_name(impl),
            category=impl.category,
        )
        node = self.lookup.root_node(impl, system)
        root_ci = _CI(system, node, None, None, "", node.category, (), segment=system.name)
        self._root = root_ci
        self._populate(root_ci, [])
        self._raise_errors()
        self._system_operation_modes(root_ci)
        self._instantiate_connections(root_ci)
        self._expand_arrays(root_ci)
        self._end_to_end_flows()
        self._properties()
        self.diagnostics.extend(self.lookup.diagnostics)
        for diagnostic in self.lookup.diagnostics:
            log.warning("%s", diagnostic)
        self.lookup.diagnostics.clear()
        return system

    # ------------------------------------------------------------------ hierarchy

    def _path(self, ci: _CI) -> str:
        parts = []
        current: _CI | None = ci
        while current is not None:
            parts.append(current.segment)
            current = current.parent
        return ".".join(reversed(parts))

    def _array_sizes(self, dims: Iterable[str], element: EObject, path: str) -> list[int]:
        sizes = []
        for dim in dims:
            text = "".join((dim or "").split())
            if not text:
                self._warn("array dimension without a size; one element instantiated", path, element)
                sizes.append(1)
                continue
            if text.isdigit():
                sizes.append(int(text))
                continue
            const = self.resolver.constant(text, element)
            value = None
            if const is not None and const.value is not None and const.value.eClass.name == "IntegerValue":
                value = const.value.value
            if value is None:
                self._error(
                    f"array size {text} is not an integer or an integer property constant", path, element
                )
                sizes.append(0)
            else:
                sizes.append(int(value))
        return sizes

    def _populate(self, ci: _CI, ancestry: list[EObject]) -> None:
        resolver = self.resolver
        classifier = ci.node.classifier
        impl = ci.node.impl
        # modes first: modal subcomponents refer to them
        factory = self.factory
        for mode in resolver.modes(classifier):
            mi = factory.new("ModeInstance", name=mode.name, mode=mode.name, initial=bool(mode.initial))
            ci.modes[(mode.name or "").lower()] = mi
            ci.mode_list.append(mi)
        factory.extend(ci.obj, "modeInstances", ci.mode_list)
        if impl is not None:
            subs = self._in_osate_order(
                impl,
                resolver.subcomponents(impl),
                lambda sub: sub,
                lambda sub: _lit(sub.category),
                _SUBCOMPONENT_ORDER,
            )
            for sub in subs:
                self._instantiate_subcomponent(ci, sub, ancestry)
            factory.extend(ci.obj, "componentInstances", [child.obj for child in ci.children])
        if ci.node.ctype is not None or (classifier is not None and _is(classifier, "ComponentType")):
            self._instantiate_features(ci)
        transitions = resolver.mode_transitions(classifier)
        for transition in transitions:
            self._mode_transition(ci, transition)
        if transitions:
            factory.extend(ci.obj, "modeTransitionInstances", [mti for mti, _ in ci.transitions])
        specs = []
        for spec in resolver.flow_specifications(classifier):
            kind = spec.kind
            fsi = factory.new("FlowSpecificationInstance", name=spec.name, kind=kind)
            src = self._flow_end(ci, spec.inEnd)
            dst = self._flow_end(ci, spec.outEnd)
            if _enum(kind) in ("path", "sink") and src is not None:
                factory.set(fsi, "source", src.obj)
            if _enum(kind) in ("path", "source") and dst is not None:
                factory.set(fsi, "destination", dst.obj)
            specs.append(fsi)
            ci.flow_specs[(spec.name or "").lower()] = fsi
        factory.extend(ci.obj, "flowSpecifications", specs)

    def _flow_end(self, ci: _CI, text: str | None) -> _FI | None:
        segments = split_path(text or "")
        if not segments:
            return None
        fi = ci.feature(segments[0].key)
        for segment in segments[1:]:
            if fi is None:
                return None
            fi = fi.child(segment.key)
        return fi

    def _in_osate_order(self, classifier: EObject, items: list, member, category, table) -> list:
        """Members of ``classifier`` (``member(item)`` is the declaration) in the order OSATE lists
        them (getAllSubcomponents, getAllFeatures): the farthest ancestor's first, each
        classifier's by category (``category(item)``, ranked by ``table`` for the classifier's
        class), declaration order within one; a refinement counts among its own classifier's
        (OSATE removes the refined member and appends the refinement). OSATE 2.0's files show
        the same order."""
        if len(items) < 2:
            return items
        chain = list(reversed(self.resolver.extends_chain(classifier)))
        level = {id(c): n for n, c in enumerate(chain)}

        def key(pair: tuple[int, Any]) -> tuple[int, int, int]:
            position, item = pair
            owner = member(item).eContainer()
            order = table.get(_lit(getattr(owner, "category", None)), ())
            word = category(item)
            return (
                level.get(id(owner), len(chain)),
                order.index(word) if word in order else len(order),
                position,
            )

        return [item for _, item in sorted(enumerate(items), key=key)]

    def _instantiate_subcomponent(self, ci: _CI, sub: EObject, ancestry: list[EObject]) -> None:
        resolver = self.resolver
        parent_path = _LazyPath(self, ci)
        if any(sub is a for a in ancestry):
            self._error(
                f"containment cycle: subcomponent {sub.name} contains itself",
                f"{parent_path}.{sub.name}",
                sub,
            )
            return
        classifier_name = resolver.subcomponent_classifier_name(sub)
        classifier = resolver.subcomponent_classifier(sub)
        if classifier_name and classifier is None:
            classifier = self._prototype_classifier(ci, sub, classifier_name)
            if classifier is None:
                message = f"classifier {classifier_name} of subcomponent {sub.name} not found"
                if self.strict:
                    self._error(message, f"{parent_path}.{sub.name}", sub)
                    return
                self._warn(message + "; instantiated without a classifier", f"{parent_path}.{sub.name}", sub)
        if classifier is not None and not _is(classifier, "ComponentClassifier"):
            self._error(
                f"classifier {classifier_name} of subcomponent {sub.name} is not a component classifier",
                f"{parent_path}.{sub.name}",
                sub,
            )
            return
        dims = list(resolver.effective_attribute(sub, "arrayDimensions") or [])
        sizes = self._array_sizes(dims, sub, f"{parent_path}.{sub.name}") if dims else []
        indices: list[tuple[int, ...]] = (
            [tuple(combo) for combo in itertools.product(*(range(1, n + 1) for n in sizes))]
            if sizes
            else [()]
        )
        qualified = resolver.qualified_name(classifier) if classifier is not None else None
        in_modes = [
            m.split("=>")[0].strip().lower() for m in (resolver.effective_attribute(sub, "inModes") or [])
        ]
        parent_modes = [ci.modes[m] for m in in_modes if m in ci.modes]
        key = (sub.name or "").lower()
        factory = self.factory
        for index in indices:
            self._count += 1
            if self._count > MAX_COMPONENT_INSTANCES:
                raise ModelError(
                    f"more than {MAX_COMPONENT_INSTANCES} component instances; check the array sizes",
                    self.resolver.location(sub, path=f"{parent_path}.{sub.name}"),
                )
            category = classifier.category if classifier is not None else sub.category
            if classifier is not None and _enum(classifier.category) == "abstract":
                category = sub.category
            obj = factory.new(
                "ComponentInstance",
                name=sub.name,
                subcomponent=sub.name,
                classifier=qualified,
                category=category,
            )
            if index:
                factory.extend(obj, "index", index)
            if parent_modes:
                factory.extend(obj, "inModes", [m.name for m in parent_modes])
            node = self.lookup.child_node(ci.node, sub, classifier, obj, index, sub.name)
            segment = (sub.name or "") + "".join(f"[{i}]" for i in index)
            child = _CI(
                obj, node, ci, sub, key, _lit(category), index, in_modes=parent_modes, segment=segment
            )
            ci.children.append(child)
            ci.by_sub.setdefault(key, []).append(child)
            self._populate(child, [*ancestry, sub])

    def _prototype_classifier(self, ci: _CI, sub: EObject, name: str) -> EObject | None:
        """A subcomponent typed by a prototype: the actual bound where the containing component is
        declared, else the prototype's constraining classifier."""
        if "::" in name or "." in name:
            return None
        wanted = name.lower()
        bindings: list[tuple[str, EObject]] = []
        if ci.sub is not None and ci.sub.prototypeBindings:
            bindings.append((ci.sub.prototypeBindings, ci.sub))
        for classifier in (ci.node.impl, ci.node.ctype):
            if classifier is None:
                continue
            for c in self.resolver.extends_chain(classifier):
                if c.prototypeBindings:
                    bindings.append((c.prototypeBindings, c))
        for text, context in bindings:
            for part in text.strip("() ").split(","):
                left, sep, right = part.partition("=>")
                if sep and left.strip().lower() == wanted:
                    words = right.split()
                    if words:
                        found = self.resolver.classifier(words[-1], context)
                        if found is not None:
                            return found
        for classifier in (ci.node.impl, ci.node.ctype):
            if classifier is None:
                continue
            for c in self.resolver.extends_chain(classifier):
                for proto in c.prototypes:
                    if (proto.name or "").lower() == wanted and proto.text:
                        words = proto.text.replace(";", " ").split()
                        for word in reversed(words):
                            found = self.resolver.classifier(word, c)
                            if found is not None:
                                return found
        return None

    def _feature_plan(self, classifier: EObject) -> list[tuple[EObject, str, str, EObject | None, int]]:
        """(declaration, category, direction, feature group type, array size) per feature."""
        key = id(classifier)
        plan = self._feature_cache.get(key)
        if plan is not None:
            return plan
        resolver = self.resolver
        ctype = resolver.component_type(classifier) if not _is(classifier, "FeatureGroupType") else None
        owner_category = _lit(ctype.category) if ctype is not None else ""
        plan = []
        for feature in resolver.features(classifier):
            category = _enum(resolver.effective_attribute(feature, "category") or feature.category)
            direction = self._direction(feature, category)
            fgt = None
            if category == "featureGroup":
                fgt = resolver.feature_classifier(feature)
                if fgt is not None and not _is(fgt, "FeatureGroupType"):
                    fgt = None
            size = 0
            dims = list(resolver.effective_attribute(feature, "arrayDimensions") or [])
            if dims and owner_category in _ARRAY_FEATURE_OWNERS:
                size = self._array_sizes(dims[:1], feature, resolver.qualified_name(feature))[0] or 0
            plan.append((feature, category, direction, fgt, size))
        if ctype is not None:
            plan = self._in_osate_order(
                ctype, plan, lambda entry: entry[0], lambda entry: entry[1], _FEATURE_ORDER
            )
        self._feature_cache[key] = plan
        return plan

    def _direction(self, feature: EObject, category: str) -> str:
        if category in _ACCESS:
            return "in out"
        chain = self.resolver.refinement_chain(feature)
        for element in chain:
            if element.eIsSet("direction"):
                return _lit(element.direction)
        if category in ("featureGroup", "abstractFeature"):
            return "in out"
        return _lit(feature.direction)

    def _instantiate_features(self, ci: _CI) -> None:
        classifier = ci.node.classifier
        if classifier is None:
            return
        for feature, category, direction, fgt, size in self._feature_plan(classifier):
            for index in range(1, size + 1) if size else (0,):
                fi = self._new_feature(ci, None, feature, category, direction, fgt, index, False, [])
                ci.features.append(fi)
                ci.feature_by_name.setdefault(fi.key, fi)
        self.factory.extend(ci.obj, "featureInstances", [fi.obj for fi in ci.features])

    def _new_feature(
        self,
        ci: _CI,
        parent: _FI | None,
        feature: EObject,
        category: str,
        direction: str,
        fgt: EObject | None,
        index: int,
        inverse: bool,
        seen: list[EObject],
    ) -> _FI:
        resolver = self.resolver
        if inverse and direction in ("in", "out"):
            direction = "out" if direction == "in" else "in"
        factory = self.factory
        fclassifier = fgt if fgt is not None else resolver.feature_classifier(feature)
        obj = factory.new(
            "FeatureInstance",
            name=feature.name,
            feature=feature.name,
            index=index or None,
            category=_enum_literal("FeatureCategory", category),
            direction=_enum_literal("DirectionType", direction),
            access=resolver.effective_attribute(feature, "access") if category in _ACCESS else None,
            classifier=resolver.qualified_name(fclassifier) if fclassifier is not None else None,
        )
        if fclassifier is None:
            name = resolver.effective_attribute(feature, "classifier")
            if name and category != "featureGroup" and not self._is_prototype_name(feature, name):
                self._warn(f"classifier {name} of feature {feature.name} not found", self._path(ci), feature)
        fi = _FI(
            obj,
            feature,
            feature.name or "",
            (feature.name or "").lower(),
            index,
            category,
            direction,
            ci,
            parent,
        )
        fi.fgt = fgt
        if category == "featureGroup":
            name = resolver.effective_attribute(feature, "classifier")
            if fgt is None and name and not self._is_prototype_name(feature, name):
                message = f"feature group type {name} of feature group {feature.name} not found"
                if self.strict:
                    self._error(message, self._path(ci), feature)
                else:
                    self._warn(message, self._path(ci), feature)
            elif fgt is not None:
                if any(f is feature for f in seen):
                    self._error(f"feature group {feature.name} contains itself", self._path(ci), feature)
                    return fi
                members, inverted = resolver.feature_group_features(fgt)
                inner_inverse = inverse ^ bool(resolver.effective_attribute(feature, "inverse")) ^ inverted
                for member in members:
                    mcat = _enum(member.category)
                    mdir = self._direction(member, mcat)
                    mfgt = resolver.feature_classifier(member) if mcat == "featureGroup" else None
                    if mfgt is not None and not _is(mfgt, "FeatureGroupType"):
                        mfgt = None
                    child = self._new_feature(
                        ci, fi, member, mcat, mdir, mfgt, 0, inner_inverse, [*seen, feature]
                    )
                    fi.children.append(child)
                factory.extend(obj, "featureInstances", [child.obj for child in fi.children])
        return fi

    def _is_prototype_name(self, element: EObject, name: str) -> bool:
        return self.resolver._is_prototype(element, name)

    def _mode_transition(self, ci: _CI, transition: EObject) -> None:
        src = ci.modes.get((transition.source or "").lower())
        dst = ci.modes.get((transition.destination or "").lower())
        name = transition.name
        triggers = list(transition.triggers)
        if not name:
            event = ""
            if triggers:
                segments = split_path(triggers[0])
                event = "_".join(s.name for s in segments)
            name = f"{transition.source}_{event + '_' if event else ''}{transition.destination}"
        factory = self.factory
        mti = factory.new("ModeTransitionInstance", name=name, source=src, destination=dst)
        for trigger in triggers:
            segments = split_path(trigger)
            port: _FI | None = None
            if len(segments) == 1:
                port = ci.feature(segments[0].key)
            elif len(segments) == 2:
                child = ci.child(segments[0].key)
                if child is not None:
                    port = child.feature(segments[1].key)
                else:
                    group = ci.feature(segments[0].key)
                    port = group.child(segments[1].key) if group is not None else None
            if port is not None:
                factory.extend(mti, "triggers", [port.obj])
        ci.transitions.append((mti, transition))

    # ------------------------------------------------------------------ system operation modes

    def _preorder(self, root: _CI) -> list[_CI]:
        if self._all:
            return self._all
        order: list[_CI] = []
        stack = [root]
        while stack:
            ci = stack.pop()
            order.append(ci)
            stack.extend(reversed(ci.children))
        self._all = order
        return order

    def _system_operation_modes(self, root: _CI) -> None:
        modal = [ci for ci in self._preorder(root) if ci.mode_list]
        system = root.obj
        if not modal:
            som = self.factory.new("SystemOperationMode", name="No Modes")
            self.factory.extend(system, "systemOperationModes", [som])
            self._soms = [(som, frozenset())]
            return
        combos: list[list[EObject]] = []

        def active(ci: _CI, chosen: dict[int, EObject]) -> bool:
            current: _CI | None = ci
            while current is not None and current.parent is not None:
                if current.in_modes:
                    mode = chosen.get(id(current.parent))
                    if mode is None or not any(mode is m for m in current.in_modes):
                        return False
                current = current.parent
            return True

        def walk(i: int, chosen: dict[int, EObject], current: list[EObject]) -> None:
            if len(combos) >= MAX_SYSTEM_OPERATION_MODES:
                return
            if i == len(modal):
                combos.append(list(current))
                return
            ci = modal[i]
            if not active(ci, chosen):
                walk(i + 1, chosen, current)
                return
            for mi in ci.mode_list:
                chosen[id(ci)] = mi
                current.append(mi)
                walk(i + 1, chosen, current)
                current.pop()
                del chosen[id(ci)]

        walk(0, {}, [])
        if len(combos) >= MAX_SYSTEM_OPERATION_MODES:
            self._warn(f"system operation modes limited to {MAX_SYSTEM_OPERATION_MODES}", system.name)
        for number, combo in enumerate(combos):
            som = self.factory.new("SystemOperationMode", name=f"som_{number}")
            self.factory.extend(som, "currentModes", combo)
            self.factory.extend(system, "systemOperationModes", [som])
            self._soms.append((som, frozenset(id(m) for m in combo)))

    def _ci_active(self, ci: _CI, som_modes: frozenset[int]) -> bool:
        current: _CI | None = ci
        while current is not None:
            if current.in_modes and not any(id(m) in som_modes for m in current.in_modes):
                return False
            current = current.parent
        return True

    # ------------------------------------------------------------------ connection ends

    def _connections(self, ci: _CI | None) -> list[_Conn]:
        if ci is None or ci.node.impl is None:
            return []
        impl = ci.node.impl
        key = id(impl)
        cached = self._conn_cache.get(key)
        if cached is not None:
            return cached
        resolver = self.resolver
        subs = {(s.name or "").lower(): s for s in resolver.subcomponents(impl)}
        own_features = {(f.name or "").lower(): f for f in resolver.features(impl)}
        result = []
        for decl in resolver.connections(impl):
            source, destination = resolver.connection_ends(decl)
            src = self._end(source, subs, own_features, decl, impl)
            dst = self._end(destination, subs, own_features, decl, impl)
            kind = _enum(resolver.effective_attribute(decl, "kind") or decl.kind)
            bidir = any(bool(e.bidirectional) for e in resolver.refinement_chain(decl))
            modes = tuple(m.lower() for m in (resolver.effective_attribute(decl, "inModes") or ()))
            conn = _Conn(decl, decl.name or "", kind, bidir, src, dst, modes)
            if kind == "featureGroupConnection" and src.feature is not None and dst.feature is not None:
                a = resolver.feature_classifier(src.feature)
                b = resolver.feature_classifier(dst.feature)
                conn.same_fg = a is not None and a is b
            if src.end_kind == "unknown" or dst.end_kind == "unknown":
                self._warn(
                    f"connection {decl.name}: end {source if src.end_kind == 'unknown' else destination} "
                    "does not name a feature or subcomponent; not instantiated",
                    resolver.qualified_name(impl),
                    decl,
                )
                continue
            result.append(conn)
        self._conn_cache[key] = result
        return result

    def _outgoing_by_context(self, ci: _CI) -> dict[str, list[_Conn]]:
        """The connections of an implementation that leave each subcomponent (by its name)."""
        impl = ci.node.impl
        key = id(impl)
        table = self._outgoing_cache.get(key)
        if table is None:
            table = {}
            for conn in self._connections(ci):
                contexts = []
                if conn.src.ctx_kind == "sub":
                    contexts.append(conn.src.ctx)
                if conn.bidir and conn.dst.ctx_kind == "sub" and conn.dst.ctx not in contexts:
                    contexts.append(conn.dst.ctx)
                for context in contexts:
                    table.setdefault(context, []).append(conn)
            self._outgoing_cache[key] = table
        return table

    def _end(self, text: str, subs: dict, own_features: dict, decl: EObject, impl: EObject) -> _End:
        resolver = self.resolver
        segments = [s.key for s in split_path(text)]
        if not segments:
            return _End(None, "", "unknown", "")
        first = segments[0]
        if first in ("processor", "self") and len(segments) >= 2:
            return _End(None, "", "internal", segments[1])
        if len(segments) == 1:
            feature = own_features.get(first)
            if feature is not None:
                return _End(None, "", "feature", first, (), feature, _enum(feature.category))
            sub = subs.get(first)
            if sub is not None:
                return _End(None, "", "sub", first, sub_category=_lit(sub.category))
            return _End(None, "", "unknown", first)
        sub = subs.get(first)
        if sub is not None:
            classifier = resolver.subcomponent_classifier(sub)
            features = {(f.name or "").lower(): f for f in resolver.features(classifier)}
            feature = features.get(segments[1])
            owner_sub = (
                classifier is not None
                and _enum(classifier.category) == "subprogram"
                and _is(classifier, "ComponentType")
            )
            category = _enum(feature.category) if feature is not None else ""
            return _End(
                "sub",
                first,
                "feature",
                segments[1],
                tuple(segments[2:]),
                feature,
                category,
                ctx_category=_lit(sub.category),
                owner_is_subprogram_type=bool(owner_sub),
            )
        group = own_features.get(first)
        if group is not None and _enum(group.category) == "featureGroup":
            fgt = resolver.feature_classifier(group)
            feature = None
            if fgt is not None and _is(fgt, "FeatureGroupType"):
                members, _ = resolver.feature_group_features(fgt)
                feature = next((f for f in members if (f.name or "").lower() == segments[1]), None)
            category = _enum(feature.category) if feature is not None else ""
            return _End("fg", first, "feature", segments[1], tuple(segments[2:]), feature, category)
        return _End(None, "", "unknown", first)

    # ------------------------------------------------------------------ connections (OSATE)

    def _instantiate_connections(self, root: _CI) -> None:
        for ci in self._preorder(root):
            if ci is root:
                self._external_connections(root)
            elif all(i <= 1 for a in self._lineage(ci) for i in a.index):
                self._start_connections(ci)

    @staticmethod
    def _lineage(ci: _CI) -> Iterable[_CI]:
        current: _CI | None = ci
        while current is not None and current.parent is not None:
            yield current
            current = current.parent

    def _start_connections(self, ci: _CI) -> None:
        category = ci.category
        parent = ci.parent
        parent_conns = self._connections(parent)
        if not parent_conns:
            return
        sub_key = ci.sub_key
        if category in _SHARED:
            for conn in parent_conns:
                src_is = conn.src.end_kind == "sub" and conn.src.end == sub_key
                dst_is = conn.dst.end_kind == "sub" and conn.dst.end == sub_key
                if src_is or (conn.bidir and dst_is):
                    self._append(_Info(ci), conn, parent, dst_is)
        outside = self._outgoing_by_context(parent).get(sub_key, [])
        if not outside:
            return
        inside = self._connections(ci)
        has_outgoing_subs = any(self._has_outgoing_feature(child) for child in ci.children)
        ending = category in _ENDING
        previous: _FI | None = None
        for fi in ci.features:
            if previous is not None and previous.key == fi.key:
                continue
            if not _has_outgoing_features(fi):
                continue
            outgoing = [
                c
                for c in outside
                if (c.src.ctx_kind == "sub" and c.src.ctx == sub_key and c.src.end == fi.key)
                or (c.bidir and c.dst.ctx_kind == "sub" and c.dst.ctx == sub_key and c.dst.end == fi.key)
            ]
            if not outgoing:
                continue
            has_access, has_port, has_group = _feature_info(fi)
            look_inside = has_outgoing_subs and (not ending or has_access)
            connected_inside = look_inside and _is_connection_end(inside, fi.key)
            destination_inside = look_inside and _is_destination(inside, fi.key)
            for conn in outgoing:
                if (not destination_inside and not (conn.bidir and connected_inside)) or (
                    ending and (has_group or has_port)
                ):
                    previous = fi
                    opposite = not (conn.src.ctx == sub_key and conn.src.end == fi.key) and (
                        conn.bidir and conn.dst.ctx == sub_key and conn.dst.end == fi.key
                    )
                    self._append(_Info(fi), conn, parent, opposite)

    def _has_outgoing_feature(self, ci: _CI) -> bool:
        for fi in ci.features:
            if fi.category in _PORTS and fi.outgoing:
                return True
            if fi.category in _ACCESS or fi.category == "featureGroup":
                return True
            if fi.category == "abstractFeature" and fi.outgoing:
                return True
        return ci.category in _SHARED

    def _external_connections(self, root: _CI) -> None:
        conns = self._connections(root)
        if not conns:
            return
        for fi in root.features:
            self._incoming(fi, root, conns)
            for contained in fi.children:
                self._incoming(contained, root, conns)

    def _incoming(self, fi: _FI, root: _CI, conns: list[_Conn]) -> None:
        if not fi.incoming or fi.index > 1:
            return
        parent_key = fi.parent.key if fi.parent is not None else None
        selected = []
        for conn in conns:
            for end in (conn.src, conn.dst) if conn.bidir else (conn.src,):
                if end.end_kind != "feature" or end.end != fi.key:
                    continue
                if (
                    end.ctx_kind is None
                    and fi.parent is None
                    or end.ctx_kind == "fg"
                    and end.ctx == parent_key
                ):
                    selected.append(conn)
        for conn in selected:
            opposite = not (conn.src.end_kind == "feature" and conn.src.end == fi.key) and (
                conn.bidir and conn.dst.end == fi.key
            )
            self._append(_Info(fi), conn, root, opposite)

    def _append(self, info: _Info, conn: _Conn, ci: _CI, opposite: bool) -> None:
        did_transition = self._mode_transition_connections(ci, info, conn)
        from_ref = conn.dst if opposite else conn.src
        to_ref = conn.src if opposite else conn.dst
        to_ci = ci.child(to_ref.ctx) if to_ref.ctx_kind == "sub" else None
        final_component = to_ref.ctx_kind == "sub" and to_ref.ctx_category in _ENDING
        pushed = popped = downed = None

        if to_ref.category == "parameter" and (
            (from_ref.end_kind == "sub" and from_ref.sub_category == "data")
            or from_ref.category == "dataAccess"
        ):
            return
        if to_ref.category == "dataAccess" and to_ref.owner_is_subprogram_type:
            return
        if to_ref.ctx_kind == "sub" and to_ci is None:
            if to_ref.ctx_category != "subprogram":
                self._warn(f"no component instance for subcomponent {to_ref.ctx}", self._path(ci), conn.decl)
            return
        dst_empty = to_ci is not None and not to_ci.children

        from_end: Any = None
        if from_ref.end_kind != "sub":
            from_ci = ci.child(from_ref.ctx) if from_ref.ctx_kind == "sub" else None
            if from_ref.ctx_kind == "sub" and from_ci is None:
                if from_ref.ctx_category != "subprogram":
                    self._warn(
                        f"no component instance for subcomponent {from_ref.ctx}", self._path(ci), conn.decl
                    )
                return
            if from_ref.ctx_kind == "fg":
                group = ci.feature(from_ref.ctx)
                from_end = group.child(from_ref.end) if group is not None else None
                if from_end is not None:
                    if self._up:
                        top = self._up[-1]
                        if not info.dst_to_match and not _same(top, from_end):
                            return
                        popped = self._up.pop()
                    else:
                        self._down.append(from_end)
                        downed = from_end
            else:
                from_end = (from_ci or ci).feature(from_ref.end)
        else:
            from_end = ci.child(from_ref.end)

        to_end: Any = None
        if to_ref.end_kind != "sub":
            if to_ref.ctx_kind == "fg":
                group = ci.feature(to_ref.ctx)
                to_end = group.child(to_ref.end) if group is not None else None
                if to_end is not None:
                    self._up.append(to_end)
                    pushed = to_end
            else:
                to_end = (to_ci or ci).feature(to_ref.end)
        else:
            to_end = ci.child(to_ref.end)

        try:
            if (
                isinstance(from_end, _FI)
                and from_end.category in _PORTS
                and isinstance(to_end, _FI)
                and to_end.parent is None
                and to_end.owner is ci
                and ci.category in _ENDING
            ):
                return
            keep, valid = info.add_segment(conn, from_end, to_end, ci, opposite)
            if not keep:
                return
            if not valid:
                self._warn(
                    f"connection from {self._object_path(info.src)} via {conn.name} has no valid direction; "
                    "no connection instance created",
                    self._path(ci),
                    conn.decl,
                )
                return
            if to_ref.end_kind == "sub":
                target = ci.child(to_ref.end)
                if target is None:
                    self._warn(
                        f"connection to {to_ref.end} could not be instantiated", self._path(ci), conn.decl
                    )
                else:
                    info.complete = True
                    self._finalize(self._root, info, target)
            elif to_ref.end_kind == "internal":
                self._warn(f"connection to {to_ref.end} could not be instantiated", self._path(ci), conn.decl)
            elif to_ref.category == "parameter":
                holder = to_ci or ci
                target = holder.feature(to_ref.end)
                if target is None:
                    self._warn(f"destination feature {to_ref.end} not found", self._path(holder), conn.decl)
                else:
                    info.complete = True
                    self._finalize(ci, info, target)
            elif dst_empty:
                target = to_ci.feature(to_ref.end)
                if target is None:
                    self._warn(f"destination feature {to_ref.end} not found", self._path(to_ci), conn.decl)
                else:
                    info.complete = True
                    self._finalize(ci, info, target)
            elif to_ref.ctx_kind != "sub":
                self._going_up(info, conn, ci, to_ref, to_end, did_transition)
            else:
                self._going_down(info, conn, ci, to_ref, to_ci, final_component)
        finally:
            if pushed is not None and self._up:
                self._up.pop()
            if popped is not None and not self._down:
                self._up.append(popped)
            if downed is not None and self._down:
                self._down.pop()

    def _going_up(
        self, info: _Info, conn: _Conn, ci: _CI, to_ref: _End, to_end: Any, did_transition: bool
    ) -> None:
        to_key = to_ref.ctx if to_ref.ctx_kind == "fg" else to_ref.end
        if ci.parent is None:
            self._finalize(ci, info, ci.feature(to_key))
            return
        next_ci = ci.parent
        parent_conns = self._connections(next_ci)
        dst_fi = ci.feature(to_key)
        if dst_fi is None:
            return
        sub_key = ci.sub_key
        conns = [
            c
            for c in parent_conns
            if (c.src.ctx_kind == "sub" and c.src.ctx == sub_key and c.src.end == dst_fi.key)
            or (c.bidir and c.dst.ctx_kind == "sub" and c.dst.ctx == sub_key and c.dst.end == dst_fi.key)
        ]
        if not conns:
            if self.legacy and not did_transition:
                self._finalize(ci, info, dst_fi)
            elif not did_transition:
                # a feature nothing continues outside (often an unused provided access): OSATE
                # warned about it until its connection rework, which drops it silently
                self._warn(
                    f"could not continue connection from {self._object_path(info.src)} through "
                    f"{self._object_path(dst_fi)}; no connection instance created",
                    self._path(ci),
                    conn.decl,
                    severity="info",
                )
            return
        for next_conn in conns:
            clone = info.clone()
            opposite = False
            if next_conn.bidir and next_conn.dst.end_kind == "feature":
                nd = next_conn.dst
                next_dst = next_ci.feature(nd.end) if nd.ctx_kind is None else None
                if next_dst is None and nd.ctx_kind == "sub":
                    sub_ci = next_ci.child(nd.ctx)
                    next_dst = sub_ci.feature(nd.end) if sub_ci is not None else None
                if next_dst is not None:
                    opposite = ci.feature(to_key) is next_dst
            self._append(clone, next_conn, next_ci, opposite)

    def _going_down(self, info: _Info, conn: _Conn, ci: _CI, to_ref: _End, to_ci: _CI, final: bool) -> None:
        target = to_ci.feature(to_ref.end)
        if target is None:
            self._warn(
                f"could not find feature {to_ref.end} of subcomponent {to_ref.ctx}; "
                "no connection instance created",
                self._path(ci),
                conn.decl,
            )
            return
        if to_ci.node.impl is None:
            info.complete = True
            self._finalize(ci, info, target)
            return
        ignored = False
        inner = []
        for c in self._connections(to_ci):
            matches = (
                (c.src.ctx_kind is None and c.src.end_kind == "feature" and c.src.end == to_ref.end)
                or (
                    c.bidir
                    and c.dst.ctx_kind is None
                    and c.dst.end_kind == "feature"
                    and c.dst.end == to_ref.end
                )
                or (c.src.ctx_kind == "fg" and c.src.ctx == to_ref.end)
                or (c.bidir and c.dst.ctx_kind == "fg" and c.dst.ctx == to_ref.end)
            )
            if not matches:
                continue
            if c.kind == "accessConnection":
                if c.src.ctx_category == "subprogram" or c.dst.ctx_category == "subprogram":
                    ignored = True
                    continue
            elif c.kind == "parameterConnection" or final:
                ignored = True
                continue
            inner.append(c)
        if not inner:
            if self.resolver.subcomponents(to_ci.node.impl):
                info.complete = True
                self._finalize(ci, info, target)
            return
        if ignored:
            clone = info.clone()
            clone.complete = True
            self._finalize(ci, clone, target)
        for next_conn in inner:
            clone = info.clone()
            nd = next_conn.dst
            opposite = (nd.ctx_kind is None and nd.end_kind == "feature" and nd.end == to_ref.end) or (
                nd.ctx_kind == "fg" and nd.ctx == to_ref.end
            )
            self._append(clone, next_conn, to_ci, opposite)

    def _mode_transition_connections(self, ci: _CI, info: _Info, conn: _Conn) -> bool:
        if conn.kind not in ("portConnection", "featureGroupConnection"):
            return False
        dst = conn.dst
        if dst.ctx_kind == "sub" or ci.parent is None or ci.sub is None:
            return False
        parent = ci.parent
        done = False
        for mti, transition in parent.transitions:
            for trigger in transition.triggers:
                segments = [s.key for s in split_path(trigger)]
                if len(segments) == 2 and segments[0] == ci.sub_key and segments[1] == dst.end:
                    clone = info.clone()
                    clone.mode_transition = True
                    self._add_connection(clone, mti)
                    done = True
        return done

    # ------------------------------------------------------------------ finishing connections

    def _finalize(self, parent: _CI | None, info: _Info, dst: Any) -> None:
        if dst is None:
            return
        up_fi = None
        if isinstance(dst, _FI):
            dst_fi = dst
            if dst_fi.category == "featureGroup" and self._up:
                up_fi = self._up.pop()
                if up_fi.parent is dst_fi:
                    dst_fi = up_fi
                elif up_fi.parent is not None and self._fg_inverse(up_fi.parent, dst_fi) and dst_fi.children:
                    position = _position(up_fi)
                    if 0 <= position < len(dst_fi.children):
                        dst_fi = dst_fi.children[position]
            try:
                if isinstance(info.src, _FI):
                    if not info.src.children and not dst_fi.children:
                        self._add_connection(info, dst_fi)
                    else:
                        self._balance(parent, info, info.src, dst_fi)
                elif isinstance(info.src, _CI):
                    if not dst_fi.children:
                        self._add_connection(info, dst_fi)
                    else:
                        self._balance(parent, info, info.src, dst_fi)
            finally:
                if up_fi is not None:
                    self._up.append(up_fi)
        elif isinstance(dst, _CI) and isinstance(info.src, _FI):
            if not info.src.children:
                self._add_connection(info, dst)
            else:
                self._balance(parent, info, info.src, dst)

    def _fg_inverse(self, a: _FI, b: _FI) -> bool:
        """Are two feature group instances inverse of each other (both with members)?"""
        ta, tb = a.fgt, b.fgt
        if ta is None or tb is None:
            return False
        resolver = self.resolver
        if not resolver.feature_group_features(ta)[0] or not resolver.feature_group_features(tb)[0]:
            return False
        if bool(resolver.effective_attribute(a.decl, "inverse")) == bool(
            resolver.effective_attribute(b.decl, "inverse")
        ):
            return self._fgt_inverse(ta, tb)
        return ta is tb

    def _fgt_inverse(self, ta: EObject, tb: EObject) -> bool:
        inv_a = self.resolver.classifier(ta.inverseOf, ta) if ta.inverseOf else None
        inv_b = self.resolver.classifier(tb.inverseOf, tb) if tb.inverseOf else None
        return inv_a is tb or inv_b is ta

    def _balance(self, parent: _CI | None, info: _Info, src: Any, dst: Any) -> None:
        if self._up:
            for up_fi in reversed(list(self._up)):
                if not isinstance(dst, _FI):
                    break
                if info.dst_to_match:
                    name = info.dst_to_match[0]
                    dst = dst.child(name)
                    info.dst_to_match = info.dst_to_match[1:]
                elif up_fi.parent is not None and self._fg_inverse(up_fi.parent, dst):
                    position = _position(up_fi)
                    if 0 <= position < len(dst.children):
                        dst = dst.children[position]
                elif isinstance(src, _FI):
                    # OSATE matches the source by name here
                    src = dst.child(up_fi.key)
                if dst is None or src is None:
                    return
        elif self._down:
            for down_fi in list(self._down):
                if not isinstance(src, _FI):
                    break
                if info.src_to_match:
                    name = info.src_to_match[0]
                    src = src.child(name)
                    info.src_to_match = info.src_to_match[1:]
                elif down_fi.parent is not None and self._fg_inverse(src, down_fi.parent):
                    position = _position(down_fi)
                    if 0 <= position < len(src.children):
                        src = src.children[position]
                else:
                    src = src.child(down_fi.key)
                if src is None:
                    return
            info.src = src
        if isinstance(src, _CI) and isinstance(dst, _CI):
            return
        if isinstance(src, _CI) or isinstance(dst, _CI):
            self._add_connection(info, dst)
        else:
            self._expand(parent, info, src, dst, info.src_to_match, info.dst_to_match)

    def _expand(
        self,
        parent: _CI | None,
        info: _Info,
        src: _FI,
        dst: _FI,
        src_match: tuple[str, ...],
        dst_match: tuple[str, ...],
    ) -> None:
        old = info.src
        try:
            if src_match:
                for fi in src.children:
                    if fi.key == src_match[0]:
                        self._expand(parent, info, fi, dst, src_match[1:], dst_match)
                        break
                return
            if dst_match:
                for fi in dst.children:
                    if fi.key == dst_match[0]:
                        self._expand(parent, info, src, fi, src_match, dst_match[1:])
                        break
                return
            if not src.children and not dst.children:
                if info.across:
                    if src.outgoing and dst.incoming:
                        info.src = src
                        self._add_connection(info, dst)
                else:
                    up_only = _up_only(info, src, dst)
                    if (up_only and src.outgoing and dst.outgoing) or (
                        not up_only and src.incoming and dst.incoming
                    ):
                        info.src = src
                        self._add_connection(info, dst)
            elif not src.children:
                target = _find_member(info, dst, at_destination=True)
                if target is not None and ((info.across and target.incoming) or target.outgoing):
                    self._expand(parent, info, src, target, src_match, dst_match)
                elif src.category == "featureGroup":
                    up_only = _up_only(info, src, dst)
                    for element in dst.children:
                        if (up_only and element.outgoing) or (not up_only and element.incoming):
                            self._expand(parent, info, src, element, src_match, dst_match)
                else:
                    info.src = src
                    self._add_connection(info, dst)
            elif not dst.children:
                target = _find_member(info, src, at_destination=False)
                if target is not None and ((info.across and target.outgoing) or target.incoming):
                    self._expand(parent, info, target, dst, src_match, dst_match)
                elif dst.category == "featureGroup" or info.src_to_match:
                    down_only = not info.across and not _up_only(info, src, dst)
                    for element in src.children:
                        if (down_only and element.incoming) or (not down_only and element.outgoing):
                            self._expand(parent, info, element, dst, src_match, dst_match)
                else:
                    info.src = src
                    self._add_connection(info, dst)
            elif self._subset_match(info):
                for element in dst.children:
                    if (info.across and element.incoming) or element.outgoing:
                        match = _find_leaf(src, element.key)
                        if match is not None:
                            self._expand(parent, info, match, element, src_match, dst_match)
            else:
                for a, b in zip(src.children, dst.children, strict=False):
                    self._expand(parent, info, a, b, src_match, dst_match)
                if len(src.children) != len(dst.children):
                    self._warn(
                        "connected feature groups do not have the same number of features",
                        self._object_path(src),
                    )
        finally:
            info.src = old

    def _subset_match(self, info: _Info) -> bool:
        key = self.lookup.property_key("Modeling_Properties::Classifier_Matching_Rule")
        for conn in info.connections:
            for member in self.resolver.refinement_chain(conn.decl):
                for pa in self.lookup.holder_associations(member).get(key, ()):
                    for mv in pa.ownedValues:
                        value = mv.value
                        if (
                            value is not None
                            and value.eClass.name == "NamedValue"
                            and (value.name or "").lower() == "subset"
                        ):
                            return True
        return False

    def _object_path(self, end: Any) -> str:
        if isinstance(end, _CI):
            return self._path(end)
        if isinstance(end, _FI):
            parts = []
            current: _FI | None = end
            while current is not None:
                parts.append(current.name + (f"[{current.index}]" if current.index else ""))
                current = current.parent
            return self._path(end.owner) + "." + ".".join(reversed(parts))
        if isinstance(end, EObject):
            return _model.instance_path(end)
        return ""

    def _relative(self, path: str, container: str) -> str:
        if path.startswith(container + "."):
            return path[len(container) + 1 :]
        return path

    def _add_connection(self, info: _Info, dst: Any) -> EObject | None:
        """OSATE's addConnectionInstance: skip duplicates, merge the two directions of an access
        connection, name the instance relative to its container, make its references."""
        count = len(info.connections)
        if not info.mode_transition and (len(info.sources) != count or len(info.destinations) != count):
            self._warn(
                f"connection from {self._object_path(info.sources[0] if info.sources else info.src)} to "
                f"{self._object_path(dst)} could not be instantiated",
                self._path(info.container or self._root),
            )
            return None
        container = info.container or self._root
        decls = [c.decl for c in info.connections]
        for record in container.conn_index.get((id(info.src), id(dst)), ()):
            if len(record.decls) == count and (
                all(a is b for a, b in zip(record.decls, decls, strict=True))
                or all(a is b for a, b in zip(record.decls, reversed(decls), strict=True))
            ):
                return None
        for record in container.conn_index.get((id(dst), id(info.src)), ()):
            if record.kind == "accessConnection":
                record.obj.bidirectional = True
                if not self.legacy:
                    record.obj.name = record.obj.name.replace("->", "<->")
                return record.obj
        factory = self.factory
        container_path = self._path(container)
        src_path = self._relative(self._object_path(info.src), container_path)
        dst_path = self._relative(self._object_path(dst), container_path)
        kind = _connection_kind(info.src, dst)
        conni = factory.new(
            "ConnectionInstance",
            name=f"{src_path} -> {dst_path}",
            complete=True if info.across else None,
            kind=_enum_literal("ConnectionKind", kind),
            source=info.src.obj,
            destination=dst if isinstance(dst, EObject) else dst.obj,
        )
        refs = []
        source = info.src
        for conn, context, destination in zip(
            info.connections, info.contexts, info.destinations, strict=False
        ):
            resolved = _resolve_feature(source, destination)
            refs.append(
                factory.new(
                    "ConnectionReference",
                    connection=conn.name,
                    context=context.obj,
                    source=source.obj if source is not None else None,
                    destination=resolved.obj if resolved is not None else None,
                )
            )
            source = resolved
        factory.extend(conni, "connectionReferences", refs)
        record = _ConnRecord(conni, info.src, dst, decls, kind, list(info.contexts))
        if not self._fill_in_modes(record, info):
            self._warn(
                f"connection {conni.name} was removed because it is not active in any system operation mode",
                container_path,
            )
            return None
        self._attach(container, record)
        return conni

    def _attach(self, container: _CI, record: _ConnRecord) -> None:
        self.factory.extend(container.obj, "connectionInstances", [record.obj])
        container.connections.append(record)
        container.conn_index.setdefault((id(record.src), id(record.dst)), []).append(record)

    def _fill_in_modes(self, record: _ConnRecord, info: _Info) -> bool:
        """OSATE's fillInModes: the system operation modes in which a modal connection exists.
        Returns False when the connection exists in none (it is then not created)."""
        refs = list(zip(info.connections, info.contexts, strict=False))

        def modes_of(index: int) -> list[EObject] | None:
            conn, ci = refs[index]
            if conn.modes:
                return [ci.modes[m] for m in conn.modes if m in ci.modes]
            current: _CI | None = ci
            while current is not None and current.parent is not None:
                if current.in_modes:
                    return list(current.in_modes)
                current = current.parent
            return None

        start = None
        first_modes = None
        for index in range(len(refs)):
            first_modes = modes_of(index)
            if first_modes is not None:
                start = index
                break
        if start is None:
            return True
        selected: list[EObject] = []

        def generate(index: int, chosen: list[EObject]) -> None:
            if index == len(refs):
                wanted = {id(m) for m in chosen}
                for som, current in self._soms:
                    if not wanted <= current:
                        continue
                    if any(som is s for s in selected):
                        continue
                    if not self._end_active(info.src, current) or not self._end_active(record.dst, current):
                        continue
                    if not all(self._ci_active(ctx, current) for _, ctx in refs):
                        continue
                    selected.append(som)
                return
            next_modes = modes_of(index)
            if next_modes is not None:
                for mi in next_modes:
                    chosen.append(mi)
                    generate(index + 1, chosen)
                    chosen.pop()
            else:
                generate(index + 1, chosen)

        for mi in first_modes or []:
            generate(start + 1, [mi])
        if not selected:
            return False
        order = {id(som): i for i, (som, _) in enumerate(self._soms)}
        selected.sort(key=lambda s: order[id(s)])
        self.factory.extend(record.obj, "inSystemOperationModes", [s.name for s in selected])
        return True

    def _end_active(self, end: Any, som_modes: frozenset[int]) -> bool:
        if isinstance(end, _FI):
            return self._ci_active(end.owner, som_modes)
        if isinstance(end, _CI):
            return self._ci_active(end, som_modes)
        return True

    # ------------------------------------------------------------------ arrays

    def _expand_arrays(self, root: _CI) -> None:
        """Connection instances were made between first array elements only (as OSATE does);
        replicate them to the other elements: across arrays following ``Connection_Pattern``
        (default: one to one for arrays of equal size, else all to all), and into the other
        elements of arrays whose first element holds connections."""
        order = self._preorder(root)
        if not any(ci.index for ci in order):
            return
        for container in order:
            if self._first_elements_only(container):
                for record in list(container.connections):
                    self._replicate(container, record)
        for container in order:
            if self._first_elements_only(container):
                continue
            twin = self._twin(container)
            if twin is None or twin is container:
                continue
            depth = len(self._lineage_list(twin))

            def move(
                ci: _CI | None, twin: _CI = twin, container: _CI = container, depth: int = depth
            ) -> _CI | None:
                return self._rebase(ci, twin, container, depth)

            for record in list(twin.connections):
                self._add_replica(container, record, move, move)

    @staticmethod
    def _first_elements_only(ci: _CI) -> bool:
        current: _CI | None = ci
        while current is not None:
            if any(i > 1 for i in current.index):
                return False
            current = current.parent
        return True

    @staticmethod
    def _lineage_list(ci: _CI) -> list[_CI]:
        chain = []
        current: _CI | None = ci
        while current is not None:
            chain.append(current)
            current = current.parent
        return list(reversed(chain))

    def _twin(self, ci: _CI) -> _CI | None:
        """The component at the same place as ``ci`` with every array index set to 1."""
        current = self._root
        for step in self._lineage_list(ci)[1:]:
            ones = tuple(1 for _ in step.index)
            current = next((c for c in current.by_sub.get(step.sub_key, []) if c.index == ones), None)
            if current is None:
                return None
        return current

    def _rebase(self, ci: _CI | None, twin: _CI, container: _CI, depth: int) -> _CI | None:
        """The component under ``container`` at the place ``ci`` has under ``twin``."""
        if ci is None:
            return None
        chain = self._lineage_list(ci)
        if len(chain) < depth or chain[depth - 1] is not twin:
            return ci
        current = container
        for step in chain[depth:]:
            current = next((c for c in current.by_sub.get(step.sub_key, []) if c.index == step.index), None)
            if current is None:
                return None
        return current

    def _array_steps(self, container: _CI, end: Any) -> list[_CI]:
        """Array components on the path from ``container`` (exclusive) down to ``end``."""
        ci = end.owner if isinstance(end, _FI) else end
        steps = []
        while ci is not None and ci is not container:
            if ci.index:
                steps.append(ci)
            ci = ci.parent
        return list(reversed(steps))

    def _replicate(self, container: _CI, record: _ConnRecord) -> None:
        src_steps = self._array_steps(container, record.src)
        dst_steps = self._array_steps(container, record.dst)
        if not src_steps and not dst_steps:
            return
        pattern = self._connection_pattern(record)

        def combos(steps: list[_CI]) -> list[tuple[tuple[int, ...], ...]]:
            ranges = []
            for step in steps:
                siblings = step.parent.by_sub.get(step.sub_key, [])
                ranges.append(sorted({c.index for c in siblings}))
            return [tuple(c) for c in itertools.product(*ranges)] if ranges else [()]

        pairs = [
            (s, d)
            for s in combos(src_steps)
            for d in combos(dst_steps)
            if self._pattern_allows(pattern, src_steps, dst_steps, s, d)
        ]
        first_src = tuple(st.index for st in src_steps)
        first_dst = tuple(st.index for st in dst_steps)
        if (first_src, first_dst) not in pairs:
            # the first-element connection itself is not part of the pattern
            self._remove_connection(container, record)
        for s, d in pairs:
            if s == first_src and d == first_dst:
                continue
            src_map = {id(st): idx for st, idx in zip(src_steps, s, strict=True)}
            dst_map = {id(st): idx for st, idx in zip(dst_steps, d, strict=True)}

            def source_side(ci: _CI | None, src_map: dict = src_map) -> _CI | None:
                return self._translate_ci(container, ci, src_map)

            def destination_side(ci: _CI | None, dst_map: dict = dst_map) -> _CI | None:
                return self._translate_ci(container, ci, dst_map)

            self._add_replica(container, record, source_side, destination_side)

    def _add_replica(self, container: _CI, record: _ConnRecord, source_side, destination_side) -> None:
        """A copy of a connection instance with its source-side components moved by
        ``source_side`` and its destination-side ones by ``destination_side``."""
        src = self._translate(record.src, source_side)
        dst = self._translate(record.dst, destination_side)
        if src is None or dst is None:
            return
        for existing in container.conn_index.get((id(src), id(dst)), ()):
            if len(existing.decls) == len(record.decls) and all(
                a is b for a, b in zip(existing.decls, record.decls, strict=True)
            ):
                return
        container_path = self._path(container)
        name = f"{self._relative(self._object_path(src), container_path)} -> " + self._relative(
            self._object_path(dst), container_path
        )
        if record.obj.bidirectional and not self.legacy:
            name = name.replace("->", "<->")
        factory = self.factory
        conni = factory.new(
            "ConnectionInstance",
            name=name,
            complete=True if record.obj.complete else None,
            bidirectional=True if record.obj.bidirectional else None,
            kind=record.obj.kind,
            source=src.obj,
            destination=dst.obj,
        )
        # references before the one declared in the container are on the source side
        across = next((i for i, c in enumerate(record.contexts) if c is container), None)
        refs = []
        contexts = []
        for position, ref in enumerate(record.obj.connectionReferences):
            before = across is not None and position < across
            at = across is not None and position == across
            context_side = source_side if before or (across is None) else destination_side
            values = {}
            context = (
                self._translate(self._mirror(ref.context), context_side) if ref.context is not None else None
            )
            if context is not None:
                values["context"] = context.obj
            contexts.append(context)
            for attr, side in (
                ("source", source_side if before or at else destination_side),
                ("destination", source_side if before else destination_side),
            ):
                value = getattr(ref, attr)
                if value is not None:
                    moved = self._translate(self._mirror(value), side)
                    if moved is not None:
                        values[attr] = moved.obj
            refs.append(factory.new("ConnectionReference", connection=ref.connection, **values))
        factory.extend(conni, "connectionReferences", refs)
        factory.extend(conni, "inSystemOperationModes", list(record.obj.inSystemOperationModes))
        self._attach(container, _ConnRecord(conni, src, dst, list(record.decls), record.kind, contexts))

    def _remove_connection(self, container: _CI, record: _ConnRecord) -> None:
        container.obj.connectionInstances.remove(record.obj)
        container.connections.remove(record)
        bucket = container.conn_index.get((id(record.src), id(record.dst)), [])
        if record in bucket:
            bucket.remove(record)

    def _connection_pattern(self, record: _ConnRecord) -> list[list[str]]:
        """Connection_Pattern of the declarations of a connection instance (lower-case literals)."""
        key = self.lookup.property_key("Communication_Properties::Connection_Pattern")
        for decl in record.decls:
            for member in self.resolver.refinement_chain(decl):
                for pa in self.lookup.holder_associations(member).get(key, ()):
                    for mv in pa.ownedValues:
                        value = mv.value
                        if value is None:
                            continue
                        rows = value.ownedItems if value.eClass.name == "ListValue" else [value]
                        pattern = []
                        for row in rows:
                            items = row.ownedItems if row.eClass.name == "ListValue" else [row]
                            pattern.append(
                                [(i.name or "").lower() for i in items if i.eClass.name == "NamedValue"]
                            )
                        return pattern
        return []

    @staticmethod
    def _pattern_allows(pattern, src_steps, dst_steps, s, d) -> bool:
        """Whether source indices ``s`` connect to destination indices ``d`` (first array level
        on each side; deeper levels connect every element)."""
        if not src_steps or not dst_steps:
            return True
        si, di = s[0], d[0]
        first_src, first_dst = src_steps[0], dst_steps[0]
        src_siblings = first_src.parent.by_sub[first_src.sub_key]
        dst_siblings = first_dst.parent.by_sub[first_dst.sub_key]
        sizes_s = [max(c.index[k] for c in src_siblings) for k in range(len(si))]
        sizes_d = [max(c.index[k] for c in dst_siblings) for k in range(len(di))]
        row = pattern[0] if pattern else []
        for k in range(min(len(si), len(di))):
            rule = row[k] if k < len(row) else ("one_to_one" if sizes_s[k] == sizes_d[k] else "all_to_all")
            a, b, n = si[k], di[k], sizes_d[k]
            if rule == "one_to_one" and a != b:
                return False
            if rule == "next" and b != a + 1:
                return False
            if rule == "previous" and b != a - 1:
                return False
            if rule == "cyclic_next" and b != (a % n) + 1:
                return False
            if rule == "cyclic_previous" and b != ((a - 2) % n) + 1:
                return False
            if rule == "one_to_all" and a != 1:
                return False
            if rule == "all_to_one" and b != 1:
                return False
        return True

    def _translate_ci(
        self, container: _CI, ci: _CI | None, mapping: dict[int, tuple[int, ...]]
    ) -> _CI | None:
        """The component at the place of ``ci`` under ``container`` with the array steps named in
        ``mapping`` (by the id of the first-element step) moved to other indices."""
        if ci is None:
            return None
        chain = []
        current: _CI | None = ci
        while current is not None and current is not container:
            chain.append(current)
            current = current.parent
        if current is None:
            return ci
        result = container
        for step in reversed(chain):
            index = mapping.get(id(step), step.index)
            result = next((c for c in result.by_sub.get(step.sub_key, []) if c.index == index), None)
            if result is None:
                return None
        return result

    @staticmethod
    def _translate(end: Any, move) -> Any:
        """A component or feature end moved to another component by ``move``."""
        if isinstance(end, _CI):
            return move(end)
        if isinstance(end, _FI):
            owner = move(end.owner)
            if owner is None:
                return None
            names = []
            current: _FI | None = end
            while current is not None:
                names.append((current.key, current.index))
                current = current.parent
            fi: _FI | None = None
            for key, index in reversed(names):
                pool = owner.features if fi is None else fi.children
                fi = next((f for f in pool if f.key == key and f.index == index), None)
                if fi is None:
                    return None
            return fi
        return end

    def _mirror(self, obj: EObject) -> Any:
        """The component or feature record of an instance object."""
        index = getattr(self, "_mirror_index", None)
        if index is None:
            index = {}
            for ci in self._preorder(self._root):
                index[id(ci.obj)] = ci
                stack = list(ci.features)
                while stack:
                    fi = stack.pop()
                    index[id(fi.obj)] = fi
                    stack.extend(fi.children)
            self._mirror_index = index
        return index.get(id(obj))

    # ------------------------------------------------------------------ end-to-end flows

    def _end_to_end_flows(self) -> None:
        for ci in self._preorder(self._root):
            impl = ci.node.impl
            if impl is None:
                continue
            for flow in self.resolver.end_to_end_flows(impl):
                elements = self._flow_elements(ci, flow, set())
                instance = self.factory.new("EndToEndFlowInstance", name=flow.name, flow=flow.name)
                unique = []
                previous = None
                for element in elements:
                    if element is not previous and not any(element is e for e in unique):
                        unique.append(element)
                    previous = element
                self.factory.extend(instance, "flowElements", unique)
                self.factory.extend(ci.obj, "endToEndFlows", [instance])

    def _flow_elements(self, ci: _CI, flow: EObject, seen: set[int]) -> list[EObject]:
        if id(flow) in seen:
            return []
        seen = seen | {id(flow)}
        elements_text = list(self.resolver.effective_attribute(flow, "elements") or [])
        pieces: list[Any] = []
        for text in elements_text:
            segments = [s.key for s in split_path(text)]
            if not segments:
                continue
            if len(segments) >= 2:
                child = ci.child(segments[0])
                if child is not None:
                    pieces.extend(self._flow_spec_elements(child, segments[1], seen))
                    continue
                group = ci.feature(segments[0])
                if group is not None:
                    continue
            name = segments[0]
            conn = next((c for c in self._connections(ci) if c.name.lower() == name), None)
            if conn is not None:
                pieces.append(("conn", conn.decl, ci))
                continue
            child = ci.child(name)
            if child is not None:
                pieces.append(child.obj)
                continue
            other = next(
                (f for f in self.resolver.end_to_end_flows(ci.node.impl) if (f.name or "").lower() == name),
                None,
            )
            if other is not None:
                pieces.extend(self._flow_elements(ci, other, seen))
        return self._resolve_flow_connections(pieces)

    def _flow_spec_elements(self, ci: _CI, spec_name: str, seen: set[int]) -> list[Any]:
        impl = ci.node.impl
        flow_impl = None
        if impl is not None:
            flow_impl = next(
                (f for f in self.resolver.flow_implementations(impl) if (f.name or "").lower() == spec_name),
                None,
            )
        if flow_impl is None:
            spec = ci.flow_specs.get(spec_name)
            return [spec if spec is not None else ci.obj]
        pieces: list[Any] = []
        for text in flow_impl.elements:
            segments = [s.key for s in split_path(text)]
            if not segments:
                continue
            if len(segments) >= 2:
                child = ci.child(segments[0])
                if child is not None:
                    pieces.extend(self._flow_spec_elements(child, segments[1], seen))
                continue
            name = segments[0]
            conn = next((c for c in self._connections(ci) if c.name.lower() == name), None)
            if conn is not None:
                pieces.append(("conn", conn.decl, ci))
                continue
            child = ci.child(name)
            if child is not None:
                pieces.append(child.obj)
        return pieces

    def _resolve_flow_connections(self, pieces: list[Any]) -> list[Any]:
        """Replace each run of declared connections of a flow by the semantic connection instance
        that goes through all of them (the first one that does, else the one that goes through
        the most of them)."""
        result: list[Any] = []
        run: list[tuple[EObject, _CI]] = []

        def flush() -> None:
            if not run:
                return
            wanted = [(id(decl), id(context)) for decl, context in run]
            best = None
            best_score = 0
            for container in self._preorder(self._root):
                for record in container.connections:
                    through = set(
                        zip((id(d) for d in record.decls), (id(c) for c in record.contexts), strict=False)
                    )
                    score = sum(1 for item in wanted if item in through)
                    if score > best_score:
                        best, best_score = record.obj, score
                        if score == len(wanted):
                            break
                if best_score == len(wanted):
                    break
            if best is not None:
                result.append(best)
            run.clear()

        for piece in pieces:
            if isinstance(piece, tuple):
                _, decl, context = piece
                run.append((decl, context))
                continue
            flush()
            result.append(piece)
        flush()
        return result

    # ------------------------------------------------------------------ properties

    def _accepts(self, key: str, kind: str, word: str) -> bool:
        marker = (key, kind, word)
        cached = self._accept_cache.get(marker)
        if cached is None:
            cached = accepts(self.lookup.definition(key), kind, word)
            self._accept_cache[marker] = cached
        return cached

    def _properties(self) -> None:
        lookup = self.lookup
        resolver = self.resolver
        order = self._preorder(self._root)
        # The properties cached on instance objects are those the model associates somewhere (as
        # OSATE caches the properties its classifiers use, here across all loaded units, so that
        # an instance's value of a property does not depend on which classifiers it happens to
        # use): each with its value where it has one, default values included.
        used = set(lookup.model_properties())
        keys = sorted(used)
        mirror = {id(ci.obj): ci for ci in order}
        binding_key = lookup.property_key("Deployment_Properties::Actual_Processor_Binding")

        def reference(anchor: Any, path: str) -> EObject | None:
            start = mirror.get(id(getattr(anchor, "obj", None))) if anchor is not None else None
            return self._resolve_reference(start or self._root, path)

        def binding(node: ComponentNode | None) -> list[EObject] | None:
            if node is None:
                return None
            if node.binding is not None:
                return node.binding
            node.binding = []
            found = lookup.with_default(lookup.component_found(node, binding_key, None), binding_key, node)
            result: list[EObject] = []
            values = []
            if found is not None:
                try:
                    values = lookup.build_value(found, binding_key, reference=reference)
                except NoValue:
                    values = []
            if values:
                for expr, _modes in values:
                    for target in _referenced(expr):
                        ci = mirror.get(id(target))
                        if ci is not None and ci.node.classifier is not None:
                            result.append(ci.node.classifier)
            node.binding = result
            return result

        for ci in order:
            node = ci.node

            def evaluate(k: str, node: ComponentNode = node) -> Found | None:
                return lookup.with_default(lookup.component_found(node, k, binding), k, node)

            for key in keys:
                if not self._accepts(key, "component", ci.category):
                    continue
                found = lookup.with_default(lookup.component_found(node, key, binding), key, node)
                if found is not None:
                    association = lookup.association(
                        ci.obj, key, found, evaluate=evaluate, reference=reference
                    )
                    if association is not None:
                        self.factory.extend(ci.obj, "ownedPropertyAssociations", [association])
            self._feature_properties(ci, keys, binding, reference)
            for mi, decl in (
                (ci.modes.get((m.name or "").lower()), m) for m in resolver.modes(node.classifier)
            ):
                if mi is None:
                    continue
                self._element_properties(ci, mi, decl, "mode", "mode", keys, binding, reference)
            for spec in resolver.flow_specifications(node.classifier):
                fsi = ci.flow_specs.get((spec.name or "").lower())
                if fsi is not None:
                    self._element_properties(
                        ci, fsi, spec, "flow", "flow specification", keys, binding, reference
                    )
            for flow_obj in ci.obj.endToEndFlows:
                decl = next(
                    (f for f in resolver.end_to_end_flows(node.impl) if (f.name or "") == flow_obj.flow), None
                )
                if decl is not None:
                    self._element_properties(
                        ci, flow_obj, decl, "end to end flow", "end to end flow", keys, binding, reference
                    )
        for container in order:
            for record in container.connections:
                self._connection_properties(container, record, keys, binding, reference)

    def _feature_properties(self, ci: _CI, keys: list[str], binding, reference) -> None:
        lookup = self.lookup
        node = ci.node
        stack: list[tuple[_FI, list[EObject], list[tuple[str, int]]]] = [
            (fi, [fi.decl], [(fi.name, fi.index)]) for fi in ci.features
        ]
        while stack:
            fi, chain, names = stack.pop()
            word = feature_category_word(fi.category)
            # OSATE 2.0 also let a feature take the properties of its classifier's category (a data
            # port of data Integer takes an inherited Priority); OSATE today goes by the feature's
            # own metaclass only (a bus access feature takes no Period)
            classifier_word = ""
            if self.legacy:
                classifier = fi.fgt if fi.fgt is not None else self.resolver.feature_classifier(fi.decl)
                classifier_word = _classifier_word(classifier)
            for key in keys:
                if not self._accepts(key, "feature", word) and not (
                    classifier_word and self._accepts(key, "classifier", classifier_word)
                ):
                    continue
                found = lookup.with_default(lookup.feature_found(node, chain, names, key, binding), key, node)
                if found is not None:

                    def evaluate(k: str, chain=chain, names=names) -> Found | None:
                        return lookup.with_default(
                            lookup.feature_found(node, chain, names, k, binding), k, node
                        )

                    association = lookup.association(
                        fi.obj, key, found, evaluate=evaluate, reference=reference
                    )
                    if association is not None:
                        self.factory.extend(fi.obj, "ownedPropertyAssociations", [association])
            for child in fi.children:
                stack.append((child, [*chain, child.decl], [*names, (child.name, child.index)]))

    def _element_properties(self, ci, obj, decl, kind, word, keys, binding, reference) -> None:
        lookup = self.lookup
        node = ci.node
        for key in keys:
            if not self._accepts(key, kind, word):
                continue
            found = lookup.with_default(lookup.element_found(node, decl, key, binding), key, node)
            if found is not None:

                def evaluate(k: str) -> Found | None:
                    return lookup.with_default(lookup.element_found(node, decl, k, binding), k, node)

                association = lookup.association(obj, key, found, evaluate=evaluate, reference=reference)
                if association is not None:
                    self.factory.extend(obj, "ownedPropertyAssociations", [association])

    def _connection_properties(self, container: _CI, record: _ConnRecord, keys, binding, reference) -> None:
        lookup = self.lookup
        word = _CONNECTION_WORDS.get(record.kind, "connection")
        refs = [(decl, context.node) for decl, context in zip(record.decls, record.contexts, strict=False)]
        owner = container.node
        for key in keys:
            if not self._accepts(key, "connection", word):
                continue
            found = lookup.with_default(lookup.connection_found(refs, owner, key, binding), key, owner)
            if found is not None:

                def evaluate(k: str) -> Found | None:
                    return lookup.with_default(lookup.connection_found(refs, owner, k, binding), k, owner)

                association = lookup.association(
                    record.obj, key, found, evaluate=evaluate, reference=reference
                )
                if association is not None:
                    self.factory.extend(record.obj, "ownedPropertyAssociations", [association])

    def _resolve_reference(self, start: _CI, path: str) -> EObject | None:
        current: Any = start
        for segment in split_path(path):
            key = segment.key
            found: Any = None
            if isinstance(current, _CI):
                for child in current.by_sub.get(key, []):
                    if segment.matches(list(child.index)):
                        found = child
                        break
                if found is None:
                    for fi in current.features:
                        if fi.key == key and segment.matches(fi.index):
                            found = fi
                            break
                if found is None:
                    mode = current.modes.get(key)
                    if mode is not None:
                        found = mode
                if found is None:
                    for record in current.connections:
                        for ref in record.obj.connectionReferences:
                            if (ref.connection or "").lower() == key and ref.context is current.obj:
                                found = record.obj
                                break
                        if found is not None:
                            break
            elif isinstance(current, _FI):
                found = current.child(key)
            if found is None:
                return None
            current = found
        if isinstance(current, (_CI, _FI)):
            return current.obj
        return current


# ---------------------------------------------------------------------- helpers


class _LazyPath:
    """The instance path of a component, computed only when a message needs it."""

    __slots__ = ("_instantiator", "_ci")

    def __init__(self, instantiator: Instantiator, ci: _CI) -> None:
        self._instantiator = instantiator
        self._ci = ci

    def __str__(self) -> str:
        return self._instantiator._path(self._ci)

    def __format__(self, spec: str) -> str:
        return format(str(self), spec)


def _is(obj: object, *names: str) -> bool:
    """Is ``obj`` an instance of one of the metamodel classes ``names``?"""
    if not isinstance(obj, EObject):
        return False
    return _class_is(obj.eClass, names)


@functools.lru_cache(maxsize=4096)
def _class_is(eclass: object, names: tuple[str, ...]) -> bool:
    """The answer of :func:`_is` for one metaclass (immutable metadata, so cached)."""
    return eclass.name in names or any(sup.name in names for sup in eclass.eAllSuperTypes())


def _classifier_word(classifier: EObject | None) -> str:
    """The metaclass word a classifier answers to in ``applies to`` lists."""
    if classifier is None:
        return ""
    if _is(classifier, "FeatureGroupType"):
        return "feature group type"
    return _lit(getattr(classifier, "category", None))


def _has_outgoing_features(fi: _FI) -> bool:
    if not fi.children:
        return fi.direction != "in"
    return any(_has_outgoing_features(child) for child in fi.children)


def _feature_info(fi: _FI) -> tuple[bool, bool, bool]:
    """(has access, has port, has feature group) of a feature or the members of a feature group."""
    if fi.category == "featureGroup":
        members = fi.children
        return (
            any(m.category in _ACCESS for m in members),
            any(m.category in _PORTS for m in members),
            any(m.category == "featureGroup" for m in members),
        )
    return fi.category in _ACCESS, fi.category in _PORTS, False


def _is_connection_end(conns: list[_Conn], key: str) -> bool:
    for conn in conns:
        if conn.kind == "parameterConnection":
            continue
        for end in (conn.src, conn.dst):
            if end.ctx_kind is None and end.end_kind == "feature" and end.end == key:
                return True
            if end.ctx_kind == "fg" and end.ctx == key:
                return True
    return False


def _is_destination(conns: list[_Conn], key: str) -> bool:
    for conn in conns:
        if conn.kind == "parameterConnection":
            continue
        ends = (conn.dst, conn.src) if conn.bidir else (conn.dst,)
        for end in ends:
            if end.ctx_kind is None and end.end_kind == "feature" and end.end == key:
                return True
            if end.ctx_kind == "fg" and end.ctx == key:
                return True
    return False


def _same(a: _FI, b: _FI) -> bool:
    return a.key == b.key and a.index == b.index


def _position(fi: _FI) -> int:
    siblings = fi.parent.children if fi.parent is not None else fi.owner.features
    for i, other in enumerate(siblings):
        if other is fi:
            return i
    return -1


def _up_only(info: _Info, src: _FI, dst: _FI) -> bool:
    if info.across:
        return False
    target = dst.owner
    current: _CI | None = src.owner
    while current is not None:
        if current is target:
            return True
        current = current.parent
    return False


def _find_leaf(group: _FI, key: str) -> _FI | None:
    stack = list(reversed(group.children))
    while stack:
        fi = stack.pop()
        if not fi.children and fi.key == key:
            return fi
        stack.extend(reversed(fi.children))
    return None


def _find_member(info: _Info, group: _FI, *, at_destination: bool) -> _FI | None:
    """OSATE's findDestinationFeatureInstance (``at_destination``) and
    findSourceFeatureInstance: the member of feature group ``group``, at that end of the
    connection, that corresponds to the leaf feature the connection reached the other end's
    feature group through.

    Walking the connection's steps from the other end (sources and destinations pairwise,
    backwards for the source end), the step whose near end is the feature group that holds
    the previous step's far end tells the member: the leaf of ``group`` with its name, or else
    (a feature group type and the inverse that names its features differently) the member at
    its position in that feature group.
    """
    steps = list(zip(info.sources, info.destinations, strict=False))
    if not at_destination:
        steps.reverse()
    target: Any = None
    for src, dst in steps:
        near, far = (src, dst) if at_destination else (dst, src)
        if isinstance(target, _FI) and target.parent is near:
            found = _find_leaf(group, target.key)
            if found is None:
                position = near.children.index(target)
                if position < len(group.children):
                    found = group.children[position]
            return found
        target = far
    return None


def _resolve_feature(orig: Any, root: Any) -> Any:
    """OSATE's resolveFeatureInstance: narrow a feature group destination to the member that
    matches the source it came from."""
    if not isinstance(orig, _FI) or not isinstance(root, _FI):
        return root
    if not root.children:
        return root
    parent: _FI = root
    if orig.parent is not None:
        if orig.parent.parent is not None:
            resolved = _resolve_feature(orig.parent, root)
            if isinstance(resolved, _FI):
                parent = resolved
        for fi in parent.children:
            if _same(orig, fi):
                return fi
    return root


def _connection_kind(src: Any, dst: Any) -> str:
    def category(end: Any) -> str:
        return end.category if isinstance(end, _FI) else ""

    s, d = category(src), category(dst)
    src_ci = isinstance(src, _CI)
    dst_ci = isinstance(dst, _CI)
    if (src_ci and d in _ACCESS) or (s in _ACCESS and dst_ci) or (s in _ACCESS and d in _ACCESS):
        return "accessConnection"
    if s == "parameter" or d == "parameter":
        return "parameterConnection"
    if s == "featureGroup" or d == "featureGroup":
        return "featureGroupConnection"
    if s == "abstractFeature" or d == "abstractFeature":
        return "featureConnection"
    return "portConnection"


def _referenced(expr: EObject) -> list[EObject]:
    if expr.eClass.name == "InstanceReferenceValue":
        return [expr.referencedInstanceObject] if expr.referencedInstanceObject is not None else []
    if expr.eClass.name == "ListValue":
        result = []
        for item in expr.ownedItems:
            result.extend(_referenced(item))
        return result
    return []


@functools.lru_cache(maxsize=256)
def _enum_literal(enum_name: str, text: str) -> Any:
    """The literal object of an enumeration of aadl.ecore for a literal name or AADL spelling."""
    from rosaadl import metamodels

    enum = metamodels.load().aadl.getEClassifier(enum_name)
    literal = enum.getEEnumLiteral(text)
    return literal if literal is not None else enum.from_string(text)


_CONNECTION_WORDS = {
    "portConnection": "port connection",
    "accessConnection": "access connection",
    "featureGroupConnection": "feature group connection",
    "featureConnection": "feature connection",
    "parameterConnection": "parameter connection",
    "modeTransitionConnection": "mode transition connection",
}
