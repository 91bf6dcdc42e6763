"""The flow latency analysis against the seven latency reports OSATE wrote in the corpus.

Each report is read in place, and compared with the analysis of the instance OSATE analysed
(``instances/*.aaxl2``, read with our ``.aaxl2`` reader) and with that of the model's ``.aadl``
sources read and instantiated by rosaadl: every contributor row (its kind, element, minimum and
maximum values and methods) and the totals of every flow and system kind.

The reports come from three releases of OSATE, whose rules differ; the analysis is run with the
rules of the release that wrote each (``LatencyPreferences.revision``):

* ``ex-latency-nobus``, ``-normal``, ``-unbound``: September 2014, before partition windows
  (``2014-early``): an ``Issues`` column; a synchronous system rounds every sampling up;
* ``ex-latency-partitioned-distributed``, ``ex-simple-thread-latency``: September 2014 with
  partition windows (``2014``);
* ``ex-pullprotocols`` (``AS-MF-ET-EQ``, 2016) and ``osate2-simple-control-modes``
  (``SS-MF-DL-EQ``, 2018): today's rules with the words of OSATE 2.2-2.4 (``2018``). The 2018
  report is written from OSATE's result model, which leaves out the *first sampling* row
  (``LatencyReportEntry.genResult`` skipped it then), and covers the first system operation mode
  only (``som_0``): the instance has two and only ``som_0`` can be compared. Its header names the
  preferences ``asynchronous system/.../full queue`` although the file name says ``SS-MF-DL-EQ``;
  the numbers (a synchronous round-up of 20 ms) follow the file name.

Sources: ``osate2-simple-control-modes`` lacks its ``Properties/Physical.aadl``; the library's
``Physical`` property set stands in (the model uses ``Physical::Voltage`` only, which the latency
analysis does not read). The other folders hold every source their reports need.

Comments are not compared (their wording changed with every release), nor the 2014 reports'
specified columns of sampling rows, which OSATE left empty.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from conftest import corpus_dir

from rosaadl.analysis.instance_values import instance_root
from rosaadl.analysis.latency import LatencyPreferences, analyze_latency
from rosaadl.formats import read_input

#: (corpus folder, report preferences when its file name has none, OSATE's rules)
REPORTS = {
    "ex-latency-nobus": ("AS-MF-ET-EQ", "2014-early"),
    "ex-latency-normal": ("AS-MF-ET-EQ", "2014-early"),
    "ex-latency-unbound": ("AS-MF-ET-EQ", "2014-early"),
    "ex-latency-partitioned-distributed": ("AS-MF-ET-EQ", "2014"),
    "ex-simple-thread-latency": ("AS-MF-DL-EQ", "2014"),
    "ex-pullprotocols": (None, "2018"),
    "osate2-simple-control-modes": (None, "2018"),
}

_TITLE = re.compile(
    r"^(?:Flow analysis for end to end flow (?P<old>\S+)(?: \((?P<mode>Async|Sync)\))?"
    r"|Latency results for end-to-end flow '(?P<new>[^']+)' of system '[^']*' ?(?P<som>\S*))"
)


@dataclass
class Section:
    flow: str
    mode: str
    som: str
    rows: list[tuple[str, str, float, str, float, str]] = field(default_factory=list)
    total: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)
    expected: tuple[float, float] = (0.0, 0.0)


def _ms(text: str) -> float:
    return float(text.strip().removesuffix("ms") or 0)


def _kind(label: str) -> tuple[str, str]:
    """(category word, element name) of an OSATE row label, across its releases."""
    label = label.strip().strip("()")
    word, _, name = label.partition(" ")
    word = word.lower()
    if word in ("sampled", "immediate", "delayed"):
        word, name = "connection", name.partition(" ")[2]
    word = {"component": "partition", "virtual": "protocol"}.get(word, word)
    return word, name.strip()


def parse_report(path: Path, default_mode: str) -> list[Section]:
    """The sections of an OSATE latency CSV of any release: flow, mode, rows, totals."""
    sections: list[Section] = []
    current: Section | None = None
    in_rows = False
    for line in path.read_text(encoding="utf-8").splitlines():
        match = _TITLE.match(line.strip('"'))
        if match:
            mode = {"Async": "async", "Sync": "sync"}.get(match["mode"] or "", default_mode)
            current = Section(match["old"] or match["new"], mode, match["som"] or "")
            sections.append(current)
            in_rows = False
            continue
        cells = line.split(",")
        if current is None:
            continue
        if cells[0] in ("Contributor", "Result"):
            in_rows = True
        elif cells[0] == "Latency Total":
            current.total = (_ms(cells[1]), _ms(cells[2]), _ms(cells[4]), _ms(cells[5]))
            in_rows = False
        elif cells[0] in ("End to End Latency", "Specified End To End Latency"):
            current.expected = (_ms(cells[2]), _ms(cells[5]))
        elif in_rows and len(cells) >= 7:
            word, name = _kind(cells[0])
            current.rows.append(
                (word, name, _ms(cells[2]), cells[3].strip(), _ms(cells[5]), cells[6].strip())
            )
    return sections


def _cases() -> list[tuple[str, Path]]:
    root = corpus_dir() / "osate" / "aaxl2"
    found = []
    for folder in REPORTS:
        for report in sorted((root / folder).glob("**/instances/reports/latency/*.csv")):
            found.append((folder, report))
    return found


def _instance(report: Path):
    (aaxl2,) = report.parent.parent.parent.glob("*.aaxl2")
    return instance_root(read_input(aaxl2).root)


def _same_name(theirs: str, ours: str) -> bool:
    if not theirs:  # OSATE 2016 printed no name for connections
        return True
    return (
        theirs == ours or ours.endswith("." + theirs) or theirs.rpartition(".")[2] == ours.rpartition(".")[2]
    )


@pytest.mark.parametrize(
    ("folder", "report"), _cases() or [("-", Path("-"))], ids=lambda v: getattr(v, "name", v)
)
def test_osate_latency_reports_are_reproduced(corpus, folder, report):
    prefs, sections = _expected(folder, report)
    _compare(analyze_latency(_instance(report), preferences=prefs), sections, report)


def _expected(folder: str, report: Path) -> tuple[LatencyPreferences, list[Section]]:
    """The preferences and rules a report was written with, and its sections."""
    if folder == "-":
        pytest.skip("no OSATE latency report in the corpus")
    default_code, revision = REPORTS[folder]
    code = re.search(r"_(\w\w-\w\w-\w\w-\w\w)\.csv$", report.name)
    prefs, synchronous = LatencyPreferences.from_code(code.group(1) if code else default_code, revision)
    sections = parse_report(report, "sync" if synchronous else "async")
    assert sections, f"no flow in {report.name}"
    return prefs, sections


#: (corpus folder, root implementation) of the models behind the reports, read from their .aadl
SOURCES = {
    "ex-latency-nobus": "latency_distributed::latencytest.nobus",
    "ex-latency-normal": "latency_distributed::latencytest.normal",
    "ex-latency-unbound": "latency_distributed::latencytest.unbound",
    "ex-latency-partitioned-distributed": "latency_distributed::latencytest.partitioned_distributed",
    "ex-simple-thread-latency": "SimpleThreadLatency::s.i",
    "ex-pullprotocols": "pullprotocols::stub.i",
    "osate2-simple-control-modes": "SimpleControlSystem::SCS.tier1",
}


@pytest.mark.parametrize(
    ("folder", "report"), _cases() or [("-", Path("-"))], ids=lambda v: getattr(v, "name", v)
)
def test_osate_latency_reports_from_the_aadl_sources(corpus, folder, report):
    """The same reports from the models' ``.aadl`` sources, read and instantiated by rosaadl."""
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.instantiate import instantiate

    prefs, sections = _expected(folder, report)
    workspace = read_files(sorted((corpus / "osate" / "aaxl2" / folder).rglob("*.aadl")))
    _compare(analyze_latency(instantiate(workspace, SOURCES[folder]), preferences=prefs), sections, report)


def _compare(result, sections: list[Section], report: Path) -> None:
    result_format = report.name.endswith("SS-MF-DL-EQ.csv")  # OSATE 2018: from its result model
    for section in sections:
        chains = [
            c
            for c in result.chains
            if c.mode == section.mode
            and c.name == section.flow
            and (not section.som or c.system_mode in ("", section.som))
        ]
        assert chains, f"{section.flow} ({section.mode}) not analysed"
        chain = chains[0]
        ours = [h for h in chain.hops if not (result_format and h.worst_method == "first sampling")]
        assert len(ours) == len(section.rows), (section.flow, section.mode, [h.label for h in ours])
        for hop, (word, name, low, low_method, high, high_method) in zip(ours, section.rows, strict=True):
            where = f"{report.name}: {section.flow} ({section.mode}) {hop.label}"
            our_word, _, our_name = hop.label.partition(" ")
            assert our_word == word and _same_name(name, our_name), where
            assert float(hop.best_us) / 1000 == pytest.approx(low, abs=1e-9), where
            assert float(hop.worst_us) / 1000 == pytest.approx(high, abs=1e-9), where
            assert (hop.best_method, hop.worst_method) == (low_method, high_method), where
        spec_low, low, spec_high, high = section.total
        assert float(chain.specified_best_us) / 1000 == pytest.approx(spec_low, abs=1e-9)
        assert float(chain.specified_worst_us) / 1000 == pytest.approx(spec_high, abs=1e-9)
        assert float(chain.best_us) / 1000 == pytest.approx(low, abs=5e-4)  # OSATE rounds to the µs
        assert float(chain.worst_us) / 1000 == pytest.approx(high, abs=5e-4)
        assert float(chain.expected_best_us or 0) / 1000 == pytest.approx(section.expected[0])
        assert float(chain.expected_us or 0) / 1000 == pytest.approx(section.expected[1])


def test_every_latency_report_of_the_corpus_is_covered(corpus):
    reports = {p.name for p in (corpus / "osate" / "aaxl2").glob("*/**/reports/latency/*.csv")}
    assert len(reports) == 7
    assert reports == {p.name for _, p in _cases()}


def test_the_2018_summary_has_osate_s_words(corpus):
    """OSATE's summary lines, word for word, as its 2018 report has them for som_0."""
    (report,) = [p for f, p in _cases() if f == "osate2-simple-control-modes"]
    prefs, _ = LatencyPreferences.from_code("SS-MF-DL-EQ", "2018")
    result = analyze_latency(_instance(report), preferences=prefs)
    chain = next(c for c in result.chains if c.mode == "sync" and c.system_mode == "som_0")
    lines = report.read_text(encoding="utf-8").splitlines()
    start = lines.index("End to end Latency Summary")
    expected = [tuple(line.split(",", 1)) for line in lines[start + 1 :] if line]
    assert list(chain.issues) == expected


def test_analyze_writes_osate_s_report_that_diffs_with_osate_s(corpus, tmp_path, capsys):
    """``analyze --only latency -o DIR``: our table and OSATE's report per system kind, whose
    rows and totals are those of the OSATE report of the same preferences (today's rules)."""
    from rosaadl.cli import main

    (report,) = [p for f, p in _cases() if f == "ex-pullprotocols"]
    (aaxl2,) = report.parent.parent.parent.glob("*.aaxl2")
    out = tmp_path / "out"
    code = main(
        ["analyze", str(aaxl2), "--only", "latency", "-o", str(out), "--latency-preferences", "AS-MF-ET-EQ"]
    )
    assert code == 1  # 300 ms over a 10 ms Latency
    names = sorted(p.name for p in out.iterdir())
    assert names == [
        "stub_i_Instance__Latency.csv",
        "stub_i_Instance__latency_AS-MF-ET-EQ.csv",
        "stub_i_Instance__latency_SS-MF-ET-EQ.csv",
    ]
    ours = parse_report(out / "stub_i_Instance__latency_AS-MF-ET-EQ.csv", "async")
    theirs = parse_report(report, "async")
    assert [s.flow for s in ours] == [s.flow for s in theirs] == ["prot.XferOnly"]
    assert ours[0].total == theirs[0].total and ours[0].expected == theirs[0].expected
    # today's word for a row that adds nothing is "no sampling/queuing latency" (2016: "no latency")
    same = [(w, lo, hi) for w, _, lo, _, hi, _ in ours[0].rows]
    assert same == [(w, lo, hi) for w, _, lo, _, hi, _ in theirs[0].rows]
    assert (
        "ERROR,Maximum actual latency total 300.0ms exceeds expected maximum end to end latency 10.0ms"
        in (out / "stub_i_Instance__latency_AS-MF-ET-EQ.csv").read_text(encoding="utf-8")
    )
    capsys.readouterr()


def test_bad_latency_preferences_are_a_usage_error(capsys):
    from rosaadl.cli import main

    assert main(["analyze", "nowhere.aadl", "--latency-preferences", "AS-XX-ET-EQ"]) == 2
    assert "latency preferences" in capsys.readouterr().err
