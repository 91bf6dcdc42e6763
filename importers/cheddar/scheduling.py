"""Schedulers of processors, cores and address spaces, as each file style writes them.

Cheddar 3 holds ``<scheduling><scheduling_parameters>`` in a core unit or an address space;
files written by the Cheddar exporters of OSATE plug-ins put the same fields (``scheduler_type``,
``quantum``, ``preemptive_type``, ...) directly under ``<scheduling>``, and Cheddar reads both
alike (see :func:`scheduling_parameters`). Cheddar 2 has a ``<scheduler>`` element whose text is
the scheduler and whose attributes are its parameters. A processor's (or core's) scheduler
goes to ``Deployment_Properties::Scheduling_Protocol`` when AADL has a literal for it, otherwise
(and always for an address space) to ``Cheddar_Properties::Scheduler``; preemption to
``Preemptive_Scheduler`` (processors) or ``Cheddar_Properties::Preemptive`` (address spaces).
"""

from __future__ import annotations

from lxml import etree
from pyecore.ecore import EObject

from rosaadl.importers.cheddar.document import children, local
from rosaadl.importers.cheddar.state import ReadState
from rosaadl.importers.cheddar.values import associate, list_value, named_value
from rosaadl.importers.cheddar.vocabulary import (
    CP,
    PREEMPTIVE_SCHEDULER,
    SCHEDULER_TO_AADL,
    SCHEDULING,
    SCHEDULING_FIELDS,
)

__all__ = ["scheduling_parameters", "scheduler_element"]


def scheduling_parameters(
    state: ReadState, owner: EObject, element: etree._Element, *, processor: bool
) -> None:
    """``<scheduling>`` of a core unit or an address space, in either Cheddar 3 style.

    Cheddar's own writer wraps the fields in ``<scheduling_parameters>``; the OSATE plug-ins'
    Cheddar exporters write them directly under ``<scheduling>``. Cheddar 3's reader
    (``xml_generic_parsers.architecture``, a SAX handler) takes no notice of either container:
    it collects ``scheduler_type``, ``quantum``, ``preemptive_type``, ... by their tag into one
    scheduling record and hands that record to the core unit or address space whose element
    closes. Both styles therefore give the same model; a ``<scheduling>`` that holds the
    wrapper *and* fields beside it is ambiguous and refused.
    """
    present_outer = state.index_children(element)
    params = present_outer.get("scheduling_parameters")
    if params is None:
        params = element  # the fields directly under <scheduling>
    elif len(present_outer) != 1:
        beside = next(c for c in children(element) if local(c) != "scheduling_parameters")
        state.fail(
            beside,
            f"<{local(beside)}> is beside <scheduling_parameters> in <scheduling>; "
            "expected the scheduling fields in one of them",
        )
    present = state.index_children(params)
    consumed = {"scheduler_type", "preemptive_type"}
    kind = present.get("scheduler_type")
    if kind is not None:
        _scheduler(owner, state.literal(kind, "scheduler"), processor)
    preemptive = present.get("preemptive_type")
    if preemptive is not None:
        _preemptive(owner, state.value(preemptive, "preemptive"), processor)
    state.fields(owner, params, SCHEDULING_FIELDS, present, consumed)
    state.leftovers(owner, params, "scheduling_parameters", present, consumed)


def scheduler_element(state: ReadState, owner: EObject, element: etree._Element, *, processor: bool) -> None:
    """``<scheduler is_preemptive=... quantum=...>LITERAL</scheduler>`` of a processor or an
    address space."""
    _scheduler(owner, state.literal(element, "scheduler"), processor)
    attributes = {k.lower(): v for k, v in element.attrib.items()}
    if "is_preemptive" in attributes:
        _preemptive(owner, state.value(element, "preemptive", attributes["is_preemptive"].strip()), processor)
    for attribute, prop, kind in (
        ("quantum", "Scheduler_Quantum", "time"),
        ("parametric_file_name", "User_Defined_Scheduler_File", "str"),
        ("automaton_name", "Automaton_Name", "str"),
    ):
        if attribute in attributes:
            associate(owner, CP + prop, state.value(element, kind, attributes[attribute].strip()))
    unknown = set(attributes) - {"is_preemptive", "quantum", "parametric_file_name", "automaton_name"}
    if unknown:
        state.lenient(element, f"<scheduler> attribute {sorted(unknown)[0]!r} is not known; ignored")


def _scheduler(owner: EObject, literal: str, processor: bool) -> None:
    if processor and literal in SCHEDULER_TO_AADL:
        associate(owner, SCHEDULING, list_value([named_value(SCHEDULER_TO_AADL[literal])]))
    else:
        associate(owner, CP + "Scheduler", named_value(literal))


def _preemptive(owner: EObject, value: EObject, processor: bool) -> None:
    associate(owner, PREEMPTIVE_SCHEDULER if processor else CP + "Preemptive", value)
