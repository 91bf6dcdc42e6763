"""The lexical rules of AADL text the writer checks names against, and the words it writes.

Identifiers, qualified names, classifier references, paths, mode references, array sizes and
``applies to`` owners as regular expressions (AS5506C 15.3); the reserved words (15.5); the words
of feature, connection and access categories; and :func:`unit_file_name`, the file a package or
property set is written to.
"""

from __future__ import annotations

import re

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.aadl_names import IDENTIFIER, RESERVED_WORDS
from rosaadl.errors import ExportError, Location

__all__ = [
    "ID",
    "ID_RE",
    "QNAME_RE",
    "CLASSIFIER_RE",
    "IMPL_NAME_RE",
    "PATH_RE",
    "MODE_REF_RE",
    "ARRAY_SIZE_RE",
    "OWNER_RE",
    "RESERVED_WORDS",
    "ACCESS_FEATURE_CATEGORY",
    "ACCESS_COMPONENT_CATEGORY",
    "CONNECTION_WORDS",
    "DIRECTED",
    "OPTIONALLY_DIRECTED",
    "literal",
    "enum_name",
    "balanced",
    "wrapped_in_parentheses",
    "unit_file_name",
]

# AS5506C 15.3: identifier ::= identifier_letter {[underline] letter_or_digit}*
ID = IDENTIFIER
ID_RE = re.compile(ID + r"\Z")
QNAME_RE = re.compile(rf"{ID}(?:\s*::\s*{ID})*\Z")
CLASSIFIER_RE = re.compile(rf"{ID}(?:\s*::\s*{ID})*(?:\s*\.\s*{ID})?\Z")
IMPL_NAME_RE = re.compile(rf"({ID})\s*\.\s*({ID})\Z")
_INTEGER = r"[0-9](?:_?[0-9])*"
_ANNEX_TEXT = r"\{\*\*.*?\*\*\}"
_PATH_SEGMENT = rf"(?:{ID}(?:\s*\[\s*{_INTEGER}\s*(?:\.\.\s*{_INTEGER}\s*)?\])?|annex\s*{_ANNEX_TEXT})"
PATH_RE = re.compile(rf"{_PATH_SEGMENT}(?:\s*\.\s*{_PATH_SEGMENT})*\Z", re.S | re.I)
MODE_REF_RE = re.compile(rf"({ID})(?:\s*=>\s*({ID}))?\Z")
ARRAY_SIZE_RE = re.compile(rf"(?:{_INTEGER}|{ID}(?:\s*::\s*{ID})*)?\Z")
OWNER_RE = re.compile(
    rf"(?:\{{\s*{ID}\s*\}}\s*\*\*\s*)?[A-Za-z]+(?:\s+[A-Za-z]+)*\Z"  # metaclass words, annex prefix
    rf"|{ID}(?:\s*::\s*{ID})+(?:\s*\.\s*{ID})?\Z"  # a qualified classifier
)


ACCESS_FEATURE_CATEGORY = {
    "busAccess": "bus",
    "dataAccess": "data",
    "subprogramAccess": "subprogram",
    "subprogramGroupAccess": "subprogram group",
    "virtualBusAccess": "virtual bus",
}
ACCESS_COMPONENT_CATEGORY = {
    "bus": "bus",
    "data": "data",
    "subprogram": "subprogram",
    "subprogramGroup": "subprogram group",
    "virtualBus": "virtual bus",
}
CONNECTION_WORDS = {
    "featureConnection": "feature",
    "parameterConnection": "parameter",
    "portConnection": "port",
    "featureGroupConnection": "feature group",
}
DIRECTED = frozenset({"dataPort", "eventPort", "eventDataPort", "parameter"})
OPTIONALLY_DIRECTED = frozenset({"featureGroup", "abstractFeature"})


def literal(value: object) -> str:
    """The AADL spelling of an enumeration value (``thread group``), or ``""``."""
    if value is None:
        return ""
    return str(getattr(value, "literal", None) or getattr(value, "name", value))


def enum_name(value: object) -> str:
    """The metamodel name of an enumeration value (``threadGroup``), or ``""``."""
    return str(getattr(value, "name", value)) if value is not None else ""


def balanced(text: str) -> bool:
    """Do the parentheses, brackets and braces of ``text`` pair up?"""
    pairs = {"(": ")", "[": "]", "{": "}"}
    stack: list[str] = []
    for char in text:
        if char in pairs:
            stack.append(pairs[char])
        elif char in ")]}" and (not stack or stack.pop() != char):
            return False
    return not stack


def wrapped_in_parentheses(text: str) -> bool:
    """``(a => b)`` is wrapped; ``(a) , (b)`` is not."""
    if not (text.startswith("(") and text.endswith(")")):
        return False
    depth = 0
    for i, char in enumerate(text):
        if char == "(":
            depth += 1
        elif char == ")":
            depth -= 1
            if depth == 0 and i != len(text) - 1:
                return False
    return True


def unit_file_name(unit: EObject) -> str:
    """``a::b`` → ``a-b.aadl``; the name must be an AADL (qualified) name."""
    name = (unit.name or "").strip()
    kind = unit.eClass.name
    what = f"{kind} {name!r}" if name else f"a {kind} without a name"
    property_set = model.is_a(unit, "PropertySet")
    if not QNAME_RE.match(name) or (property_set and not ID_RE.match(name)):
        raise ExportError(
            f"cannot write {what}: its name is not an AADL "
            f"{'identifier' if property_set else 'package name'} "
            "(letters, digits and single underscores, starting with a letter; '::' between parts)",
            Location(file=unit.sourceFile or None, line=unit.line or None, path=name or None),
        )
    return "-".join(part.strip() for part in name.split("::")) + ".aadl"
