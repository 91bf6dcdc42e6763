"""How analysis results are written: numbers for JSON, text tables and CSV files.

Every analysis module renders its own result with these helpers (see
:mod:`rosaadl.analysis.registry`), so that the text tables, the CSV files and the JSON document
of every analysis format numbers alike: exact :class:`~fractions.Fraction` values become integers
where they are whole, and floats (or fixed decimals in text) otherwise.
"""

from __future__ import annotations

import csv
import io
import math
import re
from collections.abc import Iterable, Sequence
from fractions import Fraction
from typing import Any

from rosaadl.errors import UsageError

__all__ = [
    "json_number",
    "fmt",
    "fmt3",
    "table",
    "short_path",
    "csv_text",
    "squeeze",
    "category_word",
    "as_float",
]


def as_float(value: Any) -> float:
    """``float(value)``, saturating: an exact number too large for a float (``1e308`` MIPS in
    KIPS) is an infinity, not an OverflowError."""
    try:
        return float(value)
    except OverflowError:
        return math.inf if value > 0 else -math.inf


def json_number(value: Any) -> Any:
    """An exact number for JSON: ``Fraction(3)`` → ``3``, ``Fraction(1, 3)`` → ``0.333…``;
    anything else as it is."""
    if isinstance(value, Fraction):
        return int(value) if value.denominator == 1 else as_float(value)
    return value


def fmt(value: Any, digits: int = 2) -> str:
    """A number for a text table: integers as they are, others with ``digits`` decimals."""
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, Fraction) and value.denominator == 1:
        return str(value.numerator)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, (Fraction, float)):
        return f"{as_float(value):.{digits}f}"
    return str(value)


def fmt3(value: Fraction | None) -> str:
    """Three decimals, as OSATE's reports print MIPS and KByte (``None`` is ``0.000``)."""
    return f"{as_float(value or 0):.3f}"


def table(headers: Sequence[str], rows: Iterable[Sequence[Any]]) -> list[str]:
    """A plain text table: a header line, a rule, one line per row; numbers right-aligned."""
    cells = [[str(h) for h in headers]] + [[c if isinstance(c, str) else fmt(c) for c in row] for row in rows]
    for number, row in enumerate(cells[1:], 1):
        if len(row) != len(headers):
            raise UsageError(f"table(): row {number} has {len(row)} cells for {len(headers)} headers")
    widths = [max(len(row[i]) for row in cells) for i in range(len(headers))]
    out = []
    for n, row in enumerate(cells):
        parts = []
        for i, cell in enumerate(row):
            numeric = n > 0 and i > 0 and re.fullmatch(r"-?[\d.]+|-", cell) is not None
            parts.append(cell.rjust(widths[i]) if numeric else cell.ljust(widths[i]))
        out.append("  ".join(parts).rstrip())
        if n == 0:
            out.append("  ".join("-" * w for w in widths))
    return out


def short_path(path: str) -> str:
    """An instance path without its root segment (shorter table cells)."""
    head, dot, rest = (path or "").partition(".")
    return rest if dot else path or ""


def _csv_value(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, Fraction):
        return str(value.numerator) if value.denominator == 1 else repr(as_float(value))
    if isinstance(value, float):
        return repr(value)
    return str(value)


def csv_text(rows: Iterable[Sequence[Any]]) -> str:
    """CSV text of ``rows`` (exact numbers as integers or shortest floats, booleans as
    ``true``/``false``, None empty), one ``\\n`` per line."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    for row in rows:
        writer.writerow([_csv_value(v) for v in row])
    return buffer.getvalue()


def squeeze(text: str) -> str:
    """Runs of spaces as one (OSATE's report titles with an empty mode)."""
    return re.sub(" +", " ", text)


def category_word(name: str) -> str:
    """A category literal as AADL writes it (``threadGroup`` → ``thread group``)."""
    return {"threadGroup": "thread group", "virtualProcessor": "virtual processor"}.get(name, name)
