"""One instantiation: the state every stage shares, and the stages in their order.

:class:`Instantiator` holds the options, the resolver, the property lookup and its object
factory, the per-classifier caches, the diagnostics and the component mirror tree
(:mod:`.mirrors`); the stages are functions of it, one module each: :mod:`.hierarchy` (with
:mod:`.features` and the mode instances of :mod:`.modes`), the system operation modes,
:mod:`.connections`, :mod:`.arrays`, :mod:`.flows` and :mod:`.property_values`.
"""

from __future__ import annotations

import logging
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.arguments import checked
from rosaadl.bulk import gc_paused
from rosaadl.errors import Diagnostic, Location, NameResolutionError, UsageError
from rosaadl.lookup import PropertyLookup
from rosaadl.resolution import Resolver

from .arrays import expand_arrays
from .connections import instantiate_connections
from .flows import end_to_end_flows
from .hierarchy import populate
from .mirrors import ComponentMirror, FeatureMirror
from .modes import system_operation_modes
from .property_values import property_values

__all__ = ["COMPATIBILITY_MODES", "Instantiator", "instantiate"]

log = logging.getLogger("rosaadl.transforms.instantiate")

#: Accepted values of ``compatibility``: current OSATE, or the rules of OSATE 2.0.
COMPATIBILITY_MODES = ("current", "osate-2.0")


@checked
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
    """One instantiation (use :func:`instantiate`): the state the stages share.

    Besides the options and services, it keeps what is computed once per classifier (resolved
    connection declarations, feature plans), the mirror tree (:attr:`root`, and :attr:`components`
    in preorder once the hierarchy is built), the system operation modes, and the diagnostics.
    """

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
        #: the rules of OSATE 2.0 (``compatibility="osate-2.0"``)
        self.legacy = compatibility == "osate-2.0"
        self.resolver = resolver if resolver is not None else Resolver(model)
        self.lookup = PropertyLookup(model, self.resolver)
        self.factory = self.lookup.factory
        self.diagnostics: list[Diagnostic] = []
        #: errors of the hierarchy, raised together once it is built
        self.errors: list[Diagnostic] = []
        #: component instances made so far (against MAX_COMPONENT_INSTANCES)
        self.count = 0
        # per classifier (by id): resolved connection declarations, those leaving each
        # subcomponent, feature plans
        self.declared: dict[int, list[Any]] = {}
        self.outgoing: dict[int, dict[str, list[Any]]] = {}
        self.feature_plans: dict[int, list[tuple[EObject, str, str, EObject | None, int]]] = {}
        #: the mirror of the system instance, and every component in preorder (as made)
        self.root: ComponentMirror | None = None
        self.components: list[ComponentMirror] = []
        #: (system operation mode, ids of its mode instances), in order
        self.soms: list[tuple[EObject, frozenset[int]]] = []
        # the feature group members a connection went up through (pushed on the way up, matched
        # on the way down) and came down through, while connections are followed
        self.up: list[FeatureMirror] = []
        self.down: list[FeatureMirror] = []

    # ------------------------------------------------------------------ diagnostics

    def warn(
        self, message: str, path: str | None = None, element: EObject | None = None, severity: str = "warning"
    ) -> None:
        """Record (and log) a warning, located at ``element`` and instance ``path``."""
        location = self.resolver.location(element, path=path) if element is not None else Location(path=path)
        diagnostic = Diagnostic(severity, message, location)
        self.diagnostics.append(diagnostic)
        log.log(logging.WARNING if severity == "warning" else logging.INFO, "%s", diagnostic)

    def error(self, message: str, path: str | None = None, element: EObject | None = None) -> None:
        """Record an error of the hierarchy (raised by :meth:`raise_errors`)."""
        location = self.resolver.location(element, path=path) if element is not None else Location(path=path)
        self.errors.append(Diagnostic("error", message, location))

    def raise_errors(self) -> None:
        """Raise the errors recorded so far as one located NameResolutionError."""
        if not self.errors:
            return
        first = self.errors[0]
        message = first.message
        if len(self.errors) > 1:
            message += (
                f" (and {len(self.errors) - 1} more error(s): "
                + "; ".join(str(e) for e in self.errors[1:6])
                + ("; ..." if len(self.errors) > 6 else "")
                + ")"
            )
        raise NameResolutionError(message, first.location, errors=self.errors)

    # ------------------------------------------------------------------ run

    def run(self, root: str) -> EObject:
        """Instantiate ``root`` and return the ``SystemInstance`` (not added to the model)."""
        # The instance model is built from many small objects that are never garbage; Python's
        # cyclic collector would rescan the growing heap again and again (half the time of a large
        # model), so it is paused while the instance is built (rosaadl.bulk.gc_paused).
        with gc_paused():
            return self._run(root)

    def _run(self, root: str) -> EObject:
        impl = self._root_implementation(root)
        resolver = self.resolver
        type_name, _, impl_name = (impl.name or "").partition(".")
        system = _model.eclass_of("SystemInstance").python_class(
            name=f"{type_name}_{impl_name}_Instance",
            classifier=resolver.qualified_name(impl),
            category=impl.category,
        )
        node = self.lookup.root_node(impl, system)
        root_ci = ComponentMirror(system, node, None, None, "", node.category, (), segment=system.name)
        self.root = root_ci
        populate(self, root_ci, [])
        self.raise_errors()
        system_operation_modes(self)
        instantiate_connections(self)
        expand_arrays(self)
        end_to_end_flows(self)
        property_values(self)
        self.diagnostics.extend(self.lookup.diagnostics)
        for diagnostic in self.lookup.diagnostics:
            log.warning("%s", diagnostic)
        self.lookup.diagnostics.clear()
        return system

    def _root_implementation(self, root: str) -> EObject:
        """The component implementation named ``root``, or a located NameResolutionError."""
        if root is not None and not isinstance(root, str):
            raise UsageError(f"the root is named by a string such as 'Pkg::System.impl', not {root!r}")
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
                if _model.is_a(unit, "AadlPackage")
                for c in unit.classifiers
                if _model.is_a(c, "ComponentImplementation")
            )
            hint = f"; implementations in the model: {', '.join(known[:8])}" + (
                " ..." if len(known) > 8 else ""
            )
            raise NameResolutionError(
                f"root implementation {root!r} not found"
                + (hint if known else "; the model has no implementations"),
                Location(path=root),
            )
        if not _model.is_a(impl, "ComponentImplementation"):
            impls = [
                resolver.qualified_name(c)
                for c in resolver.unit_of(impl).classifiers
                if _model.is_a(c, "ComponentImplementation") and resolver.implementation_type(c) is impl
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
        return impl
