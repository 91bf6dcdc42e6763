"""Readers do work linear in their input and hold memory bounded by it (issue: bad input).

Hostile inputs of each shape: a Cheddar file repeating an unknown section, a ``.webgmex``
whose small archive expands to millions of JSON objects, an AADL file with a huge string
literal, and large AADL files whose peak memory (measured in a child process) is the model's
and a little more: no parse tree of the whole file is held (README, "Known limits").
"""

from __future__ import annotations

import subprocess
import sys
import time
import zipfile
from pathlib import Path

from test_cheddar import _document, _task

from benchmarks.bench_aadl_reader import read_peak_per_byte
from benchmarks.generators.aadl_text import aadl_package_text, renamed_copies_text
from benchmarks.generators.corpus import aadl_texts
from rosaadl.errors import Diagnostic
from rosaadl.importers.cheddar import loads_cheddar
from rosaadl.importers.cheddar.vocabulary import CP
from rosaadl.importers.json_limits import json_value_bound
from rosaadl.properties import own_property
from tests.conftest import ROOT


def test_cheddar_repeated_unknown_section_is_read_once_with_one_counted_warning() -> None:
    repeated = "<event_analyzers><event_analyzer><name>e</name></event_analyzer></event_analyzers>\n" * 1000
    text = _document().replace("</cheddar>", repeated + "</cheddar>")
    diagnostics: list[Diagnostic] = []
    start = time.process_time()
    root = loads_cheddar(text.encode(), "repeated.xmlv3", diagnostics=diagnostics).instances[0]
    assert time.process_time() - start < 5
    (warning,) = [d for d in diagnostics if "event_analyzers" in d.message]
    assert "(1000 times)" in warning.message
    assert warning.location.line == 9
    kept = own_property(root, CP + "Unmodelled_Elements")
    assert len(kept) == 1000
    assert kept[0] == {"Section": "event_analyzers", "Xml": "<event_analyzer><name>e</name></event_analyzer>"}


def test_cheddar_warning_repeated_by_many_tasks_is_reported_once_with_its_count() -> None:
    tasks = "\n".join(
        _task(name=f"t{i}", ident=f"id{i}", extra="<policy>SCHED_LOTTERY</policy><colour>red</colour>")
        for i in range(300)
    )
    diagnostics: list[Diagnostic] = []
    loads_cheddar(_document(tasks).encode(), "many.xmlv3", diagnostics=diagnostics)
    policy, colour = diagnostics
    assert "SCHED_LOTTERY" in policy.message and policy.message.endswith("(300 times)")
    assert "<colour>" in colour.message and colour.message.endswith("(300 times)")
    assert policy.location.path == "/cheddar/tasks/periodic_task[1]/policy"


def _peak_rss_of_child(code: str, *args: str) -> tuple[int, str]:
    """Run ``code`` in a fresh interpreter; its peak resident memory (bytes, VmHWM) and output."""
    script = (
        code + "\nfrom benchmarks.harness import status_kib\nprint('PEAK', status_kib('VmHWM:') * 1024)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script, *args],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
        cwd=ROOT,
    )
    assert done.returncode == 0, done.stderr
    peak = next(int(line.split()[1]) for line in done.stdout.splitlines() if line.startswith("PEAK "))
    return peak, done.stdout


def _amplifying_webgmex(path: Path, values: int) -> int:
    """A ``.webgmex`` whose project.json is ``values`` empty arrays; the JSON's size in bytes."""
    text = b'{"rootHash": "#1", "objects": [' + b"[]," * values + b"{}]}"
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("project.json", text)
    return len(text)


_READ_WEBGMEX = """
import sys
from rosaadl.errors import ImportFormatError
from rosaadl.importers.rosmod_webgme.archive import load_project_json
try:
    load_project_json(sys.argv[1])
    print('READ')
except ImportFormatError as exc:
    print('REFUSED', exc)
"""


def test_webgmex_of_millions_of_small_values_is_refused_in_bounded_memory(tmp_path: Path) -> None:
    archive = tmp_path / "amplified.webgmex"
    size = _amplifying_webgmex(archive, 8_000_000)
    assert archive.stat().st_size < size // 100  # a small file that expands a lot
    peak, output = _peak_rss_of_child(_READ_WEBGMEX, str(archive))
    assert "REFUSED" in output and "project.json" in output and "JSON values" in output, output
    baseline, _ = _peak_rss_of_child("import rosaadl.importers.rosmod_webgme.archive")
    assert peak - baseline < 5 * size, (peak, baseline, size)


def test_json_value_bound_counts_values_and_leaves_out_commas_in_strings() -> None:
    assert json_value_bound(b'{"a": [1, 2, {"b": null}], "c": "x"}') >= 6
    text = b'["' + b",[{" * 100 + b'", 1]'
    assert json_value_bound(text, cap=10) == 3
    assert json_value_bound(b'["a\\", [", 2]', cap=1) == 3


_LONG_TOKENS = r"""
import gc, sys
from benchmarks.harness import reset_peak, status_kib
from rosaadl.errors import RosaadlError
from rosaadl.importers.aadl_syntax import parse
from rosaadl.importers.aadl_text import read_string

def package(value):
    head = 'package P\npublic\n  data D\n  properties\n    Source_Text => ('
    return head + value + ');\n  end D;\nend P;\n'

n = 1_000_000
cases = {
    'plain string': package('"' + 'a' * n + '"'),
    'escaped quotes': package('"' + '\\"' * (n // 2) + '"'),
    'doubled quotes': package('"' + '""' * (n // 2) + '"'),
    'unterminated string': package('"' + 'a\\"' * (n // 3)),
    'long integer': package('1' + '_1' * (n // 2)),
    'comment lines': package('"a"' + '\n--' * (n // 3)),
    'white space': 'package P public' + ' \t' * (n // 2) + 'end P;',
}
read_string(package('"warm up"'), 'warm.aadl')
for name, text in cases.items():
    gc.collect()
    before = reset_peak() * 1024
    try:
        read_string(text, 'long.aadl') if 'string' in name else parse(text, 'long.aadl')
    except RosaadlError as exc:
        assert exc.location.line, exc
    print('CASE', name, status_kib('VmHWM:') * 1024 - before, len(text))
"""


def test_aadl_long_tokens_are_lexed_in_memory_linear_in_their_length() -> None:
    """A 1 MB string, integer or gap costs a few times its size, not 300 bytes per character."""
    done = subprocess.run(
        [sys.executable, "-c", _LONG_TOKENS],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
        cwd=ROOT,
    )
    assert done.returncode == 0, done.stderr
    cases = [line.split()[1:] for line in done.stdout.splitlines() if line.startswith("CASE ")]
    assert len(cases) == 7, done.stdout
    for *name, grown, size in cases:
        assert int(grown) < 10 * int(size), (" ".join(name), grown, size)


def test_a_large_aadl_file_of_corpus_shape_reads_in_memory_bounded_by_its_model(tmp_path, corpus) -> None:
    """2 MB of the corpus's packages and property sets copied under new names: the reader holds
    the model (about 5x the text for such files, was 12x with one pyecore value holder per
    attribute, an index per list and a containment pair per object) and the text, never the
    whole parse tree (was 35x: the tree alone is about 18x)."""
    path = tmp_path / "copies.aadl"
    path.write_text(
        renamed_copies_text((data.decode("utf-8-sig") for _, data in aadl_texts(corpus)), 2_000_000)
    )
    ratio = read_peak_per_byte(path)
    assert ratio < 8, ratio


def test_checking_a_large_aadl_file_keeps_no_empty_list_on_the_elements_it_visits(tmp_path, corpus) -> None:
    """The same 2 MB, its names resolved and values checked: the checks read lists as they are
    stored, so the elements that own none (most own no property association, no modes, ...)
    are not given an empty one by pyecore's getter (was 17x, 6x of it such lists)."""
    path = tmp_path / "copies.aadl"
    path.write_text(
        renamed_copies_text((data.decode("utf-8-sig") for _, data in aadl_texts(corpus)), 2_000_000)
    )
    ratio = read_peak_per_byte(path, check=True)
    assert ratio < 8, ratio


def test_a_large_dense_aadl_package_reads_in_memory_bounded_by_its_model(tmp_path) -> None:
    """A generated package of 3 700 components (2 MB, 20 bytes of text per model object): the
    model is about 19x the text (was 40x), most of it the pyecore objects and their
    dictionaries (about 220 bytes per object, 11x), the peak stays near it (was 95x, the tree
    adding 45x)."""
    path = tmp_path / "generated.aadl"
    path.write_text(aadl_package_text(3_700))
    ratio = read_peak_per_byte(path)
    assert ratio < 26, ratio
