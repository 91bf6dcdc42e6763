"""The Cheddar XML document: the safe DOCTYPE check, the two file styles, element helpers.

Cheddar 2 files (DTD style, ``.xml``) carry an inline DTD that libxml2 refuses and Cheddar's
own reader ignores: :func:`strip_internal_subset` checks that it is harmless (no entities, no
external DTD) and blanks it out, line ends kept. :func:`cheddar_format_of` tells a Cheddar 2
document from a Cheddar 3 ADL one (``.xmlv3``) by the shape of its sections. Tags are matched
case-insensitively, as Cheddar's reader does (:func:`local`). :func:`canonical_xml` is the form
in which the reader keeps what rosaadl does not model.
"""

from __future__ import annotations

from copy import deepcopy

from lxml import etree

from rosaadl.errors import ImportFormatError

__all__ = ["strip_internal_subset", "cheddar_format_of", "canonical_xml", "local", "children"]


def local(element: etree._Element) -> str:
    """The element's tag without namespace, in lower case."""
    return etree.QName(element).localname.lower()


def children(element: etree._Element) -> list[etree._Element]:
    """The element's child elements (comments and processing instructions left out)."""
    return [c for c in element if isinstance(c.tag, str)]


def cheddar_format_of(root: etree._Element) -> int:
    """2 for a Cheddar 2 document, 3 for a Cheddar 3 one (by the shape of its sections)."""
    v2_tags = {"processor", "task", "resource", "message", "network"}
    for section in children(root):
        if local(section) == "core_units":
            return 3
        for item in children(section):
            tag = local(item)
            if item.get("id") is not None or tag.endswith(
                ("_task", "_resource", "_network", "_message", "_processor")
            ):
                return 3
            if tag in v2_tags:
                return 2
    return 3


def canonical_xml(element: etree._Element) -> str:
    """An element as XML text without insignificant whitespace (the form kept in the model)."""
    copy = deepcopy(element)
    for node in copy.iter():
        if node.text is not None and not node.text.strip() and len(node):
            node.text = None
        if node.tail is not None and not node.tail.strip():
            node.tail = None
        elif node.tail is not None:
            node.tail = node.tail.strip()
        if len(node) == 0 and node.text is not None:
            node.text = node.text.strip()
    copy.tail = None
    return etree.tostring(copy, encoding="unicode")


def strip_internal_subset(data: bytes, filename: str) -> bytes:
    """Blank out a DOCTYPE declaration after checking it is harmless.

    Cheddar 2 files carry an inline DTD that libxml2 refuses (it declares
    ``context_switch_overhead`` twice) and that Cheddar's own SAX reader does not use. A
    DOCTYPE that refers to an external DTD, declares entities or uses parameter entities is
    refused with a located error; a harmless one is replaced by spaces (line ends kept, so
    that line numbers stay right) before the document is parsed.
    """
    start = _doctype_start(data)
    if start < 0:
        return data
    line = data.count(b"\n", 0, start) + 1
    pos = start + len(b"<!DOCTYPE")
    end_name = pos
    while end_name < len(data) and data[end_name : end_name + 1] not in (b"[", b">"):
        end_name += 1
    header = data[pos:end_name].split()
    if len(header) > 1 and header[1].upper() in (b"SYSTEM", b"PUBLIC"):
        raise ImportFormatError(
            "the DOCTYPE refers to an external DTD; external DTDs are refused (expected a plain "
            "Cheddar XML document or an inline DTD)",
            file=filename,
            line=line,
        )
    if end_name >= len(data):
        raise ImportFormatError("the DOCTYPE declaration is not closed", file=filename, line=line)
    end = end_name
    if data[end : end + 1] == b"[":
        end = _internal_subset_end(data, end + 1, filename, line)
        while end < len(data) and data[end : end + 1] in b" \t\r\n":
            end += 1
        if data[end : end + 1] != b">":
            raise ImportFormatError("the DOCTYPE declaration is not closed", file=filename, line=line)
    blank = bytes(c if c in (0x0A, 0x0D) else 0x20 for c in data[start : end + 1])
    return data[:start] + blank + data[end + 1 :]


def _doctype_start(data: bytes) -> int:
    """Offset of ``<!DOCTYPE`` in the prolog (before the root element), or -1."""
    pos = 3 if data.startswith(b"\xef\xbb\xbf") else 0
    n = len(data)
    while pos < n:
        ch = data[pos : pos + 1]
        if ch in b" \t\r\n" and ch:
            pos += 1
            continue
        if data.startswith(b"<?", pos):
            close = data.find(b"?>", pos + 2)
            if close < 0:
                return -1
            pos = close + 2
            continue
        if data.startswith(b"<!--", pos):
            close = data.find(b"-->", pos + 4)
            if close < 0:
                return -1
            pos = close + 3
            continue
        if data.startswith(b"<!DOCTYPE", pos):
            return pos
        return -1
    return -1


def _internal_subset_end(data: bytes, pos: int, filename: str, line: int) -> int:
    """Offset just after the ``]`` closing an internal subset; refuses entity declarations."""
    n = len(data)
    while pos < n:
        if data.startswith(b"<!--", pos):
            close = data.find(b"-->", pos + 4)
            if close < 0:
                break
            pos = close + 3
            continue
        if data.startswith(b"<!ENTITY", pos):
            raise ImportFormatError(
                "the DOCTYPE declares entities; DTD entities are refused (entity expansion and "
                "external entities are not allowed in Cheddar files)",
                file=filename,
                line=data.count(b"\n", 0, pos) + 1,
            )
        ch = data[pos : pos + 1]
        if ch == b"%":
            raise ImportFormatError(
                "the DOCTYPE uses parameter entities; they are refused",
                file=filename,
                line=data.count(b"\n", 0, pos) + 1,
            )
        if ch in (b'"', b"'"):
            close = data.find(ch, pos + 1)
            if close < 0:
                break
            pos = close + 1
            continue
        if ch == b"]":
            return pos + 1
        pos += 1
    raise ImportFormatError("the DOCTYPE's internal subset is not closed", file=filename, line=line)
