"""ROSMOD ⇄ AADL conversion benchmark: the largest corpus deployment and generated projects.

Side by side for each input: ROSMOD → AADL (``rosmod_to_aadl``, with its trace), writing the
AADL text (``write_model``), and AADL → ROSMOD (``aadl_to_rosmod`` on the converted model).
Generated projects (``benchmarks.generators.rosmod.rosmod_project``) have N nodes, each running
one component instance with 5 callbacks (2 timers, 2 subscribers, 1 server) plus a publisher
and a client; there are N/2 message types, so that every topic joins 2 publishers to 4
subscribers (4 N topic connections). The table ends with how the conversion time grows from 100
to 1 000 to 5 000 nodes (the exponent k in t ∝ N^k). Floors: the corpus deployment in under
1 s, 1 000 nodes in under 20 s.

Usage: ``python -m benchmarks.bench_rosmod_convert [--sizes 100,1000,5000] [--repeat 3]``.
"""

from __future__ import annotations

import argparse
import logging
import tempfile
from pathlib import Path

from pyecore.ecore import EObject

from benchmarks.generators.corpus import corpus_dir
from benchmarks.generators.rosmod import rosmod_project
from benchmarks.harness import Goal, Report, Timing, best_of
from rosaadl import model
from rosaadl.exporters.aadl_text import write_model
from rosaadl.importers import rosmod_text
from rosaadl.transforms.aadl_to_rosmod import aadl_to_rosmod
from rosaadl.transforms.rosmod_to_aadl import rosmod_to_aadl

__all__ = ["main"]

CORPUS_PROJECT = "textual-v0.3/periodic-timers"
FLOORS = {"corpus": 1.0, 1000: 20.0}


def _threads(project: EObject) -> int:
    return sum(
        len(i.component.timers) + sum(1 for p in i.component.ports if model.is_a(p, "Subscriber", "Server"))
        for d in project.deployments
        for n in d.nodes
        for i in n.componentInstances
    )


def _measure(
    report: Report, label: str, project: EObject, repeat: int, folder: Path, floor: float | None
) -> Timing:
    forward = best_of(lambda: rosmod_to_aadl(project), repeat)
    converted = forward.result.model
    out = folder / label.replace(" ", "_").replace("/", "_")
    writing = best_of(lambda: write_model(converted, out), 1)
    back = best_of(lambda: aadl_to_rosmod(converted), repeat)
    what = f"{_threads(project)} threads"
    report.time(f"to AADL: {label}", forward, goal=Goal(floor) if floor is not None else None, note=what)
    report.time(f"write AADL: {label}", writing, note=what, detail=True)
    report.time(f"to ROSMOD: {label}", back, note=what, detail=floor is None)
    return forward


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bench_rosmod_convert", description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="100,1000,5000", help="generated project sizes (nodes)")
    parser.add_argument("--repeat", type=int, default=3, help="best of this many runs (small inputs)")
    args = parser.parse_args(argv)
    logging.disable(logging.WARNING)
    sizes = [int(s) for s in args.sizes.split(",") if s.strip()]
    report = Report("rosmod_convert")
    timings: list[tuple[int, float]] = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        corpus = corpus_dir() / "rosmod" / CORPUS_PROJECT
        if corpus.is_dir():
            project = rosmod_text.read_project(corpus)
            _measure(report, CORPUS_PROJECT, project, args.repeat, folder, FLOORS["corpus"])
        else:
            print(f"(corpus project {CORPUS_PROJECT} not found: its row is skipped)")
        for size in sizes:
            project = rosmod_project(size)
            repeat = args.repeat if size <= 1000 else 1
            forward = _measure(report, f"generated {size} nodes", project, repeat, folder, FLOORS.get(size))
            timings.append((size, forward.cpu))
    report.growth("to AADL", timings)
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())
