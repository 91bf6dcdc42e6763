"""AADL v2 concrete syntax: the lark LALR(1) grammar and a thin ``parse`` entry point.

``parse`` turns AADL text (SAE AS5506C) into a :class:`lark.Tree` whose node names and child
layouts are documented in ``aadl.lark``; turning that tree into model objects is the
builder's job.  Every syntax problem — an unexpected token or character, an unterminated
string or annex text, a premature end of file, bytes that are not UTF-8 — is raised as
:class:`rosaadl.errors.AadlSyntaxError` with file, line and column, and a message naming
what was found and what was expected.

Tokens and trees:

* ``ANNEX_TEXT`` tokens hold annex subclauses and libraries verbatim, delimiters included:
  ``token.value[3:-3]`` is exactly the text between ``{**`` and ``**}``.
* ``STRING`` tokens keep their quotes and escapes (``""`` or ``\\"``).
* Tokens carry ``line``/``column``/``end_line``/``end_column``/``start_pos``/``end_pos``, and
  every tree node has the same in ``meta``, computed on first access (see :class:`AadlTree`).

How it runs: lark compiles ``aadl.lark`` into LALR(1) tables and per-rule tree builders, once
per process (lazily; the tables are also cached in the user's cache directory, see
:func:`_cache_file`).  A small loop in :class:`_Reader` reads the text with one regular
expression made from the grammar's own terminals, finds the ~80 case-insensitive keywords by
a dictionary look-up, and drives those tables.  The trees are exactly those lark's own LALR
front end builds from the grammar, at about twice its speed.  Like lark's contextual lexer, a
reserved word that the parser cannot take where it stands, but where it can take an
identifier (and the next token after it), is read as an identifier: real models name
features ``data`` or ``source``.
"""

from __future__ import annotations

import codecs
import gc
import os
import re
import sys
from collections.abc import Callable, Mapping, Sequence
from functools import lru_cache
from importlib import resources
from pathlib import Path

from lark import Lark, Token, Tree
from lark.lexer import PatternRE, PatternStr, TerminalDef
from lark.parsers.lalr_analysis import Shift
from lark.tree import Meta

from rosaadl.errors import AadlSyntaxError

__all__ = ["parse", "decode", "AADL_GRAMMAR"]


def _grammar_text() -> str:
    if __package__:  # imported as rosaadl.importers.aadl_syntax: aadl.lark is package data
        return resources.files(__package__).joinpath("aadl.lark").read_text(encoding="utf-8")
    return Path(__file__).with_name("aadl.lark").read_text(encoding="utf-8")  # loaded by path


#: The grammar text (``aadl.lark``, package data of ``rosaadl.importers``).
AADL_GRAMMAR: str = _grammar_text()

_START = "specification"

# Token types for text that cannot be read.  No grammar rule accepts them, so the parser
# rejects them with the list of tokens it expected at that point.
_BAD_CHARACTER = "BAD_CHARACTER"
_UNTERMINATED_STRING = "UNTERMINATED_STRING"
_UNTERMINATED_ANNEX = "UNTERMINATED_ANNEX"

# How terminals that are neither punctuation nor keywords are named in messages.
_TERMINAL_NAMES = {
    "ID": "identifier",
    "INTEGER": "integer literal",
    "REAL": "real literal",
    "STRING": "string literal",
    "ANNEX_TEXT": "annex text {** ... **}",
    "ANNEX_PREFIX": "'{annex}**'",
    "_IN_BINDING": "'in binding'",
    "$END": "end of file",
}

# A keyword terminal in aadl.lark:  _WORD.2: /word\b/i
_KEYWORD_REGEX = re.compile(r"([a-z]+)\\b")

# (type, text, start, line, column, end_line, end_column, end): the arguments of lark.Token
_Lexeme = tuple[str, str, int, int, int, int, int, int]


class AadlTree(Tree):
    """A lark ``Tree`` whose ``meta`` is computed from its tokens when first asked for.

    ``meta.line``/``column``/``start_pos`` come from the first token under the node and
    ``meta.end_line``/``end_column``/``end_pos`` from the last one.  Keywords and punctuation
    are not kept in the tree, so a node starts at its first kept token (usually its name).  A
    node without any token (a flag such as ``refined``) has ``meta.empty == True``.  This is
    the information lark's ``propagate_positions`` gives, without its cost while parsing.
    """

    @property
    def meta(self) -> Meta:
        meta = self._meta
        if meta is None:
            meta = self._meta = _token_span(self.children)
        return meta


def _token_span(children: list) -> Meta:
    meta = Meta()
    for child in children:
        if isinstance(child, Token):
            meta.line, meta.column, meta.start_pos = child.line, child.column, child.start_pos
            break
        if isinstance(child, Tree) and not child.meta.empty:
            first = child.meta
            meta.line, meta.column, meta.start_pos = first.line, first.column, first.start_pos
            break
    else:
        return meta
    for child in reversed(children):
        if isinstance(child, Token):
            meta.end_line, meta.end_column, meta.end_pos = child.end_line, child.end_column, child.end_pos
            break
        if isinstance(child, Tree) and not child.meta.empty:
            last = child.meta
            meta.end_line, meta.end_column, meta.end_pos = last.end_line, last.end_column, last.end_pos
            break
    meta.empty = False
    return meta


class _Scanner:
    """The regular expressions of the grammar's terminals, with keywords in a dictionary.

    ``skip`` matches white space and comments (the grammar's ``%ignore`` terminals); ``token``
    matches one token: every terminal except the keywords, tried in lark's usual order
    (priority, then longest pattern first).  Each keyword terminal ``_WORD: /word\\b/i`` is
    found instead by looking the lower-cased text of an identifier up in ``keywords``.
    """

    def __init__(self, terminals: Sequence[TerminalDef], ignore: Sequence[str]) -> None:
        self.keywords: dict[str, str] = {}
        skipped = []
        others = []
        for term in terminals:
            pattern = term.pattern
            word = _KEYWORD_REGEX.fullmatch(pattern.value) if isinstance(pattern, PatternRE) else None
            if word and set(pattern.flags) == {"i"}:
                self.keywords[word.group(1)] = term.name
            elif term.name in ignore:
                skipped.append(term)
            else:
                others.append(term)
        others.sort(key=lambda t: (-t.priority, -t.pattern.max_width, -len(t.pattern.value), t.name))
        # a possessive repeat: the gap is matched keeping no backtracking state per part of it
        self.skip = re.compile("(?:" + "|".join(t.pattern.to_regexp() for t in skipped) + ")++")
        self.token = re.compile("|".join(f"(?P<{t.name}>{t.pattern.to_regexp()})" for t in others))
        # "{**" that did not match ANNEX_TEXT (no closing "**}") would be read as "{" "*" "*"
        self.left_brace = next((t.name for t in others if t.pattern.value == "{"), None)

    def peek(self, text: str, pos: int) -> str | None:
        """The type of the first token at or after ``pos`` (None at the end of the text)."""
        skipped = self.skip.match(text, pos)
        if skipped is not None:
            pos = skipped.end()
        if pos >= len(text):
            return None
        m = self.token.match(text, pos)
        if m is None:
            return _BAD_CHARACTER
        kind = m.lastgroup
        if kind == "ID":
            return self.keywords.get(m.group().lower(), "ID")
        if kind == self.left_brace and text.startswith("{**", pos):
            return _UNTERMINATED_ANNEX
        return kind


class _Unexpected(Exception):
    """The parser met a token it cannot take (turned into an AadlSyntaxError by ``parse``)."""

    def __init__(
        self, lexeme: _Lexeme | None, stack: list[int], previous: tuple[str | None, str | None]
    ) -> None:
        super().__init__(lexeme)
        self.lexeme = lexeme  # None at the end of the text
        self.stack = stack
        self.previous = previous  # (type, text) of the token before


class _Reader:
    """The compiled grammar: lark's LALR(1) tables and tree builders, driven by our own loop.

    lark builds the parse table and the per-rule tree callbacks from ``aadl.lark``; the loop
    in :meth:`parse` is the textbook LALR driver over that table, fed by :class:`_Scanner`.  It
    replaces lark's lexer and ``ParserState.feed_token`` because it must look at the table
    anyway (to read reserved words as names), and because it can skip building ``Token``
    objects for the punctuation and keywords that no rule keeps in the tree.
    """

    def __init__(self) -> None:
        self.lark = Lark(
            AADL_GRAMMAR,
            parser="lalr",
            lexer="basic",  # lark's lexer is not used: see _Scanner
            start=_START,
            maybe_placeholders=True,
            tree_class=AadlTree,
            cache=_cache_file(),
        )
        conf = self.lark.lexer_conf  # (set both when built and when loaded from the cache)
        self.scanner = _Scanner(conf.terminals, conf.ignore)
        self.keyword_types = frozenset(self.scanner.keywords.values())
        self.names: dict[str, str] = {}
        for term in conf.terminals:
            if term.name in _TERMINAL_NAMES:
                self.names[term.name] = _TERMINAL_NAMES[term.name]
            elif isinstance(term.pattern, PatternStr):
                self.names[term.name] = repr(term.pattern.value)
            elif term.name in self.keyword_types:
                self.names[term.name] = repr(term.name.lstrip("_").lower())

        # Which tokens become lark Token objects: those that rules keep in the tree (ID, ...)
        # at once; keywords and punctuation that only "!" rules keep (category, direction,
        # sign, ...) travel as plain tuples that those rules' callbacks turn into Tokens;
        # all others as plain strings, which the tree builder drops.
        self.kept = frozenset(
            sym.name
            for rule in self.lark.rules
            if not rule.options.keep_all_tokens
            for sym in rule.expansion
            if sym.is_term and not sym.filter_out
        )
        self.kept_by_bang_rules = frozenset(
            sym.name
            for rule in self.lark.rules
            if rule.options.keep_all_tokens
            for sym in rule.expansion
            if sym.is_term and sym.name not in self.kept
        )
        parse_conf = self.lark.parse_interactive(start=_START).parser_state.parse_conf
        self.start_state: int = parse_conf.start_state
        self.end_state: int = parse_conf.end_state
        reductions = {
            rule: (
                len(rule.expansion),
                sys.intern(str(rule.origin.name)),
                _tokens_first(callback) if rule.options.keep_all_tokens else callback,
            )
            for rule, callback in parse_conf.callbacks.items()
            if not isinstance(rule, str)
        }
        # actions[state][symbol] = (True, next state) for a shift or a goto,
        #                          (False, (size, rule name, tree callback)) for a reduction
        self.actions: list[dict[str, tuple]] = [{} for _ in range(max(parse_conf.states) + 1)]
        for state, row in parse_conf.states.items():
            self.actions[state] = {
                sys.intern(str(symbol)): (True, arg) if action is Shift else (False, reductions[arg])
                for symbol, (action, arg) in row.items()
            }

    def parse(self, text: str, hooks: Mapping[str, Callable[[Tree], object]]) -> object:
        actions = self.actions
        kept = self.kept
        kept_later = self.kept_by_bang_rules
        scanner = self.scanner
        skip = scanner.skip.match
        match = scanner.token.match
        keywords = scanner.keywords
        left_brace = scanner.left_brace
        stack = [self.start_state]
        values: list = []
        prev_kind = prev_value = None
        end = len(text)
        pos, line, line_start = 0, 1, 0
        next_newline = text.find("\n")
        if next_newline < 0:
            next_newline = end
        while True:
            # ---- the next token: kind, value, pos .. stop
            skipped = skip(text, pos)
            if skipped is not None:
                pos = skipped.end()
            while next_newline < pos:
                line += 1
                line_start = next_newline + 1
                next_newline = text.find("\n", line_start)
                if next_newline < 0:
                    next_newline = end
            if pos >= end:
                break
            m = match(text, pos)
            if m is None or (m.lastgroup == left_brace and text.startswith("{**", pos)):
                lexeme = _bad_lexeme(text, pos, line, pos - line_start + 1)
                raise _Unexpected(lexeme, list(stack), (prev_kind, prev_value))
            kind = m.lastgroup
            value = m.group()
            stop = m.end()
            row = actions[stack[-1]]
            if kind == "ID":
                keyword = keywords.get(value.lower())
                if keyword is not None and (
                    keyword in row or "ID" not in row or not self._name_fits(stack, scanner.peek(text, stop))
                ):
                    kind = keyword  # else: a reserved word used as a name where no keyword fits
            # ---- the LALR(1) step: reductions, then the shift of the token
            while True:
                entry = row.get(kind)
                if entry is None:
                    lexeme = _lexeme(kind, value, text, pos, stop, line, line_start)
                    raise _Unexpected(lexeme, list(stack), (prev_kind, prev_value))
                if entry[0]:
                    stack.append(entry[1])
                    if kind in kept:
                        if next_newline < stop:  # the token spans lines
                            values.append(Token(*_lexeme(kind, value, text, pos, stop, line, line_start)))
                        else:
                            column = pos - line_start + 1
                            values.append(
                                Token(kind, value, pos, line, column, line, column + stop - pos, stop)
                            )
                    elif kind in kept_later:
                        column = pos - line_start + 1
                        values.append((kind, value, pos, line, column, line, column + stop - pos, stop))
                    else:
                        values.append(value)  # dropped by the tree builder
                    break
                size, origin, callback = entry[1]
                if size:
                    children = values[-size:]
                    del values[-size:]
                    del stack[-size:]
                else:
                    children = []
                node = callback(children)
                if origin in hooks:
                    node = hooks[origin](node)
                values.append(node)
                stack.append(actions[stack[-1]][origin][1])
                row = actions[stack[-1]]
            prev_kind, prev_value = kind, value
            pos = stop
        while True:  # the end of the text: reduce until the start symbol is complete
            entry = actions[stack[-1]].get("$END")
            if entry is None or entry[0]:
                raise _Unexpected(None, list(stack), (prev_kind, prev_value))
            size, origin, callback = entry[1]
            children = values[-size:] if size else []
            if size:
                del values[-size:]
                del stack[-size:]
            node = callback(children)
            if origin in hooks:
                node = hooks[origin](node)
            values.append(node)
            stack.append(actions[stack[-1]][origin][1])
            if stack[-1] == self.end_state:
                return values[-1]

    def shift(self, stack: list[int], kind: str) -> list[int] | None:
        """The state stack after the parser takes a token of type ``kind``, or None if it cannot.

        LALR tables may list a token as a look-ahead of a reduction although the parser fails
        right after reducing; following the reductions on a copy of the stack tells.
        """
        actions = self.actions
        stack = list(stack)
        while True:
            entry = actions[stack[-1]].get(kind)
            if entry is None:
                return None
            if entry[0]:
                stack.append(entry[1])
                return stack
            size, origin, _ = entry[1]
            if size:
                del stack[-size:]
            stack.append(actions[stack[-1]][origin][1])
            if stack[-1] == self.end_state:
                return stack

    def _name_fits(self, stack: list[int], following: str | None) -> bool:
        """Can the parser take an identifier here, and a token of type ``following`` after it?

        Checked before reading a misplaced keyword as a name, so that a missing ``end`` is
        reported at the keyword that follows rather than one token later.
        """
        after = self.shift(stack, "ID")
        if after is None:
            return False
        if self.shift(after, "$END" if following is None else following) is not None:
            return True
        return following in self.keyword_types and self.shift(after, "ID") is not None

    def expected(self, stack: list[int]) -> list[str]:
        """The readable names of the tokens the parser could take with this state stack."""
        row = self.actions[stack[-1]]
        kinds = [kind for kind in row if kind.isupper() and self.shift(stack, kind) is not None]
        return sorted({self.names.get(kind, _TERMINAL_NAMES.get(kind, kind)) for kind in kinds})


def _tokens_first(callback: Callable[[list], object]) -> Callable[[list], object]:
    """Wrap the tree callback of a "!" rule: its keyword and punctuation children arrive as
    lexeme tuples (see ``_Reader.kept_by_bang_rules``) and become Tokens here."""

    def build(children: list) -> object:
        return callback([Token(*child) if type(child) is tuple else child for child in children])

    return build


def _lexeme(kind: str, value: str, text: str, pos: int, stop: int, line: int, line_start: int) -> _Lexeme:
    """A token's position, for a token that may span lines (``line`` is where it starts)."""
    newlines = value.count("\n")
    if not newlines:
        return (kind, value, pos, line, pos - line_start + 1, line, stop - line_start + 1, stop)
    last_start = pos + value.rindex("\n") + 1
    return (kind, value, pos, line, pos - line_start + 1, line + newlines, stop - last_start + 1, stop)


def _bad_lexeme(text: str, pos: int, line: int, column: int) -> _Lexeme:
    if text.startswith("{**", pos):
        kind, value = _UNTERMINATED_ANNEX, "{**"
    elif text[pos] == '"':
        kind, value = _UNTERMINATED_STRING, '"'
    else:
        kind, value = _BAD_CHARACTER, text[pos]
    return (kind, value, pos, line, column, line, column + len(value), pos + len(value))


def _cache_file() -> str | bool:
    """Where lark caches the compiled parse tables (about 5x faster start-up), or False.

    The file lives in the user's cache directory (``$ROSAADL_CACHE_DIR``, else
    ``$XDG_CACHE_HOME/rosaadl``, else ``~/.cache/rosaadl``), never in the source tree.  lark
    stores a hash of the grammar, the options and the lark and Python versions in it and
    rebuilds (and rewrites) a file that does not match or cannot be read, so a stale or
    damaged cache costs one slow start.  Set ``ROSAADL_CACHE_DIR`` to an empty string to
    disable the cache.
    """
    setting = os.environ.get("ROSAADL_CACHE_DIR")
    if setting == "":
        return False
    try:
        if setting:
            folder = Path(setting)
        else:
            folder = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "rosaadl"
        folder.mkdir(parents=True, exist_ok=True)
    except (OSError, RuntimeError):  # RuntimeError: no home directory
        return False
    return str(folder / "aadl-lalr.lark-cache")


@lru_cache(maxsize=1)
def _reader() -> _Reader:
    return _Reader()


def decode(data: bytes, filename: str) -> str:
    """AADL text from UTF-8 bytes (a leading byte-order mark dropped); bytes that are not UTF-8
    are an :class:`AadlSyntaxError` at their line and column."""
    if data.startswith(codecs.BOM_UTF8):
        data = data[len(codecs.BOM_UTF8) :]
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        offset = exc.start
        line = data.count(b"\n", 0, offset) + 1
        column = offset - (data.rfind(b"\n", 0, offset) + 1) + 1
        raise AadlSyntaxError(
            f"invalid UTF-8 byte 0x{data[offset]:02x} at byte offset {offset}: AADL text must be UTF-8",
            file=filename,
            line=line,
            column=column,
        ) from None


def _shorten(text: str, limit: int = 40) -> str:
    text = " ".join(text.split())
    return text if len(text) <= limit else text[: limit - 3] + "..."


#: what a syntax error says instead of the text it met, for a file that must not be echoed
_NOT_SHOWN = "(not shown: the file lies outside the input folder)"


def _syntax_error(exc: _Unexpected, text: str, filename: str, quote: bool = True) -> AadlSyntaxError:
    expected = _reader().expected(exc.stack)
    if not expected:
        wanted = ""
    elif len(expected) == 1:
        wanted = f", expected {expected[0]}"
    else:
        wanted = ", expected one of: " + ", ".join(expected)
    if exc.lexeme is None:
        line = text.count("\n") + 1
        column = len(text) - (text.rfind("\n") + 1) + 1
        return AadlSyntaxError(f"unexpected end of file{wanted}", file=filename, line=line, column=column)
    kind, value, _, line, column = exc.lexeme[:5]
    if kind == _UNTERMINATED_ANNEX:
        message = "unterminated annex text: '{**' without a closing '**}'"
    elif kind == _UNTERMINATED_STRING:
        message = "unterminated string literal: '\"' without a closing '\"'"
    elif not quote:
        what = "character" if kind == _BAD_CHARACTER else "text"
        message = f"unexpected {what} {_NOT_SHOWN}{wanted}"
    elif kind == _BAD_CHARACTER:
        message = f"unexpected character {value!r}{wanted}"
    else:
        previous_kind, previous_value = exc.previous
        after = f" after {previous_value!r}" if previous_kind == "ID" else ""
        message = f"unexpected {_shorten(value)!r}{after}{wanted}"
    return AadlSyntaxError(message, file=filename, line=line, column=column)


def parse(
    text: str | bytes,
    filename: str = "<string>",
    *,
    quote: bool = True,
    hooks: Mapping[str, Callable[[Tree], object]] | None = None,
) -> Tree[Token]:
    """Parse AADL text into a lark tree rooted at a ``specification`` node.

    ``text`` is a ``str`` or UTF-8 ``bytes`` (a leading byte-order mark is dropped).  The
    children of the root are ``package`` and ``property_set`` nodes; see ``aadl.lark`` for the
    layout of every node.  Raises :class:`AadlSyntaxError` (file, line, column, and what was
    expected) on any syntax or encoding error; without ``quote`` its message holds nothing of
    the text (not the token met, nor the one before it), for a file whose content must not be
    echoed (one reached through a symbolic link out of the folder the user named).

    ``hooks`` map rule names (``package``, ``component_type``, ...) to functions called with
    each node of that rule as soon as the parser has made it (its children complete, in text
    order); what a hook returns takes the node's place in its parent.  A reader builds its own
    objects that way while parsing, and the tree of a part already built is released at once:
    the whole tree of a large text is never held.  An exception a hook raises ends the parse.

    The cyclic garbage collector is paused while the tree is built: the tree has no cycles,
    and collections triggered by its many new objects would make large inputs 2-3x slower.
    """
    if isinstance(text, bytes | bytearray | memoryview):
        text = decode(bytes(text), filename)
    if text.startswith("\ufeff"):
        text = text[1:]
    reader = _reader()
    collecting = gc.isenabled()
    if collecting:
        gc.disable()
    try:
        return reader.parse(text, hooks or {})
    except _Unexpected as exc:
        raise _syntax_error(exc, text, filename, quote) from None
    finally:
        if collecting:
            gc.enable()
