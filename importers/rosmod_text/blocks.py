"""The block syntax every textual ROSMOD dialect shares: located tokens and nested statements.

ROSMOD text (``.rosml`` of v0.1; ``.rml``, ``.rhw`` and ``.rdp`` of v0.2 and v0.3) is a tree of
statements, ``head… ;``, ``head… = value… ;`` and ``head… { body }``, with ``/* */`` and ``//``
comments, CRLF line ends and double-quoted strings. :func:`tokenize` cuts a text into tokens with
their line and column; :func:`parse_blocks` builds the statement tree, iteratively, so that
hostile nesting meets a located error and not Python's recursion limit. What a statement means
is the business of the dialect modules (:mod:`.v03`, :mod:`.v02`, :mod:`.v01`).

One form is not a statement tree: the top-level ``group NAME { a/b/c d/e/f }`` blocks of a
deployment list names with no separator but white space (ROSMOD's ``Deployment.g4``: ``'group'
group_id '{' (port)+ '}'``, ``port: IDENT``). :func:`parse_blocks` reads the blocks whose keyword
it is given in ``listings`` that way: each item is a statement of one head and nothing else, the
tokens written together without white space between them.
"""

from __future__ import annotations

import bisect
import re
from collections.abc import Collection
from dataclasses import dataclass

from rosaadl.errors import Location, ParseError

__all__ = ["MAX_DEPTH", "Token", "Stmt", "at", "tokenize", "is_punct", "parse_blocks"]

#: Deepest nesting of ``{ }`` blocks read; deeper input is refused with a located error.
MAX_DEPTH = 200


@dataclass(slots=True)
class Token:
    """A word, a string or one punctuation character, with where it starts and ends."""

    kind: str  # "word" | "string" | "punct"
    text: str  # as written (strings without their quotes, escapes resolved)
    line: int
    column: int
    start: int
    end: int


_TOKEN_RE = re.compile(
    r"""
    \s*
    (?:
     (?P<word>[A-Za-z0-9_.~+\-]+)
    |(?P<block>/\*.*?\*/)
    |(?P<line_comment>//[^\n]*)
    |(?P<string>"(?:[^"\\\n]|\\[^\n])*")
    |(?P<open_block>/\*)
    |(?P<open_string>")
    |(?P<other>.)
    |\Z
    )
    """,
    re.S | re.X,
)
_STRING_ESCAPES = {"n": "\n", "t": "\t", '"': '"', "\\": "\\"}
_ESCAPE_RE = re.compile(r"\\(.)")


def tokenize(text: str, filename: str) -> list[Token]:
    """Tokens with 1-based line and column (a tab counts as one column)."""
    newlines = [m.start() for m in re.finditer("\n", text)]
    line_of = bisect.bisect_right

    def place(offset: int) -> tuple[int, int]:
        index = line_of(newlines, offset - 1) if offset else 0
        line_start = newlines[index - 1] + 1 if index else 0
        return index + 1, offset - line_start + 1

    tokens: list[Token] = []
    append = tokens.append
    for match in _TOKEN_RE.finditer(text):
        kind = match.lastgroup
        if kind is None or kind == "block" or kind == "line_comment":
            continue
        start = match.start(kind)
        line, column = place(start)
        if kind == "word":
            append(Token("word", match.group(kind), line, column, start, match.end()))
        elif kind == "string":
            raw = match.group(kind)[1:-1]
            if "\\" in raw:
                raw = _ESCAPE_RE.sub(lambda m: _STRING_ESCAPES.get(m.group(1), m.group(0)), raw)
            append(Token("string", raw, line, column, start, match.end()))
        elif kind == "other":
            char = match.group(kind)
            if char.isspace():
                continue
            if not char.isprintable():
                raise ParseError(
                    f"unexpected character {char!r} (the file does not look like ROSMOD text)",
                    file=filename,
                    line=line,
                    column=column,
                )
            append(Token("punct", char, line, column, start, match.end()))
        elif kind == "open_block":
            raise ParseError(
                "unterminated comment '/*' (expected '*/' before the end of the file)",
                file=filename,
                line=line,
                column=column,
            )
        else:  # open_string
            raise ParseError(
                "unterminated string (expected a closing '\"' on the same line)",
                file=filename,
                line=line,
                column=column,
            )
    return tokens


@dataclass
class Stmt:
    """``head… ;`` or ``head… = value… ;`` or ``head… { body }``."""

    head: list[Token]
    value: list[Token] | None = None
    body: list[Stmt] | None = None
    source: str = ""

    @property
    def line(self) -> int:
        return self.head[0].line

    @property
    def column(self) -> int:
        return self.head[0].column

    @property
    def keyword(self) -> str:
        return self.head[0].text if self.head and self.head[0].kind == "word" else ""

    @property
    def key(self) -> str:
        """The head as written (``Is Periodic?``), whitespace runs kept as in the file."""
        if not self.head:
            return ""
        if len(self.head) == 1 and self.head[0].kind == "string":
            return self.head[0].text
        return self.source[self.head[0].start : self.head[-1].end].strip()

    @property
    def value_text(self) -> str:
        if not self.value:
            return ""
        if len(self.value) == 1 and self.value[0].kind == "string":
            return self.value[0].text
        return self.source[self.value[0].start : self.value[-1].end].strip()

    @property
    def value_token(self) -> Token:
        return self.value[0] if self.value else self.head[-1]


def at(filename: str | None, place: Token | Stmt) -> Location:
    """Where ``place`` (a token or a statement) stands in ``filename``: for located errors."""
    return Location(file=filename, line=place.line, column=place.column)


def is_punct(token: Token, text: str) -> bool:
    return token.kind == "punct" and token.text == text


def parse_blocks(text: str, filename: str, *, listings: Collection[str] = ()) -> list[Stmt]:
    """Parse ``text`` into nested statements (iteratively: no recursion limit on hostile input).

    A top-level block whose keyword is one of ``listings`` holds a list of items (see the module
    documentation), not statements.
    """
    tokens = tokenize(text, filename)
    root: list[Stmt] = []
    stack: list[tuple[list[Stmt], Stmt | None, Token | None]] = [(root, None, None)]
    i = 0
    n = len(tokens)
    while i < n:
        tok = tokens[i]
        body = stack[-1][0]
        if is_punct(tok, ";"):
            i += 1
            continue
        if is_punct(tok, "}"):
            if len(stack) == 1:
                raise ParseError("unexpected '}' (no block is open here)", location=at(filename, tok))
            stack.pop()
            i += 1
            continue
        head: list[Token] = []
        while i < n and not (tokens[i].kind == "punct" and tokens[i].text in "{=;}"):
            head.append(tokens[i])
            i += 1
        if i >= n:
            last = head[-1]
            raise ParseError(
                f"expected ';' or '{{' after {text[head[0].start : last.end].strip()!r}, "
                "found the end of the file",
                location=at(filename, last),
            )
        stop = tokens[i]
        if not head:
            raise ParseError(f"expected a name before {stop.text!r}", location=at(filename, stop))
        if stop.text == "=":
            i += 1
            value: list[Token] = []
            while i < n and not (tokens[i].kind == "punct" and tokens[i].text in ";{}="):
                value.append(tokens[i])
                i += 1
            if i >= n or tokens[i].text != ";":
                where = tokens[i] if i < n else (value[-1] if value else stop)
                found = f"{where.text!r}" if i < n else "the end of the file"
                raise ParseError(
                    f"expected ';' after the value of {text[head[0].start : head[-1].end].strip()!r}, "
                    f"found {found}",
                    location=at(filename, where),
                )
            if not value:
                raise ParseError(
                    f"expected a value after '=' for {text[head[0].start : head[-1].end].strip()!r}",
                    location=at(filename, stop),
                )
            body.append(Stmt(head, value=value, source=text))
            i += 1
        elif stop.text == ";":
            body.append(Stmt(head, source=text))
            i += 1
        elif stop.text == "{" and len(stack) == 1 and head[0].kind == "word" and head[0].text in listings:
            stmt = Stmt(head, body=[], source=text)
            body.append(stmt)
            i = _listing(tokens, i + 1, stmt, stop, filename)
        elif stop.text == "{":
            stmt = Stmt(head, body=[], source=text)
            body.append(stmt)
            if len(stack) > MAX_DEPTH:
                raise ParseError(
                    f"blocks nested more than {MAX_DEPTH} deep",
                    location=at(filename, stop),
                )
            stack.append((stmt.body, stmt, stop))
            i += 1
        else:  # "}" right after a head: a statement without its ';'
            raise ParseError(
                f"expected ';' or '{{' after {text[head[0].start : head[-1].end].strip()!r}, found '}}'",
                location=at(filename, stop),
            )
    if len(stack) > 1:
        _, stmt, brace = stack[-1]
        assert stmt is not None and brace is not None
        chain = " > ".join(s.key for _, s, _ in stack[1:] if s is not None)
        raise ParseError(
            f"unclosed '{{' of {stmt.key!r} (in {chain}): expected '}}' before the end of the file",
            location=at(filename, brace),
        )
    return root


def _listing(tokens: list[Token], i: int, stmt: Stmt, brace: Token, filename: str) -> int:
    """The items of the listing block ``stmt`` from ``tokens[i]`` to its ``}``; the index after it."""
    assert stmt.body is not None
    items = stmt.body
    n = len(tokens)
    while i < n:
        tok = tokens[i]
        if is_punct(tok, "}"):
            return i + 1
        if tok.kind == "punct" and tok.text in "{=;":
            raise ParseError(
                f"unexpected {tok.text!r} in {stmt.key!r} (it lists names separated by white space, "
                "one a line, and ends with '}')",
                location=at(filename, tok),
            )
        if items and items[-1].head[-1].end == tok.start:  # written together: the same item
            items[-1].head.append(tok)
        else:
            items.append(Stmt([tok], source=stmt.source))
        i += 1
    raise ParseError(
        f"unclosed '{{' of {stmt.key!r}: expected '}}' before the end of the file",
        location=at(filename, brace),
    )
