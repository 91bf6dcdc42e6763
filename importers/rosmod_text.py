"""Textual ROSMOD projects (v0.3, v0.2, v0.1 and the v0.4 jsonpickle file) → ``rosmod.ecore`` models.

Layouts read by :func:`read_project`:

* **v0.3** — a folder with a ``<name>.rosmod`` marker and ``01-Software/`` (one ``.rml`` file,
  ``msg/<pkg>.<Name>.msg``, ``srv/<pkg>.<Name>.srv``, ``abl/`` and ``pnp/`` side files),
  ``02-Hardware/*.rhw`` (one :class:`System` per file) and ``03-Deployment/*.rdp`` (one
  :class:`Deployment` per file); the older folder names ``01-Software-Configuration/``,
  ``02-Hardware-Configuration/`` are accepted too;
* **v0.2** — the same folders (or the three files side by side) with a single-workspace ``.rml``
  holding ``messages``/``services``/``components``/``nodes`` blocks, ``host`` hardware and
  ``host_instance`` deployments;
* **v0.1** — a ``.rosml`` file (``workspace W;`` + v0.2-style packages; software only);
* **v0.4** — the jsonpickle ``.rml`` of ROSMOD's Python tool, read without unpickling anything.

The parsers are hand-written and tolerant of what real files do: ``/* */`` and ``//``
comments, CRLF, keys with spaces and ``?`` (``Is Periodic? = true;``), properties in any order,
unknown statements (skipped with a warning). Names are resolved after parsing; every problem
(syntax, unknown host, unknown package or component, duplicate name, unknown message type of
one of the project's own packages) is collected with its file, line and column and raised
together as a :class:`RosmodImportError`. Types of packages that are not in the project
(``std_msgs/String``) are kept as external references, not errors.

Mapping notes (ROSMOD facts without a slot in the metamodel go to ``properties`` lists):

* v0.2 ``provides S;`` / ``requires S;`` become a server ``S_server`` / client ``S_client`` (the
  names ROSMOD v0.3 gave them when the AGSE project was upgraded); v0.2 software nodes are kept
  as package properties ``node:<name>`` (JSON object instance → ``pkg/Component``) and each
  ``node_instance`` becomes a deployment :class:`Node` with those component instances;
  ``host_instance`` properties are kept as deployment properties ``host_instance:<host>``;
* v0.3 ``.abl``/``.pnp`` side files become component properties ``abl:<port>``/``pnp:<port>``;
  message files of a package that the ``.rml`` does not define are skipped with a warning, as
  ROSMOD itself did;
* a host defined twice in one ``.rhw`` is a redefinition: ROSMOD resolves ``<hardware>/<host>``
  to the later definition, so the reader keeps that one and warns (``strict=True`` makes it an
  error, like every other duplicate name);
* line and column are kept on every element read from text; ``sourceFile`` (relative to the
  project folder) on the software, each system and each deployment.
"""

from __future__ import annotations

import bisect
import functools
import json
import logging
import os
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from decimal import Decimal, InvalidOperation
from pathlib import Path
from typing import Any

from pyecore.ecore import EObject

from rosaadl import metamodels
from rosaadl.errors import (
    Diagnostic,
    ImportFormatError,
    Location,
    NameResolutionError,
    ParseError,
    RosaadlError,
)
from rosaadl.importers import ros_msg

__all__ = [
    "MAX_FILE_BYTES",
    "RosmodImportError",
    "read_project",
    "read_software_file",
    "is_rosmod_project",
    "summarize",
    "scheme_literal",
]

log = logging.getLogger(__name__)

#: Largest model file read (text or JSON); larger files are refused with a located error.
MAX_FILE_BYTES = 64 * 1024 * 1024
_MAX_DEPTH = 200

_SOFTWARE_DIRS = ("01-Software", "01-Software-Configuration")
_HARDWARE_DIRS = ("02-Hardware", "02-Hardware-Configuration")
_DEPLOYMENT_DIRS = ("03-Deployment", "03-Deployment-Configuration")
_SCHEMES = ("FIFO", "PFIFO", "EDF")


class RosmodImportError(ImportFormatError):
    """One or more located problems in a ROSMOD project; ``errors`` lists every one of them."""

    stage = "import"

    def __init__(self, errors: Sequence[RosaadlError]) -> None:
        first = errors[0]
        more = len(errors) - 1
        message = first.message if not more else f"{first.message} (and {more} more)"
        super().__init__(message, first.location, errors=list(errors))

    def __str__(self) -> str:
        return "\n".join(str(e) for e in self.errors)

    def diagnostics(self) -> list[Diagnostic]:
        return [e.as_diagnostic() for e in self.errors]


# =========================================================================== tokenizer


@dataclass(slots=True)
class _Token:
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


def _tokenize(text: str, filename: str) -> list[_Token]:
    """Tokens with 1-based line and column (a tab counts as one column)."""
    newlines = [m.start() for m in re.finditer("\n", text)]
    line_of = bisect.bisect_right

    def place(offset: int) -> tuple[int, int]:
        index = line_of(newlines, offset - 1) if offset else 0
        line_start = newlines[index - 1] + 1 if index else 0
        return index + 1, offset - line_start + 1

    tokens: list[_Token] = []
    append = tokens.append
    for match in _TOKEN_RE.finditer(text):
        kind = match.lastgroup
        if kind is None or kind == "block" or kind == "line_comment":
            continue
        start = match.start(kind)
        line, column = place(start)
        if kind == "word":
            append(_Token("word", match.group(kind), line, column, start, match.end()))
        elif kind == "string":
            raw = match.group(kind)[1:-1]
            if "\\" in raw:
                raw = _ESCAPE_RE.sub(lambda m: _STRING_ESCAPES.get(m.group(1), m.group(0)), raw)
            append(_Token("string", raw, line, column, start, match.end()))
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
            append(_Token("punct", char, line, column, start, match.end()))
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


# =========================================================================== generic blocks


@dataclass
class _Stmt:
    """``head… ;`` or ``head… = value… ;`` or ``head… { body }``."""

    head: list[_Token]
    value: list[_Token] | None = None
    body: list[_Stmt] | None = None
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
    def value_token(self) -> _Token:
        return self.value[0] if self.value else self.head[-1]


def _is(token: _Token, text: str) -> bool:
    return token.kind == "punct" and token.text == text


def _parse_blocks(text: str, filename: str) -> list[_Stmt]:
    """Parse ``text`` into nested statements (iteratively: no recursion limit on hostile input)."""
    tokens = _tokenize(text, filename)
    root: list[_Stmt] = []
    stack: list[tuple[list[_Stmt], _Stmt | None, _Token | None]] = [(root, None, None)]
    i = 0
    n = len(tokens)
    while i < n:
        tok = tokens[i]
        body = stack[-1][0]
        if _is(tok, ";"):
            i += 1
            continue
        if _is(tok, "}"):
            if len(stack) == 1:
                raise ParseError(
                    "unexpected '}' (no block is open here)", file=filename, line=tok.line, column=tok.column
                )
            stack.pop()
            i += 1
            continue
        head: list[_Token] = []
        while i < n and not (tokens[i].kind == "punct" and tokens[i].text in "{=;}"):
            head.append(tokens[i])
            i += 1
        if i >= n:
            last = head[-1]
            raise ParseError(
                f"expected ';' or '{{' after {text[head[0].start : last.end].strip()!r}, "
                "found the end of the file",
                file=filename,
                line=last.line,
                column=last.column,
            )
        stop = tokens[i]
        if not head:
            raise ParseError(
                f"expected a name before {stop.text!r}", file=filename, line=stop.line, column=stop.column
            )
        if stop.text == "=":
            i += 1
            value: list[_Token] = []
            while i < n and not (tokens[i].kind == "punct" and tokens[i].text in ";{}="):
                value.append(tokens[i])
                i += 1
            if i >= n or tokens[i].text != ";":
                where = tokens[i] if i < n else (value[-1] if value else stop)
                found = f"{where.text!r}" if i < n else "the end of the file"
                raise ParseError(
                    f"expected ';' after the value of {text[head[0].start : head[-1].end].strip()!r}, "
                    f"found {found}",
                    file=filename,
                    line=where.line,
                    column=where.column,
                )
            if not value:
                raise ParseError(
                    f"expected a value after '=' for {text[head[0].start : head[-1].end].strip()!r}",
                    file=filename,
                    line=stop.line,
                    column=stop.column,
                )
            body.append(_Stmt(head, value=value, source=text))
            i += 1
        elif stop.text == ";":
            body.append(_Stmt(head, source=text))
            i += 1
        elif stop.text == "{":
            stmt = _Stmt(head, body=[], source=text)
            body.append(stmt)
            if len(stack) > _MAX_DEPTH:
                raise ParseError(
                    f"blocks nested more than {_MAX_DEPTH} deep",
                    file=filename,
                    line=stop.line,
                    column=stop.column,
                )
            stack.append((stmt.body, stmt, stop))
            i += 1
        else:  # "}" right after a head: a statement without its ';'
            raise ParseError(
                f"expected ';' or '{{' after {text[head[0].start : head[-1].end].strip()!r}, found '}}'",
                file=filename,
                line=stop.line,
                column=stop.column,
            )
    if len(stack) > 1:
        _, stmt, brace = stack[-1]
        assert stmt is not None and brace is not None
        chain = " > ".join(s.key for _, s, _ in stack[1:] if s is not None)
        raise ParseError(
            f"unclosed '{{' of {stmt.key!r} (in {chain}): expected '}}' before the end of the file",
            file=filename,
            line=brace.line,
            column=brace.column,
        )
    return root


# =========================================================================== helpers


class _Context:
    """Errors and warnings of one import run (no global state)."""

    def __init__(self, warnings: list[Diagnostic] | None, strict: bool = False) -> None:
        self.errors: list[RosaadlError] = []
        self.warnings = warnings
        self.strict = strict

    def error(self, exc: RosaadlError) -> None:
        if isinstance(exc, (RosmodImportError, ros_msg.RosMessageError)):
            self.errors.extend(exc.errors)
        else:
            self.errors.append(exc)

    def warn(self, message: str, file: str | None = None, line: int | None = None, column: int | None = None):
        diag = Diagnostic("warning", message, Location(file=file, line=line, column=column))
        log.warning("%s", diag)
        if self.warnings is not None:
            self.warnings.append(diag)

    def raise_if_errors(self) -> None:
        if self.errors:
            raise RosmodImportError(self.errors)


def _read_text(path: Path, shown: str) -> str:
    try:
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            raise ParseError(
                f"the file is {size} bytes; ROSMOD model files above {MAX_FILE_BYTES} bytes are refused",
                file=shown,
            )
        data = path.read_bytes()
    except OSError as exc:
        raise ParseError(f"cannot read the file: {exc.strerror}", file=shown) from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        column = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
        raise ParseError(
            f"not UTF-8 text (byte 0x{data[exc.start]:02x}); expected a ROSMOD text file",
            file=shown,
            line=line,
            column=column,
        ) from None


_NUMBER_RE = re.compile(r"^([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)\s*(s|ms|us|ns)?$")
_UNIT_SCALE = {
    "s": Decimal(1),
    "ms": Decimal("0.001"),
    "us": Decimal("0.000001"),
    "ns": Decimal("0.000000001"),
}


def _seconds(stmt: _Stmt, filename: str) -> Decimal:
    text = stmt.value_text
    match = _NUMBER_RE.match(text)
    token = stmt.value_token
    if not match:
        raise ParseError(
            f"{stmt.key} = {text!r}: expected a number of seconds (such as 0.5, or 500ms in v0.2 files)",
            file=filename,
            line=token.line,
            column=token.column,
        )
    try:
        value = Decimal(match.group(1))
    except InvalidOperation:  # pragma: no cover - the regex admits only valid decimals
        raise ParseError(
            f"{text!r} is not a number", file=filename, line=token.line, column=token.column
        ) from None
    if value < 0:
        raise ParseError(
            f"{stmt.key} = {text}: a time must not be negative",
            file=filename,
            line=token.line,
            column=token.column,
        )
    unit = match.group(2)
    return value * _UNIT_SCALE[unit] if unit and unit != "s" else value


def _integer(stmt: _Stmt, filename: str, ctx: _Context) -> int:
    text = stmt.value_text
    token = stmt.value_token
    try:
        return int(text)
    except ValueError:
        pass
    try:
        number = Decimal(text)
    except InvalidOperation:
        number = None
    if number is not None and number == number.to_integral_value():
        ctx.warn(
            f"{stmt.key} = {text}: read as the integer {int(number)}", filename, token.line, token.column
        )
        return int(number)
    raise ParseError(
        f"{stmt.key} = {text!r}: expected an integer", file=filename, line=token.line, column=token.column
    )


@functools.cache
def _rosmod_class(name: str) -> Any:
    return metamodels.load().rosmod.getEClassifier(name)


def _new(class_name: str, /, **values: Any) -> EObject:
    """A ``rosmod`` object; features given as None stay unset (the metamodel default)."""
    return _rosmod_class(class_name)(**{k: v for k, v in values.items() if v is not None})


def scheme_literal(text: str) -> Any:
    """The ``rosmod.SchedulingScheme`` literal called ``text`` (FIFO, PFIFO or EDF)."""
    enum = metamodels.load().rosmod.getEClassifier("SchedulingScheme")
    return enum.from_string(text)


def _prop(key: str, value: str, stmt: _Stmt | None = None) -> EObject:
    return _new(
        "Property",
        key=key,
        value=value,
        line=stmt.line if stmt is not None else None,
        column=stmt.column if stmt is not None else None,
    )


def _located(obj_kwargs: dict[str, Any], stmt: _Stmt) -> dict[str, Any]:
    obj_kwargs["line"] = stmt.line
    obj_kwargs["column"] = stmt.column
    return obj_kwargs


def _typed_head(stmt: _Stmt, filename: str, what: str) -> tuple[str, str, _Token]:
    """``kind <ref> name`` → (ref as written without spaces, name, name token)."""
    head = stmt.head
    try:
        lt = next(k for k, t in enumerate(head) if _is(t, "<"))
        gt = next(k for k, t in enumerate(head) if _is(t, ">"))
    except StopIteration:
        lt = gt = -1
    names = head[gt + 1 :] if gt > lt >= 0 else []
    ref_tokens = head[lt + 1 : gt] if gt > lt >= 0 else []
    if lt != 1 or not ref_tokens or len(names) != 1 or names[0].kind != "word":
        raise ParseError(
            f"malformed {what}: expected '{stmt.keyword} <package/Type> name' (found {stmt.key!r})",
            file=filename,
            line=stmt.line,
            column=stmt.column,
        )
    ref = "".join(t.text for t in ref_tokens)
    return ref, names[0].text, names[0]


def _name_of(stmt: _Stmt, filename: str, what: str) -> str:
    if len(stmt.head) != 2 or stmt.head[1].kind != "word":
        raise ParseError(
            f"malformed {what}: expected '{stmt.keyword} <name>' (found {stmt.key!r})",
            file=filename,
            line=stmt.line,
            column=stmt.column,
        )
    return stmt.head[1].text


def _check_unique(
    items: Iterable[EObject], what: str, owner: str, filename: str | None, ctx: _Context, key=None
) -> None:
    items = list(items)
    all_names = [key(o) if key else o.name for o in items]
    if len(set(all_names)) == len(all_names):
        return
    seen: dict[str, EObject] = {}
    ordered = sorted(items, key=lambda o: (getattr(o, "line", 0) or 0, getattr(o, "column", 0) or 0))
    for obj in ordered:
        name = key(obj) if key else obj.name
        if name is None:
            continue
        first = seen.get(name)
        if first is None:
            seen[name] = obj
            continue
        at = f" (first defined at line {first.line})" if getattr(first, "line", None) else ""
        ctx.error(
            NameResolutionError(
                f"duplicate {what} name {name!r} in {owner}{at}",
                file=filename,
                line=getattr(obj, "line", None),
                column=getattr(obj, "column", None),
            )
        )


# =========================================================================== software (.rml)


@dataclass
class _SoftwareInfo:
    """What resolution needs to know about the software besides the model objects."""

    filename: str
    # v0.2 software nodes: package → node name → [(instance, component name, stmt)]
    nodes: dict[str, dict[str, list[tuple[str, str, _Stmt]]]] = field(default_factory=dict)
    # where each port type was written, for located resolution errors
    port_sites: list[tuple[EObject, str, str, int, int]] = field(default_factory=list)
    # the .msg/.srv file of each message and service read from a side file
    sources: dict[int, str] = field(default_factory=dict)


def _detect_rml_version(stmts: list[_Stmt]) -> str:
    if any(s.keyword == "workspace" for s in stmts):
        return "0.1"
    legacy = {"messages", "services", "components", "nodes"}
    for stmt in stmts:
        if stmt.keyword == "package" and stmt.body and any(c.keyword in legacy for c in stmt.body):
            return "0.2"
    return "0.3"


def _timer(stmt: _Stmt, filename: str, ctx: _Context, comp: EObject) -> EObject:
    name = _name_of(stmt, filename, "timer")
    timer = _new("Timer", **_located({"name": name}, stmt))
    for item in stmt.body or []:
        try:
            if item.value is None:
                raise ParseError(
                    f"unexpected {item.key!r} in timer {name!r} (expected period/priority/deadline = value;)",
                    file=filename,
                    line=item.line,
                    column=item.column,
                )
            if item.key == "period":
                timer.period = _seconds(item, filename)
            elif item.key == "deadline":
                timer.deadline = _seconds(item, filename)
            elif item.key == "priority":
                timer.priority = _integer(item, filename, ctx)
            else:
                ctx.warn(
                    f"timer {name!r}: unknown setting {item.key!r} kept as a component property",
                    filename,
                    item.line,
                    item.column,
                )
                comp.properties.append(_prop(f"{name}.{item.key}", item.value_text, item))
        except ParseError as exc:
            ctx.error(exc)
    return timer


def _callback_settings(port: EObject, stmt: _Stmt, filename: str, ctx: _Context, comp: EObject) -> None:
    for item in stmt.body or []:
        try:
            if item.value is None:
                raise ParseError(
                    f"unexpected {item.key!r} in {stmt.keyword} {port.name!r} "
                    "(expected priority/deadline = value;)",
                    file=filename,
                    line=item.line,
                    column=item.column,
                )
            if item.key == "priority" and port.eClass.findEStructuralFeature("priority") is not None:
                port.priority = _integer(item, filename, ctx)
            elif item.key == "deadline" and port.eClass.findEStructuralFeature("deadline") is not None:
                port.deadline = _seconds(item, filename)
            else:
                ctx.warn(
                    f"{stmt.keyword} {port.name!r}: unknown setting {item.key!r} kept as a component "
                    "property",
                    filename,
                    item.line,
                    item.column,
                )
                comp.properties.append(_prop(f"{port.name}.{item.key}", item.value_text, item))
        except ParseError as exc:
            ctx.error(exc)


_PORT_CLASSES = {
    "publisher": "Publisher",
    "subscriber": "Subscriber",
    "client": "Client",
    "server": "Server",
}


def _qualify(ref: str, package: str) -> str:
    return ref if "/" in ref else f"{package}/{ref}"


def _component_v03(stmt: _Stmt, pkg_name: str, info: _SoftwareInfo, ctx: _Context) -> EObject:
    filename = info.filename
    head = stmt.head
    if len(head) < 2 or head[1].kind != "word":
        raise ParseError(
            f"malformed component: expected 'component <name> : <datatype>' (found {stmt.key!r})",
            file=filename,
            line=stmt.line,
            column=stmt.column,
        )
    datatype = None
    if len(head) >= 4 and _is(head[2], ":") and head[3].kind == "word" and len(head) == 4:
        datatype = head[3].text
    elif len(head) != 2:
        raise ParseError(
            f"malformed component: expected 'component <name> : <datatype>' (found {stmt.key!r})",
            file=filename,
            line=stmt.line,
            column=stmt.column,
        )
    comp = _new("Component", **_located({"name": head[1].text, "datatype": datatype}, stmt))
    for item in stmt.body or []:
        try:
            _component_item(item, comp, pkg_name, info, ctx, legacy=False)
        except ParseError as exc:
            ctx.error(exc)
    return comp


def _component_item(
    item: _Stmt, comp: EObject, pkg_name: str, info: _SoftwareInfo, ctx: _Context, legacy: bool
):
    filename = info.filename
    kw = item.keyword
    if kw == "timer" and item.body is not None:
        comp.timers.append(_timer(item, filename, ctx, comp))
    elif kw in _PORT_CLASSES:
        ref, name, _tok = _typed_head(item, filename, kw)
        type_name = _qualify(ref, pkg_name)
        port = _new(_PORT_CLASSES[kw], **_located({"name": name, "type": type_name}, item))
        if item.body is not None:
            _callback_settings(port, item, filename, ctx, comp)
        comp.ports.append(port)
        info.port_sites.append((port, kw, ref, item.head[2].line, item.head[2].column))
    elif legacy and kw in ("provides", "requires"):
        service = _name_of(item, filename, f"{kw} statement")
        cls, suffix = ("Server", "_server") if kw == "provides" else ("Client", "_client")
        port = _new(cls, **_located({"name": service + suffix, "type": _qualify(service, pkg_name)}, item))
        comp.ports.append(port)
        kind = "server" if kw == "provides" else "client"
        info.port_sites.append((port, kind, service, item.head[1].line, item.head[1].column))
    else:
        ctx.warn(
            f"component {comp.name!r}: unknown statement {item.key!r} skipped",
            filename,
            item.line,
            item.column,
        )


def _v02_fields(stmts: list[_Stmt], pkg_name: str, filename: str, ctx: _Context) -> tuple[list, str]:
    """Inline v0.2 fields (``type name;`` / ``type NAME = value;``) → (FieldSpecs, .msg text)."""
    specs: list[ros_msg.FieldSpec] = []
    lines: list[str] = []
    for item in stmts:
        if item.body is not None or len(item.head) < 2 or item.head[-1].kind != "word":
            ctx.error(
                ParseError(
                    f"malformed field {item.key!r}: expected '<type> <name>;'",
                    file=filename,
                    line=item.line,
                    column=item.column,
                )
            )
            continue
        type_text = "".join(t.text for t in item.head[:-1])
        line_text = f"{type_text} {item.head[-1].text}"
        if item.value is not None:
            line_text += f"={item.value_text}"
        try:
            spec = ros_msg.parse_field(
                line_text, package=pkg_name, filename=filename, line=item.line, column=item.column
            )
        except ParseError as exc:
            ctx.error(exc)
            continue
        if spec is not None:
            specs.append(spec)
            lines.append(line_text)
    return specs, "".join(line + "\n" for line in lines)


def _package_v02(stmt: _Stmt, info: _SoftwareInfo, ctx: _Context) -> EObject:
    filename = info.filename
    name = _name_of(stmt, filename, "package")
    package = _new("Package", **_located({"name": name}, stmt))
    nodes: dict[str, list[tuple[str, str, _Stmt]]] = {}
    for block in stmt.body or []:
        kw = block.keyword
        if block.body is None:
            ctx.warn(
                f"package {name!r}: unknown statement {block.key!r} skipped",
                filename,
                block.line,
                block.column,
            )
            continue
        for item in block.body:
            try:
                if kw == "messages" and item.keyword == "msg":
                    msg_name = _name_of(item, filename, "msg")
                    specs, text = _v02_fields(item.body or [], name, filename, ctx)
                    msg = _new("Message", **_located({"name": msg_name, "definition": text}, item))
                    msg.fields.extend(ros_msg.fields_to_model(specs))
                    _check_unique(msg.fields, "field", f"message {msg_name!r}", filename, ctx)
                    package.messages.append(msg)
                elif kw == "services" and item.keyword == "srv":
                    srv_name = _name_of(item, filename, "srv")
                    request: list = []
                    response: list = []
                    texts = {"request": "", "response": ""}
                    for part in item.body or []:
                        if part.keyword in ("request", "response") and part.body is not None:
                            specs, text = _v02_fields(part.body, name, filename, ctx)
                            (request if part.keyword == "request" else response).extend(specs)
                            texts[part.keyword] = text
                        else:
                            ctx.warn(
                                f"srv {srv_name!r}: unknown statement {part.key!r} skipped",
                                filename,
                                part.line,
                                part.column,
                            )
                    srv = _new(
                        "Service",
                        **_located(
                            {"name": srv_name, "definition": texts["request"] + "---\n" + texts["response"]},
                            item,
                        ),
                    )
                    srv.requestFields.extend(ros_msg.fields_to_model(request))
                    srv.responseFields.extend(ros_msg.fields_to_model(response))
                    package.services.append(srv)
                elif kw == "components" and item.keyword == "component":
                    comp_name = _name_of(item, filename, "component")
                    comp = _new("Component", **_located({"name": comp_name}, item))
                    for sub in item.body or []:
                        try:
                            _component_item(sub, comp, name, info, ctx, legacy=True)
                        except ParseError as exc:
                            ctx.error(exc)
                    package.components.append(comp)
                elif kw == "nodes" and item.keyword == "node":
                    node_name = _name_of(item, filename, "node")
                    instances = []
                    for sub in item.body or []:
                        if sub.keyword != "component":
                            ctx.warn(
                                f"node {node_name!r}: unknown statement {sub.key!r} skipped",
                                filename,
                                sub.line,
                                sub.column,
                            )
                            continue
                        comp_ref, inst, _ = _typed_head(sub, filename, "component instance")
                        instances.append((inst, comp_ref, sub))
                    if node_name in nodes:
                        ctx.error(
                            NameResolutionError(
                                f"duplicate node name {node_name!r} in package {name!r}",
                                file=filename,
                                line=item.line,
                                column=item.column,
                            )
                        )
                    nodes[node_name] = instances
                    package.properties.append(
                        _prop(
                            f"node:{node_name}",
                            json.dumps({inst: _qualify(ref, name) for inst, ref, _ in instances}),
                            item,
                        )
                    )
                else:
                    ctx.warn(
                        f"package {name!r}: unknown statement {item.key!r} in {kw!r} skipped",
                        filename,
                        item.line,
                        item.column,
                    )
            except ParseError as exc:
                ctx.error(exc)
    info.nodes[name] = nodes
    return package


def _software(stmts: list[_Stmt], version: str, name: str, rel: str, shown: str, ctx: _Context):
    info = _SoftwareInfo(filename=shown)
    software = _new("Software", name=name, sourceFile=rel)
    for stmt in stmts:
        try:
            if stmt.keyword == "workspace" and version == "0.1":
                software.name = _name_of(stmt, shown, "workspace")
            elif stmt.keyword == "package" and stmt.body is not None:
                if version == "0.3":
                    pkg_name = _name_of(stmt, shown, "package")
                    package = _new("Package", **_located({"name": pkg_name}, stmt))
                    for item in stmt.body:
                        if item.keyword == "component" and item.body is not None:
                            try:
                                package.components.append(_component_v03(item, pkg_name, info, ctx))
                            except ParseError as exc:
                                ctx.error(exc)
                        else:
                            ctx.warn(
                                f"package {pkg_name!r}: unknown statement {item.key!r} skipped",
                                shown,
                                item.line,
                                item.column,
                            )
                else:
                    package = _package_v02(stmt, info, ctx)
                software.packages.append(package)
            else:
                ctx.warn(f"unknown statement {stmt.key!r} skipped", shown, stmt.line, stmt.column)
        except ParseError as exc:
            ctx.error(exc)
    return software, info


# =========================================================================== message side files (v0.3)


def _side_files(folder: Path, suffix: str) -> list[Path]:
    if not folder.is_dir():
        return []
    return sorted(
        (p for p in folder.iterdir() if p.is_file() and p.name.endswith(suffix)), key=lambda p: p.name
    )


def _load_interfaces(
    software: EObject, sw_dir: Path, root: Path, shown_root: str, info: _SoftwareInfo, ctx: _Context
) -> None:
    packages = {p.name: p for p in software.packages}
    for kind, suffix in (("msg", ".msg"), ("srv", ".srv")):
        for path in _side_files(sw_dir / kind, suffix):
            shown = _shown(shown_root, path.relative_to(root))
            parts = path.name[: -len(suffix)].split(".")
            if len(parts) != 2 or not all(parts):
                ctx.warn(f"skipped {path.name!r}: expected a file name <package>.<Name>{suffix}", shown)
                continue
            pkg_name, name = parts
            package = packages.get(pkg_name)
            if package is None:
                ctx.warn(
                    f"skipped {path.name!r}: package {pkg_name!r} is not defined in the software model",
                    shown,
                )
                continue
            try:
                text = _read_text(path, shown)
            except ParseError as exc:
                ctx.error(exc)
                continue
            # the type is declared even when its definition has errors (no cascade of
            # "unknown type" errors for the ports that use it)
            if kind == "msg":
                obj = _new("Message", name=name, definition=text)
                package.messages.append(obj)
            else:
                obj = _new("Service", name=name, definition=text)
                package.services.append(obj)
            info.sources[id(obj)] = shown
            try:
                fill = ros_msg.fill_message if kind == "msg" else ros_msg.fill_service
                fill(obj, package=pkg_name, filename=shown)
            except ParseError as exc:
                ctx.error(exc)
    for kind in ("abl", "pnp"):
        for path in _side_files(sw_dir / kind, "." + kind):
            shown = _shown(shown_root, path.relative_to(root))
            parts = path.name[: -len(kind) - 1].split(".")
            target = None
            if len(parts) == 3:
                package = packages.get(parts[0])
                comp = next((c for c in package.components if c.name == parts[1]), None) if package else None
                if comp is not None and any(x.name == parts[2] for x in [*comp.timers, *comp.ports]):
                    target = comp
            if target is None:
                ctx.warn(
                    f"skipped {path.name!r}: no port or timer <package>.<component>.<port> of that name",
                    shown,
                )
                continue
            try:
                target.properties.append(_prop(f"{kind}:{parts[2]}", _read_text(path, shown)))
            except ParseError as exc:
                ctx.error(exc)


# =========================================================================== hardware (.rhw)

_HOST_KEYS = {
    "ip_address": "ipAddress",
    "username": "username",
    "sshkey": "sshKey",
    "deployment_path": "deploymentPath",
    "install_path": "installPath",
    "arch": "architecture",
    "architecture": "architecture",
    "os": "os",
}


def _system(stmts: list[_Stmt], name: str, rel: str, shown: str, ctx: _Context) -> EObject:
    system = _new("System", name=name, sourceFile=rel)
    for stmt in stmts:
        try:
            if stmt.keyword in ("hardware", "host") and stmt.body is not None:
                host = _new("Host", **_located({"name": _name_of(stmt, shown, stmt.keyword)}, stmt))
                for item in stmt.body:
                    if item.value is None:
                        ctx.warn(
                            f"host {host.name!r}: unknown statement {item.key!r} skipped",
                            shown,
                            item.line,
                            item.column,
                        )
                        continue
                    attr = _HOST_KEYS.get(item.key)
                    if attr is not None and not host.eIsSet(attr):
                        setattr(host, attr, item.value_text)
                    else:
                        host.properties.append(_prop(item.key, item.value_text, item))
                system.hosts.append(host)
            else:
                ctx.warn(f"unknown statement {stmt.key!r} skipped", shown, stmt.line, stmt.column)
        except ParseError as exc:
            ctx.error(exc)
    if ctx.strict:
        _check_unique(system.hosts, "host", f"hardware model {name!r}", shown, ctx)
    else:
        # ROSMOD resolves '<hardware>/<host>' to the last definition of a host name: a repeated
        # host is a redefinition (real projects have them); keep the last one and say so.
        last: dict[str, EObject] = {h.name: h for h in system.hosts}
        for host in list(system.hosts):
            if last[host.name] is not host:
                later = last[host.name]
                ctx.warn(
                    f"host {host.name!r} is defined again at line {later.line}; the later definition "
                    "replaces this one (as in ROSMOD)",
                    shown,
                    host.line,
                    host.column,
                )
                system.hosts.remove(host)
    return system


# =========================================================================== deployment (.rdp)


@dataclass
class _Ref:
    obj: EObject
    text: str
    token: _Token
    kind: str  # "host" | "component" | "port" | "node02"
    extra: Any = None


@dataclass
class _DeploymentInfo:
    filename: str
    using: _Stmt | None = None
    refs: list[_Ref] = field(default_factory=list)


def _logging(block: _Stmt, inst: EObject, shown: str, ctx: _Context) -> None:
    for item in block.body or []:
        if item.value is None:
            ctx.warn(f"logging: unknown statement {item.key!r} skipped", shown, item.line, item.column)
            continue
        inst.logging.append(_prop(item.key, item.value_text, item))


def _component_instance(stmt: _Stmt, shown: str, info: _DeploymentInfo, ctx: _Context) -> EObject:
    inst = _new("ComponentInstance", **_located({"name": _name_of(stmt, shown, "component_instance")}, stmt))
    for item in stmt.body or []:
        if item.keyword == "properties" and item.body is not None:
            for prop in item.body:
                if prop.keyword == "logging" and prop.body is not None:
                    _logging(prop, inst, shown, ctx)
                elif prop.value is None:
                    ctx.warn(
                        f"component_instance {inst.name!r}: unknown statement {prop.key!r} skipped",
                        shown,
                        prop.line,
                        prop.column,
                    )
                elif prop.key == "ref" and not inst.eIsSet("componentRef"):
                    inst.componentRef = prop.value_text
                    info.refs.append(_Ref(inst, prop.value_text, prop.value_token, "component"))
                elif prop.key == "scheduling_scheme" and not inst.eIsSet("schedulingScheme"):
                    scheme = prop.value_text
                    if scheme in _SCHEMES:
                        inst.schedulingScheme = scheme_literal(scheme)
                    else:
                        ctx.warn(
                            f"component_instance {inst.name!r}: unknown scheduling scheme {scheme!r} "
                            f"(expected {', '.join(_SCHEMES)}); kept as a property",
                            shown,
                            prop.value_token.line,
                            prop.value_token.column,
                        )
                        inst.properties.append(_prop(prop.key, scheme, prop))
                else:
                    inst.properties.append(_prop(prop.key, prop.value_text, prop))
        elif item.keyword == "port_instance" and item.body is not None:
            port = _new("PortInstance", **_located({"name": _name_of(item, shown, "port_instance")}, item))
            for prop in item.body:
                if prop.key == "ref" and prop.value is not None:
                    port.port = prop.value_text
                    info.refs.append(_Ref(port, prop.value_text, prop.value_token, "port", extra=inst))
                elif prop.key == "group" and prop.value is not None:
                    port.group = prop.value_text
                else:
                    ctx.warn(
                        f"port_instance {port.name!r}: unknown statement {prop.key!r} skipped",
                        shown,
                        prop.line,
                        prop.column,
                    )
            inst.portInstances.append(port)
        else:
            ctx.warn(
                f"component_instance {inst.name!r}: unknown statement {item.key!r} skipped",
                shown,
                item.line,
                item.column,
            )
    if inst.componentRef is None:
        ctx.error(
            ParseError(
                f'component_instance {inst.name!r} has no ref = "<package>/<component>";',
                file=shown,
                line=stmt.line,
                column=stmt.column,
            )
        )
    _check_unique(inst.portInstances, "port_instance", f"component_instance {inst.name!r}", shown, ctx)
    return inst


def _node_v03(stmt: _Stmt, shown: str, info: _DeploymentInfo, ctx: _Context) -> EObject:
    node = _new("Node", **_located({"name": _name_of(stmt, shown, "node")}, stmt))
    for item in stmt.body or []:
        try:
            if item.keyword == "properties" and item.body is not None:
                for prop in item.body:
                    if prop.value is None:
                        ctx.warn(
                            f"node {node.name!r}: unknown statement {prop.key!r} skipped",
                            shown,
                            prop.line,
                            prop.column,
                        )
                    elif prop.key == "ref" and not node.eIsSet("hostRef"):
                        node.hostRef = prop.value_text
                        info.refs.append(_Ref(node, prop.value_text, prop.value_token, "host"))
                    elif prop.key == "priority" and not node.eIsSet("priority"):
                        node.priority = _integer(prop, shown, ctx)
                    elif prop.key == "cmd_args" and not node.eIsSet("arguments"):
                        node.arguments = prop.value_text
                    else:
                        node.properties.append(_prop(prop.key, prop.value_text, prop))
            elif item.keyword == "component_instance" and item.body is not None:
                node.componentInstances.append(_component_instance(item, shown, info, ctx))
            else:
                ctx.warn(
                    f"node {node.name!r}: unknown statement {item.key!r} skipped",
                    shown,
                    item.line,
                    item.column,
                )
        except ParseError as exc:
            ctx.error(exc)
    if node.hostRef is None:
        ctx.error(
            ParseError(
                f'node {node.name!r} has no ref = "<hardware>/<host>"; in its properties',
                file=shown,
                line=stmt.line,
                column=stmt.column,
            )
        )
    _check_unique(node.componentInstances, "component_instance", f"node {node.name!r}", shown, ctx)
    return node


def _host_instance_v02(stmt: _Stmt, deployment: EObject, shown: str, info: _DeploymentInfo, ctx: _Context):
    host_name = _name_of(stmt, shown, "host_instance")
    props: dict[str, str] = {}
    for item in stmt.body or []:
        if item.keyword == "properties" and item.body is not None:
            for prop in item.body:
                if prop.value is None:
                    ctx.warn(
                        f"host_instance {host_name!r}: unknown statement {prop.key!r} skipped",
                        shown,
                        prop.line,
                        prop.column,
                    )
                else:
                    props[prop.key] = prop.value_text
        elif item.keyword == "nodes" and item.body is not None:
            for sub in item.body:
                if sub.keyword != "node_instance" or sub.body is None:
                    ctx.warn(
                        f"host_instance {host_name!r}: unknown statement {sub.key!r} skipped",
                        shown,
                        sub.line,
                        sub.column,
                    )
                    continue
                node = _new(
                    "Node",
                    **_located({"name": _name_of(sub, shown, "node_instance"), "hostRef": host_name}, sub),
                )
                info.refs.append(_Ref(node, host_name, stmt.head[1], "host"))
                reference = None
                for prop in sub.body:
                    if prop.value is None:
                        ctx.warn(
                            f"node_instance {node.name!r}: unknown statement {prop.key!r} skipped",
                            shown,
                            prop.line,
                            prop.column,
                        )
                    elif prop.key == "reference" and reference is None:
                        reference = prop
                    elif prop.key == "cmdline_arguments" and not node.eIsSet("arguments"):
                        node.arguments = prop.value_text
                    else:
                        node.properties.append(_prop(prop.key, prop.value_text, prop))
                if reference is None:
                    ctx.error(
                        ParseError(
                            f'node_instance {node.name!r} has no reference = "<package>/<node>";',
                            file=shown,
                            line=sub.line,
                            column=sub.column,
                        )
                    )
                else:
                    node.properties.insert(0, _prop("reference", reference.value_text, reference))
                    info.refs.append(_Ref(node, reference.value_text, reference.value_token, "node02"))
                deployment.nodes.append(node)
        else:
            ctx.warn(
                f"host_instance {host_name!r}: unknown statement {item.key!r} skipped",
                shown,
                item.line,
                item.column,
            )
    deployment.properties.append(_prop(f"host_instance:{host_name}", json.dumps(props), stmt))


def _deployment(stmts: list[_Stmt], name: str, rel: str, shown: str, ctx: _Context):
    deployment = _new("Deployment", name=name, sourceFile=rel)
    info = _DeploymentInfo(filename=shown)
    for stmt in stmts:
        try:
            if stmt.keyword == "using" and stmt.body is None and stmt.value is None:
                ref = "".join(t.text for t in stmt.head[1:])
                if not ref:
                    raise ParseError(
                        "expected 'using <hardware model>;'", file=shown, line=stmt.line, column=stmt.column
                    )
                if info.using is not None:
                    raise ParseError(
                        f"a second 'using' (the first is at line {info.using.line})",
                        file=shown,
                        line=stmt.line,
                        column=stmt.column,
                    )
                deployment.systemName = ref
                info.using = stmt
            elif stmt.keyword == "node" and stmt.body is not None:
                deployment.nodes.append(_node_v03(stmt, shown, info, ctx))
            elif stmt.keyword == "host_instance" and stmt.body is not None:
                _host_instance_v02(stmt, deployment, shown, info, ctx)
            else:
                ctx.warn(f"unknown statement {stmt.key!r} skipped", shown, stmt.line, stmt.column)
        except ParseError as exc:
            ctx.error(exc)
    _check_unique(deployment.nodes, "node", f"deployment {name!r}", shown, ctx)
    return deployment, info


# =========================================================================== resolution


class _Names:
    """Name → object tables of a software model, built once for resolution."""

    def __init__(self, software: EObject | None) -> None:
        self.packages: dict[str, EObject] = {}
        self.messages: dict[str, set[str]] = {}
        self.services: dict[str, set[str]] = {}
        self.components: dict[str, dict[str, EObject]] = {}
        self.ports: dict[int, set[str]] = {}
        for package in software.packages if software is not None else []:
            name = package.name
            self.packages.setdefault(name, package)
            self.messages.setdefault(name, set()).update(m.name for m in package.messages)
            self.services.setdefault(name, set()).update(s.name for s in package.services)
            comps = self.components.setdefault(name, {})
            for comp in package.components:
                comps.setdefault(comp.name, comp)

    def port_names(self, comp: EObject) -> set[str]:
        names = self.ports.get(id(comp))
        if names is None:
            names = self.ports[id(comp)] = {p.name for p in comp.ports}
        return names


def _resolve_software(software: EObject, info: _SoftwareInfo, ctx: _Context) -> None:
    shown = info.filename
    _check_unique(software.packages, "package", "the software model", shown, ctx)
    names = _Names(software)
    packages = names.packages
    for package in software.packages:
        owner = f"package {package.name!r}"
        _check_unique(package.messages, "message", owner, shown, ctx)
        _check_unique(package.services, "service", owner, shown, ctx)
        _check_unique(package.components, "component", owner, shown, ctx)
        for comp in package.components:
            _check_unique(
                [*comp.timers, *comp.ports], "port or timer", f"component {comp.name!r}", shown, ctx
            )
    for port, kind, _written, line, column in info.port_sites:
        pkg_name, _, type_name = port.type.rpartition("/")
        package = packages.get(pkg_name)
        if package is None:
            continue  # a type of a package outside the project (std_msgs/String): external
        wants_msg = kind in ("publisher", "subscriber")
        pool = (names.messages if wants_msg else names.services)[pkg_name]
        if type_name not in pool:
            what = "message" if wants_msg else "service"
            known = ", ".join(sorted(pool)) or "none"
            ctx.error(
                NameResolutionError(
                    f"unknown {what} type {port.type!r} of {kind} {port.name!r}: package {pkg_name!r} "
                    f"defines no {what} {type_name!r} (its {what}s: {known})",
                    file=shown,
                    line=line,
                    column=column,
                )
            )
    # nested field types of the project's own packages
    for package in software.packages:
        for owner, fields in (
            *((m, m.fields) for m in package.messages),
            *((s, [*s.requestFields, *s.responseFields]) for s in package.services),
        ):
            for fld in fields:
                pkg_name, _, type_name = (fld.type or "").rpartition("/")
                target = packages.get(pkg_name)
                if target is not None and type_name not in names.messages[pkg_name]:
                    ctx.error(
                        NameResolutionError(
                            f"{owner.eClass.name.lower()} {package.name}/{owner.name}: field "
                            f"{fld.name!r} has unknown message type {fld.type!r}",
                            file=info.sources.get(id(owner), shown),
                            line=fld.line,
                            column=fld.column,
                            path=f"{package.name}/{owner.name}",
                        )
                    )


def _resolve_deployment(
    deployment: EObject,
    info: _DeploymentInfo,
    systems: dict[str, EObject],
    software: EObject | None,
    sw_info: _SoftwareInfo | None,
    ctx: _Context,
    software_failed: bool = False,
    failed_systems: frozenset[str] | set[str] = frozenset(),
) -> None:
    shown = info.filename
    using = None
    if deployment.systemName is not None:
        using = systems.get(deployment.systemName)
        if using is None and deployment.systemName not in failed_systems:
            tok = info.using.head[1] if info.using is not None and len(info.using.head) > 1 else None
            known = ", ".join(sorted(systems)) or "none"
            ctx.error(
                NameResolutionError(
                    f"unknown hardware model {deployment.systemName!r} in 'using' (hardware models: {known})",
                    file=shown,
                    line=tok.line if tok else None,
                    column=tok.column if tok else None,
                )
            )
        else:
            deployment.system = using
    names = _Names(software)
    packages = names.packages
    host_tables: dict[int, dict[str, EObject]] = {}
    for ref in info.refs:
        where = {"file": shown, "line": ref.token.line, "column": ref.token.column}
        if ref.kind == "host":
            sys_name, _, host_name = ref.text.rpartition("/")
            if (sys_name or deployment.systemName) in failed_systems:
                continue  # its hardware model could not be read: already reported
            system = systems.get(sys_name) if sys_name else using
            if sys_name and system is None:
                known = ", ".join(sorted(systems)) or "none"
                ctx.error(
                    NameResolutionError(
                        f"node {ref.obj.name!r}: unknown hardware model {sys_name!r} in ref {ref.text!r} "
                        f"(hardware models: {known})",
                        **where,
                    )
                )
                continue
            if system is None:
                ctx.error(
                    NameResolutionError(
                        f"node {ref.obj.name!r}: host {ref.text!r} has no hardware model (no 'using' and no "
                        "'<hardware>/<host>' ref)",
                        **where,
                    )
                )
                continue
            hosts = host_tables.get(id(system))
            if hosts is None:
                hosts = host_tables[id(system)] = {}
                for h in system.hosts:
                    hosts.setdefault(h.name, h)
            host = hosts.get(host_name)
            if host is None:
                ctx.error(
                    NameResolutionError(
                        f"node {ref.obj.name!r} is on unknown host {host_name!r}: hardware model "
                        f"{system.name!r} has no such host",
                        **where,
                    )
                )
                continue
            if using is not None and system is not using:
                ctx.warn(
                    f"node {ref.obj.name!r} uses host {ref.text!r} outside the hardware model "
                    f"{using.name!r} named by 'using'",
                    shown,
                    ref.token.line,
                    ref.token.column,
                )
            ref.obj.host = host
        elif software_failed:
            continue  # the software model could not be read: already reported
        elif ref.kind == "component":
            pkg_name, _, comp_name = ref.text.rpartition("/")
            package = packages.get(pkg_name)
            if package is None:
                known = ", ".join(sorted(packages)) or "none"
                ctx.error(
                    NameResolutionError(
                        f"component_instance {ref.obj.name!r} refers to unknown package "
                        f"{pkg_name or ref.text!r} (packages: {known})",
                        **where,
                    )
                )
                continue
            comp = names.components[pkg_name].get(comp_name)
            if comp is None:
                ctx.error(
                    NameResolutionError(
                        f"component_instance {ref.obj.name!r} refers to unknown component {comp_name!r} of "
                        f"package {pkg_name!r}",
                        **where,
                    )
                )
                continue
            ref.obj.component = comp
        elif ref.kind == "port":
            inst = ref.extra
            comp = inst.component
            comp_name, _, port_name = ref.text.rpartition("/")
            if comp is None:
                continue  # the instance's own ref already failed
            if comp_name != comp.name or port_name not in names.port_names(comp):
                ctx.error(
                    NameResolutionError(
                        f"port_instance {ref.obj.name!r}: {ref.text!r} is not a port of component "
                        f"{comp.name!r} (expected '{comp.name}/<port>')",
                        **where,
                    )
                )
        elif ref.kind == "node02":
            pkg_name, _, node_name = ref.text.rpartition("/")
            nodes = (sw_info.nodes.get(pkg_name) if sw_info is not None else None) or {}
            if pkg_name not in packages:
                known = ", ".join(sorted(packages)) or "none"
                ctx.error(
                    NameResolutionError(
                        f"node_instance {ref.obj.name!r} refers to unknown package {pkg_name or ref.text!r} "
                        f"(packages: {known})",
                        **where,
                    )
                )
                continue
            if node_name not in nodes:
                ctx.error(
                    NameResolutionError(
                        f"node_instance {ref.obj.name!r} refers to unknown node {node_name!r} of package "
                        f"{pkg_name!r}",
                        **where,
                    )
                )
                continue
            package = packages[pkg_name]
            for inst_name, comp_ref, stmt in nodes[node_name]:
                comp_pkg, _, comp_name = _qualify(comp_ref, pkg_name).rpartition("/")
                target_pkg = packages.get(comp_pkg)
                comp = names.components[comp_pkg].get(comp_name) if target_pkg is not None else None
                inst = _new(
                    "ComponentInstance",
                    name=inst_name,
                    componentRef=f"{comp_pkg}/{comp_name}",
                    component=comp,
                    line=stmt.line,
                    column=stmt.column,
                )
                if comp is None:
                    ctx.error(
                        NameResolutionError(
                            f"node {node_name!r} of package {package.name!r}: component {comp_ref!r} "
                            "is not defined",
                            file=sw_info.filename if sw_info else None,
                            line=stmt.line,
                            column=stmt.column,
                        )
                    )
                ref.obj.componentInstances.append(inst)
            _check_unique(
                ref.obj.componentInstances,
                "component instance",
                f"node {node_name!r}",
                sw_info.filename if sw_info else None,
                ctx,
            )


# =========================================================================== v0.4 (jsonpickle)


def _v04_id_map(data: Any, excluded_lists: frozenset[str]) -> dict[int, Any]:
    """jsonpickle's object ids (pre-order: instances and lists, minus some list contexts)."""
    ids: dict[int, Any] = {}
    counter = 0
    stack: list[tuple[Any, str | None]] = [(data, None)]
    while stack:
        value, ctx_key = stack.pop()
        if isinstance(value, dict):
            if "py/id" in value or "py/type" in value:
                continue
            if "py/object" in value:
                ids[counter] = value
                counter += 1
            children = [(v, k) for k, v in value.items()]
            stack.extend(reversed(children))
        elif isinstance(value, list):
            if ctx_key not in excluded_lists:
                ids[counter] = value
                counter += 1
            stack.extend(reversed([(v, None) for v in value]))
    return ids


def _v04_attrs(element: dict) -> dict[str, Any]:
    attrs = element.get("attributes")
    pairs: list = []
    if isinstance(attrs, dict):
        reduce = attrs.get("__reduce__")
        if isinstance(reduce, list) and len(reduce) >= 2 and isinstance(reduce[1], dict):
            tup = reduce[1].get("py/tuple")
            if isinstance(tup, list) and tup and isinstance(tup[0], list):
                pairs = tup[0]
    out: dict[str, Any] = {}
    for pair in pairs:
        if isinstance(pair, list) and len(pair) == 2 and isinstance(pair[0], str):
            out[pair[0]] = pair[1]
    return out


def _v04_children(element: dict) -> list:
    children = element.get("children")
    if isinstance(children, dict) and isinstance(children.get("_inner"), list):
        return children["_inner"]
    return []


def _v04_kind(value: Any) -> str | None:
    if isinstance(value, dict) and isinstance(value.get("py/object"), str):
        return value["py/object"].rpartition(".")[2]
    return None


def _read_v04(text: str, shown: str, rel: str, project: EObject, ctx: _Context) -> None:
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ParseError(
            f"malformed JSON: {exc.msg}", file=shown, line=exc.lineno, column=exc.colno
        ) from None
    except RecursionError:
        raise ParseError("the JSON document is nested too deeply", file=shown) from None
    if _v04_kind(data) != "Project":
        raise ParseError("expected a ROSMOD v0.4 project (a jsonpickle __main__.Project object)", file=shown)
    # Choose the id numbering that agrees with every 'parent' link of the file.
    anchors: list[tuple[int, dict]] = []
    stack = [data]
    while stack:
        element = stack.pop()
        for child in _v04_children(element):
            if isinstance(child, dict) and "py/object" in child:
                parent = child.get("parent")
                if isinstance(parent, dict) and isinstance(parent.get("py/id"), int):
                    anchors.append((parent["py/id"], element))
                stack.append(child)
    ids = None
    for excluded in (
        frozenset({"__reduce__", "py/seq", "_inner"}),
        frozenset({"__reduce__", "py/seq", "_allowed"}),
    ):
        candidate = _v04_id_map(data, excluded)
        if all(candidate.get(k) is e for k, e in anchors):
            ids = candidate
            break
    if ids is None:
        raise ParseError("cannot resolve the jsonpickle object references (py/id) of this file", file=shown)

    def deref(value: Any) -> Any:
        if isinstance(value, dict) and "py/id" in value:
            return ids.get(value["py/id"]) if isinstance(value["py/id"], int) else None
        return value

    def attr(element: dict, key: str) -> Any:
        value = deref(_v04_attrs(element).get(key))
        if isinstance(value, dict) and "value" in value and "py/object" in value:
            return deref(value["value"])
        return value

    made: dict[int, EObject] = {}
    pending: list[tuple[EObject, str, Any, str]] = []
    path = "Project"

    def text_or_none(value: Any) -> str | None:
        return None if value is None else str(value)

    def seconds(value: Any, where: str) -> Decimal | None:
        if value in (None, ""):
            return None
        try:
            return Decimal(str(value))
        except InvalidOperation:
            ctx.error(
                ParseError(f"{where}: expected a number of seconds, found {value!r}", file=shown, path=where)
            )
            return None

    def integer(value: Any, where: str) -> int | None:
        if value in (None, ""):
            return None
        try:
            return int(Decimal(str(value)))
        except (InvalidOperation, ValueError):
            ctx.error(ParseError(f"{where}: expected an integer, found {value!r}", file=shown, path=where))
            return None

    project.name = text_or_none(attr(data, "name")) or project.name
    software = None
    for top in _v04_children(data):
        top = deref(top)
        kind = _v04_kind(top)
        if kind == "Software":
            software = _new("Software", name=text_or_none(attr(top, "name")), sourceFile=rel)
            project.software = software
            for pkg_el in map(deref, _v04_children(top)):
                pkg = _new("Package", name=text_or_none(attr(pkg_el, "name")))
                software.packages.append(pkg)
                for el in map(deref, _v04_children(pkg_el)):
                    k = _v04_kind(el)
                    where = f"{path}/{pkg.name}/{text_or_none(attr(el, 'name'))}"
                    if k == "Message":
                        msg = _new(
                            "Message",
                            name=text_or_none(attr(el, "name")),
                            definition=text_or_none(attr(el, "definition")),
                        )
                        try:
                            ros_msg.fill_message(msg, package=pkg.name, filename=shown, path=where)
                        except ros_msg.RosMessageError as exc:
                            ctx.error(exc)
                        pkg.messages.append(msg)
                    elif k == "Service":
                        srv = _new(
                            "Service",
                            name=text_or_none(attr(el, "name")),
                            definition=text_or_none(attr(el, "definition")),
                        )
                        try:
                            ros_msg.fill_service(srv, package=pkg.name, filename=shown, path=where)
                        except ros_msg.RosMessageError as exc:
                            ctx.error(exc)
                        pkg.services.append(srv)
                    elif k == "Component":
                        comp = _new(
                            "Component",
                            name=text_or_none(attr(el, "name")),
                            datatype=text_or_none(attr(el, "type")),
                        )
                        made[id(el)] = comp
                        pkg.components.append(comp)
                        for sub in map(deref, _v04_children(el)):
                            sk = _v04_kind(sub)
                            sub_where = f"{where}/{text_or_none(attr(sub, 'name'))}"
                            if sk == "Timer":
                                comp.timers.append(
                                    _new(
                                        "Timer",
                                        name=text_or_none(attr(sub, "name")),
                                        period=seconds(attr(sub, "period"), sub_where),
                                        priority=integer(attr(sub, "priority"), sub_where),
                                        deadline=seconds(attr(sub, "deadline"), sub_where),
                                    )
                                )
                                logic = attr(sub, "business_logic")
                                if logic:
                                    comp.properties.append(_prop(f"abl:{attr(sub, 'name')}", str(logic)))
                            elif sk in ("Publisher", "Subscriber", "Client", "Server"):
                                port = _new(sk, name=text_or_none(attr(sub, "name")))
                                if sk in ("Subscriber", "Server"):
                                    port.priority = integer(attr(sub, "priority"), sub_where)
                                    port.deadline = seconds(attr(sub, "deadline"), sub_where)
                                ref_key = (
                                    "message_reference"
                                    if sk in ("Publisher", "Subscriber")
                                    else "service_reference"
                                )
                                pending.append((port, "type", _v04_attrs(sub).get(ref_key), sub_where))
                                comp.ports.append(port)
                            else:
                                ctx.warn(f"{sub_where}: unknown v0.4 element {sk!r} skipped", shown)
                    else:
                        ctx.warn(f"{where}: unknown v0.4 element {k!r} skipped", shown)
        elif kind == "Hardware":
            system = _new("System", name=text_or_none(attr(top, "name")), sourceFile=rel)
            made[id(top)] = system
            project.systems.append(system)
            for el in map(deref, _v04_children(top)):
                host = _new(
                    "Host",
                    name=text_or_none(attr(el, "name")),
                    ipAddress=text_or_none(attr(el, "ip_address")),
                    username=text_or_none(attr(el, "username")),
                    sshKey=text_or_none(attr(el, "sshkey")),
                    deploymentPath=text_or_none(attr(el, "deployment_path")),
                    installPath=text_or_none(attr(el, "install_path")),
                    architecture=text_or_none(attr(el, "arch")),
                )
                profile = attr(el, "network_profile")
                if profile:
                    host.properties.append(_prop("network_profile", str(profile)))
                made[id(el)] = host
                system.hosts.append(host)
        elif kind == "Deployment":
            dep = _new("Deployment", name=text_or_none(attr(top, "name")), sourceFile=rel)
            project.deployments.append(dep)
            pending.append((dep, "system", _v04_attrs(top).get("hardware_reference"), f"{path}/{dep.name}"))
            for el in map(deref, _v04_children(top)):
                node = _new(
                    "Node",
                    name=text_or_none(attr(el, "name")),
                    priority=integer(attr(el, "priority"), f"{path}/{dep.name}"),
                    arguments=text_or_none(attr(el, "cmd_args")) or None,
                )
                dpath = attr(el, "deployment_path")
                if dpath:
                    node.properties.append(_prop("deployment_path", str(dpath)))
                dep.nodes.append(node)
                pending.append(
                    (node, "host", _v04_attrs(el).get("computer_reference"), f"{path}/{dep.name}/{node.name}")
                )
                for sub in map(deref, _v04_children(el)):
                    inst = _new("ComponentInstance", name=text_or_none(attr(sub, "name")))
                    scheme = attr(sub, "scheduling_scheme")
                    if scheme in _SCHEMES:
                        inst.schedulingScheme = scheme_literal(scheme)
                    elif scheme:
                        inst.properties.append(_prop("scheduling_scheme", str(scheme)))
                    logging_value = attr(sub, "logging")
                    if isinstance(logging_value, dict):
                        for key in sorted(logging_value):
                            inst.logging.append(_prop(key, str(logging_value[key]).lower()))
                    node.componentInstances.append(inst)
                    pending.append(
                        (
                            inst,
                            "component",
                            _v04_attrs(sub).get("component_reference"),
                            f"{path}/{dep.name}/{node.name}/{inst.name}",
                        )
                    )
        else:
            ctx.warn(f"unknown v0.4 element {kind!r} skipped", shown)
    # references
    for obj, feature, raw, where in pending:
        holder = deref(raw)
        target_el = deref(holder.get("value")) if isinstance(holder, dict) and "value" in holder else None
        if target_el is None:
            if feature in ("host", "component"):
                ctx.error(
                    NameResolutionError(
                        f"{where}: the {feature} reference is missing", file=shown, path=where
                    )
                )
            continue
        if feature == "type":
            name = attr(target_el, "name")
            pkg_el = deref(target_el.get("parent"))
            pkg_name = attr(pkg_el, "name") if isinstance(pkg_el, dict) else None
            obj.type = f"{pkg_name}/{name}" if pkg_name else str(name)
            continue
        target = made.get(id(target_el))
        expected = {"system": "System", "host": "Host", "component": "Component"}[feature]
        if target is None or target.eClass.name != expected:
            ctx.error(
                NameResolutionError(
                    f"{where}: the {feature} reference does not name a {expected.lower()}",
                    file=shown,
                    path=where,
                )
            )
            continue
        setattr(obj, feature, target)
        if feature == "system":
            obj.systemName = target.name
        elif feature == "host":
            system = target.eContainer()
            obj.hostRef = f"{system.name}/{target.name}"
        elif feature == "component":
            obj.componentRef = f"{target.eContainer().name}/{target.name}"


# =========================================================================== entry points


def _shown(shown_root: str, rel: Path | str) -> str:
    rel_text = Path(rel).as_posix()
    if not shown_root:
        return rel_text
    return os.path.join(shown_root, rel_text)


def _pick_dir(root: Path, names: Sequence[str], shown_root: str, what: str) -> Path | None:
    found = [root / n for n in names if (root / n).is_dir()]
    if len(found) > 1:
        raise RosmodImportError(
            [
                ParseError(
                    f"two {what} folders ({', '.join(p.name for p in found)}); expected one", file=shown_root
                )
            ]
        )
    return found[0] if found else None


def is_rosmod_project(path: str | os.PathLike[str]) -> bool:
    """True for a folder that holds a ROSMOD textual project (marker, standard folders or model files)."""
    root = Path(path)
    if root.is_file():
        return root.suffix.lower() in (".rml", ".rosml")
    if not root.is_dir():
        return False
    if any(p.suffix == ".rosmod" for p in root.iterdir() if p.is_file()):
        return True
    if any((root / n).is_dir() for n in _SOFTWARE_DIRS):
        return True
    return any(p.suffix.lower() in (".rml", ".rosml") for p in root.iterdir() if p.is_file())


def _looks_like_json(text: str) -> bool:
    return text.lstrip().startswith("{")


def read_software_file(
    path: str | os.PathLike[str], *, warnings: list[Diagnostic] | None = None, strict: bool = False
) -> EObject:
    """A project holding the software of one ``.rml`` (any version) or ``.rosml`` file."""
    if not Path(path).is_file():
        raise RosmodImportError([ParseError("expected a .rml or .rosml file", file=os.fspath(path))])
    return read_project(path, warnings=warnings, strict=strict)


def read_project(
    path: str | os.PathLike[str], *, warnings: list[Diagnostic] | None = None, strict: bool = False
) -> EObject:
    """Read a ROSMOD textual project (folder) or a single ``.rml``/``.rosml`` file into a ``rosmod.Project``.

    Raises :class:`RosmodImportError` listing every located problem; warnings (skipped
    statements, skipped side files, a host defined twice in one ``.rhw`` — the later definition
    wins, as in ROSMOD) are logged and appended to ``warnings`` when given. With ``strict``,
    a repeated host is an error like every other duplicate name.
    """
    ctx = _Context(warnings, strict)
    given = os.fspath(path)
    root = Path(given)
    if not root.exists():
        raise RosmodImportError([ParseError("no such file or folder", file=given)])
    if root.is_file():
        folder, shown_root = root.parent, os.path.dirname(given)
        sw_files, hw_files, dp_files = [root], [], []
        project_name = root.stem
    else:
        folder, shown_root = root, given
        project_name = root.resolve().name
        sw_dir = _pick_dir(root, _SOFTWARE_DIRS, given, "software")
        hw_dir = _pick_dir(root, _HARDWARE_DIRS, given, "hardware")
        dp_dir = _pick_dir(root, _DEPLOYMENT_DIRS, given, "deployment")
        sw_base = sw_dir or root
        sw_files = [p for p in _side_files(sw_base, "") if p.suffix.lower() in (".rml", ".rosml")]
        hw_files = _side_files(hw_dir or root, ".rhw")
        dp_files = _side_files(dp_dir or root, ".rdp")
        if not (sw_files or hw_files or dp_files):
            raise RosmodImportError(
                [ParseError("not a ROSMOD project: no .rml, .rosml, .rhw or .rdp files found", file=given)]
            )
        if len(sw_files) > 1:
            raise RosmodImportError(
                [
                    ParseError(
                        f"a ROSMOD project has one software model; found {len(sw_files)}: "
                        f"{', '.join(p.name for p in sw_files)}",
                        file=_shown(given, sw_files[1].relative_to(root)),
                    )
                ]
            )
    project = _new("Project", name=project_name, path=given)
    software = sw_info = None
    version = None
    software_failed = False
    for sw_file in sw_files:
        rel = sw_file.relative_to(folder).as_posix()
        shown = _shown(shown_root, rel) if root.is_dir() else given
        try:
            text = _read_text(sw_file, shown)
            if _looks_like_json(text):
                version = "0.4"
                _read_v04(text, shown, rel, project, ctx)
                continue
            stmts = _parse_blocks(text, shown)
            version = _detect_rml_version(stmts)
            software, sw_info = _software(stmts, version, sw_file.stem, rel, shown, ctx)
            project.software = software
            if version == "0.3":  # messages and services live in msg/ and srv/ beside the .rml
                _load_interfaces(software, sw_file.parent, folder, shown_root, sw_info, ctx)
        except ParseError as exc:
            ctx.error(exc)
            software_failed = True
    systems: dict[str, EObject] = {}
    failed_systems: set[str] = set()  # hardware models that could not be read: no cascade errors
    legacy_hw = False
    for hw_file in hw_files:
        rel = hw_file.relative_to(folder).as_posix()
        shown = _shown(shown_root, rel)
        try:
            stmts = _parse_blocks(_read_text(hw_file, shown), shown)
            system = _system(stmts, hw_file.stem, rel, shown, ctx)
            if any(s.keyword == "host" for s in stmts):
                legacy_hw = True
            project.systems.append(system)
            systems[system.name] = system
        except ParseError as exc:
            ctx.error(exc)
            failed_systems.add(hw_file.stem)
    for sys_name, system in systems.items():
        snp_dir = (hw_files[0].parent / "snp") if hw_files else None
        if snp_dir is not None and snp_dir.is_dir():
            for snp in _side_files(snp_dir, ".snp"):
                parts = snp.name[:-4].split(".")
                shown = _shown(shown_root, snp.relative_to(folder))
                if parts[0] != sys_name or len(parts) > 2:
                    continue
                try:
                    text = _read_text(snp, shown)
                except ParseError as exc:
                    ctx.error(exc)
                    continue
                if len(parts) == 1:
                    system.properties.append(_prop("snp", text))
                else:
                    host = next((h for h in system.hosts if h.name == parts[1]), None)
                    if host is None:
                        ctx.warn(f"skipped {snp.name!r}: no host {parts[1]!r} in {sys_name!r}", shown)
                    else:
                        host.properties.append(_prop("snp", text))
    deployments = []
    for dp_file in dp_files:
        rel = dp_file.relative_to(folder).as_posix()
        shown = _shown(shown_root, rel)
        try:
            stmts = _parse_blocks(_read_text(dp_file, shown), shown)
            deployment, info = _deployment(stmts, dp_file.stem, rel, shown, ctx)
            project.deployments.append(deployment)
            deployments.append((deployment, info))
        except ParseError as exc:
            ctx.error(exc)
    if software is not None and sw_info is not None:
        _resolve_software(software, sw_info, ctx)
    for deployment, info in deployments:
        _resolve_deployment(
            deployment, info, systems, project.software, sw_info, ctx, software_failed, failed_systems
        )
    if version is None:  # no software model: tell v0.2 from v0.3 by the hardware/deployment syntax
        legacy_dp = any(p.key.startswith("host_instance:") for d in project.deployments for p in d.properties)
        version = "0.2" if (legacy_hw or legacy_dp) else "0.3"
    project.formatVersion = version
    ctx.raise_if_errors()
    return project


# =========================================================================== summary


def summarize(project: EObject) -> dict[str, int]:
    """Counts of a ROSMOD project (packages, messages, …, component instances), for checks and reports."""
    counts = dict.fromkeys(
        (
            "packages",
            "messages",
            "services",
            "actions",
            "components",
            "timers",
            "publishers",
            "subscribers",
            "clients",
            "servers",
            "action_clients",
            "action_servers",
            "systems",
            "hosts",
            "deployments",
            "containers",
            "nodes",
            "component_instances",
            "max_nodes",
            "max_component_instances",
        ),
        0,
    )
    software = project.software
    for package in software.packages if software is not None else []:
        counts["packages"] += 1
        counts["messages"] += len(package.messages)
        counts["services"] += len(package.services)
        counts["actions"] += sum(1 for p in package.properties if (p.key or "").startswith("Action:"))
        for comp in package.components:
            counts["components"] += 1
            counts["timers"] += len(comp.timers)
            for port in comp.ports:
                kind = port.eClass.name.lower() + "s"
                counts[kind] += 1
            counts["action_clients"] += sum(
                1 for p in comp.properties if (p.key or "").startswith("Action Client:")
            )
            counts["action_servers"] += sum(
                1 for p in comp.properties if (p.key or "").startswith("Action Server:")
            )
    for system in project.systems:
        counts["systems"] += 1
        counts["hosts"] += len(system.hosts)
    for deployment in project.deployments:
        counts["deployments"] += 1
        counts["containers"] += sum(
            1 for p in deployment.properties if (p.key or "").startswith("Container:")
        )
        nodes = len(deployment.nodes)
        instances = sum(len(n.componentInstances) for n in deployment.nodes)
        counts["nodes"] += nodes
        counts["component_instances"] += instances
        counts["max_nodes"] = max(counts["max_nodes"], nodes)
        counts["max_component_instances"] = max(counts["max_component_instances"], instances)
    return counts
