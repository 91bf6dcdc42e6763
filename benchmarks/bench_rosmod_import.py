"""ROSMOD import benchmark: the largest corpus projects and generated projects of growing size.

Side by side for each input: the time to tokenize and parse the files alone (the floor of the
reader), the full import into a ``rosmod.Project`` (parse, model objects, name resolution), and
saving the result as XMI. Generated v0.3 projects
(``benchmarks.generators.rosmod.write_rosmod_project``) have N nodes, each running one component
instance with 5 callbacks (2 timers, 2 subscribers, 1 server) plus 2 publishers and a client;
the table ends with how the import time grows from 100 to 1 000 to 5 000 nodes (the exponent k
in t ∝ N^k). The corpus rows are skipped when the corpus is absent.

Usage: ``python -m benchmarks.bench_rosmod_import [--sizes 100,1000,5000] [--repeat 3]``.
"""

from __future__ import annotations

import argparse
import logging
import tempfile
from pathlib import Path

from benchmarks.generators.corpus import corpus_dir
from benchmarks.generators.rosmod import write_rosmod_project
from benchmarks.harness import Report, Timing, best_of
from rosaadl import model
from rosaadl.importers import rosmod_text, rosmod_webgme
from rosaadl.importers.rosmod_text.blocks import parse_blocks

__all__ = ["main"]

CORPUS_PROJECTS = (
    "textual-v0.3/periodic-timers",
    "textual-v0.3/sequential-leds",
    "textual-v0.3/client-server",
    "textual-v0.3/agse",
    "agse2015/agse_rosmod_project",
)
CORPUS_SEEDS = ("webgme/samples-2018-05-19_noTLC.webgmex", "webgme/samples-2016-06-13_noTLC.webgmex")


def _parse_only(project: Path) -> int:
    count = 0
    for path in sorted(project.rglob("*")):
        if path.suffix in (".rml", ".rhw", ".rdp"):
            text = path.read_text()
            if not text.lstrip().startswith("{"):  # the v0.4 JSON file has no blocks to parse
                count += len(parse_blocks(text, str(path)))
    return count


def _counts(projects: list) -> str:
    counts = dict.fromkeys(("nodes", "timers", "subscribers", "servers"), 0)
    for project in projects:
        for key, value in rosmod_text.summarize(project).items():
            if key in counts:
                counts[key] += value
    callbacks = counts["timers"] + counts["subscribers"] + counts["servers"]
    return f"{counts['nodes']} nodes, {callbacks} callbacks"


def _project_rows(report: Report, label: str, path: Path, save_to: Path, repeat: int, detail: bool) -> Timing:
    parse = best_of(lambda: _parse_only(path), repeat)
    full = best_of(lambda: rosmod_text.read_project(path), repeat)
    project = full.result
    save = best_of(lambda: model.save(project, save_to), 1)
    what = _counts([project])
    report.time(f"import {label}", full, parse, against="parse only", note=what, detail=detail)
    report.time(f"save {label} as XMI", save, note=what, detail=True)
    return full


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bench_rosmod_import", description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="100,1000,5000", help="node counts of the generated projects")
    parser.add_argument("--repeat", type=int, default=3, help="best of this many runs (corpus rows)")
    args = parser.parse_args(argv)
    sizes = [int(s) for s in args.sizes.split(",") if s]
    logging.disable(logging.WARNING)  # the corpus has known, expected warnings
    report = Report("rosmod_import")
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        corpus = corpus_dir() / "rosmod"
        if corpus.is_dir():
            for name in CORPUS_PROJECTS:
                _project_rows(report, name, corpus / name, out / "p.xmi", args.repeat, True)
            for name in CORPUS_SEEDS:
                full = best_of(lambda p=corpus / name: rosmod_webgme.read_webgmex(p), args.repeat)
                label = f"{Path(name).stem} ({len(full.result)} projects)"
                report.time(f"import {label}", full, note=_counts(full.result), detail=True)
        else:
            print(f"(corpus not found at {corpus}: corpus rows skipped)")
        timings: list[tuple[int, float]] = []
        for size in sizes:
            path = write_rosmod_project(out, size)
            full = _project_rows(report, f"generated ({size} nodes)", path, out / f"g{size}.xmi", 1, False)
            timings.append((size, full.cpu))
    report.growth("import", timings)
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())
