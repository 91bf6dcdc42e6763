"""Text as EMF's XMI writer puts it in an ASCII ``.aaxl2`` document, and reading values to write.

:func:`java_double` spells a real as Java's ``Double.toString``; :func:`attr_text` escapes an
attribute value as EMF does in an ``encoding="ASCII"`` document (every other character as a
character reference); :func:`java_literal` gives an enumeration's Java literal (``in out``).
:func:`value_of` and :func:`items_of` read a feature of an object through its value holder: the
writer's hot loops read many features that were never set, and pyecore's descriptor would make
an empty holder for each (a fast path the façade does not offer).
"""

from __future__ import annotations

import math
import re
from decimal import Decimal
from typing import Any

from pyecore.ecore import EObject
from pyecore.valuecontainer import EValue

__all__ = [
    "java_double",
    "attr_text",
    "InvalidText",
    "INVALID_XML",
    "literal_name",
    "java_literal",
    "value_of",
    "items_of",
]


def java_double(value: float) -> str:
    """``Double.toString`` as Java writes it: ``100.0``, ``0.5``, ``1.0E7``, ``1.5E-4``."""
    if math.isnan(value):
        return "NaN"
    if math.isinf(value):
        return "Infinity" if value > 0 else "-Infinity"
    if value == 0:
        return "-0.0" if math.copysign(1.0, value) < 0 else "0.0"
    sign, digits, exponent = Decimal(repr(float(value))).as_tuple()
    text = "".join(str(d) for d in digits).rstrip("0") or "0"
    point = len(digits) + int(exponent)  # digits before the decimal point
    prefix = "-" if sign else ""
    if 1e-3 <= abs(value) < 1e7:
        if point <= 0:
            return f"{prefix}0.{'0' * -point}{text}"
        whole = text[:point].ljust(point, "0")
        fraction = text[point:] or "0"
        return f"{prefix}{whole}.{fraction}"
    return f"{prefix}{text[0]}.{text[1:] or '0'}E{point - 1}"


_ESCAPES = {"&": "&amp;", "<": "&lt;", '"': "&quot;", "\n": "&#xA;", "\r": "&#xD;", "\t": "&#x9;"}
_NEEDS_ESCAPE = re.compile(r'[&<"\n\r\t]|[^\x20-\x7e]')
INVALID_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")


def _char_ref(match: re.Match[str]) -> str:
    char = match.group(0)
    return _ESCAPES.get(char) or f"&#x{ord(char):X};"


class InvalidText(Exception):
    """A string holds a character that XML 1.0 cannot carry, even as a reference."""


def attr_text(text: str) -> str:
    """An attribute value as EMF writes it in an ASCII document."""
    if _NEEDS_ESCAPE.search(text) is None:
        return text
    if INVALID_XML.search(text) is not None:
        raise InvalidText(text)
    return _NEEDS_ESCAPE.sub(_char_ref, text)


def literal_name(value: Any) -> str:
    """The name of an enumeration literal or a named object (its text for anything else)."""
    return str(getattr(value, "name", value) or "")


def java_literal(value: Any) -> str:
    """An enumeration literal as Java spells it (``in out``), else its name."""
    return str(getattr(value, "literal", None) or getattr(value, "name", None) or value or "")


def value_of(obj: EObject, name: str) -> Any:
    """A feature's value without pyecore's descriptor (which also creates an empty holder for a
    feature never set); None when unset. Many-valued features give their collection."""
    held = obj.__dict__.get(name)  # rosaadl.bulk.stored_value, inline: the exporter's hottest read
    if held is None:
        return None
    return held._value if isinstance(held, EValue) else held  # a plain value, or a collection


def items_of(obj: EObject, name: str) -> Any:
    """The items of a many-valued feature (an empty tuple when it was never touched)."""
    holder = obj.__dict__.get(name)
    return holder if holder is not None else ()
