"""The ROSMOD → AADL transformation and what its rules share.

:data:`TRANSFORMATION` is a :class:`~rosaadl.transforms.engine.Transformation`; the rules are
declared on it by the modules of one ROSMOD part each (:mod:`.project_unit`, :mod:`.software`,
:mod:`.hardware`, :mod:`.deployment`). One run's :class:`State` (the project, the naming plan,
the factory and the units made so far) is passed as the run option ``state``: there is no global
state. The helpers here write what several rules write: a unit's header, a ROSMOD name that
changed, a time.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from pyecore.ecore import EObject

from rosaadl.importers import ros_msg
from rosaadl.transforms.engine import Context, Transformation
from rosaadl.transforms.rosmod_to_aadl.factory import AadlFactory
from rosaadl.transforms.rosmod_to_aadl.plan import NamingPlan
from rosaadl.transforms.rosmod_to_aadl.values import plain_seconds, seconds_to_time
from rosaadl.transforms.rosmod_to_aadl.vocabulary import NAME, POSITION, UNIT_KIND, UNIT_SUFFIXES

__all__ = ["TRANSFORMATION", "State", "name_if_changed", "set_time", "state", "unit_header"]


@dataclass
class State:
    """What the rules of one run share (kept in ``ctx.options['state']``: no global state)."""

    project: EObject
    plan: NamingPlan
    factory: AadlFactory
    units: dict[int, EObject] = field(default_factory=dict)  # position → unit
    sizes: dict[str, list[ros_msg.FieldSpec]] = field(default_factory=dict)


#: The rules, declared by the modules of each ROSMOD part.
TRANSFORMATION = Transformation("rosmod2aadl")


def state(ctx: Context) -> State:
    """The state of the run a rule is part of."""
    return ctx.options["state"]


def name_if_changed(f: AadlFactory, holder: EObject, aadl_name: str, rosmod_name: str | None) -> None:
    """``ROSMOD_Properties::Name`` on ``holder`` when its AADL name is not the ROSMOD name."""
    if rosmod_name is not None and aadl_name != rosmod_name:
        f.pa(holder, NAME, f.string(rosmod_name))


def unit_header(st: State, src: EObject, kind: str) -> EObject:
    """The package of a project, software package, hardware model or deployment, with its
    ``Unit_Kind``, its position among the units and its ROSMOD name when that changed."""
    f = st.factory
    name = st.plan.units[id(src)]
    pkg = f.package(name)
    f.pa(pkg, UNIT_KIND, f.named(kind))
    f.pa(pkg, POSITION, f.integer(st.plan.positions[id(src)]))
    suffix = UNIT_SUFFIXES.get(kind, "")
    if src.name is not None and name != f"{src.name}{suffix}":
        f.pa(pkg, NAME, f.string(src.name))
    st.units[st.plan.positions[id(src)]] = pkg
    return pkg


def set_time(
    ctx: Context, f: AadlFactory, holder: EObject, prop: str, text_prop: str, seconds: Any, src: EObject
) -> None:
    """``prop`` (an AADL time) for ROSMOD seconds, and ``text_prop`` when the seconds are not
    written plainly (``0.500``), so that the conversion back gives the same text."""
    if seconds is None:
        return
    value, unit, exact = seconds_to_time(seconds)
    if not exact:
        ctx.warn(f"{prop} = {seconds} s is not a whole number of picoseconds; rounded to {value} ps", src)
    f.pa(holder, prop, f.integer(value, unit))
    if exact and str(seconds) != str(plain_seconds(seconds)):
        f.pa(holder, text_prop, f.string(str(seconds)))
