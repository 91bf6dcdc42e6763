"""Declarative AADL (``aadl.ecore``) → ROSMOD projects (``rosmod.ecore``), with a trace.

:func:`aadl_to_rosmod` applies one of two rule sets of the rule engine
(:mod:`rosaadl.transforms.engine`):

* **the convention** (:mod:`.convention`, :mod:`.software`, :mod:`.platform`) — for packages
  made by :func:`rosaadl.transforms.rosmod_to_aadl.rosmod_to_aadl` (marked
  ``ROSMOD_Properties::Unit_Kind``), the inverse mapping, read from the declarative model:
  software packages give packages, messages, services and components (ports from the thread
  group's features, timers from its periodic threads, callback priorities and deadlines from
  the threads connected to its ports); hardware packages give hardware models (processors →
  hosts, buses → networks, bus access connections → links); deployment packages give
  deployments (processes → nodes bound to their hosts by ``Actual_Processor_Binding``, thread
  group subcomponents → component instances); the project package gives the project's own
  data. The ROSMOD name of every element is its ``ROSMOD_Properties::Name``, else the name the
  forward conversion's trace gives for it (``trace=``), else its AADL name; so a project
  converted forward and back is the original one (``docs/rosmod-aadl-mapping.md``).
* **best effort** (:mod:`.best_effort`) — for other AADL models: each root system
  implementation (``roots=``, by default the top-level ones of packages that are not part of
  rosaadl's library) is instantiated; each process becomes a node (on the host of the
  processor it is bound to), each thread a component instance of a component made from the
  thread's classifier, with a timer when the thread is periodic and publishers, subscribers,
  clients and servers from its ports (message types from ``ROS_Properties::Message_Type``,
  else an empty message named after the data classifier); processors become hosts. Each
  element that has no ROSMOD counterpart (devices, buses, memories, abstract components, ports
  without a direction ROSMOD knows, threads that neither run periodically nor on an input,
  connections that ROSMOD's matching by message type would not make) is reported as a located
  warning.

:func:`aadl_to_rosmod_traced` also gives the trace of the run (AADL element keys → ROSMOD
element keys; in a best-effort run the sources are the instance objects, keyed under the
model's ``instances``), so that AADL → ROSMOD → AADL keeps names too. Neither reads a file: the
caller names the units of rosaadl's component library in the model (``library=``; the workflow's
:func:`rosaadl.workflow.convert.library_units`), which are neither converted nor warned about.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.arguments import checked
from rosaadl.bulk import gc_paused
from rosaadl.errors import Diagnostic, TransformationError
from rosaadl.transforms import trace as tracing

from . import platform, software  # noqa: F401  (they declare the convention's rules)
from .best_effort import BEST_EFFORT, BestEffortState, top_level_systems
from .convention import CONVENTION, ConventionState, is_rosmod_convention
from .reading import Report

__all__ = [
    "aadl_to_rosmod",
    "aadl_to_rosmod_traced",
    "RosmodConversion",
    "top_level_systems",
    "is_rosmod_convention",
    "CONVENTION",
    "BEST_EFFORT",
]


@dataclass
class RosmodConversion:
    """The ROSMOD project made from an AADL model."""

    project: EObject  #: the ``rosmod.Project``
    trace: EObject | None  #: the ``trace.Trace`` (AADL element keys → ROSMOD element keys)
    warnings: list[Diagnostic] = field(default_factory=list)  #: what could not be mapped, located


@checked
def aadl_to_rosmod(
    model: EObject,
    *,
    trace: EObject | None = None,
    roots: Sequence[str] | None = None,
    library: Iterable[EObject] = (),
    warnings: list[Diagnostic] | None = None,
) -> EObject:
    """A ``rosmod.Project`` from an ``AadlModel`` (see the module documentation).

    ``trace`` is the trace of the forward conversion (a ``trace.Trace``): names that the AADL
    model no longer carries come from it. ``roots`` are the root system implementations of a
    best-effort conversion. ``library`` are the units of rosaadl's component library in
    ``model``. Warnings — one per element that could not be mapped, located by file and line
    or instance path — are logged and appended to ``warnings``.
    """
    result = _convert(model, trace, roots, library, warnings, record=False)
    return result.project


@checked
def aadl_to_rosmod_traced(
    model: EObject,
    *,
    trace: EObject | None = None,
    roots: Sequence[str] | None = None,
    library: Iterable[EObject] = (),
) -> RosmodConversion:
    """:func:`aadl_to_rosmod`, with the trace of the run and the warnings in the result."""
    warnings: list[Diagnostic] = []
    return _convert(model, trace, roots, library, warnings, record=True)


def _convert(
    model: EObject,
    forward_trace: EObject | None,
    roots: Sequence[str] | None,
    library: Iterable[EObject],
    warnings: list[Diagnostic] | None,
    *,
    record: bool,
) -> RosmodConversion:
    if not _model.is_a(model, "AadlModel"):
        raise TransformationError("expected an AADL model (AadlModel) to convert to ROSMOD")
    if forward_trace is not None and not _model.is_a(forward_trace, "trace.Trace"):
        raise TransformationError("expected the trace of the ROSMOD → AADL conversion (a trace.Trace)")
    report = Report(warnings)
    library = list(library)
    with gc_paused():
        if is_rosmod_convention(model):
            st = ConventionState(model, forward_trace, {id(u) for u in library}, report)
            result = CONVENTION.run(model, walk=st.walk, trace=record, state=st)
        else:
            chosen = list(roots) if roots is not None else top_level_systems(model, library=library)
            st = BestEffortState(model, chosen, report)
            result = BEST_EFFORT.run(model, walk=st.walk, trace=record, state=st)
    (project,) = result.context.resolve(model, "project")
    if result.trace is not None:
        tracing.key_targets(result.trace)
    return RosmodConversion(project=project, trace=result.trace, warnings=warnings or [])
