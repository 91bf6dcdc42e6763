"""The state shared while one unit is written: its lines, where the writer is, the name checks.

:class:`UnitContext` collects the output lines (:meth:`~UnitContext.emit`, wrapped where AADL
allows it), keeps the path of the element being written (``where``) for error messages, and
checks every name before it goes into the text (:meth:`~UnitContext.ident`,
:meth:`~UnitContext.qname`, :meth:`~UnitContext.path`, ...): a name that would not read back is a
located :class:`~rosaadl.errors.ExportError`. It is also the :class:`~rosaadl.property_text.NameRules`
of the property values it prints (:attr:`~UnitContext.value`).
"""

from __future__ import annotations

import logging
import re
from collections.abc import Sequence

from pyecore.ecore import EObject

from rosaadl.errors import ExportError, Location
from rosaadl.exporters.aadl_text.lexical import (
    ARRAY_SIZE_RE,
    CLASSIFIER_RE,
    ID_RE,
    MODE_REF_RE,
    PATH_RE,
    QNAME_RE,
    RESERVED_WORDS,
    balanced,
    wrapped_in_parentheses,
)
from rosaadl.property_text import ValuePrinter

__all__ = ["INDENT", "LINE_LENGTH", "UnitContext"]

log = logging.getLogger(__package__)  # the writer's one logger, rosaadl.exporters.aadl_text

INDENT = "  "
#: Lines longer than this are wrapped where AADL allows it (enumerations, units, owner lists).
LINE_LENGTH = 100


class UnitContext:
    """One unit being written: ``lines`` collects the output, ``where`` names the element being
    written, ``root`` is the model the unit belongs to (to find the classifiers it names)."""

    def __init__(self, unit: EObject) -> None:
        self.unit = unit
        self.lines: list[str] = []
        self.where: list[str] = []
        root = unit
        while root.eContainer() is not None:
            root = root.eContainer()
        self.root = root
        self.classifier_cache: dict[str, EObject | None] = {}
        #: ``value(expr)``: a property expression as AADL text, every name in it checked
        self.value = ValuePrinter(self).text

    # ----------------------------------------------------------------- errors

    def error(self, message: str, element: EObject | None = None) -> ExportError:
        """An :class:`ExportError` at ``element`` (its line, when known) and the writer's path."""
        path = " / ".join(self.where) or None
        line = getattr(element, "line", None) or None if element is not None else None
        column = getattr(element, "column", None) or None if element is not None else None
        file = getattr(self.unit, "sourceFile", None) or None
        if line is None:
            file = None  # a file name without a line would point at the source, not the model
        return ExportError(message, Location(file=file, line=line, column=column, path=path))

    def refuse(self, message: str, element: EObject | None = None) -> None:
        """What cannot be written as AADL text (a property value): raise the located error."""
        raise self.error(message, element)

    # ----------------------------------------------------------------- names

    def ident(self, name: str | None, what: str, element: EObject | None = None) -> str:
        """An AADL identifier (a reserved word is accepted, with a warning: OSATE refuses it)."""
        text = (name or "").strip()
        if not ID_RE.match(text):
            shown = repr(name) if name else "no name"
            raise self.error(
                f"{what} has {shown}: an AADL identifier is letters, digits and single underscores, "
                "starting with a letter",
                element,
            )
        if text.lower() in RESERVED_WORDS:
            log.warning(
                "%s%s is named %r, an AADL reserved word: OSATE will not read it",
                f"in {' / '.join(self.where)}: " if self.where else "",
                what,
                text,
            )
        return text

    def checked(self, text: str | None, pattern: re.Pattern[str], what: str, element: EObject | None) -> str:
        value = " ".join((text or "").split()) if pattern is not PATH_RE else (text or "").strip()
        if not pattern.match(value):
            raise self.error(f"{what} {text!r} is not well-formed", element)
        return value

    def qname(self, text: str | None, what: str, element: EObject | None = None) -> str:
        """A qualified name ``a::b::c``, written without spaces."""
        return self.checked(text, QNAME_RE, what, element).replace(" ", "")

    def classifier_ref(self, text: str | None, what: str, element: EObject | None = None) -> str:
        """A classifier reference ``Pkg::T`` or ``Pkg::T.impl``, written without spaces."""
        return self.checked(text, CLASSIFIER_RE, what, element).replace(" ", "")

    def path(self, text: str | None, what: str, element: EObject | None = None) -> str:
        """A dotted path (``a.b[2].c``, annex segments kept as written)."""
        value = self.checked(text, PATH_RE, what, element)
        if "{**" not in value:
            value = re.sub(r"\s+", "", value).replace("..", " .. ")
        return value

    def opaque(self, text: str | None, what: str, element: EObject | None) -> str:
        """Text the model keeps as written (prototype bindings): one line, balanced, no ``;``."""
        value = " ".join((text or "").split())
        if not value or not balanced(value) or ";" in value or "--" in value:
            raise self.error(f"{what} {text!r} cannot be written as AADL text", element)
        return value

    def bindings(self, text: str | None, element: EObject) -> str:
        """Prototype bindings in their parentheses."""
        value = self.opaque(text, "prototype bindings", element)
        return value if wrapped_in_parentheses(value) else f"({value})"

    def in_modes(self, modes: Sequence[str], element: EObject) -> str:
        """`` in modes (a, b => c)``, or ``""`` when there are none."""
        if not modes:
            return ""
        refs = []
        for mode in modes:
            match = MODE_REF_RE.match(" ".join((mode or "").split()))
            if not match:
                raise self.error(f"mode reference {mode!r} is not a mode name (or 'm => n')", element)
            refs.append(match.group(1) + (f" => {match.group(2)}" if match.group(2) else ""))
        return f" in modes ({', '.join(refs)})"

    def array_dimensions(self, dims: Sequence[str], element: EObject) -> str:
        """``[3][Pkg::Size][]`` from one size (or constant, or nothing) per dimension."""
        out = []
        for dim in dims:
            size = (dim or "").strip()
            if size.startswith("[") and size.endswith("]"):
                size = size[1:-1].strip()
            if not ARRAY_SIZE_RE.match(size):
                raise self.error(f"array dimension {dim!r} is not a size or a property constant", element)
            out.append(f"[{size.replace(' ', '')}]")
        return "".join(out)

    # ----------------------------------------------------------------- output

    def emit(self, level: int, text: str) -> None:
        self.lines.append(INDENT * level + text if text else "")

    def emit_wrapped(self, level: int, head: str, items: Sequence[str], tail: str) -> None:
        """``head item, item, ... tail`` on one line, or one item per line when too long."""
        one_line = f"{head}{', '.join(items)}{tail}"
        if len(INDENT * level) + len(one_line) <= LINE_LENGTH or len(items) < 2:
            self.emit(level, one_line)
            return
        self.emit(level, head.rstrip())
        for i, item in enumerate(items):
            self.emit(level + 1, item + ("," if i < len(items) - 1 else tail))

    def text(self) -> str:
        """The unit's text so far, with its final newline."""
        return "\n".join(self.lines) + "\n"
