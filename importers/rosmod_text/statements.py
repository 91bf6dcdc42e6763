"""Reading ROSMOD statements: times, integers and names out of them, and the model objects they make.

The helpers every textual dialect uses on a :class:`~.blocks.Stmt`: :func:`seconds` (``0.5``,
and v0.2's ``500ms``; :func:`time_problem` says why a number is no time, for v0.4 and
``.webgmex`` too), :func:`integer`, :func:`name_of` (``kind name``), :func:`typed_head`
(``kind <package/Type> name``), :func:`qualify`; and :func:`new`, :func:`new_property`, :func:`located`,
which make ``rosmod.ecore`` objects carrying the line and column they were read at.
:func:`scheme_literal` is the ``SchedulingScheme`` literal of a name (FIFO, PFIFO or EDF);
:func:`skip` warns of a statement that means nothing where it stands.
"""

from __future__ import annotations

import functools
import math
import re
import sys
from decimal import Decimal, InvalidOperation
from typing import Any

from pyecore.ecore import EObject

from rosaadl import metamodels
from rosaadl.errors import ParseError
from rosaadl.importers.rosmod_text.blocks import Stmt, Token, at, is_punct
from rosaadl.importers.rosmod_text.context import ImportContext

__all__ = [
    "SCHEMES",
    "seconds",
    "time_problem",
    "integer",
    "new",
    "scheme_literal",
    "new_property",
    "located",
    "typed_head",
    "name_of",
    "qualify",
    "skip",
]

#: The scheduling schemes of a ROSMOD component executor.
SCHEMES = ("FIFO", "PFIFO", "EDF")

_NUMBER_RE = re.compile(r"^([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)\s*(s|ms|us|ns)?$")
_UNIT_SCALE = {
    "s": Decimal(1),
    "ms": Decimal("0.001"),
    "us": Decimal("0.000001"),
    "ns": Decimal("0.000000001"),
}


def seconds(stmt: Stmt, filename: str) -> Decimal:
    """The value of ``stmt`` in seconds (a bare number, or with a unit s/ms/us/ns as v0.2 writes)."""
    text = stmt.value_text
    match = _NUMBER_RE.match(text)
    token = stmt.value_token
    if not match:
        raise ParseError(
            f"{stmt.key} = {text!r}: expected a number of seconds (such as 0.5, or 500ms in v0.2 files)",
            location=at(filename, token),
        )
    try:
        value = Decimal(match.group(1))
        unit = match.group(2)
        if unit and unit != "s":
            value = value * _UNIT_SCALE[unit]
    except ArithmeticError:  # InvalidOperation cannot happen (the regex admits only decimals); Overflow
        value = Decimal("Infinity")
    problem = time_problem(value)
    if problem is not None:
        raise ParseError(f"{stmt.key} = {text}: {problem}", location=at(filename, token))
    return value


def time_problem(value: Decimal) -> str | None:
    """Why ``value`` cannot be a time in seconds of the model, or None when it can.

    A time is a finite, non-negative number that stays finite and, unless zero, non-zero as a
    float (what the transformations and analyses compute with): ``1e309`` overflows to
    infinity and ``1e-400`` underflows to zero, so both are out of range, as are ``NaN`` and
    ``Infinity``.
    """
    if not value.is_finite():
        return "expected a finite number of seconds"
    if value < 0:
        return "a time must not be negative"
    converted = float(value)
    if math.isinf(converted):
        return f"out of range: a time is at most {_LARGEST_TIME:.4g} s"
    if converted == 0 and value != 0:
        return f"out of range: a non-zero time is at least {_SMALLEST_TIME:.4g} s"
    return None


_LARGEST_TIME = sys.float_info.max
_SMALLEST_TIME = math.ulp(0.0)  # the smallest positive float (a subnormal)


def integer(stmt: Stmt, filename: str, ctx: ImportContext) -> int:
    """The value of ``stmt`` as an integer (a whole decimal such as ``50.0`` is read with a warning)."""
    text = stmt.value_text
    token = stmt.value_token
    try:
        return int(text)
    except ValueError:
        pass
    number = whole_decimal(text)
    if number is not None:
        ctx.warn(
            f"{stmt.key} = {text}: read as the integer {int(number)}", filename, token.line, token.column
        )
        return int(number)
    raise ParseError(f"{stmt.key} = {text!r}: expected an integer", location=at(filename, token))


#: The integers a ROSMOD model holds are 64-bit, as AADL's (a larger number is not read).
MAX_INTEGER = 2**63 - 1


def whole_decimal(text: str) -> Decimal | None:
    """``text`` as a decimal that is a whole number of at most 64 bits (``50.0``, ``5e1``), else None."""
    try:
        number = Decimal(text)
    except InvalidOperation:
        return None
    if not number.is_finite() or number.adjusted() > 18 or abs(number) > MAX_INTEGER:
        return None
    return number if number == number.to_integral_value() else None


@functools.cache
def _rosmod_class(name: str) -> Any:
    return metamodels.load().rosmod.getEClassifier(name)


def new(class_name: str, /, **values: Any) -> EObject:
    """A ``rosmod`` object; features given as None stay unset (the metamodel default).

    The reader's values are of the right types already, so this calls pyecore's constructor
    directly: :func:`rosaadl.model.new` checks each feature and is twice as slow, which a large
    project (tens of thousands of objects) would feel.
    """
    return _rosmod_class(class_name)(**{k: v for k, v in values.items() if v is not None})


def scheme_literal(text: str) -> Any:
    """The ``rosmod.SchedulingScheme`` literal called ``text`` (FIFO, PFIFO or EDF)."""
    enum = metamodels.load().rosmod.getEClassifier("SchedulingScheme")
    return enum.from_string(text)


def new_property(key: str, value: str, stmt: Stmt | None = None) -> EObject:
    """A ``rosmod.Property`` (a ROSMOD fact without a slot), located at ``stmt`` when given."""
    return new(
        "Property",
        key=key,
        value=value,
        line=stmt.line if stmt is not None else None,
        column=stmt.column if stmt is not None else None,
    )


def located(obj_kwargs: dict[str, Any], stmt: Stmt) -> dict[str, Any]:
    """``obj_kwargs`` with the line and column of ``stmt`` added (for :func:`new`)."""
    obj_kwargs["line"] = stmt.line
    obj_kwargs["column"] = stmt.column
    return obj_kwargs


def typed_head(stmt: Stmt, filename: str, what: str) -> tuple[str, str, Token]:
    """``kind <ref> name`` → (ref as written without spaces, name, name token)."""
    head = stmt.head
    try:
        lt = next(k for k, t in enumerate(head) if is_punct(t, "<"))
        gt = next(k for k, t in enumerate(head) if is_punct(t, ">"))
    except StopIteration:
        lt = gt = -1
    names = head[gt + 1 :] if gt > lt >= 0 else []
    ref_tokens = head[lt + 1 : gt] if gt > lt >= 0 else []
    if lt != 1 or not ref_tokens or len(names) != 1 or names[0].kind != "word":
        raise ParseError(
            f"malformed {what}: expected '{stmt.keyword} <package/Type> name' (found {stmt.key!r})",
            location=at(filename, stmt),
        )
    ref = "".join(t.text for t in ref_tokens)
    return ref, names[0].text, names[0]


def name_of(stmt: Stmt, filename: str, what: str) -> str:
    """The name of a ``kind name`` statement (``what`` names it in the error)."""
    if len(stmt.head) != 2 or stmt.head[1].kind != "word":
        raise ParseError(
            f"malformed {what}: expected '{stmt.keyword} <name>' (found {stmt.key!r})",
            location=at(filename, stmt),
        )
    return stmt.head[1].text


def qualify(ref: str, package: str) -> str:
    """``ref`` as ``package/Name`` (a bare name means one of ``package``)."""
    return ref if "/" in ref else f"{package}/{ref}"


def skip(ctx: ImportContext, stmt: Stmt, filename: str, owner: str | None = None, within: str | None = None):
    """Warn that ``stmt`` (in ``owner``, in its block ``within``) is unknown there and skipped."""
    prefix = f"{owner}: " if owner else ""
    inside = f" in {within!r}" if within is not None else ""
    ctx.warn(f"{prefix}unknown statement {stmt.key!r}{inside} skipped", filename, stmt.line, stmt.column)
