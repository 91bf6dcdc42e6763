"""The entry points of the ``.aaxl2`` reader: from a path or bytes to an :class:`ImportResult`.

One read: parse (without indentation text nodes, under :func:`~rosaadl.bulk.gc_paused`), read
the root into the model (instance or declarative), resolve the queued references, decode the
positional literals once the era is known, and free the parsed document last
(:meth:`~.document.Reader.release`). A file whose references name ``xmi:id``s that the first
pass did not index is read a second time with them.
"""

from __future__ import annotations

import logging
import os
from pathlib import Path

from lxml import etree

from rosaadl.bulk import gc_paused
from rosaadl.errors import ImportFormatError, Location
from rosaadl.fileio import parse_xml_bytes

from .declarative import DeclarativeReader
from .document import Reader
from .instances import read_instance_roots
from .literals import decode_literals
from .references import IdsNeeded, resolve_pending
from .result import ImportResult
from .xmi import ROOT_PACKAGE, ROOT_PROPERTY_SET, ROOT_SYSTEM, ROOT_XMI, XMI_ID_KEY

__all__ = ["read_aaxl2", "loads_aaxl2", "load_document", "carries_id", "DEFAULT_MAX_BYTES"]

log = logging.getLogger(__package__)

#: Files larger than this are refused before parsing (override with ``max_bytes``).
DEFAULT_MAX_BYTES = 512 * 1024 * 1024


def read_aaxl2(
    path: str | os.PathLike[str], *, strict: bool = False, max_bytes: int = DEFAULT_MAX_BYTES
) -> ImportResult:
    """Read an OSATE ``.aaxl2`` file; every problem is a located :class:`ImportFormatError`.

    ``strict`` turns unknown elements (otherwise skipped with a warning) into errors;
    ``max_bytes`` refuses larger files before reading them.
    """
    source = Path(path)
    filename = str(path)
    try:
        size = source.stat().st_size
    except OSError as exc:
        raise ImportFormatError(f"cannot read the file: {exc.strerror}", file=filename) from None
    if size > max_bytes:
        raise ImportFormatError(
            f"the file is {size} bytes, more than the {max_bytes}-byte limit for .aaxl2 files", file=filename
        )
    try:
        data = source.read_bytes()
    except OSError as exc:
        raise ImportFormatError(f"cannot read the file: {exc.strerror}", file=filename) from None
    return loads_aaxl2(data, filename, strict=strict, max_bytes=max_bytes)


def loads_aaxl2(
    data: bytes, filename: str = "<aaxl2>", *, strict: bool = False, max_bytes: int = DEFAULT_MAX_BYTES
) -> ImportResult:
    """Read ``.aaxl2`` content from bytes (``filename`` is used in messages and for sidecars)."""
    if len(data) > max_bytes:
        raise ImportFormatError(
            f"the document is {len(data)} bytes, more than the {max_bytes}-byte limit for .aaxl2 files",
            file=filename,
        )
    try:
        return load_document(data, filename, strict=strict, with_ids=False)
    except IdsNeeded:
        return load_document(data, filename, strict=strict, with_ids=True)


def carries_id(root_el: etree._Element) -> bool:
    """Does the root or one of its first descendants carry an ``xmi:id`` (then every object does)?"""
    element = root_el
    for _depth in range(3):
        if element.get(XMI_ID_KEY) is not None:
            return True
        for child in element:
            if isinstance(child.tag, str):
                element = child
                break
        else:
            return False
    return False


def load_document(data: bytes, filename: str, *, strict: bool, with_ids: bool) -> ImportResult:
    """Parse ``data``, read its root (instance or declarative), resolve the references and decode
    the literals: one pass of :func:`loads_aaxl2` (``with_ids``: index every ``xmi:id``)."""
    with gc_paused():
        # indentation is never read (annex text is re-indented): half the nodes to build and free
        tree = parse_xml_bytes(data, filename, remove_blank_text=True)
        root_el = tree.getroot()
        reader = Reader(filename, tree, strict=strict)
        # cheap facts about the text that let the reader skip work: no ids to index, and no
        # namespace prefix declared below the root (so xsi:type prefixes mean the same everywhere).
        # EMF writes an xmi:id on every object of a resource that uses them, so the root and its
        # first child tell; a file that refers to an id only deeper down is read again with ids
        reader.has_ids = with_ids or carries_id(root_el)
        reader.nsmap_is_global = data.count(b"xmlns") <= len(reader.nsmap)
        tag = root_el.tag
        if tag in (ROOT_SYSTEM, ROOT_XMI):
            aadl_model = read_instance_roots(reader, root_el)
            kind = "instance"
        elif tag in (ROOT_PACKAGE, ROOT_PROPERTY_SET):
            aadl_model, kind = DeclarativeReader(reader, root_el).read()
        else:
            raise ImportFormatError(
                f"unexpected root element <{tag}>; expected instance:SystemInstance, xmi:XMI, aadl2:Package "
                "or aadl2:PropertySet (an OSATE .aaxl2 file)",
                Location(file=filename, line=root_el.sourceline, path=tree.getpath(root_el)),
            )
        resolve_pending(reader)
        choice = decode_literals(reader)
    model_name = os.path.basename(filename).rsplit(".", 1)[0] if not filename.startswith("<") else "aaxl2"
    reader.fast.set_value(aadl_model, reader.f["AadlModel.name"], model_name)
    result = ImportResult(
        model=aadl_model,
        source=filename,
        kind=kind,
        era=choice.era,
        property_set_eras=dict(choice.set_eras),
        warnings=reader.warnings,
        sidecar_uris=tuple(sorted(reader.declarative_uris)),
        base_dir=reader.base_dir,
    )
    log.debug("read %s: %s, era %s, %d warning(s)", filename, kind, choice.era, len(reader.warnings))
    # the document goes last: see Reader.release
    reader.release()
    return result
