"""The jinja2 environment of the generator and the filters its templates use.

Every value that comes from the model reaches a template through a filter that makes it safe
where it lands: :func:`py_literal` (a Python literal, long strings split across lines),
:func:`doc_text` (docstring text: no quotes that could end it, no backslashes, bounded length),
:func:`comment_text` (one comment line), :func:`xml_text` (XML character data).
"""

from __future__ import annotations

import textwrap
from functools import lru_cache

import jinja2

from rosaadl.exporters.rclpy.nodes import QoS
from rosaadl.exporters.rclpy.twin import payload_note

__all__ = [
    "LINE_LENGTH",
    "environment",
    "render_template",
    "py_literal",
    "call_argument",
    "keyword_argument",
    "pair_expression",
    "doc_text",
    "docwrap",
    "comment_text",
    "xml_text",
    "qos_expression",
    "import_line",
]

#: ROS 2's flake8 line length.
LINE_LENGTH = 99
_DOC_NAME_LIMIT = 48


def _clean(text: object) -> str:
    """One line of printable text: control characters and line breaks become spaces."""
    text = str(text)
    if not text.isprintable():
        text = "".join(c if c.isprintable() else " " for c in text)
    return " ".join(text.split())


def py_literal(value: object, indent: int | None = None) -> str:
    """A Python literal for ``value``; a string too long for one line is split in adjacent
    literals, one per line at ``indent`` spaces (for arguments that start a line)."""
    if isinstance(value, bool) or value is None or isinstance(value, int):
        return repr(value)
    if isinstance(value, float):
        return repr(float(value))
    text = str(value)
    literal = repr(text)
    if indent is None or indent + len(literal) + 2 <= LINE_LENGTH:
        return literal
    width = max(16, LINE_LENGTH - indent - 6)
    pieces: list[str] = []
    current = ""
    for char in text:
        if len(repr(current + char)) > width and current:
            pieces.append(repr(current))
            current = ""
        current += char
    if current or not pieces:
        pieces.append(repr(current))
    return ("\n" + " " * indent).join(pieces)


def call_argument(value: object, column: int, indent: int) -> str:
    """A string argument written right after an opening parenthesis at ``column``: on the same
    line when it fits, else on the next lines (hanging indent at ``indent + 4``)."""
    literal = py_literal(value)
    if column + len(literal) + 1 <= LINE_LENGTH:
        return literal
    return "\n" + " " * (indent + 4) + py_literal(value, indent + 4)


def keyword_argument(value: object, column: int, indent: int) -> str:
    """A string written after ``name=`` at ``column``: as it is when it fits, else parenthesised
    over the next lines (hanging indent at ``indent + 4``)."""
    literal = py_literal(value)
    if column + len(literal) + 1 <= LINE_LENGTH:
        return literal
    return "(\n" + " " * (indent + 4) + py_literal(value, indent + 4) + ")"


def pair_expression(pair: tuple[object, object], indent: int) -> str:
    """``('a', 'b')`` on one line when it fits, else one element per line."""
    first, second = pair
    line = f"({py_literal(first)}, {py_literal(second)})"
    if indent + len(line) + 1 <= LINE_LENGTH:
        return line
    pad = " " * (indent + 4)
    return (
        f"(\n{pad}{py_literal(first, indent + 4)},\n{pad}{py_literal(second, indent + 4)},\n{' ' * indent})"
    )


def doc_text(value: object) -> str:
    """Text for a docstring: no quotes or backslashes, one line, at most 48 characters."""
    text = _clean(value).replace("\\", "/").replace('"', "'")
    if len(text) > _DOC_NAME_LIMIT:
        text = text[: _DOC_NAME_LIMIT - 3] + "..."
    return text


def docwrap(value: object, indent: int = 0) -> str:
    """A docstring paragraph wrapped at the line length, continuation lines indented."""
    text = _clean(value).replace("\\", "/").replace('"', "'")
    if len(text) <= LINE_LENGTH - indent:
        return text
    lines = textwrap.wrap(
        text, width=LINE_LENGTH - indent, break_long_words=True, break_on_hyphens=False
    ) or [""]
    return ("\n" + " " * indent).join(lines)


def comment_text(value: object, indent: int | None = None) -> str:
    """Text for ``#`` comments; wrapped over several comment lines when ``indent`` is given."""
    text = _clean(value)
    if indent is None:
        return text
    lines = textwrap.wrap(text, width=LINE_LENGTH - indent - 2, break_long_words=True) or [""]
    return ("\n" + " " * indent + "# ").join(lines)


def xml_text(value: object) -> str:
    """XML character data (also safe in attribute values)."""
    text = _clean(value)
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")


def qos_expression(qos: QoS, indent: int) -> str:
    """``QoSProfile(...)`` over several lines, continuation lines at ``indent + 4``."""
    pad = " " * (indent + 4)
    return (
        "QoSProfile(\n"
        f"{pad}history=QoSHistoryPolicy.{qos.history},\n"
        f"{pad}depth={qos.depth},\n"
        f"{pad}reliability=QoSReliabilityPolicy.{qos.reliability},\n"
        f"{pad}durability=QoSDurabilityPolicy.{qos.durability})"
    )


def import_line(module: str, names: list[str]) -> str:
    """``import m`` or ``from m import a, b`` (parenthesised over lines when too long)."""
    if not names:
        return f"import {module}"
    line = f"from {module} import {', '.join(names)}"
    if len(line) <= LINE_LENGTH:
        return line
    inner = "".join(f"    {name},\n" for name in names)
    return f"from {module} import (\n{inner})"


@lru_cache(maxsize=1)
def environment() -> jinja2.Environment:
    """The generator's template environment (templates are package data)."""
    env = jinja2.Environment(
        loader=jinja2.PackageLoader("rosaadl.exporters.rclpy", "templates"),
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        undefined=jinja2.StrictUndefined,
        autoescape=False,
    )
    env.filters.update(
        py=py_literal,
        arg=call_argument,
        kwarg=keyword_argument,
        pair=pair_expression,
        doc=doc_text,
        docwrap=docwrap,
        comment=comment_text,
        xml=xml_text,
        qos=qos_expression,
        import_line=import_line,
        payload_note=payload_note,
        self_attr=lambda name: f"self.{name}",
        self_call=lambda name: f"self.{name}()",
    )
    return env


def render_template(name: str, **context: object) -> str:
    return environment().get_template(name).render(**context)
