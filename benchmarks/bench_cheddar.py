"""Cheddar XML benchmark: import and export of the corpus files and of a generated large model.

Side by side in one run, per file:
  * the raw lxml parse of the file (the floor an importer cannot beat);
  * ``loads_cheddar`` (parse + checks + instance model);
  * ``dumps_cheddar`` of that model in the same format;
  * the comparison of the round trip (import of the export vs the first import, with
    ``rosaadl.model.model_differences``; for the generated file only with ``--compare``).

The generated file (``benchmarks.generators.cheddar.cheddar_document``) has ``--tasks`` tasks
(10 000 by default) on 8 mono-core processors, with one shared resource and one buffer per 100
tasks and the buffers' dependencies.
Usage: ``python -m benchmarks.bench_cheddar [--tasks N] [--repeat R] [--no-corpus] [--compare]``.
"""

from __future__ import annotations

import argparse
import statistics

from lxml import etree

from benchmarks.generators.cheddar import cheddar_document
from benchmarks.generators.corpus import corpus_dir
from benchmarks.harness import Goal, Report, best_of
from rosaadl import model
from rosaadl.exporters.cheddar import dumps_cheddar
from rosaadl.fileio import safe_xml_parser
from rosaadl.importers.cheddar import cheddar_format_of, loads_cheddar, strip_internal_subset

__all__ = ["main"]


def _task_count(tree: etree._Element) -> int:
    section = next((s for s in tree if isinstance(s.tag, str) and s.tag.lower() == "tasks"), None)
    return sum(1 for t in section if isinstance(t.tag, str)) if section is not None else 0


def _measure(report: Report, name: str, data: bytes, repeat: int, compare: bool, detail: bool) -> tuple:
    """Rows of one file: import against the raw parse, export, the round trip's comparison;
    returns (import / parse, whether the round trip differs, or None when not compared)."""
    stripped = strip_internal_subset(data, name)
    parse = best_of(lambda: etree.fromstring(stripped, safe_xml_parser()), repeat)
    fmt = cheddar_format_of(parse.result)
    what = f"{len(data) / 1024:.1f} KiB, {_task_count(parse.result)} tasks, Cheddar {fmt}"
    load = best_of(lambda: loads_cheddar(data, name), repeat)
    first = load.result
    dump = best_of(lambda: dumps_cheddar(first, cheddar_format=fmt), repeat)
    report.time(f"import {name}", load, parse, against="lxml parse", note=what, detail=detail)
    report.time(f"export {name}", dump, note=what, detail=detail)
    differs = None
    if compare:
        second = loads_cheddar(dump.result, name)
        took = best_of(lambda: model.model_differences(first, second), 1)
        differs = bool(took.result)
        verdict = "DIFFERS" if differs else "equal"
        report.time(f"round trip {name}", took, note=f"compared: {verdict}", detail=True)
    return load.cpu / parse.cpu, differs


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bench_cheddar", description=__doc__.splitlines()[0])
    parser.add_argument("--tasks", type=int, default=10_000, help="tasks of the generated file")
    parser.add_argument("--repeat", type=int, default=3, help="runs per corpus measurement (best is shown)")
    parser.add_argument("--no-corpus", action="store_true", help="only the generated file")
    parser.add_argument(
        "--compare",
        action="store_true",
        help="also compare the generated model's round trip (slow: about a minute)",
    )
    options = parser.parse_args(argv)
    report = Report("cheddar")
    folder = corpus_dir() / "cheddar"
    ratios, round_trips = [], []
    if not options.no_corpus and folder.is_dir():
        for path in sorted(folder.glob("*.xml*")):
            ratio, differs = _measure(report, path.name, path.read_bytes(), options.repeat, True, True)
            ratios.append(ratio)
            round_trips.append(differs)
    elif not options.no_corpus:
        print(f"(corpus not found at {folder}; only the generated file is measured)")
    if ratios:
        report.add(
            "corpus: import / raw parse, median", statistics.median(ratios), "", note=f"{len(ratios)} files"
        )
        report.add(
            "corpus: round trips that differ",
            sum(round_trips),
            "",
            goal=Goal(0),
            note=f"of {len(round_trips)} files",
        )
    name = f"generated {options.tasks} tasks"
    _, differs = _measure(report, name, cheddar_document(options.tasks), 1, options.compare, False)
    if differs is not None:
        report.add(f"{name}: round trip differs", int(differs), "", goal=Goal(0))
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())
