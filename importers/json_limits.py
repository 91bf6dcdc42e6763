"""How much a JSON text may build once parsed: a bound on its values, checked before parsing.

A JSON document of small values amplifies: ``[]`` is two bytes of text but a 56-byte Python
list, so a file under the byte caps can still ask for gigabytes once parsed. Readers of JSON
from elsewhere (``.webgmex`` archives, ROSMOD v0.4 ``.rml`` files) call
:func:`json_value_bound` before :func:`json.loads`: it counts, without parsing, an upper
bound on the values the text holds, and the reader refuses a text over its cap, so the parsed
structure stays within a bound proportional to the cap, not to the amplification.
"""

from __future__ import annotations

import re

__all__ = ["MAX_JSON_VALUES", "json_value_bound"]

#: The values (objects, arrays, strings, numbers, literals) a JSON text read by rosaadl may
#: hold: 50 times the largest WebGME sample project (about 20 000 values), at most a few
#: hundred megabytes once parsed.
MAX_JSON_VALUES = 1_000_000

# A JSON string literal (escapes included), matched without backtracking: the "unrolled loop".
_STRING = re.compile(rb'"[^"\\]*(?:\\.[^"\\]*)*"', re.DOTALL)


def _structural_count(text: bytes | bytearray) -> int:
    return text.count(b",") + text.count(b"[") + text.count(b"{") + 1


def json_value_bound(text: bytes | bytearray, cap: int = MAX_JSON_VALUES) -> int:
    """An upper bound on the number of values in the JSON ``text`` (linear, nothing parsed).

    Every value but the first of each array or object follows a comma, and every array and
    object opens with a bracket, so commas + brackets + 1 bounds the values (a key counts
    with its value). The commas and brackets inside strings are left out only when the quick
    count is over ``cap`` (the strings are then blanked out and the count redone), so a
    result over ``cap`` is exact enough to refuse on.
    """
    quick = _structural_count(text)
    if quick <= cap:
        return quick
    return _structural_count(_STRING.sub(b'""', text))
