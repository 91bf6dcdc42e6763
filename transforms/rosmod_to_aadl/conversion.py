"""The entry point of ROSMOD → AADL: :func:`rosmod_to_aadl` runs the rules on a project and
gives the generated packages, each with its ``with`` clause, the root of each deployment and
the trace.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.arguments import checked
from rosaadl.bulk import gc_paused
from rosaadl.errors import RosaadlError, TransformationError
from rosaadl.transforms import trace as tracing
from rosaadl.transforms.rosmod_to_aadl import deployment, hardware, project_unit, software
from rosaadl.transforms.rosmod_to_aadl.factory import AadlFactory
from rosaadl.transforms.rosmod_to_aadl.interfaces import interface_units
from rosaadl.transforms.rosmod_to_aadl.plan import NamingPlan
from rosaadl.transforms.rosmod_to_aadl.rules import TRANSFORMATION, State

__all__ = ["ConversionResult", "RULE_MODULES", "rosmod_to_aadl"]

#: The modules that declare the rules of :data:`~.rules.TRANSFORMATION`, one part of a project each.
RULE_MODULES = (project_unit, software, hardware, deployment)


@dataclass
class ConversionResult:
    """The AADL model made from a ROSMOD project."""

    model: EObject  #: ``AadlModel`` holding the generated packages (not the library)
    roots: dict[str, str]  #: deployment name → root implementation (``Pkg::System.impl``)
    trace: EObject | None  #: the ``trace.Trace`` (ROSMOD element keys → AADL element keys)
    warnings: list[RosaadlError] = field(default_factory=list)

    @property
    def units(self) -> list[EObject]:
        return list(self.model.units)


_PREDECLARED = frozenset(
    {
        "timing_properties",
        "thread_properties",
        "memory_properties",
        "deployment_properties",
        "communication_properties",
        "programming_properties",
        "modeling_properties",
        "aadl_project",
    }
)


def _withs(unit: EObject) -> list[str]:
    """The packages and property sets a generated unit refers to (its ``with`` clause)."""
    names: set[str] = set()

    def qualifier(text: str | None) -> None:
        if text and "::" in text:
            names.add(text.rpartition("::")[0])

    def associations(holder: EObject) -> None:
        for assoc in holder.ownedPropertyAssociations:
            qualifier(assoc.property)

    associations(unit)
    for classifier in unit.classifiers:
        qualifier(classifier.extended)
        associations(classifier)
        for member_list in ("features", "subcomponents", "connections"):
            feature = classifier.eClass.findEStructuralFeature(member_list)
            if feature is None:
                continue
            for member in classifier.eGet(feature):
                if member_list != "connections":
                    qualifier(member.classifier)
                associations(member)
    names.discard(unit.name)
    return sorted((n for n in names if n.lower() not in _PREDECLARED), key=str.lower)


@checked
def rosmod_to_aadl(
    project: EObject, *, trace: bool = True, reserved_units: Iterable[str] = ()
) -> ConversionResult:
    """Convert a ``rosmod.Project`` into AADL packages (see :mod:`rosaadl.transforms.rosmod_to_aadl`).

    No generated package takes a name of ``reserved_units`` (compared case-insensitively): give
    the names of the units the packages will be read with, such as the library's
    (:func:`rosaadl.workflow.workspace.library_unit_names`), since a unit named like one of them
    would replace it.

    Raises a located :class:`~rosaadl.errors.TransformationError` (rule, element, file and line)
    for what cannot be converted: a component instance whose component is not in the project, a
    node on a host that does not resolve, a port of an unknown type of a project package, a
    link that does not join a host's interface to a network. Warnings (a time rounded to
    picoseconds, a client with several servers) are in ``warnings``.
    """
    if not model.is_a(project, "rosmod.Project"):
        raise TransformationError("expected a rosmod Project to convert")
    with gc_paused():
        plan = NamingPlan(project, reserved_units)
        state = State(project=project, plan=plan, factory=AadlFactory())
        result = TRANSFORMATION.run(project, state=state)
        interface_units(state)
        f = state.factory
        aadl = f.fb.make("AadlModel", name=plan.units[id(project)])
        units = [state.units[k] for k in sorted(state.units)]
        for unit in units:
            f.add(unit, "withs", *_withs(unit))
        f.add(aadl, "units", *units)
        roots = {
            dep.name: f"{plan.units[id(dep)]}::{plan.extra[(id(dep), 'type')]}.impl"
            for dep in project.deployments
        }
        if trace:
            tracing.key_targets(result.trace)
    return ConversionResult(
        model=aadl, roots=roots, trace=result.trace if trace else None, warnings=list(result.warnings)
    )
