"""The convention: packages made by :func:`rosaadl.transforms.rosmod_to_aadl.rosmod_to_aadl`
back into the ROSMOD project, as rules of :data:`CONVENTION` on the declarative model.

This module holds what the rules share — the :class:`ConventionState` (the packages by
``Unit_Kind`` in ``Position`` order, the implementation each thread group and system is read
from, the ROSMOD name of an element), the walk that decides which elements the rules see and
in which order — and the rules on the model and its packages as a whole. The rules on the
software are in :mod:`.software`, those on hardware and deployments in :mod:`.platform`
(the package imports both, which declares them).

The walk visits, in this order: the packages outside the project (each a warning), the model
(the project), then per kind in ``Position`` order: each software package, its data types and
subprograms, then per thread group its features, the group, and the subcomponents of its
implementation; each hardware package and the subcomponents and connections of its system
implementation; each deployment package and the subcomponents of its system implementation.
So the warnings come in the order of the project's own files, and a rule that looks up what an
earlier one made (a callback thread, the port it serves) finds it.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.properties import own_property
from rosaadl.transforms import rosmod_to_aadl as fwd
from rosaadl.transforms import trace as tracing
from rosaadl.transforms.engine import Context, Transformation

from .reading import (
    ClassifierIndex,
    Report,
    add,
    declared_location,
    declared_path,
    enum_name,
    integer,
    new,
    settings,
    text,
)

__all__ = [
    "CONVENTION",
    "ConventionState",
    "is_rosmod_convention",
    "state",
    "unit_kind",
    "holder_role",
    "placed",
    "COMPONENT",
    "COMPONENT_IMPL",
    "HARDWARE",
    "DEPLOYMENT",
]

#: the rules of the convention (declared here and in :mod:`.software` and :mod:`.platform`)
CONVENTION = Transformation("aadl2rosmod")

_t = CONVENTION

#: the roles of the classifiers whose members the walk visits
COMPONENT = "component"  # a thread group type of a software package: its features are ports
COMPONENT_IMPL = "component implementation"  # its implementation: threads are timers or callbacks
HARDWARE = "hardware"  # the system implementation of a hardware package
DEPLOYMENT = "deployment"  # the system implementation of a deployment package


def is_rosmod_convention(model: EObject) -> bool:
    """True when the model holds packages made by the ROSMOD → AADL conversion."""
    return any(
        _model.is_a(unit, "AadlPackage") and own_property(unit, fwd.UNIT_KIND) is not None
        for unit in model.units
    )


def _system_implementation(unit: EObject) -> EObject | None:
    return next(
        (
            c
            for c in unit.classifiers
            if _model.is_a(c, "ComponentImplementation") and enum_name(c.category) == "system"
        ),
        None,
    )


class ConventionState:
    """What the rules of one run share (``ctx.options['state']``): the plan of the model read
    once, the names, and the warnings."""

    def __init__(
        self, model: EObject, forward_trace: EObject | None, library: set[int], report: Report
    ) -> None:
        self.model = model
        self.report = report
        self.index = ClassifierIndex(model)
        self.trace = tracing.TraceIndex(forward_trace) if forward_trace is not None else None
        self.foreign: list[EObject] = []  # packages that are neither the project's nor the library's
        self.kind: dict[int, str] = {}  # unit → software, hardware, deployment, project, ...
        ranked: dict[str, list[tuple[int, int, EObject]]] = {}
        for position, unit in enumerate(u for u in model.units if _model.is_a(u, "AadlPackage")):
            kind = own_property(unit, fwd.UNIT_KIND)
            if kind is None:
                if id(unit) not in library:
                    self.foreign.append(unit)
                    self.kind[id(unit)] = "foreign"
                continue
            self.kind[id(unit)] = str(kind).lower()
            ranked.setdefault(str(kind).lower(), []).append(
                (integer(unit, fwd.POSITION) or 10**9, position, unit)
            )
        self.units = {k: [u for *_, u in sorted(v, key=lambda t: (t[0], t[1]))] for k, v in ranked.items()}
        self.roles: dict[int, str] = {}
        self.implementation: dict[int, EObject | None] = {}  # thread group type or unit → its implementation
        self.components: dict[str, EObject] = {}  # lower qualified impl/type name → thread group type
        self.component_of: dict[int, EObject] = {}  # thread group implementation → its type
        for unit in self.units.get("software", []):
            for ctype in self.thread_groups(unit):
                impl = self.index.implementation(ctype)
                self.implementation[id(ctype)] = impl
                self.roles[id(ctype)] = COMPONENT
                if impl is not None:
                    self.roles[id(impl)] = COMPONENT_IMPL
                    self.component_of[id(impl)] = ctype
                self.components[f"{unit.name}::{impl.name if impl is not None else ctype.name}".lower()] = (
                    ctype
                )
                self.components.setdefault(f"{unit.name}::{ctype.name}".lower(), ctype)
        self.hardware: dict[str, EObject] = {}  # lower 'unit::impl' → hardware package
        for kind, role in (("hardware", HARDWARE), ("deployment", DEPLOYMENT)):
            for unit in self.units.get(kind, []):
                impl = _system_implementation(unit)
                self.implementation[id(unit)] = impl
                if impl is not None:
                    self.roles[id(impl)] = role
                    if kind == "hardware":
                        self.hardware[f"{unit.name}::{impl.name}".lower()] = unit
        self.cache: dict[tuple[str, int], Any] = {}  # per-classifier indexes the rules build once
        self.placed: dict[int, tuple[str | None, str]] = {}  # member → (role of its holder, category)

    # -- the walk
    @staticmethod
    def thread_groups(unit: EObject) -> list[EObject]:
        return [
            c
            for c in unit.classifiers
            if _model.is_a(c, "ComponentType") and enum_name(c.category) == "threadGroup"
        ]

    def walk(self, model: EObject) -> Iterator[EObject]:
        """The elements the rules see, in the order of the module documentation."""
        yield from self.foreign
        yield model
        for unit in self.units.get("software", []):
            yield unit
            yield from (
                c
                for c in unit.classifiers
                if _model.is_a(c, "ComponentType") and enum_name(c.category) != "threadGroup"
            )
            for ctype in self.thread_groups(unit):
                yield from ctype.features
                yield ctype
                impl = self.implementation[id(ctype)]
                if impl is not None:
                    yield from impl.subcomponents
        for kind in ("hardware", "deployment"):
            for unit in self.units.get(kind, []):
                yield unit
                impl = self.implementation[id(unit)]
                if impl is not None:
                    yield from impl.subcomponents
                    if kind == "hardware":
                        yield from impl.connections

    # -- names
    def name(self, element: EObject, default: str | None = None, suffix: str = "") -> str | None:
        """The ROSMOD name of an element: its ``ROSMOD_Properties::Name``, else the name of the
        ROSMOD element the forward trace made it from, else its AADL name (less ``suffix``)."""
        given = text(element, fwd.NAME)
        if given is not None:
            return given
        if self.trace is not None and element.eContainer() is not None:
            origin = self._traced_name(element)
            if origin is not None:
                return origin
        name = default if default is not None else element.name
        if suffix and name and name.endswith(suffix) and len(name) > len(suffix):
            return name[: -len(suffix)]
        return name

    def _traced_name(self, element: EObject) -> str | None:
        keys = self.trace.origin_keys(tracing.element_key(element))
        if not keys:
            return None
        step = keys[0].rstrip("/").rpartition("/")[2]
        if "[" in step and step.endswith("]"):
            return step[step.index("[") + 1 : -1]
        return None

    def warn(self, message: str, element: EObject | None) -> None:
        self.report.warn(message, declared_location(element, declared_path(element)))

    def unit_of(self, classifier: EObject) -> EObject:
        return self.index.unit_of[id(classifier)]


def state(ctx: Context) -> ConventionState:
    return ctx.options["state"]


def unit_kind(ctx: Context, unit: EObject) -> str | None:
    """The rules' key on packages: the ``Unit_Kind`` of a package (``foreign``: none, and not the
    library's)."""
    return ctx.options["state"].kind.get(id(unit))


def holder_role(ctx: Context, member: EObject) -> str | None:
    """The rules' key on features and connections: the role of the classifier holding them."""
    return ctx.options["state"].roles.get(id(member.eContainer()))


def placed(ctx: Context, member: EObject) -> tuple[str | None, str]:
    """The rules' key on subcomponents and classifiers: (the role of what holds ``member``, its
    category); a package has no role. Read once per element."""
    st = ctx.options["state"]
    found = st.placed.get(id(member))
    if found is None:
        found = st.placed[id(member)] = (st.roles.get(id(member.eContainer())), enum_name(member.category))
    return found


# --------------------------------------------------------------------------- the project


@_t.rule("AadlPackage", name="foreign_package", where=(unit_kind, "foreign"))
def _foreign_package(ctx: Context, unit: EObject) -> None:
    state(ctx).warn(f"package {unit.name} is not part of a ROSMOD project (no Unit_Kind); skipped", unit)


@_t.rule("AadlModel", name="project")
def _project(ctx: Context, model: EObject) -> EObject:
    st = state(ctx)
    project_units = st.units.get("project", [])
    if len(project_units) > 1:
        st.warn(f"{len(project_units)} project packages; the first one is used", project_units[1])
    project = new("Project", name=model.name)
    software_units = st.units.get("software", [])
    if project_units:
        unit = project_units[0]
        project.name = st.name(unit, suffix=fwd.UNIT_SUFFIXES["Project"])
        project.formatVersion = text(unit, fwd.FORMAT_VERSION)
        project.path = text(unit, fwd.PROJECT_PATH)
        project.properties.extend(settings(unit))
        software_name = text(unit, fwd.SOFTWARE_NAME)
        if software_name is not None or software_units:
            project.software = new("Software", name=software_name, sourceFile=text(unit, fwd.SOURCE_FILE))
    elif software_units:
        project.software = new("Software", name=model.name)
    return project


@_project.bind
def _project_bind(ctx: Context, model: EObject, project: EObject) -> None:
    st = state(ctx)
    for kind, owner, feature in (
        ("software", project.software, "packages"),
        ("hardware", project, "systems"),
        ("deployment", project, "deployments"),
    ):
        units = st.units.get(kind, [])
        if units:
            add(owner, feature, ctx.resolve_all(units))


#: the categories of subcomponents each role maps (or skips without a word)
_KNOWN = {
    COMPONENT_IMPL: ("thread", "data"),
    HARDWARE: ("processor", "bus"),
    DEPLOYMENT: ("system", "process", "virtualBus"),
}


def _unmapped(ctx: Context, sub: EObject) -> bool:
    role, category = placed(ctx, sub)
    known = _KNOWN.get(role)
    return known is not None and category not in known


@_t.rule("Subcomponent", name="unmapped_subcomponent", when=_unmapped)
def _unmapped_subcomponent(ctx: Context, sub: EObject) -> None:
    owner = sub.eContainer()
    where = "in" if state(ctx).roles[id(owner)] == COMPONENT_IMPL else "of"
    state(ctx).warn(
        f"{enum_name(sub.category)} {sub.name} {where} {owner.name} has no ROSMOD counterpart; skipped", sub
    )
