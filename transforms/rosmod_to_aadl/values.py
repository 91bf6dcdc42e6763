"""ROSMOD values as AADL values: times in seconds ↔ integer AADL times, and values that are set.

ROSMOD gives periods and deadlines in seconds (``0.0333333``); AADL times are integers with a
unit. :func:`seconds_to_time` gives the exact integer time in ``ms`` when there is one, else in
``us``, ``ns``, ``ps``; :func:`time_to_seconds` goes back, exactly. :func:`given` tells a ROSMOD
value that is not set from one set to 0.
"""

from __future__ import annotations

from decimal import ROUND_HALF_EVEN, Decimal, InvalidOperation
from typing import Any

from pyecore.ecore import EObject

from rosaadl.errors import TransformationError

__all__ = ["given", "plain_seconds", "seconds_to_time", "time_to_seconds"]


def given(obj: EObject, feature: str) -> Any:
    """The value of a feature that is set, else None (pyecore answers 0, False or ``Decimal(0)``
    for an unset number or boolean: a ROSMOD priority or deadline that is not given)."""
    return obj.eGet(feature) if obj.eIsSet(feature) else None


_TIME_SCALES = (
    ("ms", Decimal(10) ** 3),
    ("us", Decimal(10) ** 6),
    ("ns", Decimal(10) ** 9),
    ("ps", Decimal(10) ** 12),
)
_UNIT_SECONDS = {
    "ps": Decimal("1e-12"),
    "ns": Decimal("1e-9"),
    "us": Decimal("1e-6"),
    "ms": Decimal("0.001"),
    "sec": Decimal(1),
    "min": Decimal(60),
    "hr": Decimal(3600),
}


def seconds_to_time(seconds: Decimal | int | str) -> tuple[int, str, bool]:
    """``(value, unit, exact)``: the seconds as an integer AADL time in ``ms`` when that is
    exact, else ``us``, ``ns``, ``ps``; ``exact`` is False when even ``ps`` had to be rounded.
    Anything but a finite number, or a time no AADL integer (64 bits) holds, is a
    :class:`~rosaadl.errors.TransformationError`."""
    value = _decimal(seconds)
    if value.adjusted() > 18:  # more than 10**19 s: checked before scaling (a huge exponent)
        raise TransformationError(f"{seconds} s is too long for an AADL time (a 64-bit integer)")
    scaled = value
    for unit, scale in _TIME_SCALES:
        scaled = value * scale
        if scaled == scaled.to_integral_value():
            return _integer(scaled, unit, seconds), unit, True
    return _integer(scaled.to_integral_value(ROUND_HALF_EVEN), "ps", seconds), "ps", False


#: The largest AADL integer (AADL integers are 64-bit: the AADL reader refuses larger ones).
_MAX_INTEGER = 2**63 - 1


def _integer(scaled: Decimal, unit: str, seconds: object) -> int:
    if abs(scaled) > _MAX_INTEGER:
        raise TransformationError(f"{seconds} s in {unit} is too large for an AADL integer (64 bits)")
    return int(scaled)


def plain_seconds(value: Decimal | int | str) -> Decimal:
    """The plain decimal of a number of seconds: no exponent, no trailing zeros (``0.500`` →
    ``0.5``, ``10`` stays ``10``); what :func:`time_to_seconds` gives."""
    return Decimal(format(_decimal(value).normalize(), "f"))


def _decimal(seconds: Decimal | int | str) -> Decimal:
    try:
        value = Decimal(seconds)
    except (InvalidOperation, TypeError, ValueError):
        value = None
    if value is None or not value.is_finite():
        raise TransformationError(f"not a number of seconds: {seconds!r}")
    return value


def time_to_seconds(value: int | float, unit: str | None) -> Decimal | None:
    """Seconds of an AADL time, exact and plain (:func:`plain_seconds`); None for a unit that is
    not a time unit."""
    factor = _UNIT_SECONDS.get((unit or "").strip().lower() if unit else "")
    if factor is None:
        return None
    try:
        number = Decimal(value) if isinstance(value, int) else Decimal(repr(float(value)))
    except (InvalidOperation, ValueError):
        return None
    return plain_seconds(number * factor)
