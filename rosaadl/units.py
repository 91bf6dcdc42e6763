"""AADL units: quantities with units and conversion between the literals of one units type.

The standard units types of AADL_Project (SAE AS5506C, appendix A) and the SEI set are known
here as facts, so that values convert even before any property set is read. A
:class:`UnitSystem` can be extended with the ``UnitsType`` elements of property sets a model
actually uses (:meth:`UnitSystem.add_units_type`).
"""

from __future__ import annotations

import numbers
from collections.abc import Iterable
from dataclasses import dataclass
from fractions import Fraction

from rosaadl.arguments import describe
from rosaadl.errors import ModelError, UsageError

__all__ = ["Quantity", "UnitSystem", "STANDARD_UNITS", "standard_units"]

# name -> [(literal, base literal or None, factor)] in the order of OSATE's current AADL_Project
# (the standard's literals, with kbps/Mbps/Gbps and KiByte..TiByte as OSATE added them).
STANDARD_UNITS: dict[str, list[tuple[str, str | None, int | Fraction]]] = {
    "Time_Units": [
        ("ps", None, 1),
        ("ns", "ps", 1000),
        ("us", "ns", 1000),
        ("ms", "us", 1000),
        ("sec", "ms", 1000),
        ("min", "sec", 60),
        ("hr", "min", 60),
    ],
    "Size_Units": [
        ("bits", None, 1),
        ("Bytes", "bits", 8),
        ("KByte", "Bytes", 1000),
        ("MByte", "KByte", 1000),
        ("GByte", "MByte", 1000),
        ("TByte", "GByte", 1000),
        ("KiByte", "Bytes", 1024),
        ("MiByte", "KiByte", 1024),
        ("GiByte", "MiByte", 1024),
        ("TiByte", "GiByte", 1024),
    ],
    "Data_Rate_Units": [
        ("bitsps", None, 1),
        ("kbps", "bitsps", 1000),
        ("Mbps", "kbps", 1000),
        ("Gbps", "Mbps", 1000),
        ("Bytesps", "bitsps", 8),
        ("KBytesps", "Bytesps", 1000),
        ("MBytesps", "KBytesps", 1000),
        ("GBytesps", "MBytesps", 1000),
    ],
    "Processor_Speed_Units": [
        ("KIPS", None, 1),
        ("MIPS", "KIPS", 1000),
        ("GIPS", "MIPS", 1000),
    ],
    "Frequency": [
        ("Hz", None, 1),
        ("KHz", "Hz", 1000),
        ("MHz", "KHz", 1000),
        ("GHz", "MHz", 1000),
    ],
    "Power_Units": [
        ("mW", None, 1),
        ("W", "mW", 1000),
        ("KW", "W", 1000),
    ],
}


class UnitSystem:
    """Units types and their literals; converts values between literals of the same type."""

    def __init__(self) -> None:
        self._type_of: dict[str, str] = {}  # lower-case literal -> units type name
        self._scale: dict[str, Fraction] = {}  # lower-case literal -> factor to the type's base
        self._spelling: dict[str, str] = {}  # lower-case literal -> declared spelling
        self._types: dict[str, list[str]] = {}

    def add_type(
        self, type_name: str, literals: Iterable[tuple[str, str | None, int | Fraction | float]]
    ) -> None:
        names: list[str] = []
        for literal, base, factor in literals:
            key = literal.lower()
            if base is None:
                scale = Fraction(1)
            else:
                base_key = base.lower()
                if base_key not in self._scale:
                    raise ModelError(f"units type {type_name}: {literal} refers to unknown unit {base}")
                scale = self._scale[base_key] * Fraction(factor)
            self._type_of[key] = type_name
            self._scale[key] = scale
            self._spelling[key] = literal
            names.append(literal)
        self._types[type_name] = names

    def add_units_type(self, units_type) -> None:
        """Add a ``UnitsType`` model element (from a property set)."""
        from rosaadl.properties import python_value

        literals = []
        for lit in units_type.ownedLiterals:
            factor = python_value(lit.factor) if lit.factor is not None else 1
            if hasattr(factor, "value"):
                factor = factor.value
            literals.append(
                (lit.name, lit.baseUnit or None, Fraction(str(factor)) if factor is not None else 1)
            )
        self.add_type(units_type.name, literals)

    def knows(self, unit: str) -> bool:
        return unit.lower() in self._type_of

    def type_of(self, unit: str) -> str:
        try:
            return self._type_of[unit.lower()]
        except KeyError:
            raise ModelError(f"unknown unit {unit!r}") from None

    def literals(self, type_name: str) -> list[str]:
        return list(self._types.get(type_name, []))

    def spelling(self, unit: str) -> str:
        return self._spelling.get(unit.lower(), unit)

    def factor(self, unit: str, to: str) -> Fraction:
        a, b = unit.lower(), to.lower()
        if a not in self._scale:
            raise ModelError(f"unknown unit {unit!r}")
        if b not in self._scale:
            raise ModelError(f"unknown unit {to!r}")
        if self._type_of[a] != self._type_of[b]:
            raise ModelError(f"cannot convert {unit} ({self._type_of[a]}) to {to} ({self._type_of[b]})")
        return self._scale[a] / self._scale[b]

    def convert(self, value: float | int | Fraction, unit: str, to: str) -> float | int | Fraction:
        factor = self.factor(unit, to)
        if isinstance(value, Fraction):
            return value * factor
        result = Fraction(value) * factor if isinstance(value, int) else value * float(factor)
        if isinstance(result, Fraction):
            return int(result) if result.denominator == 1 else float(result)
        return result


def standard_units() -> UnitSystem:
    """A fresh unit system with the standard AADL and SEI units types."""
    system = UnitSystem()
    for name, literals in STANDARD_UNITS.items():
        system.add_type(name, literals)
    return system


_STANDARD = standard_units()


@dataclass(frozen=True)
class Quantity:
    """A number with an AADL unit literal (``Quantity(33333, "us")``); unit may be None."""

    value: float | int
    unit: str | None = None

    def to(self, unit: str, system: UnitSystem | None = None) -> float | int:
        """The value in ``unit`` (same units type), exactly for integers where possible."""
        if self.unit is None:
            raise ModelError(f"{self.value} has no unit; cannot convert to {unit}")
        if not isinstance(unit, str):
            raise UsageError(f"Quantity.to(): unit must be str, not {describe(unit)}")
        try:
            return (system or _STANDARD).convert(self.value, self.unit, unit)
        except (TypeError, AttributeError):
            if isinstance(self.value, numbers.Real) and isinstance(self.unit, str):
                raise
            raise ModelError(f"{self!r} is not a number with a unit literal; cannot convert it") from None

    def __str__(self) -> str:
        return f"{self.value} {self.unit}" if self.unit else str(self.value)
