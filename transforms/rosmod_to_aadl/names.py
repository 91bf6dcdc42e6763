"""AADL names for ROSMOD names: identifiers, reserved words and the names of one namespace.

A ROSMOD name that is not an AADL identifier, is a reserved word or repeats another name of the
same AADL namespace (AADL names are case-insensitive) gets a unique identifier from the
:class:`NameScope` of that namespace; the rules keep the ROSMOD name in
``ROSMOD_Properties::Name`` when it changed.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from rosaadl.aadl_names import RESERVED_WORDS  # never used as generated names

__all__ = ["RESERVED_WORDS", "NameScope", "aadl_identifier"]


_NOT_ALNUM = re.compile(r"[^A-Za-z0-9]+")


def aadl_identifier(name: str | None) -> str:
    """An AADL identifier for a ROSMOD name: other characters become single ``_``, a name that
    does not start with a letter gets an ``x`` in front (``3_Sat`` → ``x3_Sat``)."""
    text = _NOT_ALNUM.sub("_", name or "").strip("_")
    if not text:
        return "x"
    if not text[0].isalpha():
        text = "x" + text
    return text


class NameScope:
    """The names of one AADL namespace: :meth:`take` gives each wanted name a unique identifier
    (compared case-insensitively, as AADL does), never a reserved word."""

    def __init__(self, reserved: Iterable[str] = ()) -> None:
        self._taken: set[str] = {w.lower() for w in reserved} | set(RESERVED_WORDS)
        self._counters: dict[str, int] = {}  # base → last suffix tried (no quadratic probing)

    def take(self, wanted: str | None) -> str:
        base = aadl_identifier(wanted)
        name = base
        key = base.lower()
        if key in self._taken:
            count = self._counters.get(key, 0)
            while name.lower() in self._taken:
                count += 1
                name = f"{base}_{count}"
            self._counters[key] = count
        self._taken.add(name.lower())
        return name

    def __contains__(self, name: str) -> bool:
        return name.lower() in self._taken
