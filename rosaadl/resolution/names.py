"""AADL names and paths as they are written in the text.

The declarative model keeps every cross reference as written (``ros_data::Image.rgb``,
``Timing_Properties::Period``, ``applies to a.b[2].c``). This module holds the small helpers that
take such text apart, case- and space-insensitively as AADL reads it: qualified names
(:func:`split_name`), dotted paths with array ranges (:func:`split_path`, :class:`PathSegment`),
``renames P::all`` targets, enumeration values of the metamodel, and the AADL words of a feature
category (:data:`FEATURE_WORDS`).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

from rosaadl.errors import ModelError

__all__ = [
    "FEATURE_WORDS",
    "PathSegment",
    "enum_name",
    "feature_category_word",
    "lower",
    "split_name",
    "split_path",
    "squeeze",
    "strip_all",
]

#: The AADL words of each ``FeatureCategory`` of ``aadl.ecore`` (as in ``applies to`` lists).
FEATURE_WORDS: dict[str, str] = {
    "dataPort": "data port",
    "eventPort": "event port",
    "eventDataPort": "event data port",
    "parameter": "parameter",
    "busAccess": "bus access",
    "dataAccess": "data access",
    "subprogramAccess": "subprogram access",
    "subprogramGroupAccess": "subprogram group access",
    "featureGroup": "feature group",
    "abstractFeature": "abstract feature",
    "virtualBusAccess": "virtual bus access",
}

_INDEX_RE = re.compile(r"\[\s*(\d+)\s*(?:\.\.\s*(\d+)\s*)?\]")


@dataclass(frozen=True)
class PathSegment:
    """One element of a dotted AADL path: ``name`` and the array ``ranges`` written after it.

    ``ranges`` holds one ``(low, high)`` pair per ``[...]`` (``[2]`` is ``(2, 2)``); an empty
    tuple means "every element".
    """

    name: str
    ranges: tuple[tuple[int, int], ...] = ()

    @property
    def key(self) -> str:
        return self.name.lower()

    def matches(self, index: Iterable[int] | int | None) -> bool:
        """Does an element with 1-based ``index`` (list, int or None/0) fall in the ranges?"""
        if not self.ranges:
            return True
        values = list(index) if isinstance(index, Iterable) else ([index] if index else [])
        if len(values) < len(self.ranges):
            return False
        try:
            return all(low <= value <= high for (low, high), value in zip(self.ranges, values, strict=False))
        except TypeError:
            raise ModelError(f"not an array index: {index!r}") from None

    def __str__(self) -> str:
        text = self.name
        for low, high in self.ranges:
            text += f"[{low}]" if low == high else f"[{low} .. {high}]"
        return text


def split_path(text: str) -> list[PathSegment]:
    """``"a.b[2].c"`` → segments ``a``, ``b[2]``, ``c`` (annex elements are kept as one name)."""
    if not isinstance(text, str):
        if text is not None:
            raise ModelError(f"expected a path, got {text!r}")
        text = ""
    segments: list[PathSegment] = []
    for raw in _split_dots(text):
        raw = raw.strip()
        if not raw:
            continue
        bracket = raw.find("[")
        if bracket < 0:
            segments.append(PathSegment(raw))
            continue
        ranges = tuple(
            (int(m.group(1)), int(m.group(2) or m.group(1))) for m in _INDEX_RE.finditer(raw[bracket:])
        )
        segments.append(PathSegment(raw[:bracket].strip(), ranges))
    return segments


def _split_dots(text: str) -> Iterator[str]:
    depth = 0
    start = 0
    for i, ch in enumerate(text):
        if ch in "[{":
            depth += 1
        elif ch in "]}":
            depth -= 1
        elif ch == "." and depth == 0:
            # "1 .. 3" inside brackets is protected by depth; a bare ".." cannot occur here
            yield text[start:i]
            start = i + 1
    yield text[start:]


def split_name(name: str) -> tuple[str | None, str]:
    """``"a::b::T.impl"`` → ``("a::b", "T.impl")``; ``"T"`` → ``(None, "T")`` (spaces removed)."""
    text = "".join((name or "").split())  # squeeze(name), inline: asked for every name
    if "::" in text:
        qualifier, _, local = text.rpartition("::")
        return qualifier, local
    return None, text


def squeeze(name: str | None) -> str:
    """A name as written, without the spaces AADL allows around ``::`` and ``.``."""
    return "".join((name or "").split())


def lower(name: str | None) -> str:
    """The case-insensitive key of a name (``""`` for none)."""
    return (name or "").lower()


def strip_all(target: str | None) -> str:
    """The package of a ``renames P::all`` target (``P``); any other target squeezed."""
    text = squeeze(target)
    if text.lower().endswith("::all"):
        text = text[: -len("::all")]
    return text


def enum_name(value: object) -> str:
    """The name of an enumeration value of the metamodel (``""`` for none)."""
    return str(getattr(value, "name", value) or "")


def feature_category_word(category: object) -> str:
    """The AADL words of a ``FeatureCategory`` value (``data port``, ``feature group``, ...)."""
    name = getattr(category, "name", category)
    return FEATURE_WORDS.get(str(name), str(name))
