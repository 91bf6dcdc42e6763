"""User-code blocks between preservation markers: reading them, and putting them back.

A block is the text between an opening and a closing marker, named after the model element it
belongs to::

    # <user-code name="ocv_color_tracking.image_tracker.cb_msg">
    ...hand-written code...
    # </user-code>

XML files (``package.xml``) write the same markers as comments (``<!-- <user-code name="…"> -->``).
Blocks whose element is gone are kept, commented out, in an *orphan section* at the end of the
file, between ``<orphaned-user-code>`` and ``</orphaned-user-code>``; a block there comes back
into place when an element of the same name appears again.

:func:`parse` reads a file into text segments and blocks (malformed markers are a located
:class:`~rosaadl.errors.GenerationError`); :func:`render` writes a freshly generated text with
the chosen block contents and the orphan section.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

from rosaadl.errors import GenerationError
from rosaadl.exporters.rclpy import naming

__all__ = [
    "STYLES",
    "Content",
    "Block",
    "ParsedFile",
    "parse",
    "render",
    "marker_lines",
    "fit_marker",
    "ORPHAN_TITLE",
]

#: A block's content: one ``(relative, text)`` pair per line; relative lines are indented like
#: their marker (the marker's indentation is not part of ``text``), others are kept as written.
Content = list[tuple[bool, str]]

ORPHAN_TITLE = "orphaned-user-code"
_LOOKS_LIKE_MARKER = re.compile(r"^[ \t]*<?/?(user-code|orphaned-user-code)\b")
_ORPHAN_NOTE = (
    "User code whose model element is no longer in the model, kept here commented out.",
    "A block comes back into place when an element of the same name appears again;",
    "move what you still need into a current block, then delete it from here.",
)


@dataclass(frozen=True)
class _Style:
    name: str
    open_re: re.Pattern[str]
    close_re: re.Pattern[str]
    orphan_open: str
    orphan_close: str
    prefix: str
    suffix: str

    def comment(self, text: str) -> str:
        if self.name == "xml":
            return f"{self.prefix}{_xml_escape(text)}{self.suffix}" if text else f"{self.prefix}{self.suffix}"
        if _LOOKS_LIKE_MARKER.match(text) or text.startswith("\\"):
            text = "\\" + text
        return f"{self.prefix}{text}".rstrip() if text else self.prefix.rstrip()

    def uncomment(self, line: str) -> str | None:
        """The text of a commented line of the orphan section (None when it is not one)."""
        stripped = line.strip()
        if self.name == "xml":
            if stripped.startswith("<!--") and stripped.endswith("-->"):
                inner = stripped[4:-3]
                inner = inner[1:] if inner.startswith(" ") else inner
                inner = inner[:-1] if inner.endswith(" ") else inner
                return _xml_unescape(inner)
            return None
        if stripped.startswith("#"):
            text = line.lstrip()[1:]
            text = text[1:] if text.startswith(" ") else text
            return text[1:] if text.startswith("\\") else text
        return None


def _hash_style() -> _Style:
    return _Style(
        name="hash",
        open_re=re.compile(r'^(?P<indent>[ \t]*)#[ \t]*<user-code[ \t]+name="(?P<name>[^"]*)"[ \t]*>[ \t]*$'),
        close_re=re.compile(r"^[ \t]*#[ \t]*</user-code>[ \t]*$"),
        orphan_open=f"# <{ORPHAN_TITLE}>",
        orphan_close=f"# </{ORPHAN_TITLE}>",
        prefix="# ",
        suffix="",
    )


def _xml_style() -> _Style:
    return _Style(
        name="xml",
        open_re=re.compile(
            r'^(?P<indent>[ \t]*)<!--[ \t]*<user-code[ \t]+name="(?P<name>[^"]*)"[ \t]*>[ \t]*-->[ \t]*$'
        ),
        close_re=re.compile(r"^[ \t]*<!--[ \t]*</user-code>[ \t]*-->[ \t]*$"),
        orphan_open=f"<!-- <{ORPHAN_TITLE}> -->",
        orphan_close=f"<!-- </{ORPHAN_TITLE}> -->",
        prefix="<!-- ",
        suffix=" -->",
    )


#: Comment styles by name: ``hash`` (Python, CMake, setup.cfg, .msg/.srv) and ``xml``.
STYLES: dict[str, _Style] = {"hash": _hash_style(), "xml": _xml_style()}


def _xml_escape(text: str) -> str:
    # XML comments may not contain "--" nor end with "-": escape every "-" (and the escape).
    return text.replace("\\", "\\\\").replace("-", "\\-")


def _xml_unescape(text: str) -> str:
    out = []
    chars = iter(text)
    for char in chars:
        if char == "\\":
            out.append(next(chars, "\\"))
        else:
            out.append(char)
    return "".join(out)


@dataclass
class Block:
    """One user-code block of a file."""

    name: str
    content: Content
    indent: str = ""
    line: int = 0  # 1-based line of the opening marker (0 for generated text)
    orphan: bool = False

    def text(self) -> str:
        """The block's lines as plain text (relative lines without indentation)."""
        return "\n".join(t for _, t in self.content)


@dataclass
class ParsedFile:
    """A file split into plain text and blocks, plus the blocks of its orphan section."""

    segments: list[str | Block] = field(default_factory=list)
    blocks: dict[str, Block] = field(default_factory=dict)
    orphans: dict[str, Block] = field(default_factory=dict)

    @property
    def has_markers(self) -> bool:
        return bool(self.blocks or self.orphans)


#: Longest marker line in Python files (ROS 2's flake8 line length).
_LINE_LENGTH = 99


def fit_marker(name: str, indent: int) -> str:
    """``name`` when its ``# <user-code name="…">`` line at ``indent`` fits the line length, else
    the same dotted name with each part shortened (start and hash), which still tells the element."""
    room = _LINE_LENGTH - indent - len('# <user-code name="">')
    if len(name) <= room:
        return name
    parts = name.split(".")
    each = max(10, (room - (len(parts) - 1)) // len(parts))
    return ".".join(naming.shorten(part, each) for part in parts)


def marker_lines(name: str, style: str = "hash", indent: str = "") -> tuple[str, str]:
    """The opening and closing marker lines of block ``name``."""
    s = STYLES[style]
    if s.name == "xml":
        return f'{indent}<!-- <user-code name="{name}"> -->', f"{indent}<!-- </user-code> -->"
    return f'{indent}# <user-code name="{name}">', f"{indent}# </user-code>"


def _error(message: str, filename: str, line: int) -> GenerationError:
    return GenerationError(
        f"{message} (user-code markers must open and close in pairs)", file=filename, line=line
    )


def parse(text: str, style: str, filename: str = "<generated>") -> ParsedFile:
    """Split ``text`` into segments and blocks; malformed markers raise a located error."""
    s = STYLES[style]
    result = ParsedFile()
    lines = text.splitlines()
    pending: list[str] = []
    current: Block | None = None
    index = 0
    while index < len(lines):
        line = lines[index]
        number = index + 1
        if "user-code" not in line:  # most lines: no marker
            if current is None:
                pending.append(line)
            elif current.indent and line.startswith(current.indent):
                current.content.append((True, line[len(current.indent) :]))
            elif not line.strip():
                current.content.append((True, ""))
            else:
                current.content.append((current.indent == "", line))
            index += 1
            continue
        if current is None and line.strip() == s.orphan_open:
            if pending:
                result.segments.append("\n".join(pending) + "\n")
                pending = []
            index = _parse_orphans(lines, index + 1, s, filename, result)
            continue
        opened = s.open_re.match(line)
        if opened:
            if current is not None:
                raise _error(
                    f"block {opened['name']!r} opens inside block {current.name!r} "
                    f"(opened on line {current.line})",
                    filename,
                    number,
                )
            name = opened["name"]
            if name in result.blocks:
                raise _error(
                    f"block {name!r} appears twice (first on line {result.blocks[name].line})",
                    filename,
                    number,
                )
            if pending:
                result.segments.append("\n".join(pending) + "\n")
                pending = []
            current = Block(name=name, content=[], indent=opened["indent"], line=number)
        elif s.close_re.match(line):
            if current is None:
                raise _error("a closing marker without an opening one", filename, number)
            result.blocks[current.name] = current
            result.segments.append(current)
            current = None
        elif current is not None:
            if current.indent and line.startswith(current.indent):
                current.content.append((True, line[len(current.indent) :]))
            elif not line.strip():
                current.content.append((True, ""))
            else:
                current.content.append((current.indent == "", line))
        else:
            pending.append(line)
        index += 1
    if current is not None:
        raise _error(f"block {current.name!r} is never closed", filename, current.line)
    if pending:
        result.segments.append("\n".join(pending) + ("\n" if text.endswith("\n") else ""))
    return result


def _parse_orphans(lines: list[str], index: int, s: _Style, filename: str, result: ParsedFile) -> int:
    start = index
    current: Block | None = None
    while index < len(lines):
        line = lines[index]
        number = index + 1
        if line.strip() == s.orphan_close:
            if current is not None:
                raise _error(f"orphaned block {current.name!r} is never closed", filename, current.line)
            return index + 1
        opened = s.open_re.match(line)
        if opened:
            if current is not None:
                raise _error(f"orphaned block {opened['name']!r} opens inside another", filename, number)
            current = Block(name=opened["name"], content=[], line=number, orphan=True)
        elif s.close_re.match(line):
            if current is None:
                raise _error("a closing marker without an opening one", filename, number)
            # Two orphans of the same name (the element vanished twice): keep both.
            name = current.name
            suffix = 2
            while name in result.orphans:
                name = f"{current.name}#{suffix}"
                suffix += 1
            result.orphans[name] = current
            current = None
        elif current is not None:
            text = s.uncomment(line)
            if text is None:
                raise _error(f"orphaned block {current.name!r}: line is not commented out", filename, number)
            current.content.append((True, text))
        index += 1
    raise _error("the orphan section is never closed", filename, start)


def _content_lines(content: Content, indent: str) -> list[str]:
    out = []
    for relative, text in content:
        if relative:
            out.append(f"{indent}{text}" if text else "")
        else:
            out.append(text)
    return out


def render(
    generated: ParsedFile,
    choose: Callable[[Block], Content | None],
    orphans: Iterable[tuple[str, Content]],
    style: str,
) -> str:
    """The generated text with each block's content from ``choose`` (None keeps the default), then
    the orphan section with ``orphans`` (name, content) when there are any."""
    s = STYLES[style]
    out: list[str] = []
    for segment in generated.segments:
        if isinstance(segment, str):
            out.append(segment)
            continue
        chosen = choose(segment)
        content = segment.content if chosen is None else chosen
        opening, closing = marker_lines(segment.name, style, segment.indent)
        body = _content_lines(content, segment.indent)
        out.append("\n".join([opening, *body, closing]) + "\n")
    text = "".join(out)
    orphan_list = list(orphans)
    if orphan_list:
        if not text.endswith("\n"):
            text += "\n"
        section = ["", s.orphan_open]
        section.extend(s.comment(line) for line in _ORPHAN_NOTE)
        for name, content in orphan_list:
            opening, closing = marker_lines(name.partition("#")[0], style)
            section.append(opening)
            for relative, line in content:
                section.append(s.comment(line) if relative else s.comment(line.strip()))
            section.append(closing)
        section.append(s.orphan_close)
        text += "\n".join(section) + "\n"
    return text
