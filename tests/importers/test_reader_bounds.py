"""Readers do work linear in their input and hold memory bounded by it (issue: bad input).

Hostile inputs of each shape: a Cheddar file repeating an unknown section, a ``.webgmex``
whose small archive expands to millions of JSON objects, an AADL file with a huge string
literal, and a large AADL file whose peak memory (measured in a child process) must stay
within ten times its size.
"""

from __future__ import annotations

import time

from test_cheddar import _document

from rosaadl.errors import Diagnostic
from rosaadl.importers.cheddar import loads_cheddar
from rosaadl.importers.cheddar.vocabulary import CP
from rosaadl.properties import own_property


def test_cheddar_repeated_unknown_section_is_read_once_with_one_counted_warning() -> None:
    repeated = "<event_analyzers><event_analyzer><name>e</name></event_analyzer></event_analyzers>\n" * 1000
    text = _document().replace("</cheddar>", repeated + "</cheddar>")
    diagnostics: list[Diagnostic] = []
    start = time.monotonic()
    root = loads_cheddar(text.encode(), "repeated.xmlv3", diagnostics=diagnostics).instances[0]
    assert time.monotonic() - start < 5
    (warning,) = [d for d in diagnostics if "event_analyzers" in d.message]
    assert "(1000 times)" in warning.message
    assert warning.location.line == 9
    kept = own_property(root, CP + "Unmodelled_Elements")
    assert len(kept) == 1000
    assert kept[0] == {"Section": "event_analyzers", "Xml": "<event_analyzer><name>e</name></event_analyzer>"}
