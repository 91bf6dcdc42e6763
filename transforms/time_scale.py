"""A system instance with its periods scaled: the model of a run whose rates were slowed down.

``rosaadl run --period-scale F`` multiplies every period of the generated nodes by ``F`` (their
timers, so every publish and event rate follows) and leaves the execution times as they are:
the application does the same work ``F`` times less often. :func:`scale_periods` makes the
instance that run is the deployment of: every ``Period``, ``Deadline`` and ``Dispatch_Offset``
(where in its period a generated timer releases) held by a component instance (thread, process,
device, ...) multiplied by ``F``, in every mode; the execution times
(``Compute_Execution_Time``), sizes, bandwidth capacities and connection latencies are kept.
Scaling periods and deadlines alike keeps every deadline relative to its period (an implicit
deadline stays implicit, deadline-monotonic priorities keep their order), so the scaled model is
the original one on a processor ``F`` times faster; its CPU loads are the original's divided by
``F`` and its response times and chain latencies are those of the scaled timing.

A scaled value is written in nanoseconds (``33333 us`` × 1.9 → ``63332700 ns``), rounded to the
nearest nanosecond: AADL times are integers.
"""

from __future__ import annotations

from fractions import Fraction

from pyecore.ecore import EObject

from rosaadl.errors import ModelError
from rosaadl.model import component_instances
from rosaadl.properties import property_name_matches
from rosaadl.units import standard_units

__all__ = ["SCALED_PROPERTIES", "scale_periods", "period_scale_factor"]

#: The timing properties a period scale multiplies.
SCALED_PROPERTIES = ("Period", "Deadline", "Dispatch_Offset")


def period_scale_factor(value: float | int | str | Fraction) -> Fraction:
    """``value`` as an exact positive factor (``1.9`` → 19/10); a :class:`ModelError` otherwise."""
    try:
        factor = Fraction(str(value)) if not isinstance(value, Fraction) else value
    except (ValueError, ZeroDivisionError):
        raise ModelError(f"a period scale is a positive number, not {value!r}") from None
    if factor <= 0:
        raise ModelError(f"a period scale is a positive number, not {value!r}")
    return factor


def _scaled(value: EObject, factor: Fraction) -> bool:
    """Multiply one time value (``IntegerValue``/``RealValue`` with a unit) in place."""
    kind = value.eClass.name
    if kind not in ("IntegerValue", "RealValue") or not value.unit or value.value is None:
        return False
    units = standard_units()
    if not units.knows(value.unit):
        return False
    nanoseconds = Fraction(value.value) * units.factor(value.unit, "ns") * factor
    value.value = round(nanoseconds) if kind == "IntegerValue" else float(nanoseconds)
    value.unit = "ns"
    return True


def scale_periods(root: EObject, factor: float | int | str | Fraction) -> int:
    """Multiply every ``Period``, ``Deadline`` and ``Dispatch_Offset`` below the system instance ``root`` by
    ``factor``, in place (see the module docstring); the number of values scaled. A factor of 1
    changes nothing."""
    factor = period_scale_factor(factor)
    if factor == 1:
        return 0
    count = 0
    for component in component_instances(root):
        for association in component.ownedPropertyAssociations:
            if not any(property_name_matches(association.property or "", name) for name in SCALED_PROPERTIES):
                continue
            for modal in association.ownedValues:
                if modal.value is not None and _scaled(modal.value, factor):
                    count += 1
    return count
