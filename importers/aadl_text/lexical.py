"""The text below the parse tree: literal values and the source text around the tokens.

The grammar (:mod:`rosaadl.importers.aadl_syntax`) gives tokens as written; this module turns
integer and string literals into their values (:func:`parse_integer`, :func:`unescape`) and,
through :class:`SourceText`, reads what the tree does not keep: the text of a construct that the
metamodel keeps as text (prototypes, prototype bindings), where a construct starts after some
keywords, and the line and column of a position.
"""

from __future__ import annotations

import bisect
import math
import re
from typing import Any

__all__ = ["SourceText", "find_end", "normalise", "parse_integer", "shown", "unescape"]

_TRIVIA = re.compile(r"(?:\s+|--[^\n]*)*")
# the next character that matters when looking for the end of an opaque piece of text
_INTERESTING = re.compile(r'"(?:[^"\\]|\\.|"")*"|\{\*\*.*?\*\*\}|--[^\n]*|[()\[\]{};]', re.S)
_COMMENT_OR_STRING = re.compile(r'"(?:[^"\\]|\\.|"")*"|--[^\n]*')
_ESCAPE = re.compile(r'\\(u[0-9a-fA-F]{4}|.)|""', re.S)
_ESCAPES = {"b": "\b", "t": "\t", "n": "\n", "f": "\f", "r": "\r", '"': '"', "'": "'", "\\": "\\"}
_INTEGER_PARTS = re.compile(r"([0-9_]+)(?:#([0-9a-fA-F_]+)#)?(?:[eE]\+?([0-9]+))?\Z")


def shown(text: str, limit: int = 40) -> str:
    """A literal as shown in a message (long ones shortened)."""
    return text if len(text) <= limit else text[: limit - 3] + "..."


def parse_integer(literal: str) -> int:
    """The value of an INTEGER token; ValueError (with a message) when malformed or huge."""
    literal_shown = shown(literal)
    match = _INTEGER_PARTS.match(literal)
    if match is None:  # the grammar's INTEGER terminal makes this impossible
        raise ValueError(f"malformed integer literal {literal_shown!r}")
    digits, based, exponent = match.groups()
    digits = digits.replace("_", "")
    if based is not None:
        base = int(digits) if len(digits) < 4 else 0
        if not 2 <= base <= 16:
            raise ValueError(f"the base of {literal_shown} must be 2 .. 16")
        text = based.replace("_", "")
        if any(int(c, 16) >= base for c in text):
            raise ValueError(f"{literal_shown} has digits that are not base-{base} digits")
    else:
        base, text = 10, digits
    text = text.lstrip("0") or "0"
    too_big = f"integer {literal_shown} does not fit in 64 bits (AADL integers are -2**63 .. 2**63-1)"
    if len(text) > 64:  # more digits than a 64-bit number has in any base
        raise ValueError(too_big)
    mantissa = int(text, base)
    if exponent is None or mantissa == 0:
        return mantissa
    exponent = exponent.lstrip("0") or "0"
    if len(exponent) > 3 or int(exponent) * math.log2(base) > 64:  # checked before computing it
        raise ValueError(too_big)
    return mantissa * base ** int(exponent)


def unescape(token: str) -> str:
    """The value of a STRING token: quotes removed, ``""`` and backslash escapes replaced."""
    inner = token[1:-1]
    if "\\" not in inner and '""' not in inner:
        return inner

    def replace(match: re.Match[str]) -> str:
        escape = match.group(1)
        if escape is None:
            return '"'
        if len(escape) == 5:
            code = int(escape[1:], 16)
            return match.group() if 0xD800 <= code <= 0xDFFF else chr(code)  # no lone surrogates
        return _ESCAPES.get(escape, "\\" + escape)

    return _ESCAPE.sub(replace, inner)


def normalise(text: str) -> str:
    """Source text without comments, white space runs as one space."""
    if "--" in text:
        text = _COMMENT_OR_STRING.sub(lambda m: m.group() if m.group().startswith('"') else " ", text)
    return " ".join(text.split())


def find_end(text: str, pos: int, depth: int, stop: str) -> int:
    """The position of the ``stop`` character (``;`` or a closing bracket) that ends the
    construct starting at ``pos``, ``depth`` brackets deep; strings, annex texts and
    comments are stepped over.  ``len(text)`` when there is none."""
    search = _INTERESTING.search
    while True:
        match = search(text, pos)
        if match is None:
            return len(text)
        char = match.group()
        pos = match.end()
        if len(char) != 1:
            continue  # string, annex text or comment
        if char in "([{":
            depth += 1
        elif char in ")]}":
            depth -= 1
            if depth == 0 and stop == ")":
                return match.start()
        elif char == ";" and depth == 0 and stop == ";":
            return match.start()


class SourceText:
    """The text of one file being read, for what its parse tree does not keep."""

    __slots__ = ("text", "_newlines")

    def __init__(self, text: str) -> None:
        self.text = text
        self._newlines: list[int] | None = None  # positions of the line breaks, when needed

    def after(self, pos: int, *words: str) -> int:
        """The position after white space, comments and those of ``words`` that follow ``pos``."""
        text = self.text
        pos = _TRIVIA.match(text, pos).end()
        for word in words:
            end = pos + len(word)
            follows = text[end : end + 1]
            if text[pos:end].lower() == word and not (
                word.isalpha() and (follows.isalnum() or follows == "_")
            ):
                pos = _TRIVIA.match(text, end).end()
        return pos

    def line_column(self, pos: int) -> tuple[int, int]:
        """(line, column) of a position of the text (1-based, as the tokens')."""
        if self._newlines is None:
            self._newlines = [m.start() for m in re.finditer("\n", self.text)]
        before = bisect.bisect_left(self._newlines, pos)
        start = self._newlines[before - 1] + 1 if before else 0
        return before + 1, pos - start + 1

    def until_end(self, start: int) -> str:
        """The text from ``start`` to the ``;`` that ends its declaration, normalised."""
        return normalise(self.text[start : find_end(self.text, start, 0, ";")])

    def bindings(self, node: Any) -> str:
        """A prototype bindings node, ``(p => data T, ...)``, as written (comments and line
        breaks dropped)."""
        first = node.children[0].children[0]
        stop = find_end(self.text, first.start_pos, 1, ")")
        return "(" + normalise(self.text[first.start_pos : stop]) + ")"
