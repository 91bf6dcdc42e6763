"""Reading a Cheddar document into an AADL instance model: the public entry points.

:func:`loads_cheddar` checks the DOCTYPE, parses the XML, tells the file style (Cheddar 2 or
Cheddar 3 ADL) and reads the sections in the order that makes every name resolvable, each with
the reader of its style (:mod:`~rosaadl.importers.cheddar.v3`, :mod:`~rosaadl.importers.cheddar.v2`).
Sections rosaadl does not model are kept verbatim (``Unmodelled_Elements``), as are the fields
nobody read (``Unmodelled_Fields``), the order of the sections (``Section_Order``) and the file's
format (``Cheddar_Format``, which the exporter writes back by default), so that
import → export → import gives an equal model.
"""

from __future__ import annotations

from pathlib import Path

from lxml import etree
from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.arguments import checked, expect_path
from rosaadl.bulk import gc_paused
from rosaadl.errors import Diagnostic, ImportFormatError, RosaadlError
from rosaadl.fileio import parse_xml_bytes
from rosaadl.importers.cheddar import v2, v3
from rosaadl.importers.cheddar.document import (
    canonical_xml,
    cheddar_format_of,
    children,
    local,
    strip_internal_subset,
)
from rosaadl.importers.cheddar.state import ReadState
from rosaadl.importers.cheddar.values import (
    aadl_identifier,
    associate,
    int_value,
    list_value,
    record_value,
    str_value,
)
from rosaadl.importers.cheddar.vocabulary import CP, SECTIONS_V2, SECTIONS_V3

__all__ = ["loads_cheddar", "load_cheddar", "read_document"]


def read_document(state: ReadState, data: bytes) -> EObject:
    """The ``AadlModel`` of one document's bytes (the work of :func:`loads_cheddar`)."""
    data = strip_internal_subset(data, state.filename)
    tree = parse_xml_bytes(data, state.filename, allow_doctype=True)
    root_element = tree.getroot()
    if local(root_element) != "cheddar":
        state.fail(root_element, f"the root element is <{local(root_element)}>; expected <cheddar>")
    state.version = cheddar_format_of(root_element)
    stem = Path(state.filename).stem or "cheddar"
    aadl_model = model.new("AadlModel", name=aadl_identifier(stem))
    root = model.new("SystemInstance", name=aadl_identifier(stem), category="system")
    state.root = root
    state.names[id(root)] = set()

    sections: dict[str, list[etree._Element]] = {}
    order: list[str] = []
    for section in children(root_element):
        name = local(section)
        order.append(name)
        sections.setdefault(name, []).append(section)
    if state.version == 3:
        v3.collect_ids(state, sections)
    known = SECTIONS_V3 if state.version == 3 else SECTIONS_V2
    for name, repeated in sections.items():
        if name not in known:
            _keep_sections(state, name, repeated)
    readers = v3.SECTION_READERS if state.version == 3 else v2.SECTION_READERS
    for name in known:
        for section in sections.get(name, []):
            state.attach()
            readers[name](state, section)
    state.attach()
    if state.version == 3:
        v3.keep_unreferenced_cores(state, sections.get("core_units", []))
    for owner, kept in state.kept_fields.values():
        associate(owner, CP + "Unmodelled_Fields", list_value(kept))
    associate(root, CP + "Section_Order", list_value(str_value(s) for s in order))
    associate(root, CP + "Cheddar_Format", int_value(state.version))
    if state.kept:
        associate(
            root,
            CP + "Unmodelled_Elements",
            list_value(
                record_value([("Section", str_value(s)), ("Xml", str_value(x))]) for s, x in state.kept
            ),
        )
    aadl_model.instances.append(root)
    return aadl_model


def _keep_sections(state: ReadState, name: str, sections: list[etree._Element]) -> None:
    """Keep verbatim every section called ``name`` (not modelled), with one warning for all.

    Each section is visited once (the reading stays linear in the file's size); a name
    repeated ``n`` times gives one warning at its first section, counting them (see
    :meth:`ReadState.report_warnings`).
    """
    if state.strict:
        state.fail(sections[0], f"section <{name}> is not modelled by rosaadl")
    for section in sections:
        state.warn(section, f"section <{name}> is not modelled by rosaadl; kept as it is")
        for item in children(section):
            state.kept.append((name, canonical_xml(item)))


@checked
def loads_cheddar(
    data: bytes | str,
    filename: str = "<cheddar>",
    *,
    time_unit: str = "us",
    strict: bool = False,
    diagnostics: list[Diagnostic] | None = None,
) -> EObject:
    """Read a Cheddar 2 or 3 XML document into an ``AadlModel`` holding one ``SystemInstance``.

    ``time_unit`` says what Cheddar's plain integer times are (``us`` or ``ms``);
    ``strict`` turns what Cheddar's reader tolerates (undeclared names in Cheddar 2 files,
    unknown fields and sections, unknown enumeration values) into errors. Warnings are
    appended to ``diagnostics`` when given (and logged). Problems raise a located
    :class:`ImportFormatError` (file, line and element path).
    """
    if isinstance(data, str):
        data = data.encode("utf-8")
    state = ReadState(filename, time_unit, strict, diagnostics)
    try:
        with gc_paused():
            return read_document(state, data)
    except RosaadlError:
        raise
    except RecursionError:
        raise ImportFormatError("the document is nested too deeply", file=filename) from None
    finally:
        state.report_warnings()


@checked
def load_cheddar(
    path: str | Path,
    *,
    time_unit: str = "us",
    strict: bool = False,
    diagnostics: list[Diagnostic] | None = None,
) -> EObject:
    """Read a Cheddar file (``.xmlv3`` / ``.xml``); see :func:`loads_cheddar`."""
    source = expect_path(path)
    try:
        data = source.read_bytes()
    except OSError as exc:
        raise ImportFormatError(f"cannot read the file: {exc.strerror}", file=str(path)) from None
    return loads_cheddar(data, str(path), time_unit=time_unit, strict=strict, diagnostics=diagnostics)
