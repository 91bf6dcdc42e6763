"""Atomic, contained file writes; hardened XML and bounded JSON parsing for every reader."""

from __future__ import annotations

import contextlib
import json
import os
import stat
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Any

from lxml import etree

from rosaadl.arguments import expect_path
from rosaadl.errors import ExportError, ImportFormatError, Location, RosaadlError, UsageError

__all__ = [
    "atomic_write",
    "atomic_write_bytes",
    "atomic_write_text",
    "safe_join",
    "safe_xml_parser",
    "parse_xml_bytes",
    "element_path",
    "cannot_write",
    "existing",
    "JSON_INT_DIGITS",
    "JsonLimitError",
    "loads_bounded",
]


@contextmanager
def atomic_write(path: str | os.PathLike[str], mode: str = "wb") -> Iterator[IO]:
    """Write to a temporary file beside ``path`` and rename it into place on success.

    On any exception the temporary file is removed and ``path`` is left as it was: a failed
    run never leaves a partial output file. A file the system refuses to write (its folder is
    a file, the name is too long, the path is a folder) is an :class:`ExportError` naming it.
    """
    target = expect_path(path, "the file to write", error=ExportError)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
    except OSError as exc:
        raise cannot_write(target, exc) from None
    try:
        encoding = None if "b" in mode else "utf-8"
        newline = None if "b" in mode else ""
        with os.fdopen(fd, mode, encoding=encoding, newline=newline) as handle:
            yield handle
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(tmp, target)
    except BaseException as exc:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        if isinstance(exc, OSError):
            raise cannot_write(target, exc) from None
        raise


def cannot_write(target: Path, exc: OSError) -> ExportError:
    """The located error for a file or folder the system refused to make at ``target``."""
    blocker = next((p for p in target.parents if _is_file(p)), None)
    if isinstance(exc, (FileExistsError, NotADirectoryError)) and blocker is not None:
        reason = f"{blocker} is a file, not a folder"
    elif isinstance(exc, IsADirectoryError):
        reason = "it is a folder"
    else:
        reason = exc.strerror or str(exc)
    return ExportError(f"cannot write here: {reason}", file=str(target))


def _is_file(path: Path) -> bool:
    try:
        return not stat.S_ISDIR(path.stat().st_mode)
    except (OSError, ValueError):
        return False


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> None:
    with atomic_write(path, "wb") as handle:
        handle.write(data)


def atomic_write_text(path: str | os.PathLike[str], text: str) -> None:
    with atomic_write(path, "w") as handle:
        handle.write(text)


def safe_join(root: str | os.PathLike[str], *parts: str) -> Path:
    """Join ``parts`` under ``root`` and refuse any result outside it (``..``, absolute, links)."""
    try:
        base = Path(root).resolve()
        candidate = base.joinpath(*parts)
        resolved = candidate.resolve()
    except (OSError, ValueError) as exc:
        raise ExportError(f"cannot write {'/'.join(parts)!r} under {str(root)!r}: {exc}") from None
    if resolved != base and base not in resolved.parents:
        raise ExportError(
            f"refusing to write {'/'.join(parts)!r}: it would land outside the output directory {str(root)!r}"
        )
    return candidate


def safe_xml_parser(*, remove_blank_text: bool = False, deep: bool = False) -> etree.XMLParser:
    """An lxml parser with entity resolution, DTD loading and network access all off.

    ``deep`` raises libxml2's nesting limit from 256 to 2 048 elements (its "huge" mode, which
    also lifts its text-size limits; entities stay refused): for our own deep models.
    """
    return etree.XMLParser(
        resolve_entities=False,
        no_network=True,
        load_dtd=False,
        dtd_validation=False,
        huge_tree=deep,
        remove_blank_text=remove_blank_text,
        remove_comments=False,
    )


def element_path(element: etree._Element) -> str:
    """A readable XPath-like path for an element (``/cheddar/tasks/periodic_task[2]``)."""
    tree = element.getroottree()
    try:
        path = tree.getpath(element)
    except ValueError:
        return element.tag if isinstance(element.tag, str) else "?"
    # Make namespaced steps readable: {uri}name -> prefix:name
    return path


def parse_xml_bytes(
    data: bytes,
    filename: str,
    *,
    allow_doctype: bool = False,
    remove_blank_text: bool = False,
    deep: bool = False,
) -> etree._ElementTree:
    """Parse ``data`` with the hardened parser; errors become located :class:`ImportFormatError`.

    ``remove_blank_text`` drops whitespace-only text between elements (indentation), for
    readers that never look at it: the tree has half the nodes, and parses and frees faster.
    ``deep``: see :func:`safe_xml_parser`.

    A DOCTYPE that declares entities is refused (entity-expansion bombs, external entities);
    a plain DOCTYPE is refused too unless ``allow_doctype`` (Cheddar v2 files carry one).
    """
    if not data or data.isspace():
        raise ImportFormatError("the file is empty; expected an XML document", file=filename, line=1)
    try:
        tree = etree.ElementTree(
            etree.fromstring(data, safe_xml_parser(remove_blank_text=remove_blank_text, deep=deep))
        )
    except etree.XMLSyntaxError as exc:
        line, column = exc.position if exc.position else (None, None)
        raise ImportFormatError(
            f"malformed XML: {exc.msg}", file=filename, line=line, column=column
        ) from None
    docinfo = tree.docinfo
    if docinfo.doctype:
        internal = docinfo.internalDTD
        entities = [e.name for e in internal.iterentities()] if internal is not None else []
        if entities:
            problem = f"declares entities ({', '.join(entities[:5])})"
        elif docinfo.system_url:
            problem = f"refers to an external DTD ({docinfo.system_url})"
        elif not allow_doctype:
            problem = "is not expected here"
        else:
            problem = ""
        if problem:
            raise ImportFormatError(
                f"the document's DOCTYPE {problem}; DTD entities and external DTDs are refused "
                "(expected a plain XML document)",
                Location(file=filename, line=1),
            )
    return tree


def existing(path: str | os.PathLike[str], error: type[RosaadlError] = UsageError) -> bool:
    """Whether ``path`` names something that exists; a path the system cannot look up at all
    (a name too long, a NUL byte, a loop of links) is an ``error`` naming it."""
    target = expect_path(path)
    try:
        target.stat()
    except (FileNotFoundError, NotADirectoryError):
        return False
    except OSError as exc:
        raise error(f"cannot use this path: {exc.strerror or exc}", file=str(target)) from None
    return True


# --------------------------------------------------------------------------- JSON text
# Python's json.loads raises a bare ValueError for an integer literal longer than the
# interpreter's conversion limit (4 300 digits) and RecursionError for deep nesting; readers of
# user files call loads_bounded and turn JsonLimitError (and json.JSONDecodeError) into their
# own located errors.

#: The longest integer literal accepted (Python's own default conversion limit).
JSON_INT_DIGITS = 4300


class JsonLimitError(ValueError):
    """The JSON text is well formed but beyond what a reader accepts."""


def _bounded_int(text: str) -> int:
    digits = len(text.lstrip("-"))
    if digits > JSON_INT_DIGITS:
        raise JsonLimitError(f"an integer of {digits} digits (at most {JSON_INT_DIGITS})")
    return int(text)


def _refused_constant(name: str) -> float:
    raise JsonLimitError(f"{name} is not a JSON number")


def loads_bounded(text: str, *, allow_nan: bool = True) -> Any:
    """``json.loads(text)`` with long integers, deep nesting and (unless ``allow_nan``) the
    non-standard ``NaN``/``Infinity`` refused as :class:`JsonLimitError`."""
    extra = {} if allow_nan else {"parse_constant": _refused_constant}
    try:
        return json.loads(text, parse_int=_bounded_int, **extra)
    except RecursionError:
        raise JsonLimitError("the JSON is nested too deeply") from None
