"""Reading JSON text within bounds: every failure of the input is a :class:`JsonLimitError`.

Python's :func:`json.loads` raises a bare ``ValueError`` for an integer literal longer than
the interpreter's conversion limit (4 300 digits) and ``RecursionError`` for deep nesting;
readers of user files call :func:`loads_bounded` and turn :class:`JsonLimitError` (and
:class:`json.JSONDecodeError`) into their own located errors.
"""

from __future__ import annotations

import json
from typing import Any

__all__ = ["JSON_INT_DIGITS", "JsonLimitError", "loads_bounded"]

#: The longest integer literal accepted (Python's own default conversion limit).
JSON_INT_DIGITS = 4300


class JsonLimitError(ValueError):
    """The JSON text is well formed but beyond what a reader accepts."""


def _bounded_int(text: str) -> int:
    digits = len(text.lstrip("-"))
    if digits > JSON_INT_DIGITS:
        raise JsonLimitError(f"an integer of {digits} digits (at most {JSON_INT_DIGITS})")
    return int(text)


def _refused_constant(name: str) -> float:
    raise JsonLimitError(f"{name} is not a JSON number")


def loads_bounded(text: str, *, allow_nan: bool = True) -> Any:
    """``json.loads(text)`` with long integers, deep nesting and (unless ``allow_nan``) the
    non-standard ``NaN``/``Infinity`` refused as :class:`JsonLimitError`."""
    extra = {} if allow_nan else {"parse_constant": _refused_constant}
    try:
        return json.loads(text, parse_int=_bounded_int, **extra)
    except RecursionError:
        raise JsonLimitError("the JSON is nested too deeply") from None
